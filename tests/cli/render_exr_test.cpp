// `aalab render --out X.exr` writes the float resolve (display-linear, not quantised): checked
// against the 8-bit code levels, against the PNG of the same samples, and against the float
// reference that `aalab run` writes for the same scene at the same sample count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "cli_util.h"
#include "core/color.h"
#include "io/image_io.h"

namespace {
namespace fs = std::filesystem;
using aalab::clitest::Aalab;
using aalab::clitest::CmdResult;
using aalab::clitest::TempDir;

/// Distance from v to the nearest 8-bit level decoded to linear, SrgbDecode(k / 255).
double DistanceToNearestLevel(double v) {
  double best = 1.0;
  for (int k = 0; k < 256; ++k) best = std::min(best, std::abs(v - aalab::SrgbDecode(k / 255.0f)));
  return best;
}

// circle: a near-white disk edge on a dark background, 64×64 = 4096 samples per pixel.
TEST(RenderExr, EdgeAt4096SppIsTheFloatResolveAndMatchesTheReference) {
  const fs::path dir = TempDir("render_exr");
  const std::string exr = (dir / "circle.exr").string();
  CmdResult r = Aalab("render --scene circle --size 48x27 --spp 4096 --out " + exr);
  ASSERT_EQ(r.code, 0) << r.output;
  const aalab::ImageF img = aalab::ReadImage(exr).pixels;
  ASSERT_EQ(img.Width(), 48);
  ASSERT_EQ(img.Channels(), 3);

  // Near white, the 8-bit frame decoded to linear can only be 0.9560, 0.9647, 0.9734, 0.9823,
  // 0.9911 or 1 (codes 250..255): levels about 0.0088 apart. A float resolve of 4096 samples at
  // an edge lands between them: count pixels more than 1e-3 from every level.
  int near_white = 0, between = 0;
  for (int y = 0; y < img.Height(); ++y) {
    for (int x = 0; x < img.Width(); ++x) {
      const double v = img.At(x, y, 0);
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, 1.0);
      if (v < 0.95 || v >= 1.0) continue;
      ++near_white;
      if (DistanceToNearestLevel(v) > 1e-3) ++between;
    }
  }
  EXPECT_GT(near_white, 5);
  EXPECT_GT(between, near_white / 2) << "values sit on the 8-bit levels: the EXR is a quantised frame";

  // The run's reference at the same sample count: an independent stratified estimate of the
  // same pixel integrals (its own jitter stream), so equal up to sampling noise. At 4096
  // stratified samples an edge pixel's estimate varies by well under 1e-2 (the 8-bit step near
  // white is 0.0088); away from edges both are exact.
  const fs::path run = dir / "run";
  r = Aalab("run --scenes circle --methods none --size 48x27 --ref-spp 4096 --repeat 1 --quiet --out " + run.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const aalab::ImageF ref = aalab::ReadImage((run / "images/circle/reference.exr").string()).pixels;
  ASSERT_EQ(ref.Width(), img.Width());
  ASSERT_EQ(ref.Height(), img.Height());
  double sum = 0, worst = 0;
  for (int y = 0; y < img.Height(); ++y) {
    for (int x = 0; x < img.Width(); ++x) {
      for (int c = 0; c < 3; ++c) {
        const double d = std::abs(static_cast<double>(img.At(x, y, c)) - ref.At(x, y, c));
        sum += d;
        worst = std::max(worst, d);
      }
    }
  }
  EXPECT_LT(worst, 1e-2);
  EXPECT_LT(sum / (img.Width() * img.Height() * 3), 5e-4);
}

// The EXR and the PNG of one command are the same samples: the PNG is the EXR sRGB-encoded and
// rounded to 8 bits.
TEST(RenderExr, PngIsTheQuantisedExr) {
  const fs::path dir = TempDir("render_exr_png");
  for (const char* spp : {"1", "16"}) {
    const std::string exr = (dir / (std::string("w") + spp + ".exr")).string();
    const std::string png = (dir / (std::string("w") + spp + ".png")).string();
    ASSERT_EQ(Aalab(std::string("render --scene wedges --size 33x17 --spp ") + spp + " --out " + exr).code, 0);
    ASSERT_EQ(Aalab(std::string("render --scene wedges --size 33x17 --spp ") + spp + " --out " + png).code, 0);
    const aalab::ImageF f = aalab::ReadImage(exr).pixels;
    const aalab::Image8 q = aalab::ReadImage8(png);
    int mismatches = 0;
    for (int y = 0; y < f.Height(); ++y) {
      for (int x = 0; x < f.Width(); ++x) {
        for (int c = 0; c < 3; ++c) {
          if (aalab::QuantizeUnorm8(aalab::SrgbEncode(f.At(x, y, c))) != q.Pixel(x, y)[c]) ++mismatches;
        }
      }
    }
    EXPECT_EQ(mismatches, 0) << "spp " << spp;
  }
}

}  // namespace
