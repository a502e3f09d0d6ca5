// The same model written four ways — plain floats, KHR_mesh_quantization (int16 positions
// under a node scale, normalized uint16 texture coordinates), EXT_meshopt_compression
// (meshoptimizer's encoder) and KHR_draco_mesh_compression (draco's encoder, lossless
// sequential) — loads to the same triangles and renders the same picture, bit for bit.
// And BLEND: a half-transparent surface over an opaque one over the background, against
// the over-composite worked out by hand.
#include <gtest/gtest.h>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/color.h"
#include "io/image_io.h"
#include "scenes/gltf_load.h"
#include "scenes/render.h"
#include "scenes/scene.h"
#include "scenes/tracer.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::json;

/// This file's scratch folder, made on first use.
const fs::path& Dir() {
  static const fs::path kDir = testenv::ScratchDir("gltf-variants");
  return kDir;
}

/// A bumpy 6 × 6 grid of quads on integer sixteenths (positions q/16, q an int16), uvs
/// k/65535 (exact for normalized uint16), shared vertices, 72 triangles.
struct Grid {
  static constexpr int kN = 6;
  std::vector<int16_t> q;    // xyz per vertex, in sixteenths
  std::vector<uint16_t> uq;  // uv per vertex, in 1/65535
  std::vector<uint32_t> idx;
  Grid() {
    for (int j = 0; j <= kN; ++j) {
      for (int i = 0; i <= kN; ++i) {
        q.push_back(static_cast<int16_t>(i * 16 - 48));
        q.push_back(static_cast<int16_t>(j * 16 - 48));
        q.push_back(static_cast<int16_t>(((i * 7 + j * 3) % 5) * 3));
        uq.push_back(static_cast<uint16_t>(i * 65535 / kN));
        uq.push_back(static_cast<uint16_t>(65535 - j * 65535 / kN));
      }
    }
    for (int j = 0; j < kN; ++j) {
      for (int i = 0; i < kN; ++i) {
        const uint32_t a = static_cast<uint32_t>(j * (kN + 1) + i);
        idx.insert(idx.end(), {a, a + 1, a + kN + 2, a, a + kN + 2, a + kN + 1});
      }
    }
  }
  size_t Vertices() const { return q.size() / 3; }
  std::vector<float> Positions() const {
    std::vector<float> p;
    for (int16_t v : q) p.push_back(static_cast<float>(v) / 16.0f);
    return p;
  }
  std::vector<float> Uvs() const {  // as the loader maps normalized uint16: v / 65535.0f
    std::vector<float> p;
    for (uint16_t v : uq) p.push_back(static_cast<float>(v) / 65535.0f);
    return p;
  }
};

template <typename T>
std::string Bytes(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

std::string Pad4(std::string s) {
  while (s.size() % 4) s.push_back('\0');
  return s;
}

/// A glTF document with the common parts (an unlit textured material, one node, the
/// checker texture `tex.png`) and the given mesh, buffer views and accessors.
Json Doc(const Json& prim, const Json& views, const Json& accessors, size_t bin_len, const std::string& bin_name,
         const Json& node_extra = Json::object()) {
  Json d = {{"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", {0}}}}},
            {"meshes", {{{"primitives", {prim}}}}},
            {"materials",
             {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
               {"extensions", {{"KHR_materials_unlit", Json::object()}}}}}},
            {"textures", {{{"source", 0}, {"sampler", 0}}}},
            {"samplers", {{{"magFilter", 9728}, {"minFilter", 9728}}}},
            {"images", {{{"uri", "tex.png"}}}},
            {"bufferViews", views},
            {"accessors", accessors},
            {"buffers", {{{"byteLength", bin_len}, {"uri", bin_name}}}},
            {"extensionsUsed", {"KHR_materials_unlit"}}};
  Json node = {{"mesh", 0}};
  for (auto it = node_extra.begin(); it != node_extra.end(); ++it) node[it.key()] = it.value();
  d["nodes"] = {node};
  return d;
}

fs::path Write(const std::string& name, Json doc, const std::string& bin) {
  std::ofstream(Dir() / (name + ".bin"), std::ios::binary) << bin;
  std::ofstream(Dir() / (name + ".gltf")) << doc.dump();
  return Dir() / (name + ".gltf");
}

fs::path Plain(const Grid& g) {
  const std::string p = Bytes(g.Positions()), u = Bytes(g.Uvs()), i = Bytes(g.idx);
  const Json views = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", p.size()}},
                      {{"buffer", 0}, {"byteOffset", p.size()}, {"byteLength", u.size()}},
                      {{"buffer", 0}, {"byteOffset", p.size() + u.size()}, {"byteLength", i.size()}}};
  const Json acc = {{{"bufferView", 0}, {"componentType", 5126}, {"count", g.Vertices()}, {"type", "VEC3"}},
                    {{"bufferView", 1}, {"componentType", 5126}, {"count", g.Vertices()}, {"type", "VEC2"}},
                    {{"bufferView", 2}, {"componentType", 5125}, {"count", g.idx.size()}, {"type", "SCALAR"}}};
  const Json prim = {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}};
  return Write("plain", Doc(prim, views, acc, p.size() + u.size() + i.size(), "plain.bin"), p + u + i);
}

fs::path Quantized(const Grid& g) {
  // int16 xyz padded to 8 bytes a vertex (stride 8: attribute rows are 4-byte aligned).
  std::vector<int16_t> q4;
  for (size_t v = 0; v < g.Vertices(); ++v) q4.insert(q4.end(), {g.q[v * 3], g.q[v * 3 + 1], g.q[v * 3 + 2], 0});
  const std::string p = Bytes(q4), u = Bytes(g.uq), i = Bytes(g.idx);
  const Json views = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", p.size()}, {"byteStride", 8}},
                      {{"buffer", 0}, {"byteOffset", p.size()}, {"byteLength", u.size()}},
                      {{"buffer", 0}, {"byteOffset", p.size() + u.size()}, {"byteLength", i.size()}}};
  const Json acc = {
      {{"bufferView", 0}, {"componentType", 5122}, {"count", g.Vertices()}, {"type", "VEC3"}},
      {{"bufferView", 1}, {"componentType", 5123}, {"normalized", true}, {"count", g.Vertices()}, {"type", "VEC2"}},
      {{"bufferView", 2}, {"componentType", 5125}, {"count", g.idx.size()}, {"type", "SCALAR"}}};
  const Json prim = {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}};
  Json d = Doc(prim, views, acc, p.size() + u.size() + i.size(), "quant.bin", {{"scale", {0.0625, 0.0625, 0.0625}}});
  d["extensionsUsed"].push_back("KHR_mesh_quantization");
  d["extensionsRequired"] = {"KHR_mesh_quantization"};
  return Write("quant", d, p + u + i);
}

fs::path Meshopt(const Grid& g) {
  const std::vector<float> pos = g.Positions(), uv = g.Uvs();
  auto encode_vb = [](const std::vector<float>& v, size_t n, size_t stride) {
    std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(n, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), v.data(), n, stride));
    return std::string(out.begin(), out.end());
  };
  // Each compressed stream keeps its exact length (the decoder checks it); padding to 4
  // bytes goes between them.
  const std::string p0 = encode_vb(pos, g.Vertices(), 12), u0 = encode_vb(uv, g.Vertices(), 8);
  std::vector<unsigned char> ib(meshopt_encodeIndexBufferBound(g.idx.size(), g.Vertices()));
  ib.resize(meshopt_encodeIndexBuffer(ib.data(), ib.size(), g.idx.data(), g.idx.size()));
  const std::string i0(ib.begin(), ib.end());
  const std::string p = Pad4(p0), u = Pad4(u0), i = Pad4(i0);
  auto view = [](size_t off, size_t len, size_t raw_len, size_t stride, size_t count, const char* mode, bool vertex) {
    Json v = {{"buffer", 1},
              {"byteLength", raw_len},
              {"extensions",
               {{"EXT_meshopt_compression",
                 {{"buffer", 0},
                  {"byteOffset", off},
                  {"byteLength", len},
                  {"byteStride", stride},
                  {"count", count},
                  {"mode", mode}}}}}};
    if (vertex) v["byteStride"] = stride;
    return v;
  };
  const Json views = {view(0, p0.size(), pos.size() * 4, 12, g.Vertices(), "ATTRIBUTES", true),
                      view(p.size(), u0.size(), uv.size() * 4, 8, g.Vertices(), "ATTRIBUTES", true),
                      view(p.size() + u.size(), i0.size(), g.idx.size() * 4, 4, g.idx.size(), "TRIANGLES", false)};
  const Json acc = {{{"bufferView", 0}, {"componentType", 5126}, {"count", g.Vertices()}, {"type", "VEC3"}},
                    {{"bufferView", 1}, {"componentType", 5126}, {"count", g.Vertices()}, {"type", "VEC2"}},
                    {{"bufferView", 2}, {"componentType", 5125}, {"count", g.idx.size()}, {"type", "SCALAR"}}};
  const Json prim = {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}};
  Json d = Doc(prim, views, acc, p.size() + u.size() + i.size(), "meshopt.bin");
  // The fallback buffer the views point at: declared, never read.
  d["buffers"].push_back({{"byteLength", (pos.size() + uv.size() + g.idx.size()) * 4},
                          {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
  d["extensionsUsed"].push_back("EXT_meshopt_compression");
  d["extensionsRequired"] = {"EXT_meshopt_compression"};
  return Write("meshopt", d, p + u + i);
}

fs::path Draco(const Grid& g) {
  const std::vector<float> pos = g.Positions(), uv = g.Uvs();
  const int nf = static_cast<int>(g.idx.size() / 3);
  draco::TriangleSoupMeshBuilder b;
  b.Start(nf);
  const int pa = b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int ta = b.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  for (int f = 0; f < nf; ++f) {
    const uint32_t* t = &g.idx[static_cast<size_t>(f) * 3];
    b.SetAttributeValuesForFace(pa, draco::FaceIndex(f), &pos[t[0] * 3], &pos[t[1] * 3], &pos[t[2] * 3]);
    b.SetAttributeValuesForFace(ta, draco::FaceIndex(f), &uv[t[0] * 2], &uv[t[1] * 2], &uv[t[2] * 2]);
  }
  std::unique_ptr<draco::Mesh> mesh = b.Finalize();
  draco::Encoder enc;
  enc.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);  // keeps the triangle order; floats lossless
  draco::EncoderBuffer buf;
  EXPECT_TRUE(enc.EncodeMeshToBuffer(*mesh, &buf).ok());
  const std::string bytes = Pad4(std::string(buf.data(), buf.size()));
  const Json views = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", buf.size()}}};
  const size_t np = mesh->num_points();
  const Json acc = {{{"componentType", 5126}, {"count", np}, {"type", "VEC3"}},
                    {{"componentType", 5126}, {"count", np}, {"type", "VEC2"}},
                    {{"componentType", 5125}, {"count", g.idx.size()}, {"type", "SCALAR"}}};
  const Json prim = {
      {"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}},
      {"indices", 2},
      {"material", 0},
      {"extensions",
       {{"KHR_draco_mesh_compression",
         {{"bufferView", 0},
          {"attributes",
           {{"POSITION", mesh->attribute(pa)->unique_id()}, {"TEXCOORD_0", mesh->attribute(ta)->unique_id()}}}}}}}};
  Json d = Doc(prim, views, acc, bytes.size(), "draco.bin");
  d["extensionsUsed"].push_back("KHR_draco_mesh_compression");
  d["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  return Write("draco", d, bytes);
}

Image8 RenderModel(const fs::path& model) {
  const Json scene = {
      {"name", "variant"},
      {"effects", {"unlit", "textures"}},
      {"camera", {{"type", "perspective"}, {"position", {0.3, -0.4, 9}}, {"look_at", {0, 0, 0}}, {"fov_y", 40}}},
      {"materials", Json::object()},
      {"objects", {{{"shape", "gltf"}, {"file", model.filename().string()}}}}};
  const Scene sc = ParseScene(scene.dump(), "variant", Dir().string());
  Tracer tracer(sc);
  RenderSpec spec;
  return RenderFrame(tracer, 96, 64, spec, 1, nullptr);
}

TEST(GltfVariants, QuantizedMeshoptDracoGiveThePlainPicture) {
  // An 8 × 8 checker of distinct greys, point-sampled (NEAREST): any uv error shows.
  Image8 tex(8, 8, 4, 255);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      for (int c = 0; c < 3; ++c) tex.At(x, y, c) = static_cast<uint8_t>(((x + y) % 2) * 160 + x * 8 + y * 3 + c * 20);
    }
  }
  WriteImage8((Dir() / "tex.png").string(), tex);
  const Grid g;
  const fs::path plain = Plain(g);
  const GltfContent base = LoadGltf(plain.string());
  ASSERT_EQ(base.triangles, 72u);
  const Image8 want = RenderModel(plain);
  int lit = 0;
  for (int y = 0; y < want.Height(); ++y) {
    for (int x = 0; x < want.Width(); ++x) lit += want.At(x, y, 0) != 0;
  }
  EXPECT_GT(lit, 96 * 64 / 4);  // the grid fills a good part of the frame
  for (const fs::path& p : {Quantized(g), Meshopt(g), Draco(g)}) {
    const GltfContent v = LoadGltf(p.string());
    ASSERT_EQ(v.triangles, base.triangles) << p;
    // The same triangles in the same order at the same positions and uvs (draco: per-corner,
    // so compared through the triangles; meshopt's index codec may rotate a triangle's
    // corners, keeping its winding).
    const Shape& s0 = base.shapes[0];
    const Shape& s1 = v.shapes[0];
    for (size_t t = 0; t < s0.triangles.size(); ++t) {
      bool same = false;
      for (int r = 0; r < 3 && !same; ++r) {
        same = true;
        for (int k = 0; k < 3; ++k) {
          const uint32_t a = s0.triangles[t][k], b = s1.triangles[t][(k + r) % 3];
          same = same && s0.positions[a] == s1.positions[b] && s0.uvs[a] == s1.uvs[b];
        }
      }
      EXPECT_TRUE(same) << p << " triangle " << t;
    }
    EXPECT_TRUE(RenderModel(p) == want) << p << ": a different picture";
  }
}

TEST(GltfBlend, HalfTransparentOverOpaqueOverBackgroundIsTheHandOverComposite) {
  // Two unlit quads facing +z: at z = 1 a BLEND red (1, 0, 0) with alpha 0.25 covering the
  // whole frame's left half, at z = 0 an opaque blue (0, 0, 1) covering the top half; the
  // background is green (0, 1, 0). In linear light: top-left 0.25·red + 0.75·blue; bottom-left
  // 0.25·red + 0.75·green; top-right blue; bottom-right green.
  std::vector<float> pos = {-10, -10, 1, 0,  -10, 1, 0,  10, 1, -10, 10, 1,   // left half, z = 1
                            -10, 0,   0, 10, 0,   0, 10, 10, 0, -10, 10, 0};  // top half, z = 0
  std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
  const std::string p = Bytes(pos), i = Bytes(idx);
  const Json views = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                      {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
                      {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 24}}};
  const Json acc = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                    {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                    {{"bufferView", 2}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}};
  Json d = {{"asset", {{"version", "2.0"}}},
            {"scenes", {{{"nodes", {0, 1}}}}},
            {"nodes", {{{"mesh", 0}}, {{"mesh", 1}}}},
            {"meshes",
             {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 2}, {"material", 0}}}}},
              {{"primitives", {{{"attributes", {{"POSITION", 1}}}, {"indices", 2}, {"material", 1}}}}}}},
            {"materials",
             {{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 0.25}}}},
               {"alphaMode", "BLEND"},
               {"extensions", {{"KHR_materials_unlit", Json::object()}}}},
              {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 1, 1}}}},
               {"extensions", {{"KHR_materials_unlit", Json::object()}}}}}},
            {"bufferViews", views},
            {"accessors", acc},
            {"buffers", {{{"byteLength", 120}, {"uri", "blend.bin"}}}},
            {"extensionsUsed", {"KHR_materials_unlit"}}};
  const fs::path model = Write("blend", d, p + i);
  const Json scene = {
      {"name", "blend"},
      {"effects", {"unlit", "alpha_blend"}},
      {"camera", {{"type", "orthographic"}, {"position", {0, 0, 5}}, {"look_at", {0, 0, 0}}, {"height", 4}}},
      {"background", {0, 1, 0}},
      {"materials", Json::object()},
      {"objects", {{{"shape", "gltf"}, {"file", "blend.gltf"}}}}};
  const Scene sc = ParseScene(scene.dump(), "blend", Dir().string());
  Tracer tracer(sc);
  const ImageF img = RenderFrameLinear(tracer, 8, 8, RenderSpec{}, 1, nullptr);
  auto px = [&](int x, int y) { return glm::vec3(img.At(x, y, 0), img.At(x, y, 1), img.At(x, y, 2)); };
  const float a = 0.25f;
  EXPECT_NEAR(glm::length(px(1, 1) - glm::vec3(a, 0, 1 - a)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(px(1, 6) - glm::vec3(a, 1 - a, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(px(6, 1) - glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(px(6, 6) - glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
  // MSAA: the blended surface gives coverage by geometry only (no alpha-to-coverage), and
  // its samples composite the same way.
  RenderSpec msaa;
  msaa.msaa.samples = 4;
  const ImageF m = RenderFrameLinear(tracer, 8, 8, msaa, 1, nullptr);
  EXPECT_NEAR(glm::length(glm::vec3(m.At(1, 1, 0), m.At(1, 1, 1), m.At(1, 1, 2)) - glm::vec3(a, 0, 1 - a)), 0.0f,
              1e-6f);
}

}  // namespace
}  // namespace aalab
