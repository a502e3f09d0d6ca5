// Viewing conditions: presets, the pixels-per-degree geometry, overrides and bad specs, and
// FLIP's dependence on pixels per degree, against values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.h"
#include "metrics/flip.h"
#include "metrics/viewing.h"

namespace aalab {
namespace {

TEST(Viewing, DefaultKeepsFlipsSixtySevenExactly) {
  const ViewingCondition v = ResolveViewing("");
  EXPECT_EQ(v.preset, "default");
  EXPECT_EQ(v.ppd, kFlipDefaultPpd);  // bit-exact: every default result stays as it was
  EXPECT_EQ(v.fps, 60.0);
  EXPECT_EQ(ResolveViewing("default").ppd, 67.0);
}

TEST(Viewing, GeometryGivesPixelsPerDegree) {
  // 0.7 m wide 3840-px display at 0.7 m: NVIDIA's FLIP tool's small-angle formula gives
  // 0.7·3840/0.7·π/180 = 3840·π/180 = 67.02064; the exact angle of one pixel differs by
  // (pitch/2d)²/3 ≈ 6e-9 relative. A 31.62-inch 16:9 diagonal is 31.62·0.0254·16/√337 =
  // 0.70000 m wide.
  EXPECT_NEAR(PixelsPerDegree(3840, 2160, 31.62, 0.7), 3840.0 * std::numbers::pi / 180.0, 2e-3);
  // 55-inch 1080p at 2 m: width 55·0.0254·1920/√(1920²+1080²) = 1.217591 m, pitch
  // 6.341620e-4 m, one pixel subtends 2·atan(pitch/4 m) = 0.0181674°, 55.0436 px/deg.
  EXPECT_NEAR(ResolveViewing("tv-1080p-2m").ppd, 55.0436, 1e-3);
  // Twice the distance, twice the pixels per degree (to within the small-angle error).
  EXPECT_NEAR(ResolveViewing("default:distance_m=1.4").ppd, 2.0 * 67.0206, 2e-3);
  // An explicit ppd wins over the geometry.
  EXPECT_EQ(ResolveViewing("tv-1080p-2m:ppd=40,distance_m=3").ppd, 40.0);
  EXPECT_EQ(ResolveViewing("tv-1080p-2m:fps=30").fps, 30.0);
  EXPECT_EQ(ResolveViewing("tv-1080p-2m:fps=30").spec, "tv-1080p-2m:fps=30");
}

TEST(Viewing, BadSpecsNameWhatIsAllowed) {
  try {
    ResolveViewing("cinema");
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown preset 'cinema'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("tv-1080p-2m"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ResolveViewing("default:ppd=0"), UserError);
  EXPECT_THROW(ResolveViewing("default:fps=-1"), UserError);
  EXPECT_THROW(ResolveViewing("default:colour=1"), UserError);
  EXPECT_THROW(ResolveViewing("default:ppd=abc"), UserError);
}

TEST(Viewing, FlipCsfWidthScalesWithPixelsPerDegree) {
  // FLIP's achromatic CSF is a Gaussian of σ = sqrt(b1/(2π²)) degrees (b1 = 0.0047), i.e.
  // σ·ppd pixels: 1.03385 px at 67, 2.0677 at 134, 0.5169 at 33.5. The sampled kernel's
  // standard deviation matches to ~1e-6 (sampling error e^{−2π²σ²}, truncation at 3σ of the
  // wider Cz Gaussian: far out).
  const double sigma_deg = std::sqrt(0.0047 / (2.0 * std::numbers::pi * std::numbers::pi));
  for (double ppd : {67.0, 134.0, 100.0}) {
    const auto k = flip::MakeSpatialKernels(ppd);
    double var = 0.0;
    for (size_t i = 0; i < k.y.size(); ++i) {
      const double x = static_cast<double>(i) - k.radius;
      var += k.y[i] * x * x;
    }
    EXPECT_NEAR(std::sqrt(var), sigma_deg * ppd, 1e-4) << ppd;
  }
}

TEST(Viewing, FlipColourErrorOfPixelCheckerFallsWithDistance) {
  // A one-pixel black/white checker against the grey of the same linear mean (sRGB 0.7354):
  // the further away (more pixels per degree), the more the eye's CSF averages the checker
  // into that grey, so FLIP's colour error (the CSF pipeline) must fall monotonically with
  // ppd. (The feature pipeline is not a low-pass: its edge detector widens with ppd too.)
  const int n = 40;
  ImageF checker(n, n, 3), grey(n, n, 3);
  const float g = 0.735356983f;  // sRGB encoding of linear 0.5
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      for (int c = 0; c < 3; ++c) {
        checker.At(x, y, c) = static_cast<float>((x + y) % 2);
        grey.At(x, y, c) = g;
      }
    }
  }
  double last = 2.0;
  for (double ppd : {10.0, 20.0, 40.0, 67.0, 134.0}) {
    double sum = 0.0;
    for (double v : flip::ColorErrorValues(grey, checker, ppd)) sum += v;
    const double mean = sum / (n * n);
    EXPECT_LT(mean, last) << ppd;
    last = mean;
  }
}

}  // namespace
}  // namespace aalab
