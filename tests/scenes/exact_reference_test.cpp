// The exact reference: closed-form areas checked against hand-computed values, coverage sums
// against shape areas, refusals, and the sampled reference converging to it.
#include "scenes/exact_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/color.h"
#include "scenes/analytic_geometry.h"
#include "scenes/render.h"
#include "scenes/tracer.h"
#include "scene_test_util.h"

namespace aalab {
namespace {

using testing::MakeScene;
using testing::ParseText;

constexpr double kPi = 3.14159265358979323846;

TEST(AnalyticGeometry, HandComputedAreas) {
  // Unit pixel cut by x + y <= 1 (45°, through two corners): half the pixel.
  const ConvexPoly px = RectPoly(0, 0, 1, 1);
  EXPECT_NEAR(std::fabs(SignedArea(ClipHalfPlane(px, 1, 1, 1))), 0.5, 1e-15);
  // x + y <= 0.5: the corner triangle with legs 0.5: 0.125.
  EXPECT_NEAR(std::fabs(SignedArea(ClipHalfPlane(px, 1, 1, 0.5))), 0.125, 1e-15);
  // Quarter disk r = 2 in [0, 2]²: π; whole disk inside a big square: 4π.
  EXPECT_NEAR(DiskRectArea(0, 0, 2, 0, 0, 2, 2), kPi, 1e-12);
  EXPECT_NEAR(DiskPolyArea({0, 0}, 2, RectPoly(0, 0, 2, 2)), kPi, 1e-12);
  EXPECT_NEAR(DiskPolyArea({0.3, -0.2}, 2, RectPoly(-5, -5, 5, 5)), 4 * kPi, 1e-12);
  // Half disk: the square's edge through the centre.
  EXPECT_NEAR(DiskPolyArea({1, 1}, 0.5, RectPoly(1, -3, 4, 4)), kPi * 0.125, 1e-12);
  // Circular segment: r = 1, chord at distance 0.5 → r²·acos(h) − h·√(r² − h²).
  const double seg = std::acos(0.5) - 0.5 * std::sqrt(0.75);
  EXPECT_NEAR(DiskPolyArea({0, 0}, 1, RectPoly(0.5, -2, 3, 2)), seg, 1e-12);
  EXPECT_NEAR(DiskRectArea(0, 0, 1, 0.5, -2, 3, 2), seg, 1e-12);
  // Capsule: πr² + 2rL; its left cap alone: πr²/2.
  EXPECT_NEAR(CapsulePolyArea({0, 0}, {3, 4}, 0.5, RectPoly(-9, -9, 9, 9)), kPi * 0.25 + 5.0, 1e-12);
  EXPECT_NEAR(CapsulePolyArea({0, 0}, {5, 0}, 0.5, RectPoly(-9, -9, 0, 9)), kPi * 0.125, 1e-12);
}

TEST(AnalyticGeometry, DiskPolygonAgreesWithTheRectanglePrimitive) {
  // Two independent closed forms (edge decomposition vs the odd-odd primitive G).
  uint32_t s = 12345;
  auto rnd = [&s] {
    s = s * 1664525u + 1013904223u;
    return (s >> 8) * (1.0 / 16777216.0);
  };
  for (int i = 0; i < 500; ++i) {
    const double cx = rnd() * 4 - 2, cy = rnd() * 4 - 2, r = 0.05 + rnd() * 3;
    const double x0 = rnd() * 2 - 1, y0 = rnd() * 2 - 1;
    const double x1 = x0 + 0.01 + rnd(), y1 = y0 + 0.01 + rnd();
    EXPECT_NEAR(DiskPolyArea({cx, cy}, r, RectPoly(x0, y0, x1, y1)), DiskRectArea(cx, cy, r, x0, y0, x1, y1), 1e-12)
        << i;
  }
}

// Frame 97 × 61, camera height 4: 15.25 px per world unit (an odd size on purpose).
constexpr int kW = 97, kH = 61;
constexpr double kPxPerUnit = 61.0 / 4.0;

TEST(ExactReference, DiskCoveragesSumToPiRSquared) {
  const Scene sc =
      ParseText(MakeScene(R"(["unlit"])", R"({"m": {"shading": "unlit", "color": [1,1,1]}})",
                          R"([{"shape": "disk", "radius": 1.23, "transform": {"translate": [0.311, -0.17, 0]},
                                            "material": "m"}])"));
  const std::vector<double> a = ExactVisibleAreas(sc, kW, kH);
  const double r = 1.23f * kPxPerUnit;  // the scene stores the radius as float
  EXPECT_NEAR(a[0], kPi * r * r, 1e-9 * kPi * r * r);
  EXPECT_NEAR(a[1], kW * kH - kPi * r * r, 1e-8);
}

TEST(ExactReference, PolygonCoveragesSumToItsAreaAndOcclusionIsExact) {
  // A triangle (area 1.5 world units²) in front of a capsule; a quad behind everything whose
  // left edge passes through a disk's centre, the disk in front of it.
  const Scene sc =
      ParseText(MakeScene(R"(["unlit"])",
                          R"({"a": {"shading": "unlit", "color": [1,0,0]}, "b": {"shading": "unlit", "color": [0,1,0]},
          "c": {"shading": "unlit", "color": [0,0,1]}, "d": {"shading": "unlit", "color": [1,1,0]}})",
                          R"([{"shape": "polygon", "points": [[-2.5,-1.5,1],[-0.5,-1.5,1],[-2.5,0,1]], "material": "a"},
          {"shape": "capsule", "from": [-2.6,-1.0,0], "to": [-1.0,-1.0,0], "radius": 0.25, "material": "b"},
          {"shape": "disk", "radius": 0.5, "transform": {"translate": [1.5,1.0,0]}, "material": "c"},
          {"shape": "quad", "size": [1.0, 3.0], "transform": {"translate": [2.0,0,-1]}, "material": "d"}])"));
  const std::vector<double> a = ExactVisibleAreas(sc, kW, kH);
  const double u2 = kPxPerUnit * kPxPerUnit;
  EXPECT_NEAR(a[0], 1.5 * u2, 1e-9 * u2);
  // Disk fully visible; the quad loses exactly the disk's right half.
  const double disk = kPi * 0.25f * 0.25f * 4 * u2;  // r = 0.5 (float)
  EXPECT_NEAR(a[2], disk, 1e-9 * u2);
  EXPECT_NEAR(a[3], 3.0 * u2 - disk / 2, 1e-9 * u2);
  // Everything adds up to the frame.
  double total = 0;
  for (double v : a) total += v;
  EXPECT_NEAR(total, kW * kH, 1e-8);
  // The capsule is partly behind the triangle: visible < full area, > 0.
  const double capsule = (kPi * 0.0625 + 0.5 * 1.6) * u2;
  EXPECT_GT(a[1], 0.05 * capsule);
  EXPECT_LT(a[1], capsule - 1.0);
}

std::string RefusalOf(const std::string& json) { return ExactReferenceRefusal(ParseText(json)); }

TEST(ExactReference, RefusesWhatItCannotComputeNamingTheField) {
  const std::string mat = R"({"m": {"shading": "unlit", "color": [1,1,1]}})";
  EXPECT_EQ(RefusalOf(MakeScene(R"(["unlit"])", mat, R"([{"shape": "disk", "radius": 1, "material": "m"}])")), "");
  std::string persp = MakeScene(R"(["unlit"])", mat, R"([{"shape": "disk", "radius": 1, "material": "m"}])");
  persp.replace(persp.find("orthographic"), 12, "perspective");
  persp.replace(persp.find("\"height\": 4"), 11, "\"fov_y\": 40");
  EXPECT_NE(RefusalOf(persp).find("/camera/type"), std::string::npos);
  EXPECT_NE(
      RefusalOf(MakeScene(R"(["lambert"])", R"({"m": {"shading": "lambert", "color": [1,1,1]}})",
                          R"([{"shape": "disk", "radius": 1, "material": "m"}])",
                          R"(, "light_units": "aalab-pi", "lights": [{"type": "directional", "direction": [0,0,-1]}])"))
          .find("/effects declares 'lambert'"),
      std::string::npos);
  EXPECT_NE(
      RefusalOf(MakeScene(R"(["unlit"])", mat,
                          R"([{"shape": "cylinder", "from": [0,0,0], "to": [1,0,0], "radius": 0.1, "material": "m"}])"))
          .find("/objects/0 is a cylinder"),
      std::string::npos);
  EXPECT_NE(
      RefusalOf(MakeScene(R"(["unlit"])", mat,
                          R"([{"shape": "disk", "radius": 1, "transform": {"rotate": [30,0,0]}, "material": "m"}])"))
          .find("/objects/0 is a disk whose normal"),
      std::string::npos);
  const std::string two = RefusalOf(MakeScene(R"(["unlit"])", mat,
                                              R"([{"shape": "disk", "radius": 1, "material": "m"},
          {"shape": "sphere", "radius": 1, "transform": {"translate": [1.5,0,-3]}, "material": "m"}])"));
  EXPECT_NE(two.find("/objects/0 and /objects/1 are curved shapes that overlap"), std::string::npos) << two;
  const std::string tilted = RefusalOf(MakeScene(R"(["unlit"])", mat,
                                                 R"([{"shape": "disk", "radius": 0.5, "material": "m"},
          {"shape": "quad", "size": [3,3], "transform": {"rotate": [0,60,0]}, "material": "m"}])"));
  EXPECT_NE(tilted.find("depth ranges overlap"), std::string::npos) << tilted;
}

/// Mean and RMS of (sampled − exact) in linear light over every pixel and channel.
std::pair<double, double> ErrorVsExact(const ImageF& sampled, const ImageF& exact) {
  double sum = 0, sum2 = 0;
  for (size_t i = 0; i < exact.Data().size(); ++i) {
    const double e = static_cast<double>(SrgbDecode(sampled.Data()[i])) - SrgbDecode(exact.Data()[i]);
    sum += e;
    sum2 += e * e;
  }
  const double n = static_cast<double>(exact.Data().size());
  return {sum / n, std::sqrt(sum2 / n)};
}

TEST(ExactReference, SampledReferenceConvergesToItAtTheStratifiedRate) {
  // Disks, a capsule and a triangle; pixel conventions of the tracer and the exact reference
  // must agree for the error to keep falling.
  const Scene sc = ParseText(MakeScene(
      R"(["unlit"])",
      R"({"w": {"shading": "unlit", "color": [0.9,0.8,0.7]}, "g": {"shading": "unlit", "color": [0.2,0.5,0.3]}})",
      R"([{"shape": "disk", "radius": 0.83, "transform": {"translate": [-1.1,0.2,0]}, "material": "w"},
          {"shape": "sphere", "radius": 0.31, "transform": {"translate": [1.2,0.9,0]}, "material": "g"},
          {"shape": "capsule", "from": [0.2,-1.4,0], "to": [2.1,-0.3,0], "radius": 0.04, "material": "w"},
          {"shape": "polygon", "points": [[0.1,0.3,-1],[1.7,-0.2,-1],[0.9,1.6,-1]], "material": "g"}])"));
  const int w = 96, h = 64;
  const Reference exact = RenderExactReference(sc, w, h);
  const Tracer tracer(sc);
  std::vector<double> log_spp, log_rms;
  for (int grid : {2, 4, 8, 16}) {
    const Reference sampled = RenderReference(tracer, w, h, grid, 7, nullptr);
    const auto [mean, rms] = ErrorVsExact(sampled.image, exact.image);
    // No bias: the mean error is far below the per-pixel noise (it averages ~18k values).
    EXPECT_LT(std::fabs(mean), 0.05 * rms) << grid;
    std::printf("grid %d: mean %.3g rms %.3g\n", grid, mean, rms);
    log_spp.push_back(std::log(grid * grid));
    log_rms.push_back(std::log(rms));
  }
  // Least-squares slope of log RMS against log spp. Stratified sampling of a pixel crossed by
  // a smooth edge: variance ∝ N^(−3/2), RMS ∝ N^(−3/4) (uniform jitter would give −1/2).
  double mx = 0, my = 0;
  for (size_t i = 0; i < log_spp.size(); ++i) {
    mx += log_spp[i];
    my += log_rms[i];
  }
  mx /= log_spp.size();
  my /= log_rms.size();
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < log_spp.size(); ++i) {
    sxy += (log_spp[i] - mx) * (log_rms[i] - my);
    sxx += (log_spp[i] - mx) * (log_spp[i] - mx);
  }
  const double slope = sxy / sxx;
  std::printf("slope %.4f\n", slope);
  EXPECT_LT(slope, -0.65);
  EXPECT_GT(slope, -0.85);
}

TEST(ExactReference, NoiseFreeAndDeterministic) {
  const Scene sc = ParseText(MakeScene(R"(["unlit"])", R"({"m": {"shading": "unlit", "color": [1,1,1]}})",
                                       R"([{"shape": "disk", "radius": 1.1, "material": "m"}])"));
  const Reference a = RenderExactReference(sc, 33, 21);
  const Reference b = RenderExactReference(sc, 33, 21);
  EXPECT_EQ(a.image.Data(), b.image.Data());
  EXPECT_EQ(a.half_a.Data(), a.half_b.Data());  // the noise floor is infinite
  // Centre pixel fully inside, a corner pixel fully outside.
  EXPECT_FLOAT_EQ(a.image.At(16, 10, 0), 1.0f);
  EXPECT_FLOAT_EQ(a.image.At(0, 0, 0), 0.0f);
  EXPECT_EQ(a.edge_mask.At(16, 10, 0), 0.0f);
}

}  // namespace
}  // namespace aalab
