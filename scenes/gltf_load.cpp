// glTF 2.0 scenes (scenes/gltf_load.h), built from the file as written (scenes/gltf_doc.h).
// Order: the document and every byte range are checked (ReadGltfDoc); the node graph
// (indices, one parent each, no cycles, depth, walked with an explicit stack); meshes into
// shapes (indices against their vertices, finite positions); materials; cameras; and only
// then the textures: every header read and the budget summed before the first decode, so a
// refusal never waits on texture decoding.
//
// Static pose (glTF 2.0 §3.7, §3.8): nodes' own TRS or matrix; a skinned mesh's vertices
// by Σ wᵢ · world(jointᵢ) · inverseBindMatrixᵢ (the node transforms as stored, i.e. the pose
// the file is in with no animation playing); morph targets at node.weights, else
// mesh.weights, else 0. Animations are not sampled.
#include "scenes/gltf_load.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include <glm/gtc/quaternion.hpp>

#include "core/error.h"
#include "scenes/gltf_lights.h"

namespace aalab {
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

/// A node's local transform (matrix, or T · R · S), in double.
glm::dmat4 LocalMatrix(const GltfDoc& d, const Json& n, const std::string& at) {
  if (n.contains("matrix")) {
    const std::vector<double> m = GltfNumbers(d, n, "matrix", at, 16, {});
    glm::dmat4 r;
    for (int c = 0; c < 4; ++c) {
      for (int k = 0; k < 4; ++k) r[c][k] = m[static_cast<size_t>(c * 4 + k)];  // column-major, as glTF stores it
    }
    return r;
  }
  const std::vector<double> t = GltfNumbers(d, n, "translation", at, 3, {0, 0, 0});
  const std::vector<double> q = GltfNumbers(d, n, "rotation", at, 4, {0, 0, 0, 1});
  const std::vector<double> s = GltfNumbers(d, n, "scale", at, 3, {1, 1, 1});
  glm::dquat rot(q[3], q[0], q[1], q[2]);  // glTF stores x, y, z, w
  const double len = glm::length(rot);
  rot = len > 0.0 ? rot / len : glm::dquat(1, 0, 0, 0);
  glm::dmat4 m = glm::mat4_cast(rot);
  for (int c = 0; c < 3; ++c) m[c] *= s[static_cast<size_t>(c)];
  m[3] = glm::dvec4(t[0], t[1], t[2], 1.0);
  return m;
}

/// World matrices of every node reachable from the scene's roots, and the order to visit
/// them (depth first, children in file order). Checks the graph without recursion.
struct NodeGraph {
  std::vector<glm::dmat4> world;
  std::vector<char> reached;
  std::vector<size_t> order;
};

NodeGraph WalkNodes(const GltfDoc& d) {
  const Json& nodes = GltfArray(d, d.j, "nodes", "");
  const size_t n = nodes.size();
  std::vector<long long> parent(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const std::string at = GltfAt("/nodes", i);
    if (!nodes[i].is_object()) d.Fail(at, "must be an object");
    const Json& ch = GltfArray(d, nodes[i], "children", at);
    for (size_t k = 0; k < ch.size(); ++k) {
      if (!ch[k].is_number_integer() || ch[k].get<long long>() < 0 ||
          ch[k].get<long long>() >= static_cast<long long>(n)) {
        d.Fail(GltfAt(GltfAt(at, "children"), k),
               "names node " + ch[k].dump() + ", which does not exist (rule: index out of range)");
      }
      const size_t c = ch[k].get<size_t>();
      if (c == i) d.Fail(GltfAt(GltfAt(at, "children"), k), "a node is its own child (rule: recursive nodes)");
      if (parent[c] >= 0) {
        d.Fail(GltfAt(GltfAt(at, "children"), k),
               "node " + std::to_string(c) + " already has parent " + std::to_string(parent[c]) +
                   " (rule: a node has one parent; shared or recursive nodes are invalid)");
      }
      parent[c] = static_cast<long long>(i);
    }
  }
  // A cycle: following parents from a node never reaches a root. Walk each chain once.
  std::vector<char> state(n, 0);  // 0 unvisited, 1 on the current chain, 2 known to reach a root
  for (size_t i = 0; i < n; ++i) {
    std::vector<size_t> chain;
    size_t c = i;
    while (state[c] == 0) {
      state[c] = 1;
      chain.push_back(c);
      if (parent[c] < 0) break;
      c = static_cast<size_t>(parent[c]);
    }
    // Stopped on a node of this same chain that has a parent: the chain closed on itself.
    if (state[c] == 1 && parent[c] >= 0) d.Fail(GltfAt("/nodes", c), "is its own ancestor (rule: recursive nodes)");
    for (size_t k : chain) state[k] = 2;
  }
  // Roots: the scene's nodes (`scene`, else scene 0), else every parentless node.
  std::vector<size_t> roots;
  const Json& scenes = GltfArray(d, d.j, "scenes", "");
  if (!scenes.empty()) {
    const long long si = d.j.contains("scene") ? GltfIndex(d, d.j, "scene", "", "scenes") : 0;
    const std::string at = GltfAt("/scenes", static_cast<size_t>(si));
    if (!scenes[static_cast<size_t>(si)].is_object()) d.Fail(at, "must be an object");
    const Json& sn = GltfArray(d, scenes[static_cast<size_t>(si)], "nodes", at);
    for (size_t k = 0; k < sn.size(); ++k) {
      if (!sn[k].is_number_integer() || sn[k].get<long long>() < 0 ||
          sn[k].get<long long>() >= static_cast<long long>(n)) {
        d.Fail(GltfAt(GltfAt(at, "nodes"), k),
               "names node " + sn[k].dump() + ", which does not exist (rule: index out of range)");
      }
      const size_t r = sn[k].get<size_t>();
      if (parent[r] >= 0)
        d.Fail(GltfAt(GltfAt(at, "nodes"), k),
               "node " + std::to_string(r) + " is not a root (it has parent " + std::to_string(parent[r]) + ")");
      roots.push_back(r);
    }
  } else {
    for (size_t i = 0; i < n; ++i) {
      if (parent[i] < 0) roots.push_back(i);
    }
  }
  NodeGraph g;
  g.world.assign(n, glm::dmat4(1.0));
  g.reached.assign(n, 0);
  std::vector<size_t> stack(roots.rbegin(), roots.rend());
  std::vector<int> depth(n, 0);
  while (!stack.empty()) {
    const size_t i = stack.back();
    stack.pop_back();
    if (g.reached[i]) d.Fail(GltfAt("/nodes", i), "is reached twice from the scene (rule: a node has one parent)");
    g.reached[i] = 1;
    if (parent[i] >= 0) depth[i] = depth[static_cast<size_t>(parent[i])] + 1;
    if (depth[i] > kMaxGltfNodeDepth)
      d.Fail(GltfAt("/nodes", i), "lies " + std::to_string(depth[i]) + " nodes deep (rule: node depth, at most " +
                                      std::to_string(kMaxGltfNodeDepth) + ")");
    const glm::dmat4 local = LocalMatrix(d, nodes[i], GltfAt("/nodes", i));
    g.world[i] = parent[i] >= 0 ? g.world[static_cast<size_t>(parent[i])] * local : local;
    g.order.push_back(i);
    const Json& ch = GltfArray(d, nodes[i], "children", "");
    for (size_t k = ch.size(); k-- > 0;) stack.push_back(ch[k].get<size_t>());
  }
  return g;
}

/// The vertex streams of primitive `pr` (plain accessors or Draco).
GltfPrimData ReadPrimitive(const GltfDoc& d, const Json& pr, const std::string& at, std::vector<std::string>& notes) {
  static const std::map<std::string, int> kComps = {{"POSITION", 3},   {"NORMAL", 3},     {"TANGENT", 4},
                                                    {"TEXCOORD_0", 2}, {"TEXCOORD_1", 2}, {"JOINTS_0", 4},
                                                    {"WEIGHTS_0", 4}};
  GltfPrimData p;
  if (!pr.contains("attributes") || !pr["attributes"].is_object())
    d.Fail(GltfAt(at, "attributes"), "is required (an object)");
  const Json& attrs = pr["attributes"];
  if (!attrs.contains("POSITION")) d.Fail(GltfAt(at, "attributes"), "has no POSITION");
  const bool draco = pr.contains("extensions") && pr["extensions"].is_object() &&
                     pr["extensions"].contains("KHR_draco_mesh_compression");
  if (draco) {
    DecodeGltfDraco(d, pr["extensions"]["KHR_draco_mesh_compression"],
                    GltfAt(at, "extensions/KHR_draco_mesh_compression"), kComps, p);
  }
  for (const auto& [name, comps] : kComps) {
    if (!attrs.contains(name) || p.attr.count(name)) continue;
    const long long a = GltfIndex(d, attrs, name.c_str(), GltfAt(at, "attributes"), "accessors");
    if (name == "JOINTS_0") {
      const std::vector<uint32_t> u = ReadGltfUints(d, a, GltfAt(GltfAt(at, "attributes"), name), 4);
      p.attr[name].assign(u.begin(), u.end());
    } else {
      p.attr[name] = ReadGltfFloats(d, a, GltfAt(GltfAt(at, "attributes"), name), comps);
    }
  }
  p.vertices = static_cast<long long>(p.attr["POSITION"].size() / 3);
  for (const auto& [name, v] : p.attr) {
    if (static_cast<long long>(v.size()) != p.vertices * kComps.at(name)) {
      d.Fail(GltfAt(GltfAt(at, "attributes"), name), "has " + std::to_string(v.size() / kComps.at(name)) +
                                                         " elements but POSITION has " + std::to_string(p.vertices) +
                                                         " (rule: attribute counts must match)");
    }
  }
  if (attrs.contains("COLOR_0")) notes.push_back(at + ": vertex colours (COLOR_0) are not drawn");
  if (!draco && pr.contains("indices")) {
    const long long a = GltfIndex(d, pr, "indices", at, "accessors");
    p.indices = ReadGltfUints(d, a, GltfAt(at, "indices"), 1);
    p.has_indices = true;
  }
  return p;
}

/// Applies morph targets at `weights` to POSITION, NORMAL and TANGENT (xyz).
void ApplyMorph(const GltfDoc& d, const Json& pr, const std::string& at, const std::vector<double>& weights,
                GltfPrimData& p) {
  const Json& targets = GltfArray(d, pr, "targets", at);
  for (size_t t = 0; t < targets.size() && t < weights.size(); ++t) {
    if (weights[t] == 0.0) continue;
    const std::string tat = GltfAt(GltfAt(at, "targets"), t);
    for (const char* name : {"POSITION", "NORMAL", "TANGENT"}) {
      if (!targets[t].is_object() || !targets[t].contains(name) || !p.attr.count(name)) continue;
      const std::vector<float> delta =
          ReadGltfFloats(d, GltfIndex(d, targets[t], name, tat, "accessors"), GltfAt(tat, name), 3);
      std::vector<float>& v = p.attr[name];
      const int comps = std::string(name) == "TANGENT" ? 4 : 3;
      if (static_cast<long long>(delta.size() / 3) != p.vertices)
        d.Fail(GltfAt(tat, name), "count differs from POSITION's (rule: attribute counts must match)");
      for (long long i = 0; i < p.vertices; ++i) {
        for (int c = 0; c < 3; ++c)
          v[static_cast<size_t>(i * comps + c)] +=
              static_cast<float>(weights[t]) * delta[static_cast<size_t>(i * 3 + c)];
      }
    }
  }
}

glm::vec3 V3(const std::vector<float>& v, size_t i) { return {v[i * 3], v[i * 3 + 1], v[i * 3 + 2]}; }

/// One primitive placed by `world` (or skinned by `joints`) as one triangle shape.
Shape BuildShape(const GltfDoc& d, const GltfPrimData& p, const std::string& at, long long mode,
                 const glm::dmat4& world, const std::vector<glm::dmat4>* joints) {
  Shape s;
  s.kind = ShapeKind::kTriangles;
  s.source = "gltf";
  const size_t nv = static_cast<size_t>(p.vertices);
  const auto& pos = p.attr.at("POSITION");
  const bool has_n = p.attr.count("NORMAL") > 0, has_t = has_n && p.attr.count("TANGENT") > 0;
  s.positions.resize(nv);
  s.uvs.assign(nv, glm::vec2(0.0f));
  if (p.attr.count("TEXCOORD_1")) s.uvs1.resize(nv);
  if (has_n) s.normals.resize(nv);
  if (has_t) s.tangents.resize(nv);
  for (size_t i = 0; i < nv; ++i) {
    glm::dmat4 m = world;
    if (joints) {
      const auto& jn = p.attr.at("JOINTS_0");
      const auto& wt = p.attr.at("WEIGHTS_0");
      m = glm::dmat4(0.0);
      for (int k = 0; k < 4; ++k) {
        const size_t j = static_cast<size_t>(jn[i * 4 + k]);
        const double w = wt[i * 4 + k];
        if (w == 0.0) continue;
        if (j >= joints->size())
          d.Fail(GltfAt(at, "attributes/JOINTS_0"), "vertex " + std::to_string(i) + " names joint " +
                                                        std::to_string(j) + " beyond the skin's " +
                                                        std::to_string(joints->size()) + " (rule: index out of range)");
        m += (*joints)[j] * w;
      }
    }
    const glm::dmat3 lin(m);
    const glm::dvec3 q = glm::dvec3(m * glm::dvec4(glm::dvec3(V3(pos, i)), 1.0));
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(q[c]) || std::fabs(q[c]) > 1e8) {
        d.Fail(GltfAt(at, "attributes/POSITION"),
               "vertex " + std::to_string(i) + " has a NaN, infinite or out-of-range (|x| > 1e8) position");
      }
    }
    s.positions[i] = glm::vec3(q);
    if (p.attr.count("TEXCOORD_0")) {
      const auto& uv = p.attr.at("TEXCOORD_0");
      s.uvs[i] = {uv[i * 2], uv[i * 2 + 1]};
      if (!std::isfinite(s.uvs[i].x) || !std::isfinite(s.uvs[i].y))
        d.Fail(GltfAt(at, "attributes/TEXCOORD_0"), "has a non-finite texture coordinate");
    }
    if (!s.uvs1.empty()) {
      const auto& uv = p.attr.at("TEXCOORD_1");
      s.uvs1[i] = {uv[i * 2], uv[i * 2 + 1]};
      if (!std::isfinite(s.uvs1[i].x) || !std::isfinite(s.uvs1[i].y))
        d.Fail(GltfAt(at, "attributes/TEXCOORD_1"), "has a non-finite texture coordinate");
    }
    if (has_n) {
      const glm::dmat3 nrm = glm::transpose(glm::inverse(lin));
      const glm::vec3 wn = glm::vec3(nrm * glm::dvec3(V3(p.attr.at("NORMAL"), i)));
      const float len = glm::length(wn);
      s.normals[i] = (len > 0.0f && std::isfinite(len)) ? wn / len : glm::vec3(0, 0, 1);
      if (has_t) {
        const auto& t = p.attr.at("TANGENT");
        const glm::vec3 wt = glm::vec3(lin * glm::dvec3(t[i * 4], t[i * 4 + 1], t[i * 4 + 2]));
        const float tl = glm::length(wt);
        s.tangents[i] = glm::vec4((tl > 0.0f && std::isfinite(tl)) ? wt / tl : glm::vec3(1, 0, 0),
                                  t[i * 4 + 3] < 0.0f ? -1.0f : 1.0f);
      }
    }
  }
  std::vector<uint32_t> idx = p.indices;
  if (!p.has_indices) {
    idx.resize(nv);
    for (size_t i = 0; i < nv; ++i) idx[i] = static_cast<uint32_t>(i);
  }
  for (size_t k = 0; k < idx.size(); ++k) {
    if (idx[k] >= nv) {
      d.Fail(GltfAt(at, "indices"), "element " + std::to_string(k) + " is index " + std::to_string(idx[k]) +
                                        ", beyond the primitive's " + std::to_string(nv) +
                                        " vertices (rule: index out of range)");
    }
  }
  if (mode == 4) {
    for (size_t k = 0; k + 2 < idx.size(); k += 3) s.triangles.emplace_back(idx[k], idx[k + 1], idx[k + 2]);
  } else if (mode == 5) {  // strip: the winding alternates (glTF 2.0 §3.7.2.1)
    for (size_t k = 0; k + 2 < idx.size(); ++k) {
      s.triangles.push_back(k % 2 == 0 ? glm::uvec3(idx[k], idx[k + 1], idx[k + 2])
                                       : glm::uvec3(idx[k + 1], idx[k], idx[k + 2]));
    }
  } else {  // fan
    for (size_t k = 1; k + 1 < idx.size(); ++k) s.triangles.emplace_back(idx[k], idx[k + 1], idx[0]);
  }
  return s;
}

/// glTF sampler wrap enums to WrapMode.
WrapMode ToWrap(long long mode) {
  return mode == 33071 ? WrapMode::kClampToEdge : mode == 33648 ? WrapMode::kMirroredRepeat : WrapMode::kRepeat;
}

/// Reads materials and collects the images they use (decoded later, in LoadGltf).
class MaterialReader {
 public:
  explicit MaterialReader(const GltfDoc& d) : d_(d) {}

  Material Read(long long index) {
    Material m;
    GltfMaterial g;
    m.name = fs::path(d_.path).filename().string() + "#" + (index < 0 ? std::string("default") : std::to_string(index));
    m.shading = Shading::kPbr;
    m.alpha_cutoff = 0.5f;
    g.double_sided = false;
    if (index >= 0) {
      const Json& mat = d_.j["materials"][static_cast<size_t>(index)];
      const std::string at = GltfAt("/materials", static_cast<size_t>(index));
      if (!mat.is_object()) d_.Fail(at, "must be an object");
      if (mat.contains("name") && mat["name"].is_string() && !mat["name"].get<std::string>().empty())
        m.name += ":" + mat["name"].get<std::string>();
      for (const char* k : {"pbrMetallicRoughness", "normalTexture", "occlusionTexture", "emissiveTexture"}) {
        if (mat.contains(k) && !mat[k].is_object()) d_.Fail(GltfAt(at, k), "must be an object");
      }
      if (mat.contains("pbrMetallicRoughness")) {
        const Json& pbr = mat["pbrMetallicRoughness"];
        const std::string pat = GltfAt(at, "pbrMetallicRoughness");
        const std::vector<double> b = GltfNumbers(d_, pbr, "baseColorFactor", pat, 4, {1, 1, 1, 1});
        g.base_factor = glm::vec4(b[0], b[1], b[2], b[3]);
        g.metallic = static_cast<float>(GltfNum(d_, pbr, "metallicFactor", pat, 1.0, 0.0, 1.0));
        g.roughness = static_cast<float>(GltfNum(d_, pbr, "roughnessFactor", pat, 1.0, 0.0, 1.0));
        g.base_tex = Tex(pbr, "baseColorTexture", pat, true);
        g.mr_tex = Tex(pbr, "metallicRoughnessTexture", pat, false);
      }
      g.normal_tex = Tex(mat, "normalTexture", at, false);
      if (g.normal_tex.Has())
        g.normal_scale =
            static_cast<float>(GltfNum(d_, mat["normalTexture"], "scale", GltfAt(at, "normalTexture"), 1.0, -1e7, 1e7));
      g.occlusion_tex = Tex(mat, "occlusionTexture", at, false);
      if (g.occlusion_tex.Has())
        g.occlusion_strength = static_cast<float>(
            GltfNum(d_, mat["occlusionTexture"], "strength", GltfAt(at, "occlusionTexture"), 1.0, 0.0, 1.0));
      g.emissive_tex = Tex(mat, "emissiveTexture", at, true);
      const std::vector<double> e = GltfNumbers(d_, mat, "emissiveFactor", at, 3, {0, 0, 0});
      double strength = 1.0;
      if (mat.contains("extensions") && mat["extensions"].is_object()) {
        const Json& x = mat["extensions"];
        if (x.contains("KHR_materials_unlit")) m.shading = Shading::kUnlit;
        if (x.contains("KHR_materials_emissive_strength")) {
          strength = GltfNum(d_, x["KHR_materials_emissive_strength"], "emissiveStrength",
                             GltfAt(at, "extensions/KHR_materials_emissive_strength"), 1.0, 0.0, 1e7);
        }
      }
      g.emissive = glm::vec3(glm::dvec3(e[0], e[1], e[2]) * strength);
      const std::string mode =
          mat.contains("alphaMode") && mat["alphaMode"].is_string() ? mat["alphaMode"].get<std::string>() : "OPAQUE";
      if (mode != "OPAQUE" && mode != "MASK" && mode != "BLEND")
        d_.Fail(GltfAt(at, "alphaMode"), "'" + mode + "' (allowed: OPAQUE, MASK, BLEND)");
      g.alpha_mode = mode == "MASK" ? AlphaMode::kMask : mode == "BLEND" ? AlphaMode::kBlend : AlphaMode::kOpaque;
      m.alpha_cutoff = static_cast<float>(GltfNum(d_, mat, "alphaCutoff", at, 0.5, 0.0, 1e7));
      if (mat.contains("doubleSided")) {
        if (!mat["doubleSided"].is_boolean()) d_.Fail(GltfAt(at, "doubleSided"), "must be a boolean");
        g.double_sided = mat["doubleSided"].get<bool>();
      }
      for (float v : {g.base_factor.x, g.base_factor.y, g.base_factor.z, g.base_factor.w, g.emissive.x, g.emissive.y,
                      g.emissive.z}) {
        if (!std::isfinite(v) || v < -1e7f || v > 1e7f) d_.Fail(at, "has a non-finite or huge factor");
      }
    }
    m.color = glm::vec3(g.base_factor);
    m.gltf = g;
    return m;
  }

  /// The images to decode: (texture's image index, sRGB) → content image index.
  const std::map<std::pair<long long, bool>, int>& Images() const { return images_; }

 private:
  TextureRef Tex(const Json& parent, const char* key, const std::string& at, bool srgb) {
    TextureRef ref;
    if (!parent.contains(key)) return ref;
    const Json& info = parent[key];
    const std::string iat = GltfAt(at, key);
    if (!info.is_object()) d_.Fail(iat, "must be an object (a textureInfo)");
    const long long tex = GltfIndex(d_, info, "index", iat, "textures");
    if (tex < 0) d_.Fail(GltfAt(iat, "index"), "is required");
    ref.texcoord = static_cast<int>(GltfInt(d_, info, "texCoord", iat, 0, 0, 1 << 20));
    if (info.contains("extensions") && info["extensions"].is_object() &&
        info["extensions"].contains("KHR_texture_transform")) {
      const Json& x = info["extensions"]["KHR_texture_transform"];
      const std::string xat = GltfAt(iat, "extensions/KHR_texture_transform");
      const std::vector<double> off = GltfNumbers(d_, x, "offset", xat, 2, {0, 0});
      const std::vector<double> sc = GltfNumbers(d_, x, "scale", xat, 2, {1, 1});
      const double r = GltfNum(d_, x, "rotation", xat, 0.0, -1e7, 1e7);
      ref.texcoord = static_cast<int>(GltfInt(d_, x, "texCoord", xat, ref.texcoord, 0, 1 << 20));
      // uv' = T · R · S · uv with R = [[cos r, sin r], [−sin r, cos r]] (rows), as the
      // Khronos sample viewer and three.js apply it (counter-clockwise in the image, v down).
      const double c = std::cos(r), s = std::sin(r);
      ref.uv_transform =
          glm::mat3x2(glm::vec2(c * sc[0], -s * sc[0]), glm::vec2(s * sc[1], c * sc[1]), glm::vec2(off[0], off[1]));
      ref.transformed = true;
    }
    if (ref.texcoord > 1)
      d_.Fail(GltfAt(iat, "texCoord"), "TEXCOORD_" + std::to_string(ref.texcoord) + " (aalab reads sets 0 and 1)");
    const Json& t = d_.j["textures"][static_cast<size_t>(tex)];
    const std::string tat = GltfAt("/textures", static_cast<size_t>(tex));
    const long long source = GltfIndex(d_, t, "source", tat, "images");
    if (source < 0) d_.Fail(tat, "has no source image that aalab can read (a PNG or JPEG 'source')");
    const long long sampler = GltfIndex(d_, t, "sampler", tat, "samplers");
    if (sampler >= 0) {
      const Json& sm = d_.j["samplers"][static_cast<size_t>(sampler)];
      const std::string sat = GltfAt("/samplers", static_cast<size_t>(sampler));
      const long long mag = GltfInt(d_, sm, "magFilter", sat, 9729, 9728, 9729);
      const long long min = GltfInt(d_, sm, "minFilter", sat, 9987, 9728, 9987);
      if (min > 9729 && min < 9984)
        d_.Fail(GltfAt(sat, "minFilter"), std::to_string(min) + " (allowed: 9728, 9729, 9984, 9985, 9986, 9987)");
      ref.filter = SamplerFilterOf(static_cast<int>(mag), static_cast<int>(min));
      for (const char* w : {"wrapS", "wrapT"}) {
        const long long v = GltfInt(d_, sm, w, sat, 10497, 10497, 33648);
        if (v != 10497 && v != 33071 && v != 33648)
          d_.Fail(GltfAt(sat, w), std::to_string(v) + " (allowed: 10497, 33071, 33648)");
        (std::string(w) == "wrapS" ? ref.wrap_s : ref.wrap_t) = ToWrap(v);
      }
    }
    const auto image_key = std::make_pair(source, srgb);
    auto it = images_.find(image_key);
    if (it == images_.end()) it = images_.emplace(image_key, static_cast<int>(images_.size())).first;
    ref.image = it->second;
    return ref;
  }

  const GltfDoc& d_;
  std::map<std::pair<long long, bool>, int> images_;
};

std::string JoinList(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

}  // namespace

GltfContent LoadGltf(const std::string& path, const GltfLoadOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw UserError("glTF file '" + path + "' not found");
  const GltfDoc d = ReadGltfDoc(path);
  GltfContent out;
  if (!d.ignored_extensions.empty()) {
    out.notes.push_back("extensions used but not drawn (ignored, as glTF allows): " + JoinList(d.ignored_extensions));
  }
  for (const char* part : {"animations", "skins"}) {
    if (!GltfArray(d, d.j, part, "").empty()) {
      out.notes.push_back(std::string("has ") + part +
                          ": drawn at the static pose (nodes' own transforms; no animation sampled)");
    }
  }
  const NodeGraph graph = WalkNodes(d);
  const Json& nodes = GltfArray(d, d.j, "nodes", "");
  const Json& meshes = GltfArray(d, d.j, "meshes", "");
  MaterialReader mats(d);
  std::map<long long, int> material_of;  // file material (-1: default) -> content index, first use order
  bool morphed = false, skipped = false;
  for (size_t ni : graph.order) {
    const Json& node = nodes[ni];
    const std::string nat = GltfAt("/nodes", ni);
    const long long mi = GltfIndex(d, node, "mesh", nat, "meshes");
    if (mi < 0) continue;
    const std::string mat_at = GltfAt("/meshes", static_cast<size_t>(mi));
    const Json& mesh = meshes[static_cast<size_t>(mi)];
    if (!mesh.is_object()) d.Fail(mat_at, "must be an object");
    // Skin: each joint's world matrix times its inverse bind matrix.
    std::vector<glm::dmat4> joints;
    const long long ski = GltfIndex(d, node, "skin", nat, "skins");
    if (ski >= 0) {
      const Json& skin = d.j["skins"][static_cast<size_t>(ski)];
      const std::string sat = GltfAt("/skins", static_cast<size_t>(ski));
      const Json& js = GltfArray(d, skin, "joints", sat);
      std::vector<float> ibm;
      const long long ia = GltfIndex(d, skin, "inverseBindMatrices", sat, "accessors");
      if (ia >= 0) ibm = ReadGltfFloats(d, ia, GltfAt(sat, "inverseBindMatrices"), 16);
      if (!ibm.empty() && ibm.size() / 16 < js.size())
        d.Fail(GltfAt(sat, "inverseBindMatrices"), "has fewer matrices than the skin has joints");
      for (size_t k = 0; k < js.size(); ++k) {
        if (!js[k].is_number_integer() || js[k].get<long long>() < 0 || js[k].get<size_t>() >= nodes.size()) {
          d.Fail(GltfAt(GltfAt(sat, "joints"), k),
                 "names node " + js[k].dump() + ", which does not exist (rule: index out of range)");
        }
        glm::dmat4 b(1.0);
        for (int c = 0; c < 16 && !ibm.empty(); ++c) b[c / 4][c % 4] = ibm[k * 16 + static_cast<size_t>(c)];
        joints.push_back(graph.world[js[k].get<size_t>()] * b);
      }
    }
    std::vector<double> weights =
        GltfNumbers(d, mesh, "weights", mat_at, GltfArray(d, mesh, "weights", mat_at).size(), {});
    if (node.contains("weights"))
      weights = GltfNumbers(d, node, "weights", nat, GltfArray(d, node, "weights", nat).size(), {});
    const Json& prims = GltfArray(d, mesh, "primitives", mat_at);
    for (size_t pi = 0; pi < prims.size(); ++pi) {
      const Json& pr = prims[pi];
      const std::string at = GltfAt(GltfAt(mat_at, "primitives"), pi);
      if (!pr.is_object()) d.Fail(at, "must be an object");
      const long long mode = GltfInt(d, pr, "mode", at, 4, 0, 6);
      if (mode < 4) {
        skipped = true;
        continue;
      }
      GltfPrimData p = ReadPrimitive(d, pr, at, out.notes);
      if (pr.contains("targets")) {
        morphed = true;
        ApplyMorph(d, pr, at, weights, p);
      }
      const bool skinned = !joints.empty() && p.attr.count("JOINTS_0") && p.attr.count("WEIGHTS_0");
      Shape s = BuildShape(d, p, at, mode, graph.world[ni], skinned ? &joints : nullptr);
      if (s.triangles.empty()) continue;
      const long long fm = GltfIndex(d, pr, "material", at, "materials");
      auto it = material_of.find(fm);
      if (it == material_of.end()) {
        it = material_of.emplace(fm, static_cast<int>(out.materials.size())).first;
        out.materials.push_back(mats.Read(fm));
      }
      s.material = it->second;
      out.triangles += s.triangles.size();
      out.shapes.push_back(std::move(s));
    }
  }
  if (morphed) out.notes.push_back("has morph targets: drawn at the default weights (node.weights, else mesh.weights)");
  if (skipped) out.notes.push_back("points and lines primitives are not drawn (aalab renders triangles)");
  if (out.shapes.empty()) d.Fail("/scenes", "the scene has no triangles to draw");
  // A material sampling TEXCOORD_1 on a primitive without it samples (0, 0), as a GPU reading
  // an unbound attribute would; name it instead.
  for (const Shape& s : out.shapes) {
    const GltfMaterial& g = *out.materials[static_cast<size_t>(s.material)].gltf;
    for (const TextureRef* t : {&g.base_tex, &g.mr_tex, &g.normal_tex, &g.emissive_tex, &g.occlusion_tex}) {
      if (t->Has() && t->texcoord == 1 && s.uvs1.empty()) {
        d.Fail("/materials", "material '" + out.materials[static_cast<size_t>(s.material)].name +
                                 "' samples TEXCOORD_1 on a primitive that has none");
      }
    }
  }
  out.bounds_min = glm::vec3(std::numeric_limits<float>::max());
  out.bounds_max = glm::vec3(-std::numeric_limits<float>::max());
  for (const Shape& s : out.shapes) {
    for (const glm::uvec3& t : s.triangles) {
      for (int k = 0; k < 3; ++k) {
        out.bounds_min = glm::min(out.bounds_min, s.positions[t[k]]);
        out.bounds_max = glm::max(out.bounds_max, s.positions[t[k]]);
      }
    }
  }
  // Cameras: projection from the JSON, placement from the node (glTF cameras look down −Z).
  const Json& cams = GltfArray(d, d.j, "cameras", "");
  for (size_t ni : graph.order) {
    const long long ci = GltfIndex(d, nodes[ni], "camera", GltfAt("/nodes", ni), "cameras");
    if (ci < 0) continue;
    const Json& cj = cams[static_cast<size_t>(ci)];
    const std::string at = GltfAt("/cameras", static_cast<size_t>(ci));
    Camera cam;
    const std::string type = cj.contains("type") && cj["type"].is_string() ? cj["type"].get<std::string>() : "";
    if (type == "perspective" && cj.contains("perspective")) {
      cam.type = CameraType::kPerspective;
      cam.fov_y_deg = static_cast<float>(
          GltfNum(d, cj["perspective"], "yfov", GltfAt(at, "perspective"), -1.0, 1e-6, 3.12) * 57.29577951308232);
      if (!(cam.fov_y_deg > 0.0f)) d.Fail(GltfAt(at, "perspective/yfov"), "is required (radians in (0, 3.12))");
    } else if (type == "orthographic" && cj.contains("orthographic")) {
      cam.type = CameraType::kOrthographic;
      cam.height =
          static_cast<float>(2.0 * GltfNum(d, cj["orthographic"], "ymag", GltfAt(at, "orthographic"), -1.0, -1e9, 1e9));
      if (!(cam.height != 0.0f)) d.Fail(GltfAt(at, "orthographic/ymag"), "is required (non-zero)");
      cam.height = std::fabs(cam.height);
    } else {
      d.Fail(at, "is neither a perspective (yfov) nor an orthographic (ymag) camera");
    }
    const glm::dmat4& w = graph.world[ni];
    cam.position = glm::vec3(w * glm::dvec4(0, 0, 0, 1));
    cam.look_at = cam.position + glm::vec3(glm::normalize(glm::dmat3(w) * glm::dvec3(0, 0, -1)));
    cam.up = glm::vec3(glm::normalize(glm::dmat3(w) * glm::dvec3(0, 1, 0)));
    out.cameras.push_back(cam);
  }
  // KHR_lights_punctual from this same parsed document (scenes/gltf_lights.h), checked before
  // any texture is decoded; AddGltfObject (scene_parse.cpp) places them by the object.
  try {
    out.lights = GltfPunctualLights(d.j);
  } catch (const nlohmann::json::exception& e) {
    throw UserError(std::string("KHR_lights_punctual: malformed node or light (") + e.what() + ")");
  }

  // Textures: every header and the budget first, then the decodes (scenes/gltf_images.cpp).
  std::vector<std::pair<long long, bool>> wanted(mats.Images().size());
  for (const auto& [key, idx] : mats.Images()) wanted[static_cast<size_t>(idx)] = key;
  gltf_detail::ReadGltfImages(d, wanted, options.decode_images, out);
  const Json& buffers = GltfArray(d, d.j, "buffers", "");
  for (size_t i = 0; i < buffers.size(); ++i) {
    const Json& b = buffers[i];
    if (b.is_object() && b.contains("uri") && b["uri"].is_string() &&
        b["uri"].get<std::string>().rfind("data:", 0) != 0) {
      out.files_read.push_back(GltfUriFile(d, b["uri"].get<std::string>(), GltfAt(GltfAt("/buffers", i), "uri")));
    }
  }
  out.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace aalab
