// glTF 2.0 through Assimp (scenes/gltf_load.h). Two passes: the file's JSON is checked first
// (buffers present and long enough, accessors inside their buffer views, counts bounded,
// features aalab does not render named), so that Assimp only ever reads a file whose byte
// ranges are sound; then Assimp's glTF2 importer builds the meshes, the node hierarchy,
// materials and cameras, and the result is checked again (indices, finite positions).
#include "scenes/gltf_load.h"

#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/core/error.h"
#include "harness/core/input_files.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

using Json = nlohmann::json;

[[noreturn]] void Refuse(const std::string& path, const std::string& what) {
  throw UserError("glTF file '" + path + "': " + what);
}

std::string ReadBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) Refuse(path, "cannot be read");
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

uint32_t Le32(const std::string& b, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

/// The JSON document of a .gltf or .glb file, and the length of a .glb's BIN chunk (-1: none).
struct GltfJson {
  Json doc;
  long long glb_bin = -1;
};

GltfJson ParseGltfJson(const std::string& path) {
  const std::string bytes = ReadBytes(path);
  GltfJson out;
  std::string text = bytes;
  if (bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0) {
    if (bytes.size() < 20) Refuse(path, "truncated GLB header");
    if (Le32(bytes, 4) != 2) Refuse(path, "GLB container version " + std::to_string(Le32(bytes, 4)) + " (allowed: 2)");
    const uint32_t json_len = Le32(bytes, 12);
    if (Le32(bytes, 16) != 0x4E4F534Au || 20ull + json_len > bytes.size()) Refuse(path, "GLB has no complete JSON chunk");
    text = bytes.substr(20, json_len);
    const size_t bin_at = 20ull + json_len;
    if (bin_at + 8 <= bytes.size() && Le32(bytes, bin_at + 4) == 0x004E4942u) {
      const uint32_t bin_len = Le32(bytes, bin_at);
      if (bin_at + 8 + bin_len > bytes.size()) Refuse(path, "GLB BIN chunk is truncated");
      out.glb_bin = bin_len;
    }
  }
  try {
    out.doc = Json::parse(text);
  } catch (const Json::exception& e) {
    Refuse(path, std::string("not valid glTF JSON: ") + e.what());
  }
  if (!out.doc.is_object()) Refuse(path, "the JSON document is not an object");
  return out;
}

long long IntAt(const Json& o, const char* key, long long fallback) {
  if (!o.is_object() || !o.contains(key)) return fallback;
  const Json& v = o.at(key);
  if (!v.is_number_integer() && !v.is_number_unsigned()) return -2;
  return v.get<long long>();
}

int ComponentBytes(long long type) {
  switch (type) {
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
  }
}

int TypeComponents(const std::string& t) {
  static const std::map<std::string, int> k = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                               {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
  auto it = k.find(t);
  return it == k.end() ? 0 : it->second;
}

/// The checks on the JSON (see the file comment); fills the cameras' projections.
void CheckGltfJson(const std::string& path, const GltfJson& g, std::vector<Camera>& cams) {
  const Json& d = g.doc;
  const std::string version = d.contains("asset") && d["asset"].contains("version") && d["asset"]["version"].is_string()
                                  ? d["asset"]["version"].get<std::string>() : "";
  if (version.empty() || version[0] != '2') Refuse(path, "asset.version '" + version + "' (allowed: 2.x)");
  for (const char* list : {"extensionsRequired", "extensionsUsed"}) {
    if (!d.contains(list)) continue;
    for (const Json& e : d[list]) {
      const std::string name = e.is_string() ? e.get<std::string>() : "?";
      if (name != "KHR_materials_unlit") {
        Refuse(path, std::string(list) + " names '" + name + "', which aalab does not render (supported: KHR_materials_unlit)");
      }
    }
  }
  for (const char* part : {"animations", "skins"}) {
    if (d.contains(part) && d[part].is_array() && !d[part].empty()) {
      Refuse(path, std::string("has ") + part + ", which aalab does not render (a still pose would be a different picture)");
    }
  }
  const fs::path dir = fs::path(path).parent_path();
  std::vector<long long> buffer_len;
  if (d.contains("buffers")) {
    for (size_t i = 0; i < d["buffers"].size(); ++i) {
      const Json& b = d["buffers"][i];
      const long long len = IntAt(b, "byteLength", -1);
      const std::string where = "buffer " + std::to_string(i);
      if (len < 1) Refuse(path, where + " has no valid byteLength");
      if (!b.contains("uri")) {
        if (g.glb_bin < 0 || i != 0) Refuse(path, where + " has no uri and no GLB BIN chunk holds it");
        if (len > g.glb_bin) Refuse(path, where + " declares " + std::to_string(len) + " bytes but the GLB BIN chunk has " + std::to_string(g.glb_bin));
      } else {
        const std::string uri = b["uri"].is_string() ? b["uri"].get<std::string>() : "";
        if (uri.rfind("data:", 0) != 0) {
          const fs::path bp = dir / uri;
          std::error_code ec;
          if (!fs::is_regular_file(bp, ec)) Refuse(path, where + ": file '" + bp.string() + "' not found");
          NoteInputFile(bp.string());  // an input of the run (harness/core/input_files.h)
          const auto size = static_cast<long long>(fs::file_size(bp, ec));
          if (ec || size < len) {
            Refuse(path, where + ": file '" + bp.string() + "' has " + std::to_string(size) + " bytes, byteLength declares " + std::to_string(len));
          }
        }
      }
      buffer_len.push_back(len);
    }
  }
  std::vector<long long> view_len;
  if (d.contains("bufferViews")) {
    for (size_t i = 0; i < d["bufferViews"].size(); ++i) {
      const Json& v = d["bufferViews"][i];
      const long long b = IntAt(v, "buffer", -1), off = IntAt(v, "byteOffset", 0), len = IntAt(v, "byteLength", -1);
      const std::string where = "bufferView " + std::to_string(i);
      if (b < 0 || b >= static_cast<long long>(buffer_len.size())) Refuse(path, where + " names buffer " + std::to_string(b) + ", which does not exist");
      if (off < 0 || len < 1 || off + len > buffer_len[static_cast<size_t>(b)]) {
        Refuse(path, where + " (bytes " + std::to_string(off) + ".." + std::to_string(off + len) + ") lies outside buffer " +
                         std::to_string(b) + " (" + std::to_string(buffer_len[static_cast<size_t>(b)]) + " bytes)");
      }
      view_len.push_back(len);
    }
  }
  if (d.contains("accessors")) {
    for (size_t i = 0; i < d["accessors"].size(); ++i) {
      const Json& a = d["accessors"][i];
      const std::string where = "accessor " + std::to_string(i);
      const long long count = IntAt(a, "count", -1);
      if (count < 1 || count > kMaxGltfAccessorCount) {
        Refuse(path, where + " declares count " + std::to_string(count) + " (allowed: 1 to " + std::to_string(kMaxGltfAccessorCount) + ")");
      }
      if (a.contains("sparse")) Refuse(path, where + " is sparse, which aalab does not read");
      const int cb = ComponentBytes(IntAt(a, "componentType", -1));
      const int nc = TypeComponents(a.contains("type") && a["type"].is_string() ? a["type"].get<std::string>() : "");
      if (cb == 0 || nc == 0) Refuse(path, where + " has an invalid componentType or type");
      if (!a.contains("bufferView")) continue;  // all zeros
      const long long v = IntAt(a, "bufferView", -1);
      if (v < 0 || v >= static_cast<long long>(view_len.size())) Refuse(path, where + " names bufferView " + std::to_string(v) + ", which does not exist");
      const Json& bv = d["bufferViews"][static_cast<size_t>(v)];
      const long long elem = static_cast<long long>(cb) * nc;
      const long long stride = IntAt(bv, "byteStride", elem);
      const long long off = IntAt(a, "byteOffset", 0);
      const long long need = off + (count - 1) * std::max(stride, elem) + elem;
      if (off < 0 || need > view_len[static_cast<size_t>(v)]) {
        Refuse(path, where + " reads " + std::to_string(count) + " elements (" + std::to_string(need) + " bytes) beyond bufferView " +
                         std::to_string(v) + " (" + std::to_string(view_len[static_cast<size_t>(v)]) + " bytes)");
      }
    }
  }
  if (d.contains("meshes")) {
    for (size_t m = 0; m < d["meshes"].size(); ++m) {
      const Json& mesh = d["meshes"][m];
      if (!mesh.contains("primitives")) continue;
      for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
        const Json& pr = mesh["primitives"][p];
        const std::string where = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
        const long long mode = IntAt(pr, "mode", 4);
        if (mode < 4 || mode > 6) Refuse(path, where + " has mode " + std::to_string(mode) + " (points or lines; aalab renders triangles: modes 4, 5, 6)");
        if (pr.contains("targets")) Refuse(path, where + " has morph targets, which aalab does not render");
        if (pr.contains("attributes") && pr["attributes"].contains("COLOR_0")) {
          Refuse(path, where + " has vertex colours (COLOR_0), which aalab does not render");
        }
      }
    }
  }
  if (d.contains("materials")) {
    for (size_t m = 0; m < d["materials"].size(); ++m) {
      const Json& mat = d["materials"][m];
      std::vector<const Json*> infos;
      if (mat.contains("pbrMetallicRoughness")) {
        for (const char* k : {"baseColorTexture", "metallicRoughnessTexture"}) {
          if (mat["pbrMetallicRoughness"].contains(k)) infos.push_back(&mat["pbrMetallicRoughness"][k]);
        }
      }
      for (const char* k : {"normalTexture", "occlusionTexture", "emissiveTexture"}) {
        if (mat.contains(k)) infos.push_back(&mat[k]);
      }
      for (const Json* t : infos) {
        if (IntAt(*t, "texCoord", 0) != 0) {
          Refuse(path, "material " + std::to_string(m) + " uses texture coordinate set " + std::to_string(IntAt(*t, "texCoord", 0)) +
                           " (aalab reads TEXCOORD_0 only)");
        }
      }
    }
  }
  if (d.contains("samplers")) {
    for (size_t s = 0; s < d["samplers"].size(); ++s) {
      const Json& sm = d["samplers"][s];
      const long long mag = IntAt(sm, "magFilter", 9729), min = IntAt(sm, "minFilter", 9987);
      if (mag != 9729 || (min != 9987 && min != 9729 && min != 9985)) {
        Refuse(path, "sampler " + std::to_string(s) + " asks for filters mag " + std::to_string(mag) + " / min " + std::to_string(min) +
                         " (aalab samples trilinear: mag LINEAR 9729, min LINEAR_MIPMAP_LINEAR 9987, LINEAR_MIPMAP_NEAREST 9985 or LINEAR 9729 are accepted and all filtered trilinear)");
      }
    }
  }
  if (d.contains("cameras")) {
    for (size_t c = 0; c < d["cameras"].size(); ++c) {
      const Json& cj = d["cameras"][c];
      Camera cam;
      const std::string type = cj.contains("type") && cj["type"].is_string() ? cj["type"].get<std::string>() : "";
      const std::string where = "camera " + std::to_string(c);
      if (type == "perspective" && cj.contains("perspective") && cj["perspective"].contains("yfov") && cj["perspective"]["yfov"].is_number()) {
        cam.type = CameraType::kPerspective;
        const double yfov = cj["perspective"]["yfov"].get<double>();
        if (!(yfov > 0.0 && yfov < 3.12)) Refuse(path, where + " has yfov " + std::to_string(yfov) + " (allowed: (0, 3.12) radians)");
        cam.fov_y_deg = static_cast<float>(yfov * 57.29577951308232);
      } else if (type == "orthographic" && cj.contains("orthographic") && cj["orthographic"].contains("ymag") && cj["orthographic"]["ymag"].is_number()) {
        cam.type = CameraType::kOrthographic;
        const double ymag = cj["orthographic"]["ymag"].get<double>();
        if (!(ymag > 0.0 && ymag < 1e9)) Refuse(path, where + " has ymag " + std::to_string(ymag) + " (allowed: > 0)");
        cam.height = static_cast<float>(2.0 * ymag);
      } else {
        Refuse(path, where + " is neither a valid perspective (yfov) nor an orthographic (ymag) camera");
      }
      cams.push_back(cam);
    }
  }
}

glm::mat4 ToGlm(const aiMatrix4x4& m) {
  glm::mat4 g;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) g[c][r] = m[r][c];
  }
  return g;
}

glm::mat4 NodeWorld(const aiNode* n) {
  glm::mat4 m(1.0f);
  for (; n; n = n->mParent) m = ToGlm(n->mTransformation) * m;
  return m;
}

WrapMode ToWrap(int mode) {
  switch (mode) {
    case aiTextureMapMode_Clamp: return WrapMode::kClampToEdge;
    case aiTextureMapMode_Mirror: return WrapMode::kMirroredRepeat;
    default: return WrapMode::kRepeat;
  }
}

/// Reads the file's materials and decodes their textures (each image once per colour space).
class MaterialReader {
 public:
  MaterialReader(const std::string& path, const aiScene* sc, GltfContent& out) : path_(path), sc_(sc), out_(out) {}

  Material Read(unsigned index) {
    const aiMaterial* am = sc_->mMaterials[index];
    Material m;
    aiString name;
    m.name = fs::path(path_).filename().string() + "#" + std::to_string(index);
    if (am->Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0) m.name += ":" + std::string(name.C_Str());
    GltfMaterial g;
    aiColor4D base(1, 1, 1, 1);
    if (am->Get(AI_MATKEY_BASE_COLOR, base) != AI_SUCCESS) am->Get(AI_MATKEY_COLOR_DIFFUSE, base);
    g.base_factor = {base.r, base.g, base.b, base.a};
    g.base_tex = Tex(am, aiTextureType_BASE_COLOR, true);
    if (!g.base_tex.Has()) g.base_tex = Tex(am, aiTextureType_DIFFUSE, true);
    am->Get(AI_MATKEY_METALLIC_FACTOR, g.metallic);
    am->Get(AI_MATKEY_ROUGHNESS_FACTOR, g.roughness);
    g.mr_tex = Tex(am, aiTextureType_UNKNOWN, false);
    if (!g.mr_tex.Has()) g.mr_tex = Tex(am, aiTextureType_METALNESS, false);
    g.normal_tex = Tex(am, aiTextureType_NORMALS, false);
    am->Get(AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0), g.normal_scale);
    aiColor3D em(0, 0, 0);
    am->Get(AI_MATKEY_COLOR_EMISSIVE, em);
    g.emissive = {em.r, em.g, em.b};
    g.emissive_tex = Tex(am, aiTextureType_EMISSIVE, true);
    g.occlusion_tex = Tex(am, aiTextureType_LIGHTMAP, false);
    am->Get(AI_MATKEY_GLTF_TEXTURE_STRENGTH(aiTextureType_LIGHTMAP, 0), g.occlusion_strength);
    aiString mode;
    if (am->Get(AI_MATKEY_GLTF_ALPHAMODE, mode) == AI_SUCCESS) {
      const std::string s = mode.C_Str();
      g.alpha_mode = s == "MASK" ? AlphaMode::kMask : s == "BLEND" ? AlphaMode::kBlend : AlphaMode::kOpaque;
      if (g.alpha_mode == AlphaMode::kBlend) {
        Refuse(path_, "material '" + m.name + "' has alphaMode BLEND, which aalab does not render yet (OPAQUE and MASK are supported)");
      }
    }
    m.alpha_cutoff = 0.5f;
    am->Get(AI_MATKEY_GLTF_ALPHACUTOFF, m.alpha_cutoff);
    int two = 0;  // glTF's default is single-sided (doubleSided false)
    g.double_sided = am->Get(AI_MATKEY_TWOSIDED, two) == AI_SUCCESS && two != 0;
    int model = 0;
    const bool unlit = am->Get(AI_MATKEY_SHADING_MODEL, model) == AI_SUCCESS && model == aiShadingMode_Unlit;
    m.shading = unlit ? Shading::kUnlit : Shading::kPbr;
    m.color = glm::vec3(g.base_factor);
    for (float v : {g.base_factor.x, g.base_factor.y, g.base_factor.z, g.base_factor.w, g.metallic, g.roughness,
                    g.emissive.x, g.emissive.y, g.emissive.z, m.alpha_cutoff, g.normal_scale, g.occlusion_strength}) {
      if (!std::isfinite(v) || v < -1e7f || v > 1e7f) Refuse(path_, "material '" + m.name + "' has a non-finite or huge factor");
    }
    m.gltf = g;
    return m;
  }

 private:
  TextureRef Tex(const aiMaterial* am, aiTextureType type, bool srgb) {
    TextureRef ref;
    if (am->GetTextureCount(type) == 0) return ref;
    aiString file;
    aiTextureMapMode modes[2] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
    if (am->GetTexture(type, 0, &file, nullptr, nullptr, nullptr, nullptr, modes) != AI_SUCCESS) return ref;
    int ms = aiTextureMapMode_Wrap, mt = aiTextureMapMode_Wrap;
    am->Get(AI_MATKEY_MAPPINGMODE_U(type, 0), ms);
    am->Get(AI_MATKEY_MAPPINGMODE_V(type, 0), mt);
    ref.wrap_s = ToWrap(ms);
    ref.wrap_t = ToWrap(mt);
    ref.image = Image(file.C_Str(), srgb);
    return ref;
  }

  int Image(const std::string& uri, bool srgb) {
    const std::string key = uri + (srgb ? "|srgb" : "|linear");
    if (auto it = cache_.find(key); it != cache_.end()) return it->second;
    MipLevel level;
    if (const aiTexture* t = sc_->GetEmbeddedTexture(uri.c_str())) {
      const std::string name = "'" + uri + "' embedded in '" + path_ + "'";
      if (t->mHeight != 0) Refuse(path_, "texture " + name + " is stored uncompressed, which aalab does not read");
      level = DecodeTextureImage(name, "", reinterpret_cast<const uint8_t*>(t->pcData), t->mWidth, t->achFormatHint, srgb);
    } else {
      const fs::path p = fs::path(path_).parent_path() / uri;
      std::error_code ec;
      if (!fs::is_regular_file(p, ec)) Refuse(path_, "image '" + p.string() + "' not found");
      NoteInputFile(p.string());  // an input of the run (harness/core/input_files.h)
      level = DecodeTextureImage("'" + p.string() + "'", p.string(), nullptr, 0, "", srgb);
    }
    const int index = static_cast<int>(out_.images.size());
    out_.images.push_back(std::make_shared<const MipChain>(BuildMipChain(std::move(level), uri)));
    cache_[key] = index;
    return index;
  }

  const std::string& path_;
  const aiScene* sc_;
  GltfContent& out_;
  std::map<std::string, int> cache_;
};

/// The primitive `mesh` placed by `world` as one triangle shape.
Shape MeshShape(const std::string& path, const aiMesh* mesh, const glm::mat4& world) {
  if (mesh->mPrimitiveTypes & (aiPrimitiveType_POINT | aiPrimitiveType_LINE)) {
    Refuse(path, "mesh '" + std::string(mesh->mName.C_Str()) + "' has points or lines (aalab renders triangles)");
  }
  Shape s;
  s.kind = ShapeKind::kTriangles;
  s.source = "gltf";
  const glm::mat3 lin(world);
  const glm::mat3 nrm = glm::transpose(glm::inverse(lin));
  const bool has_n = mesh->HasNormals(), has_uv = mesh->HasTextureCoords(0), has_t = mesh->HasTangentsAndBitangents();
  s.positions.resize(mesh->mNumVertices);
  s.uvs.resize(mesh->mNumVertices, glm::vec2(0.0f));
  if (has_n) s.normals.resize(mesh->mNumVertices);
  if (has_t && has_n) s.tangents.resize(mesh->mNumVertices);
  for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
    const aiVector3D& v = mesh->mVertices[i];
    const glm::vec3 p = glm::vec3(world * glm::vec4(v.x, v.y, v.z, 1.0f));
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(p[c]) || std::fabs(p[c]) > 1e8f) {
        Refuse(path, "mesh '" + std::string(mesh->mName.C_Str()) + "' vertex " + std::to_string(i) +
                         " has a NaN, infinite or out-of-range (|x| > 1e8) position");
      }
    }
    s.positions[i] = p;
    if (has_uv) {
      const glm::vec2 uv(mesh->mTextureCoords[0][i].x, mesh->mTextureCoords[0][i].y);
      if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) Refuse(path, "mesh '" + std::string(mesh->mName.C_Str()) + "' has a non-finite texture coordinate");
      s.uvs[i] = uv;
    }
    if (has_n) {
      const aiVector3D& n = mesh->mNormals[i];
      const glm::vec3 wn = nrm * glm::vec3(n.x, n.y, n.z);
      const float len = glm::length(wn);
      s.normals[i] = (len > 0.0f && std::isfinite(len)) ? wn / len : glm::vec3(0, 0, 1);
      if (!s.tangents.empty()) {
        const glm::vec3 t(mesh->mTangents[i].x, mesh->mTangents[i].y, mesh->mTangents[i].z);
        const glm::vec3 b(mesh->mBitangents[i].x, mesh->mBitangents[i].y, mesh->mBitangents[i].z);
        const float w = glm::dot(glm::cross(glm::vec3(n.x, n.y, n.z), t), b) < 0.0f ? -1.0f : 1.0f;
        const glm::vec3 wt = lin * t;
        const float tl = glm::length(wt);
        s.tangents[i] = glm::vec4((tl > 0.0f && std::isfinite(tl)) ? wt / tl : glm::vec3(1, 0, 0), w);
      }
    }
  }
  for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
    const aiFace& face = mesh->mFaces[f];
    if (face.mNumIndices != 3) continue;  // POINT/LINE were refused; nothing else remains
    glm::uvec3 tri(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
    for (int k = 0; k < 3; ++k) {
      if (tri[k] >= mesh->mNumVertices) {
        Refuse(path, "mesh '" + std::string(mesh->mName.C_Str()) + "' triangle " + std::to_string(f) + " has index " +
                         std::to_string(tri[k]) + " beyond its " + std::to_string(mesh->mNumVertices) + " vertices");
      }
    }
    s.triangles.push_back(tri);
  }
  return s;
}

}  // namespace

GltfContent LoadGltf(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw UserError("glTF file '" + path + "' not found");
  GltfContent out;
  std::vector<Camera> cams;
  CheckGltfJson(path, ParseGltfJson(path), cams);

  Assimp::Importer importer;
  const unsigned flags = aiProcess_Triangulate | aiProcess_CalcTangentSpace | aiProcess_ValidateDataStructure |
                         aiProcess_FlipUVs;  // Assimp stores v flipped; FlipUVs restores glTF's (0,0) = top-left
  const aiScene* sc = importer.ReadFile(path, flags);
  if (!sc || (sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !sc->mRootNode) {
    Refuse(path, std::string("Assimp could not read it: ") + importer.GetErrorString());
  }
  // Only the materials some primitive uses, in the order of their first use (Assimp adds a
  // default material that no primitive of a glTF file may use).
  MaterialReader mats(path, sc, out);
  std::map<unsigned, int> material_of;
  auto material_index = [&](unsigned ai) {
    if (ai >= sc->mNumMaterials) Refuse(path, "a mesh names material " + std::to_string(ai) + ", which does not exist");
    auto it = material_of.find(ai);
    if (it != material_of.end()) return it->second;
    const int k = static_cast<int>(out.materials.size());
    out.materials.push_back(mats.Read(ai));
    material_of[ai] = k;
    return k;
  };
  // Meshes in node order (depth first, children in file order): deterministic shape order.
  std::vector<const aiNode*> stack = {sc->mRootNode};
  while (!stack.empty()) {
    const aiNode* n = stack.back();
    stack.pop_back();
    const glm::mat4 world = NodeWorld(n);
    for (unsigned k = 0; k < n->mNumMeshes; ++k) {
      const aiMesh* mesh = sc->mMeshes[n->mMeshes[k]];
      if (mesh->mNumAnimMeshes > 0) Refuse(path, "mesh '" + std::string(mesh->mName.C_Str()) + "' has morph targets");
      Shape s = MeshShape(path, mesh, world);
      if (s.triangles.empty()) continue;
      s.material = material_index(mesh->mMaterialIndex);
      out.triangles += s.triangles.size();
      out.shapes.push_back(std::move(s));
    }
    for (unsigned c = n->mNumChildren; c-- > 0;) stack.push_back(n->mChildren[c]);
  }
  if (out.shapes.empty()) Refuse(path, "has no triangles in its scene");
  // Cameras: the projection from the JSON (CheckGltfJson), the placement from the node.
  for (unsigned i = 0; i < sc->mNumCameras && i < cams.size(); ++i) {
    const aiCamera* ac = sc->mCameras[i];
    const aiNode* node = sc->mRootNode->FindNode(ac->mName);
    const glm::mat4 world = node ? NodeWorld(node) : glm::mat4(1.0f);
    Camera& c = cams[i];
    c.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    const glm::vec3 fwd = glm::normalize(glm::mat3(world) * glm::vec3(0, 0, -1));  // glTF cameras look down −Z
    c.look_at = c.position + fwd;
    c.up = glm::normalize(glm::mat3(world) * glm::vec3(0, 1, 0));
  }
  out.cameras = cams;
  return out;
}

}  // namespace aalab
