// The reference render (RenderReference) against its definition, pixel by pixel: stratified
// positions from SampleJitter, every sample through DisplayLinearInline, double sums in sample
// order (all, strata with i + j even, odd), sRGB encode; the raw edge mask from the samples'
// surfaces and shadow bits. Its pixel-parallel resolve, its camera packets and its unlit
// shading path must give these exact bits. Also the batched procedural patterns against
// EvaluatePattern, and SampleFields::kShading against a full Trace.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/hash.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/scene.h"
#include "scenes/tracer.h"
#include "scenes/tracer_internal.h"

namespace aalab {
namespace {

constexpr uint64_t kStreamReference = 0x5265665374726174ULL;  // the reference's jitter stream ("RefStrat")

/// One pixel of the reference by its definition: its spp samples traced in one call (whole
/// 16-ray packets, as in the render's tiles when spp is a multiple of 16).
struct PixelTruth {
  float image[3], half_a[3], half_b[3];
  bool edge;
};

PixelTruth ReferencePixel(const Tracer& tracer, int width, int height, int grid, uint64_t seed, int x, int y,
                          TraceCounters* counters) {
  const int spp = grid * grid;
  std::vector<SamplePos> pos(static_cast<size_t>(spp));
  for (int j = 0; j < grid; ++j) {
    for (int i = 0; i < grid; ++i) {
      const int s = j * grid + i;
      const float j0 = SampleJitter(x, y, s, seed ^ kStreamReference, 0);
      const float j1 = SampleJitter(x, y, s, seed ^ kStreamReference, 1);
      pos[static_cast<size_t>(s)] = {static_cast<float>(x) + (static_cast<float>(i) + j0) / static_cast<float>(grid),
                                     static_cast<float>(y) + (static_cast<float>(j) + j1) / static_cast<float>(grid)};
    }
  }
  std::vector<SampleResult> res(static_cast<size_t>(spp));
  tracer.Trace(pos.data(), spp, width, height, res.data(), counters, TextureFootprint{0.0f, 1});
  double all[3] = {0, 0, 0}, a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
  PixelTruth t{};
  for (int j = 0; j < grid; ++j) {
    for (int i = 0; i < grid; ++i) {
      const SampleResult& r = res[static_cast<size_t>(j * grid + i)];
      float d[3];
      DisplayLinearInline(tracer.GetScene().display, r.rgb, d);
      for (int c = 0; c < 3; ++c) {
        all[c] += d[c];
        ((i + j) % 2 == 0 ? a : b)[c] += d[c];
      }
      t.edge = t.edge || r.surface != res[0].surface || r.shadowed != res[0].shadowed;
    }
  }
  for (int c = 0; c < 3; ++c) {
    t.image[c] = SrgbEncode(static_cast<float>(all[c] / spp));
    t.half_a[c] = SrgbEncode(static_cast<float>(a[c] / (spp / 2)));
    t.half_b[c] = SrgbEncode(static_cast<float>(b[c] / (spp / 2)));
  }
  return t;
}

/// Returns the number of edge pixels.
int ExpectReferenceMatchesDefinition(const std::string& name, int grid) {
  SCOPED_TRACE(name + " grid " + std::to_string(grid));
  const Scene scene = LoadScene(name);
  const Tracer tracer(scene);
  const int W = 13, H = 11;  // a full 8-wide tile and a 5-wide one, in both axes
  const uint64_t seed = 29;
  TraceCounters got_counters, want_counters;
  const Reference ref = RenderReference(tracer, W, H, grid, seed, &got_counters);
  int mismatches = 0, edges = 0;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const PixelTruth t = ReferencePixel(tracer, W, H, grid, seed, x, y, &want_counters);
      for (int c = 0; c < 3; ++c) {
        mismatches += ref.image.At(x, y, c) != t.image[c];
        mismatches += ref.half_a.At(x, y, c) != t.half_a[c];
        mismatches += ref.half_b.At(x, y, c) != t.half_b[c];
      }
      mismatches += ref.edge_mask_raw.At(x, y, 0) != (t.edge ? 1.0f : 0.0f);
      edges += t.edge;
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(got_counters.primary_rays, want_counters.primary_rays);
  EXPECT_EQ(got_counters.shadow_rays, want_counters.shadow_rays);
  EXPECT_EQ(got_counters.texture_lookups, want_counters.texture_lookups);
  EXPECT_EQ(got_counters.shading_evals, want_counters.shading_evals);
  return edges;
}

// Unlit + noise texture (orthographic), unlit + checker (perspective), Reinhard/ACES
// tonemapped edges, shadows (shadow bits in the edge mask), glTF cut-outs with shadows.
TEST(ReferenceResolve, MatchesItsDefinitionPixelByPixel) {
  for (const char* name : {"detail-texture", "checker-plane", "hdr-edges", "hard-hdr-extreme", "shadow-stipple"}) {
    ExpectReferenceMatchesDefinition(name, 4);
  }
  EXPECT_GT(ExpectReferenceMatchesDefinition("wedges", 8), 0);  // edge pixels: the edge test is exercised
  EXPECT_GT(ExpectReferenceMatchesDefinition("real-foliage", 4), 0);
}

TEST(ReferenceResolve, ShadingFieldsLeaveDistanceAndPointAlone) {
  const Scene scene = LoadScene("checker-plane");
  const Tracer tracer(scene);
  std::vector<SamplePos> pos;
  for (int k = 0; k < 37; ++k) pos.push_back({3.5f + 0.37f * k, 20.25f + 0.11f * k});  // a partial last packet
  std::vector<SampleResult> all(pos.size()), some(pos.size());
  for (SampleResult& r : some) {
    r.t = -7.0f;
    r.position[0] = r.position[1] = r.position[2] = -9.0f;
  }
  tracer.Trace(pos.data(), static_cast<int>(pos.size()), 64, 36, all.data(), nullptr);
  tracer.Trace(pos.data(), static_cast<int>(pos.size()), 64, 36, some.data(), nullptr, TextureFootprint{},
               SampleFields::kShading);
  int hits = 0;
  for (size_t k = 0; k < pos.size(); ++k) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(all[k].rgb[c], some[k].rgb[c]);
    EXPECT_EQ(all[k].surface, some[k].surface);
    EXPECT_EQ(all[k].shadowed, some[k].shadowed);
    EXPECT_EQ(some[k].t, -7.0f);
    EXPECT_EQ(some[k].position[1], -9.0f);
    hits += all[k].surface >= 0 && std::isfinite(all[k].t);
  }
  EXPECT_GT(hits, 0);
}

// The unlit scenes' fused path (Trace with SampleFields::kShading: each camera packet shaded in
// place, TraceCameraRaysUnlit) against the general path (SampleFields::kAll: org/dir/Hit arrays,
// ShadeUnlit): the same rgb, surface, shadow bits and counters, sample for sample. The scene has
// every kind of unlit hit: a noise sphere and a checker disk (curved shapes: uv from the packet's
// ray and hit), a stripes quad, a flat quad, two textured shapes of one material in a row, the
// background; the samples cover the frame in an order that mixes the shapes inside packets, with
// a partial last packet.
TEST(ReferenceResolve, UnlitPacketsShadedInPlaceEqualTheGeneralPath) {
  const std::string json = R"({"name": "unlit-mix", "effects": ["unlit", "textures"],
    "camera": {"type": "perspective", "position": [0, 0, 10], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_y": 50},
    "background": [0.1, 0.2, 0.3],
    "materials": {
      "noise": {"shading": "unlit", "texture": {"pattern": "noise", "scale": 9, "seed": 3,
                "color_a": [0.1, 0.7, 0.2], "color_b": [0.9, 0.1, 0.4]}},
      "check": {"shading": "unlit", "texture": {"pattern": "checker", "scale": 5,
                "color_a": [0.2, 0.2, 0.9], "color_b": [1.0, 0.8, 0.1]}},
      "stripe": {"shading": "unlit", "texture": {"pattern": "stripes", "scale": 4, "angle": 30, "duty": 0.3,
                 "color_a": [0.5, 0.0, 0.5], "color_b": [0.0, 0.9, 0.9]}},
      "flat": {"shading": "unlit", "color": [0.6, 0.5, 0.4]}},
    "objects": [
      {"shape": "sphere", "radius": 1.6, "material": "noise", "transform": {"translate": [-2.2, 0.8, 0]}},
      {"shape": "disk", "radius": 1.4, "material": "check", "transform": {"translate": [2.0, 1.0, 0.5]}},
      {"shape": "quad", "size": [3, 2], "material": "stripe", "transform": {"translate": [-1.5, -2.2, -1]}},
      {"shape": "quad", "size": [2.5, 1.5], "material": "flat", "transform": {"translate": [2.2, -2.0, 0]}},
      {"shape": "sphere", "radius": 0.5, "material": "check", "transform": {"translate": [0.2, 0.4, 1]}}]})";
  const Scene scene = ParseScene(json, "unlit-mix", ".");
  const Tracer tracer(scene);
  std::vector<SamplePos> pos;
  for (int k = 0; k < 997; ++k) {  // a scrambled walk over the 64 × 36 frame; 997 = 62 packets + 5
    pos.push_back({0.3f + static_cast<float>((k * 37) % 64) + 0.013f * static_cast<float>(k % 7),
                   0.2f + static_cast<float>((k * 11) % 36) + 0.017f * static_cast<float>(k % 5)});
  }
  std::vector<SampleResult> all(pos.size()), some(pos.size());
  TraceCounters c_all, c_some;
  tracer.Trace(pos.data(), static_cast<int>(pos.size()), 64, 36, all.data(), &c_all);
  tracer.Trace(pos.data(), static_cast<int>(pos.size()), 64, 36, some.data(), &c_some, TextureFootprint{0.0f, 1},
               SampleFields::kShading);
  int seen[6] = {0, 0, 0, 0, 0, 0};  // background, then shapes 0..4
  for (size_t k = 0; k < pos.size(); ++k) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(all[k].rgb[c], some[k].rgb[c]) << k;
    EXPECT_EQ(all[k].surface, some[k].surface) << k;
    EXPECT_EQ(all[k].shadowed, some[k].shadowed) << k;
    ++seen[all[k].surface + 1];
  }
  for (int s = 0; s < 6; ++s) EXPECT_GT(seen[s], 0) << "no sample sees surface " << s - 1;
  EXPECT_EQ(c_all.samples, c_some.samples);
  EXPECT_EQ(c_all.primary_rays, c_some.primary_rays);
  EXPECT_EQ(c_all.coverage_rays, c_some.coverage_rays);
  EXPECT_EQ(c_all.shading_evals, c_some.shading_evals);
  EXPECT_EQ(c_all.texture_lookups, c_some.texture_lookups);
  EXPECT_EQ(c_all.shadow_rays, c_some.shadow_rays);
  EXPECT_GT(c_all.texture_lookups, 0u);
}

// The packets of the reference's tiles (16 samples in one pixel) mostly hit one textured
// triangle; those lanes get their checker or noise colour in the packet, not queued
// (UnlitShading::TexturedTriangleLanes). Against the general path, sample for sample: quads of
// every pattern and a flat one filling a perspective frame (packets on one triangle, on a
// quad's two triangles, across two shapes, on the background), a partial last packet.
TEST(ReferenceResolve, UniformTexturedPacketsEqualTheGeneralPath) {
  const std::string json = R"({"name": "unlit-quads", "effects": ["unlit", "textures"],
    "camera": {"type": "perspective", "position": [0, 0, 10], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_y": 40},
    "background": [0.3, 0.1, 0.2],
    "materials": {
      "noise": {"shading": "unlit", "texture": {"pattern": "noise", "scale": 23, "seed": 11,
                "color_a": [0.1, 0.7, 0.2], "color_b": [0.9, 0.1, 0.4]}},
      "check": {"shading": "unlit", "texture": {"pattern": "checker", "scale": 7.5,
                "color_a": [0.2, 0.2, 0.9], "color_b": [1.0, 0.8, 0.1]}},
      "stripe": {"shading": "unlit", "texture": {"pattern": "stripes", "scale": 4, "angle": 30, "duty": 0.3,
                 "color_a": [0.5, 0.0, 0.5], "color_b": [0.0, 0.9, 0.9]}},
      "flat": {"shading": "unlit", "color": [0.6, 0.5, 0.4]}},
    "objects": [
      {"shape": "quad", "size": [3.5, 2.5], "material": "noise", "transform": {"translate": [-1.8, 1.3, 0]}},
      {"shape": "quad", "size": [3.5, 2.5], "material": "check", "transform": {"translate": [1.8, 1.3, 0],
       "rotate": [20, 10, 0]}},
      {"shape": "quad", "size": [3.5, 2.5], "material": "stripe", "transform": {"translate": [-1.8, -1.3, 0]}},
      {"shape": "quad", "size": [3.5, 2.0], "material": "flat", "transform": {"translate": [1.8, -1.3, 0]}}]})";
  const Scene scene = ParseScene(json, "unlit-quads", ".");
  const Tracer tracer(scene);
  const int W = 48, H = 27;
  std::vector<SamplePos> pos;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      for (int s = 0; s < 16; ++s) {  // one packet per pixel: a 4 × 4 grid, jittered
        pos.push_back({static_cast<float>(x) + (static_cast<float>(s % 4) + 0.31f + 0.02f * (s % 3)) / 4.0f,
                       static_cast<float>(y) + (static_cast<float>(s / 4) + 0.57f - 0.03f * (s % 5)) / 4.0f});
      }
    }
  }
  for (int k = 0; k < 7; ++k) pos.push_back({20.3f + 0.01f * k, 6.2f});  // a partial packet in the noise quad
  std::vector<SampleResult> all(pos.size()), some(pos.size());
  TraceCounters c_all, c_some;
  tracer.Trace(pos.data(), static_cast<int>(pos.size()), W, H, all.data(), &c_all);
  tracer.Trace(pos.data(), static_cast<int>(pos.size()), W, H, some.data(), &c_some, TextureFootprint{0.0f, 1},
               SampleFields::kShading);
  int seen[5] = {0, 0, 0, 0, 0};  // background, then shapes 0..3
  for (size_t k = 0; k < pos.size(); ++k) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(std::memcmp(&all[k].rgb[c], &some[k].rgb[c], sizeof(float)), 0) << k;
    EXPECT_EQ(all[k].surface, some[k].surface) << k;
    EXPECT_EQ(all[k].shadowed, some[k].shadowed) << k;
    ++seen[all[k].surface + 1];
  }
  for (int s = 0; s < 5; ++s) EXPECT_GT(seen[s], 0) << "no sample sees surface " << s - 1;
  EXPECT_EQ(c_all.shading_evals, c_some.shading_evals);
  EXPECT_EQ(c_all.texture_lookups, c_some.texture_lookups);
  EXPECT_EQ(c_all.primary_rays, c_some.primary_rays);
}

TEST(ReferenceResolve, PatternBatchEqualsEvaluatePattern) {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<glm::vec2> uv;
  for (int k = 0; k < 200; ++k) uv.push_back({-3.7f + 0.0731f * k, 5.3f - 0.0457f * k});
  for (float v : {0.0f, -0.0f, 1e7f, -1e7f, 3e9f, -3e9f, 1e30f, inf, -inf, std::nanf(""), -0.3f, 8388607.5f,
                  -8388607.5f, 16777217.0f, -9.223372e18f, 9.223372e18f, -9.3e18f, 9.3e18f, -2.5e9f}) {
    uv.push_back({v, 0.25f});
    uv.push_back({0.25f, v});
    uv.push_back({v, v});
  }
  for (TexturePattern p : {TexturePattern::kChecker, TexturePattern::kNoise, TexturePattern::kStripes}) {
    Texture tex;
    tex.pattern = p;
    tex.scale = 7.5f;
    tex.seed = 12345;
    tex.angle_deg = 30.0f;
    tex.duty = 0.4f;
    std::vector<float> t(uv.size());
    tracer_detail::EvaluatePatternBatch(tex, uv.data(), static_cast<int>(uv.size()), t.data());
    // EvaluatePatternLanes (the packets' path: 8 lanes at a time, then a tail), from split arrays.
    std::vector<float> xs, ys, tl(uv.size());
    for (const glm::vec2& q : uv) xs.push_back(q.x), ys.push_back(q.y);
    tracer_detail::EvaluatePatternLanes(tex, xs.data(), ys.data(), static_cast<int>(uv.size()), tl.data());
    int zeros = 0, ones = 0;
    for (size_t k = 0; k < uv.size(); ++k) {
      const float want = EvaluatePattern(tex, uv[k]);
      EXPECT_EQ(std::memcmp(&t[k], &want, sizeof want), 0)
          << "pattern " << static_cast<int>(p) << " uv " << uv[k].x << ", " << uv[k].y;
      EXPECT_EQ(std::memcmp(&tl[k], &want, sizeof want), 0)
          << "lanes, pattern " << static_cast<int>(p) << " uv " << uv[k].x << ", " << uv[k].y;
      zeros += want == 0.0f;
      ones += want == 1.0f;
    }
    if (p != TexturePattern::kNoise) {
      EXPECT_TRUE(zeros > 0 && ones > 0);
    }
  }
}

// SurfaceAt's normals against their definition (FillSurface before it skipped the second
// normalisation): ng = h.ng / |h.ng| where 0 < |h.ng| < ∞, else −dir; n = the interpolated
// vertex normal (or h.ng without vertex normals) normalised the same way with ng as its
// fallback; each flipped to face the ray. Hits built by hand on every kind of shape, one
// triangle mesh with vertex normals, with normals that are ordinary, unnormalised, huge
// (|ng| overflows), tiny (|ng| underflows to 0), zero, infinite and NaN, facing and not.
glm::vec3 SafeNormalizeDefinition(glm::vec3 v, glm::vec3 fallback) {
  const float len = std::sqrt((v.x * v.x + v.y * v.y) + v.z * v.z);
  return (len > 0.0f && std::isfinite(len)) ? glm::vec3(v.x / len, v.y / len, v.z / len) : fallback;
}

glm::vec3 FacingDefinition(glm::vec3 v, glm::vec3 dir) {
  return (v.x * dir.x + v.y * dir.y) + v.z * dir.z > 0.0f ? -v : v;
}

bool SameBits(glm::vec3 a, glm::vec3 b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(ReferenceResolve, SurfaceNormalsMatchTheirDefinition) {
  Scene scene = ParseScene(
      R"({"name": "shapes", "effects": ["lambert"], "camera": {"type": "perspective", "position": [0, 0, 10], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_y": 50},
    "materials": {"a": {"shading": "lambert", "color": [0.5, 0.5, 0.5]}},
    "light_units": "gltf", "lights": [{"type": "directional", "direction": [0, -1, 0]}],
    "objects": [
      {"shape": "box", "size": [1, 2, 3], "material": "a"},
      {"shape": "sphere", "radius": 1.5, "material": "a"},
      {"shape": "disk", "radius": 1.0, "material": "a", "transform": {"rotate": [20, 30, 0]}},
      {"shape": "capsule", "from": [0, 0, 0], "to": [1, 1, 0], "radius": 0.2, "material": "a"}]})",
      "shapes", ".");
  Shape smooth = scene.shapes[0];  // the box's triangles with vertex normals of their own
  ASSERT_EQ(smooth.kind, ShapeKind::kTriangles);
  for (size_t k = 0; k < smooth.positions.size(); ++k) {
    const glm::vec3 p = smooth.positions[k];
    smooth.normals.push_back(glm::vec3(p.x + 0.3f * static_cast<float>(k % 3), p.y - 0.1f, p.z * 2.0f));
  }
  ASSERT_GE(smooth.normals.size(), 8u);
  for (int k = 0; k < 4; ++k) smooth.normals[static_cast<size_t>(k)] = glm::vec3(0.0f);  // n vanishes: ng's fallback
  for (int k = 4; k < 8; ++k)
    smooth.normals[static_cast<size_t>(k)] = glm::vec3(std::numeric_limits<float>::infinity(), 0, 0);
  scene.shapes.push_back(smooth);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  const glm::vec3 ngs[] = {
      {0, 0, 1},   {0.3f, -0.4f, 0.87f}, {-2, 5, 0.5f},      {3e37f, 2e38f, -1e38f},    {1e-30f, 2e-30f, 0}, {0, 0, 0},
      {inf, 0, 0}, {nan, 1, 0},          {-0.0f, -0.0f, -1}, {1e-20f, -3e-20f, 1e-20f}, {0.6f, 0, -0.8f}};
  const glm::vec3 dirs[] = {glm::normalize(glm::vec3(0.1f, -0.2f, -1)), glm::normalize(glm::vec3(-0.3f, 0.5f, 1)),
                            glm::vec3(1, 0, 0)};
  int with_vertex_normals = 0;
  for (int shape = 0; shape < static_cast<int>(scene.shapes.size()); ++shape) {
    const Shape& s = scene.shapes[static_cast<size_t>(shape)];
    const unsigned prims = s.kind == ShapeKind::kTriangles ? static_cast<unsigned>(s.triangles.size()) : 1u;
    for (unsigned prim = 0; prim < prims; ++prim) {
      for (const glm::vec3 ng : ngs) {
        for (const glm::vec3 dir : dirs) {
          tracer_detail::Hit h;
          h.t = 2.5f;
          h.shape = shape;
          h.prim = prim;
          h.u = 0.25f;
          h.v = 0.125f + 0.5f * static_cast<float>(prim % 2);
          h.ng = ng;
          const glm::vec3 org(0.5f, 1.0f, 6.0f);
          const tracer_detail::Surface got = tracer_detail::SurfaceAt(scene, h, org, dir, false, true);
          glm::vec3 n = ng;
          if (!s.normals.empty()) {
            const glm::uvec3 tri = s.triangles[prim];
            const float w = 1.0f - h.u - h.v;
            n = s.normals[tri.x] * w + s.normals[tri.y] * h.u + s.normals[tri.z] * h.v;
            ++with_vertex_normals;
          }
          const glm::vec3 ng_unit = SafeNormalizeDefinition(ng, -dir);
          const glm::vec3 n_unit = SafeNormalizeDefinition(n, ng_unit);
          EXPECT_TRUE(SameBits(got.ng, FacingDefinition(ng_unit, dir))) << shape << " " << prim;
          EXPECT_TRUE(SameBits(got.n, FacingDefinition(n_unit, dir))) << shape << " " << prim;
        }
      }
    }
  }
  EXPECT_GT(with_vertex_normals, 0);
}

}  // namespace
}  // namespace aalab
