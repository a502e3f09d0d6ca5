// Analytical AA: pixel-size methods on known gradients, the article's blends, the linear
// ramp against exact box coverage of a half-plane (derived by hand), and the renderer end to
// end against the exact reference.
#include "scenes/analytic.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/color.h"
#include "scenes/analytic_geometry.h"
#include "scenes/exact_reference.h"
#include "scenes/render.h"
#include "scene_test_util.h"

namespace aalab {
namespace {

using testing::MakeScene;
using testing::ParseText;

TEST(Aaa, PixelSizeMethodsOnAKnownGradient) {
  // d changes by gx = 0.6, gy = -0.8 per pixel step: length 1, fwidth |gx| + |gy| = 1.4.
  EXPECT_DOUBLE_EQ(AaaPixelSizeOf(AaaPixelSize::kLength, 7.0, 0.6, -0.8), 1.0);
  EXPECT_DOUBLE_EQ(AaaPixelSizeOf(AaaPixelSize::kFwidth, 7.0, 0.6, -0.8), 1.4);
  EXPECT_DOUBLE_EQ(AaaPixelSizeOf(AaaPixelSize::kObject, 7.0, 0.6, -0.8), 7.0);
  // A diagonal gradient: fwidth is √2 times the length.
  const double g = std::sqrt(0.5);
  EXPECT_NEAR(AaaPixelSizeOf(AaaPixelSize::kFwidth, 1.0, g, g) / AaaPixelSizeOf(AaaPixelSize::kLength, 1.0, g, g),
              std::sqrt(2.0), 1e-15);
}

TEST(Aaa, BlendsFollowTheArticle) {
  AnalyticSpec s;  // object, division, shrink 0.5, smoothing 1: alpha = clamp(0.5 − d/p)
  EXPECT_DOUBLE_EQ(AaaAlpha(s, 0.0, 1.0, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(AaaAlpha(s, 0.25, 1.0, 1.0), 0.25);
  EXPECT_DOUBLE_EQ(AaaAlpha(s, 2.0, 1.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(AaaAlpha(s, -2.0, 1.0, 1.0), 1.0);
  // Units cancel: d and p in world units (p = 0.01 per pixel).
  EXPECT_DOUBLE_EQ(AaaAlpha(s, 0.0025, 0.01, 0.01), 0.25);
  // Division is clamped by the framebuffer: equal to linstep everywhere.
  AnalyticSpec lin = s;
  lin.blend = AaaBlend::kLinstep;
  for (double d = -2; d <= 2; d += 0.125) EXPECT_EQ(AaaAlpha(s, d, 1, 1), AaaAlpha(lin, d, 1, 1)) << d;
  // smoothstep(1, 1 − px, dist): t = 0.25 → t²(3 − 2t) = 0.15625.
  AnalyticSpec sm = s;
  sm.blend = AaaBlend::kSmoothstep;
  EXPECT_DOUBLE_EQ(AaaAlpha(sm, 0.25, 1, 1), 0.15625);
  // shrink 1: the ramp lies inside the outline, alpha = clamp(−d/p); the 3D demo's
  // −dist/(px·√2) with smoothing √2.
  AnalyticSpec in = s;
  in.shrink = 1.0;
  EXPECT_DOUBLE_EQ(AaaAlpha(in, 0.0, 1, 1), 0.0);
  EXPECT_DOUBLE_EQ(AaaAlpha(in, -0.5, 1, 1), 0.5);
  in.smoothing = std::sqrt(2.0);
  EXPECT_NEAR(AaaAlpha(in, -0.5, 1, 1), 0.5 / std::sqrt(2.0), 1e-15);
}

/// Exact box coverage of the unit pixel centred at the origin by the half-plane at angle θ
/// whose edge lies at signed distance s (px, positive: the centre is outside) from the centre.
double BoxCoverage(double theta, double s) {
  const double nx = std::cos(theta), ny = std::sin(theta);
  return std::fabs(SignedArea(ClipHalfPlane(RectPoly(-0.5, -0.5, 0.5, 0.5), nx, ny, -s)));
}

TEST(Aaa, LinearRampAgainstTrueHalfPlaneCoverage) {
  const AnalyticSpec spec;  // the article's centred 1 px linear ramp
  double max0 = 0, max45 = 0, arg45 = 0;
  for (int i = -1000; i <= 1000; ++i) {
    const double s = i / 1000.0;
    max0 = std::max(max0, std::fabs(AaaAlpha(spec, s, 1, 1) - BoxCoverage(0.0, s)));
    const double e45 = std::fabs(AaaAlpha(spec, s, 1, 1) - BoxCoverage(M_PI / 4, s));
    if (e45 > max45) {
      max45 = e45;
      arg45 = std::fabs(s);
    }
  }
  // 0°: the box coverage of an axis-aligned edge is exactly clamp(0.5 − s).
  EXPECT_LT(max0, 1e-12);
  // 45°: coverage is (√2/2 − |s|)² outside and 1 minus that inside; the ramp's worst error is
  // (3 − 2√2)/4 ≈ 0.0429, at |s| = 0.5 (ramp 0, true (√2/2 − 1/2)²) and at |s| = (√2 − 1)/2.
  EXPECT_NEAR(max45, (3.0 - 2.0 * std::sqrt(2.0)) / 4.0, 1e-9);
  EXPECT_TRUE(std::fabs(arg45 - 0.5) < 1e-9 || std::fabs(arg45 - (std::sqrt(2.0) - 1) / 2) < 1e-3) << arg45;
  // fwidth at 45° spreads the ramp over √2 px (and, with shrink 0.5, moves it inward by
  // (√2 − 1)/2 px): at the nominal edge alpha = (1 − √2/2)/√2 instead of 0.5.
  AnalyticSpec fw = spec;
  fw.pixel_size = AaaPixelSize::kFwidth;
  const double p = AaaPixelSizeOf(AaaPixelSize::kFwidth, 1.0, std::sqrt(0.5), std::sqrt(0.5));
  EXPECT_NEAR(AaaAlpha(fw, 0.0, p, 1.0), (1.0 - std::sqrt(0.5)) / std::sqrt(2.0), 1e-12);
}

TEST(Aaa, RenderedDiskAgainstTheExactReference) {
  // A large white disk on black, unlit, at an odd size: the rendered alpha (linear light)
  // against the exact coverage differs by at most the 45° half-plane bound (3 − 2√2)/4 plus
  // curvature and 8-bit rounding, and reaches close to it somewhere.
  const Scene sc = ParseText(MakeScene(R"(["unlit"])", R"({"m": {"shading": "unlit", "color": [1,1,1]}})",
                                       R"([{"shape": "disk", "radius": 1.7, "transform": {"translate": [0.013,0.021,0]},
                                            "material": "m"}])"));
  const int w = 151, h = 101;
  const Tracer tracer(sc);
  AnalyticSpec spec;
  spec.enabled = true;
  AnalyticCounters ac;
  const Image8 img = RenderAnalyticFrame(tracer, w, h, spec, nullptr, &ac);
  const Reference exact = RenderExactReference(sc, w, h);
  double max_err = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double got = SrgbDecode(img.Pixel(x, y)[0] / 255.0f);
      const double want = SrgbDecode(exact.image.At(x, y, 0));
      max_err = std::max(max_err, std::fabs(got - want));
    }
  }
  EXPECT_LT(max_err, (3.0 - 2.0 * std::sqrt(2.0)) / 4.0 + 0.006);
  EXPECT_GT(max_err, 0.035);
  // Every edge pixel of the 1x frame lies on the disk's outline.
  EXPECT_GT(ac.edge_pixels, 100u);
  EXPECT_EQ(ac.analytic_edge_pixels, ac.edge_pixels);
  // Same bits at any thread count is covered by the CLI determinism tests; same bits twice:
  EXPECT_EQ(RenderAnalyticFrame(tracer, w, h, spec, nullptr, nullptr).Data(), img.Data());
}

TEST(Aaa, PerspectiveSphereMatchesSupersamplingWithinTheRampBound) {
  // A perspective camera: the distance gradient comes through the normalised ray direction.
  // Against 16×16 ordered supersampling the centred ramp stays within the 45° half-plane
  // bound (3 − 2√2)/4 plus the 16×16 grid's own coverage error (≤ 1/32 on a straight edge)
  // and 8-bit rounding; `none` does not (it is off by up to a whole pixel's coverage).
  std::string json = MakeScene(R"(["unlit"])", R"({"m": {"shading": "unlit", "color": [1,1,1]}})",
                               R"([{"shape": "sphere", "radius": 0.9, "transform": {"translate": [0.4,-0.2,1]},
                                    "material": "m"}])");
  json.replace(json.find("\"orthographic\""), 14, "\"perspective\"");
  json.replace(json.find("\"height\": 4"), 11, "\"fov_y\": 40");
  const Scene sc = ParseText(json);
  const int w = 120, h = 80;
  const Tracer tracer(sc);
  AnalyticSpec spec;
  spec.enabled = true;
  spec.pixel_size = AaaPixelSize::kLength;  // exercises the exact gradient through the camera
  const Image8 aaa = RenderAnalyticFrame(tracer, w, h, spec, nullptr, nullptr);
  RenderSpec ss;
  ss.pattern = SamplePattern::kOrderedGrid;
  ss.grid = 16;
  const Image8 truth = RenderFrame(tracer, w, h, ss, 1, nullptr);
  const Image8 none = RenderFrame(tracer, w, h, RenderSpec{}, 1, nullptr);
  double max_aaa = 0, max_none = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double t = SrgbDecode(truth.Pixel(x, y)[0] / 255.0f);
      max_aaa = std::max(max_aaa, std::fabs(SrgbDecode(aaa.Pixel(x, y)[0] / 255.0f) - t));
      max_none = std::max(max_none, std::fabs(SrgbDecode(none.Pixel(x, y)[0] / 255.0f) - t));
    }
  }
  EXPECT_LT(max_aaa, (3.0 - 2.0 * std::sqrt(2.0)) / 4.0 + 1.0 / 32.0 + 0.006);
  EXPECT_GT(max_none, 0.3);
}

TEST(Aaa, TrianglesStayAsNoneRendersThem) {
  // A quad only: no analytic shape, so the frame equals the 1x frame bit for bit.
  const Scene sc = ParseText(MakeScene(R"(["unlit"])", R"({"m": {"shading": "unlit", "color": [1,0.5,0.2]}})",
                                       R"([{"shape": "quad", "size": [1.3,0.7], "transform": {"rotate": [0,0,17]},
                                            "material": "m"}])"));
  const Tracer tracer(sc);
  AnalyticSpec spec;
  spec.enabled = true;
  AnalyticCounters ac;
  const Image8 a = RenderAnalyticFrame(tracer, 63, 37, spec, nullptr, &ac);
  const Image8 none = RenderFrame(tracer, 63, 37, RenderSpec{}, 1, nullptr);
  EXPECT_EQ(a.Data(), none.Data());
  EXPECT_GT(ac.edge_pixels, 0u);
  EXPECT_EQ(ac.analytic_edge_pixels, 0u);
}

}  // namespace
}  // namespace aalab
