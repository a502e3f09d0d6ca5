#include <gtest/gtest.h>

#include <cmath>

#include "core/color.h"
#include "core/parallel.h"
#include "metrics/metric.h"
#include "scene_test_util.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace aalab {
namespace {
using testing::MakeScene;
using testing::ParseText;

const std::string kQuadBig = R"([{"shape": "quad", "size": [100,100], "material": "w"}])";

TraceCounters CountFrame(const Scene& scene, int w, int h, int grid) {
  Tracer tracer(scene);
  RenderSpec spec;
  if (grid > 1) {
    spec.pattern = SamplePattern::kOrderedGrid;
    spec.grid = grid;
  }
  TraceCounters c;
  RenderFrame(tracer, w, h, spec, 1, &c);
  return c;
}

TEST(Effects, UnlitCostsOnePrimaryRayAndNothingElse) {
  const Scene s = ParseText(MakeScene(R"(["unlit"])", R"({"w": {"shading": "unlit"}})", kQuadBig));
  const TraceCounters c = CountFrame(s, 16, 8, 2);
  EXPECT_EQ(c.samples, 16u * 8u * 4u);
  EXPECT_EQ(c.primary_rays, 16u * 8u * 4u);
  EXPECT_EQ(c.shadow_rays, 0u);
  EXPECT_EQ(c.texture_lookups, 0u);
}

TEST(Effects, LightsWithoutShadowsTraceNoShadowRays) {
  const std::string light =
      R"(, "light_units": "aalab-pi", "lights": [{"type": "directional", "direction": [0,0,-1]}])";
  const Scene s = ParseText(MakeScene(R"(["lambert"])", R"({"w": {"shading": "lambert"}})", kQuadBig, light));
  const TraceCounters c = CountFrame(s, 16, 8, 1);
  EXPECT_EQ(c.shadow_rays, 0u);
  EXPECT_EQ(c.texture_lookups, 0u);
}

TEST(Effects, ShadowsCostOneRayPerLitSampleAndLight) {
  // The quad fills the view and faces the light: every sample sends exactly one shadow ray.
  const std::string light =
      R"(, "light_units": "aalab-pi", "lights": [{"type": "directional", "direction": [0,0,-1], "shadows": true}])";
  const Scene s =
      ParseText(MakeScene(R"(["lambert", "shadows"])", R"({"w": {"shading": "lambert"}})", kQuadBig, light));
  const TraceCounters c = CountFrame(s, 16, 8, 2);
  EXPECT_EQ(c.shadow_rays, 16u * 8u * 4u);
  EXPECT_EQ(c.texture_lookups, 0u);
}

TEST(Effects, TexturesCostOneLookupPerTexturedSample) {
  // Left half of the view: textured quad; right half: background (no lookup).
  const Scene s = ParseText(MakeScene(
      R"(["unlit", "textures"])", R"({"w": {"shading": "unlit", "texture": {"pattern": "checker", "scale": 2}}})",
      R"([{"shape": "quad", "size": [4,4], "material": "w", "transform": {"translate": [-2,0,0]}}])"));
  // Ortho height 4, 16x8 px → width 8 world units: x in [-4, 4], the quad covers [-4, 0].
  const TraceCounters c = CountFrame(s, 16, 8, 1);
  EXPECT_EQ(c.texture_lookups, 8u * 8u);
  EXPECT_EQ(c.shadow_rays, 0u);
}

TEST(Effects, AlphaCutoutsShowWhatIsBehind) {
  // Stripes along x with duty 0.5 and scale 1: u in [k, k+0.5) kept. A red quad behind.
  const Scene s = ParseText(
      MakeScene(R"(["unlit", "alpha_test"])",
                R"({"front": {"shading": "unlit", "color": [1,1,1], "alpha": {"pattern": "stripes", "scale": 1}},
          "back": {"shading": "unlit", "color": [1,0,0]}})",
                R"([{"shape": "quad", "size": [100,100], "material": "front"},
          {"shape": "quad", "size": [100,100], "material": "back", "transform": {"translate": [0,0,-1]}}])"));
  Tracer tracer(s);
  TraceCounters c;
  const Image8 img = RenderFrame(tracer, 16, 8, RenderSpec{}, 1, &c);
  // 16 px over 8 world units: pixel x centre → world x = (x + 0.5) / 2 − 4; kept when frac(x_world) < 0.5.
  for (int x = 0; x < 16; ++x) {
    const float wx = (static_cast<float>(x) + 0.5f) / 2.0f - 4.0f;
    const bool kept = wx - std::floor(wx) < 0.5f;
    EXPECT_EQ(img.At(x, 3, 1), kept ? 255 : 0) << x;
  }
  // Every sample looks up the alpha once; rejected ones continue (a second primary ray).
  EXPECT_EQ(c.texture_lookups, 16u * 8u);
  EXPECT_EQ(c.primary_rays, 16u * 8u + 8u * 8u);
}

TEST(Tracer, DeterministicAcrossThreadCounts) {
  const Scene scene = LoadScene("shadow-stipple");
  Image8 a, b;
  Reference ra, rb;
  TraceCounters ca, cb;
  {
    SetThreadCount(1);
    Tracer t(scene);
    RenderSpec jitter;
    jitter.pattern = SamplePattern::kJitter;
    jitter.spp = 3;
    a = RenderFrame(t, 48, 27, jitter, 7, &ca);
    ra = RenderReference(t, 48, 27, 4, 7, nullptr);
  }
  {
    SetThreadCount(2);
    Tracer t(scene);
    RenderSpec jitter;
    jitter.pattern = SamplePattern::kJitter;
    jitter.spp = 3;
    b = RenderFrame(t, 48, 27, jitter, 7, &cb);
    rb = RenderReference(t, 48, 27, 4, 7, nullptr);
  }
  SetThreadCount(0);
  EXPECT_TRUE(a == b);
  EXPECT_TRUE(ra.image == rb.image);
  EXPECT_TRUE(ra.edge_mask == rb.edge_mask);
  EXPECT_EQ(ca.primary_rays, cb.primary_rays);
  EXPECT_EQ(ca.shadow_rays, cb.shadow_rays);
}

// Exact area of the unit pixel [x, x+1] × [y, y+1] where py > m·px + b (y down), by clipping the
// square against the half-plane (Sutherland–Hodgman) and the shoelace formula.
double CoveredArea(int x, int y, double m, double b) {
  std::vector<std::pair<double, double>> poly = {{x, y}, {x + 1.0, y}, {x + 1.0, y + 1.0}, {x, y + 1.0}};
  auto f = [&](std::pair<double, double> p) { return p.second - (m * p.first + b); };
  std::vector<std::pair<double, double>> out;
  for (size_t i = 0; i < poly.size(); ++i) {
    const auto p = poly[i], q = poly[(i + 1) % poly.size()];
    const double fp = f(p), fq = f(q);
    if (fp >= 0) out.push_back(p);
    if ((fp >= 0) != (fq >= 0)) {
      const double t = fp / (fp - fq);
      out.push_back({p.first + t * (q.first - p.first), p.second + t * (q.second - p.second)});
    }
  }
  double area = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    const auto p = out[i], q = out[(i + 1) % out.size()];
    area += p.first * q.second - q.first * p.second;
  }
  return std::fabs(area) * 0.5;
}

TEST(Reference, MatchesAnalyticCoverageOfAHalfPlane) {
  // Orthographic camera with 1 world unit per pixel: pixel (px, py) ↔ world (px − W/2, H/2 − py).
  // A white unlit polygon covers py > m·px + b (below the line, y down) on a black background,
  // display "none": the reference's decoded value is the covered fraction of each pixel.
  const int W = 32, H = 16;
  const double m = 0.3, b = 3.7;
  auto world = [&](double px, double py) {
    return "[" + std::to_string(px - W / 2.0) + "," + std::to_string(H / 2.0 - py) + ",0]";
  };
  const std::string poly = "[" + world(-50, m * -50 + b) + "," + world(-50, 200) + "," + world(200, 200) + "," +
                           world(200, m * 200 + b) + "]";
  const Scene s = ParseText(
      R"({"name": "t", "effects": ["unlit"], "camera": {"type": "orthographic", "position": [0,0,10],
          "look_at": [0,0,0], "height": 16}, "materials": {"w": {"shading": "unlit", "color": [1,1,1]}},
          "objects": [{"shape": "polygon", "material": "w", "points": )" +
      poly + "}]}");
  Tracer tracer(s);
  const Reference ref = RenderReference(tracer, W, H, 16, 3, nullptr);
  double max_err = 0, sum_err = 0;
  int edge_pixels = 0;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const double want = CoveredArea(x, y, m, b);
      const double got = SrgbDecode(ref.image.At(x, y, 1));
      const double err = std::fabs(got - want);
      max_err = std::max(max_err, err);
      sum_err += err;
      if (want > 0 && want < 1) {
        ++edge_pixels;
        EXPECT_GT(ref.edge_mask_raw.At(x, y, 0), 0.5f) << x << "," << y;
      } else {
        EXPECT_EQ(got, want) << "fully covered or empty pixels are exact: " << x << "," << y;
      }
    }
  }
  EXPECT_GT(edge_pixels, 30);
  // 16×16 jittered strata: the edge crosses ≤ 32 strata, each wrong by at most 1/256 and on
  // average ~0 ⇒ per-pixel error well under 0.03.
  EXPECT_LT(max_err, 0.03);
  EXPECT_LT(sum_err / (W * H), 0.003);
}

TEST(Reference, ConvergesAndReportsAFiniteNoiseFloor) {
  const Scene scene = LoadScene("circle");
  Tracer t(scene);
  const int W = 64, H = 36;
  const Reference r1024 = RenderReference(t, W, H, 32, 11, nullptr);
  const Reference r256 = RenderReference(t, W, H, 16, 12, nullptr);
  const Reference r64 = RenderReference(t, W, H, 8, 13, nullptr);
  const double p64 = *PsnrFromMse(MeanSquaredError(r64.image, r1024.image).mse);
  const double p256 = *PsnrFromMse(MeanSquaredError(r256.image, r1024.image).mse);
  EXPECT_LT(p64, p256);
  const auto halves = PsnrFromMse(MeanSquaredError(r256.half_a, r256.half_b).mse);
  ASSERT_TRUE(halves.has_value());
  EXPECT_TRUE(std::isfinite(*halves));
  EXPECT_GT(*halves, 30.0);
}

TEST(Reference, GridValidation) {
  EXPECT_EQ(ReferenceGridForSpp(256), 16);
  EXPECT_EQ(ReferenceGridForSpp(4), 2);
  EXPECT_THROW(ReferenceGridForSpp(100 + 1), UserError);
  EXPECT_THROW(ReferenceGridForSpp(9), UserError);  // odd grid: the halves would be unequal
  EXPECT_THROW(ReferenceGridForSpp(1), UserError);
}

TEST(Ssaa, FourByFourBeatsNoneOnEveryEdgeScene) {
  for (const char* name :
       {"wedges", "circle", "thin-wires", "checker-plane", "specular-spheres", "shadow-stipple", "hdr-edges", "mesh"}) {
    const Scene scene = LoadScene(name);
    Tracer t(scene);
    const int W = 96, H = 54;
    const Reference ref = RenderReference(t, W, H, 8, 5, nullptr);
    const Image8 none = RenderFrame(t, W, H, RenderSpec{}, 5, nullptr);
    RenderSpec ss;
    ss.pattern = SamplePattern::kOrderedGrid;
    ss.grid = 4;
    const Image8 ssaa = RenderFrame(t, W, H, ss, 5, nullptr);
    const double e_none = MeanSquaredError(ToFloat(none), ref.image).mse;
    const double e_ssaa = MeanSquaredError(ToFloat(ssaa), ref.image).mse;
    EXPECT_LT(e_ssaa, e_none) << name;
  }
}

TEST(Ssaa, NoEdgesMeansSsaaEqualsNoneUpToQuantization) {
  // A constant unlit colour filling the frame: every sample is identical.
  const Scene s =
      ParseText(MakeScene(R"(["unlit"])", R"({"w": {"shading": "unlit", "color": [0.3,0.5,0.7]}})", kQuadBig));
  Tracer t(s);
  RenderSpec ss;
  ss.pattern = SamplePattern::kOrderedGrid;
  ss.grid = 4;
  EXPECT_TRUE(RenderFrame(t, 12, 7, ss, 1, nullptr) == RenderFrame(t, 12, 7, RenderSpec{}, 1, nullptr));
}

TEST(Display, ExtremeRadianceSaturatesToWhiteNotBlack) {
  // Within every documented range (ambient and colour <= 1e7, exposure <= 1e9) the radiance
  // reaches 1e23: ACES overflowed to NaN there and the pixel came out black (Reinhard did the
  // same for infinite radiance, e.g. a point light almost on a surface: tests/core/color_test).
  const std::string lit = R"({"w": {"shading": "lambert", "color": [1e7, 1e7, 1e7]}})";
  for (const char* tonemap : {"none", "reinhard", "aces"}) {
    const Scene s = ParseText(MakeScene(
        R"(["lambert"])", lit, kQuadBig,
        std::string(R"(, "ambient": [1e7, 1e7, 1e7], "display": {"exposure": 1e9, "tonemap": ")") + tonemap + R"("})"));
    Tracer t(s);
    const Reference ref = RenderReference(t, 4, 3, 2, 1, nullptr);
    const Image8 frame = RenderFrame(t, 4, 3, RenderSpec{}, 1, nullptr);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(frame.At(1, 1, c), 255) << tonemap;
      EXPECT_EQ(ref.image.At(1, 1, c), 1.0f) << tonemap;
    }
  }
}

}  // namespace
}  // namespace aalab
