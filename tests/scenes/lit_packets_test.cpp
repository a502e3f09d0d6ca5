// The lit camera packets (Trace with SampleFields::kShading in a lambert scene without
// textures, specular, glTF or an environment: TraceCameraRaysLit, each lane shaded from
// Embree's packet, the shadow rays packed straight into RTCRay16) against the general path
// (SampleFields::kAll: org/dir/Hit/Surface arrays, ShadowRays + OccludedRays, ShadeHits):
// the same rgb bits, surface, shadow bits and counters, sample for sample.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "scenes/library.h"
#include "scenes/scene.h"
#include "scenes/tracer.h"

namespace aalab {
namespace {

/// What a comparison saw, so a test can check its scene reached every branch.
struct Seen {
  int background = 0, hits = 0, shadowed[4] = {0, 0, 0, 0}, partly = 0;
  uint64_t shadow_rays = 0;
};

/// Both paths over `pos`: every field the shading path writes, bit for bit, and the counters.
Seen ExpectLitPacketsEqualGeneralPath(const Scene& scene, const std::vector<SamplePos>& pos, int w, int h) {
  const Tracer tracer(scene);
  std::vector<SampleResult> all(pos.size()), some(pos.size());
  TraceCounters c_all, c_some;
  tracer.Trace(pos.data(), static_cast<int>(pos.size()), w, h, all.data(), &c_all);
  tracer.Trace(pos.data(), static_cast<int>(pos.size()), w, h, some.data(), &c_some, TextureFootprint{0.0f, 1},
               SampleFields::kShading);
  Seen seen;
  int bad = 0;
  for (size_t k = 0; k < pos.size(); ++k) {
    bool same = std::memcmp(all[k].rgb, some[k].rgb, sizeof(all[k].rgb)) == 0;
    same = same && all[k].surface == some[k].surface && all[k].shadowed == some[k].shadowed;
    if (!same && ++bad <= 5) {
      ADD_FAILURE() << "sample " << k << ": rgb " << all[k].rgb[0] << " " << all[k].rgb[1] << " " << all[k].rgb[2]
                    << " vs " << some[k].rgb[0] << " " << some[k].rgb[1] << " " << some[k].rgb[2] << ", surface "
                    << all[k].surface << " vs " << some[k].surface << ", shadowed " << all[k].shadowed << " vs "
                    << some[k].shadowed;
    }
    seen.background += all[k].surface < 0;
    seen.hits += all[k].surface >= 0;
    for (int l = 0; l < 4; ++l) seen.shadowed[l] += (all[k].shadowed >> l) & 1u;
    seen.partly += all[k].shadowed != 0 && all[k].shadowed != 3u;
  }
  EXPECT_EQ(bad, 0);
  EXPECT_EQ(c_all.samples, c_some.samples);
  EXPECT_EQ(c_all.primary_rays, c_some.primary_rays);
  EXPECT_EQ(c_all.coverage_rays, c_some.coverage_rays);
  EXPECT_EQ(c_all.shadow_rays, c_some.shadow_rays);
  EXPECT_EQ(c_all.shading_evals, c_some.shading_evals);
  EXPECT_EQ(c_all.texture_lookups, c_some.texture_lookups);
  seen.shadow_rays = c_all.shadow_rays;
  return seen;
}

/// A scrambled walk over the w × h frame (shapes mixed inside packets, shadow packets that
/// straddle camera packets), with a partial last packet.
std::vector<SamplePos> ScrambledWalk(int w, int h, int n) {
  std::vector<SamplePos> pos;
  for (int k = 0; k < n; ++k) {
    pos.push_back({0.3f + static_cast<float>((k * 37) % w) + 0.013f * static_cast<float>(k % 7),
                   0.2f + static_cast<float>((k * 11) % h) + 0.017f * static_cast<float>(k % 5)});
  }
  return pos;
}

/// The reference's order: one 16-sample packet per pixel, row by row, then a partial packet.
std::vector<SamplePos> PixelPackets(int w, int h) {
  std::vector<SamplePos> pos;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int s = 0; s < 16; ++s) {
        pos.push_back({static_cast<float>(x) + (static_cast<float>(s % 4) + 0.31f + 0.02f * (s % 3)) / 4.0f,
                       static_cast<float>(y) + (static_cast<float>(s / 4) + 0.57f - 0.03f * (s % 5)) / 4.0f});
      }
    }
  }
  for (int k = 0; k < 9; ++k) pos.push_back({10.3f + 0.11f * k, 20.2f});
  return pos;
}

// Lights of each kind in one scene: a directional and a point light casting shadows (bits 0
// and 1), a spot and a ranged point light without; a lit ground, boxes, a sphere (grazing rays at
// its rim), a disk seen from the back, a wall the point light sits behind, an unlit quad, the
// background. Re-summed samples lose one light or two. Then the same scene with only the
// directional, the point and a second unshadowed point light (packets on one lambert shape take
// LitShading::ShadeUniformPacket's lanes there; with a spot or a ranged light they do not).
TEST(LitPackets, EqualTheGeneralPath) {
  std::string json = R"({"name": "lit-mix", "effects": ["lambert", "shadows", "unlit"], "light_units": "gltf",
    "camera": {"type": "perspective", "position": [0, 3, 9], "look_at": [0, 0.5, 0], "up": [0, 1, 0], "fov_y": 60},
    "background": [0.1, 0.2, 0.3], "ambient": [0.05, 0.06, 0.07],
    "materials": {
      "ground": {"shading": "lambert", "color": [0.8, 0.7, 0.6]},
      "grey": {"shading": "lambert", "color": [0.4, 0.45, 0.5]},
      "glow": {"shading": "unlit", "color": [0.9, 0.2, 0.1]}},
    "lights": [
      {"type": "directional", "direction": [0.3, -1, -0.2], "color": [1, 0.9, 0.8], "intensity": 2.0, "shadows": true},
      {"type": "point", "position": [-2.5, 2.5, 1.5], "color": [0.6, 0.7, 1.0], "intensity": 20, "shadows": true},
      {"type": "spot", "position": [2, 4, 2], "direction": [-0.3, -1, -0.3], "inner_cone_deg": 10,
       "outer_cone_deg": 30, "intensity": 30},
      {"type": "point", "position": [1.5, 0.6, 2.5], "intensity": 8, "range": 4}],
    "objects": [
      {"shape": "plane", "size": [14, 14], "material": "ground"},
      {"shape": "box", "size": [0.8, 1.6, 0.8], "material": "grey", "transform": {"translate": [-1, 0.8, 0]}},
      {"shape": "box", "size": [3, 0.2, 0.2], "material": "grey", "transform": {"translate": [0.5, 2.2, 0.5],
       "rotate": [0, 30, 0]}},
      {"shape": "sphere", "radius": 0.9, "material": "grey", "transform": {"translate": [1.6, 0.9, -0.5]}},
      {"shape": "disk", "radius": 0.7, "material": "grey", "transform": {"translate": [-2.6, 1.2, 2.5],
       "rotate": [-100, 0, 0]}},
      {"shape": "quad", "size": [1.5, 1.5], "material": "grey", "transform": {"translate": [-3.2, 1.0, 1.5],
       "rotate": [0, 90, 0]}},
      {"shape": "quad", "size": [1.0, 0.8], "material": "glow", "transform": {"translate": [2.8, 1.8, 1.0]}}]})";
  const std::string spot =
      R"({"type": "spot", "position": [2, 4, 2], "direction": [-0.3, -1, -0.3], "inner_cone_deg": 10,
       "outer_cone_deg": 30, "intensity": 30},
      {"type": "point", "position": [1.5, 0.6, 2.5], "intensity": 8, "range": 4})";
  for (const bool lanes : {false, true}) {
    SCOPED_TRACE(lanes ? "directional and point lights" : "with a spot and a ranged light");
    if (lanes)
      json.replace(json.find(spot), spot.size(), R"({"type": "point", "position": [1.5, 0.6, 2.5], "intensity": 8})");
    const Scene scene = ParseScene(json, "lit-mix", ".");
    for (const auto& pos : {ScrambledWalk(64, 36, 2011), PixelPackets(32, 24)}) {
      const Seen s =
          ExpectLitPacketsEqualGeneralPath(scene, pos, pos.size() == 2011 ? 64 : 32, pos.size() == 2011 ? 36 : 24);
      EXPECT_GT(s.background, 0);
      EXPECT_GT(s.hits, 0);
      EXPECT_GT(s.shadowed[0], 0);  // the directional light blocked
      EXPECT_GT(s.shadowed[1], 0);  // the point light blocked
      EXPECT_GT(s.partly, 0);       // one blocked, the other not
      EXPECT_GT(s.shadow_rays, 0u);
    }
  }
}

// An orthographic camera over a lit quad and sphere with a directional light's shadows.
TEST(LitPackets, OrthographicShadowsEqualTheGeneralPath) {
  const std::string json = R"({"name": "shadow-bits", "effects": ["lambert", "shadows"], "light_units": "gltf",
    "camera": {"type": "orthographic", "position": [0, 6, 6], "look_at": [0, 0, 0], "up": [0, 1, 0], "height": 8},
    "background": [0.3, 0.2, 0.1],
    "materials": {"ground": {"shading": "lambert", "color": [0.8, 0.7, 0.6]}},
    "lights": [{"type": "directional", "direction": [0.2, -1, 0.1], "intensity": 3.0, "shadows": true}],
    "objects": [
      {"shape": "quad", "size": [5, 5], "material": "ground", "transform": {"rotate": [-90, 0, 0]}},
      {"shape": "sphere", "radius": 0.8, "material": "ground", "transform": {"translate": [0, 1.5, 0]}}]})";
  const Scene scene = ParseScene(json, "shadow-bits", ".");
  const Seen s = ExpectLitPacketsEqualGeneralPath(scene, ScrambledWalk(48, 48, 1501), 48, 48);
  EXPECT_GT(s.background, 0);
  EXPECT_GT(s.shadowed[0], 0);
}

// The library's lit scenes the path was written for: shadow-stipple (directional light,
// shadows) and motion-orbit (a point light, no shadows, orthographic).
TEST(LitPackets, LibraryScenesEqualTheGeneralPath) {
  for (const char* name : {"shadow-stipple", "motion-orbit"}) {
    SCOPED_TRACE(name);
    const Scene scene = LoadScene(name);
    const Seen s = ExpectLitPacketsEqualGeneralPath(scene, PixelPackets(40, 24), 40, 24);
    EXPECT_GT(s.hits, 0);
  }
}

}  // namespace
}  // namespace aalab
