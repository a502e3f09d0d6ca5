#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <bit>
#include <cstdio>
#include <numeric>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "metrics/flip.h"
#include "tests/metrics/test_images.h"

namespace aalab {
namespace {

using flip::Color;

void ExpectColorNear(const Color& got, const Color& want, double tol, const char* what) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], tol) << what << " component " << i;
}

// ---- Colour pipeline, piece by piece ----

TEST(FlipColor, SrgbDecode) {
  // IEC 61966-2-1: ((0.5 + 0.055)/1.055)^2.4 = 0.2140411405; linear segment below 0.04045.
  EXPECT_NEAR(flip::SrgbToLinear(0.5), 0.21404114048223255, 1e-15);
  EXPECT_NEAR(flip::SrgbToLinear(0.04045), 0.04045 / 12.92, 1e-17);
  EXPECT_EQ(flip::SrgbToLinear(1.0), 1.0);
  EXPECT_EQ(flip::SrgbToLinear(-0.5), 0.0);  // clamped
  EXPECT_EQ(flip::SrgbToLinear(std::nan("")), 0.0);
}

TEST(FlipColor, YCxCzOfKnownColours) {
  using flip::LinearRgbToXyz;
  using flip::XyzToYCxCz;
  // Black: XYZ = 0 → Y = 116·0 − 16 = −16, Cx = Cz = 0 exactly.
  ExpectColorNear(XyzToYCxCz(LinearRgbToXyz({0, 0, 0})), {-16, 0, 0}, 0.0, "black");
  // White: XYZ = row sums of the matrix = (0.9504285454, 1, 1.0889003708) ≈ the white point
  // (0.950428545, 1, 1.088900371) to 4e-10, so (100, 0, 0) to 500·4e-10 = 2e-7.
  ExpectColorNear(XyzToYCxCz(LinearRgbToXyz({1, 1, 1})), {100, 0, 0}, 1e-6, "white");
  // Red: XYZ = first column = (10135552/24577794, 2613072/12288897, 1425312/73733382)
  // = (0.41238656, 0.21263682, 0.01933062); divided by the white: (0.43389539, 0.21263682,
  // 0.01775242). Y = 116·0.21263682 − 16 = 8.6658713; Cx = 500·(0.43389539 − 0.21263682)
  // = 110.629284; Cz = 200·(0.21263682 − 0.01775242) = 38.976880.
  ExpectColorNear(XyzToYCxCz(LinearRgbToXyz({1, 0, 0})), {8.6658713, 110.629284, 38.976880}, 2e-6, "red");
  // Round trips.
  const Color o = {37.5, -12.25, 20.0};
  ExpectColorNear(XyzToYCxCz(flip::YCxCzToXyz(o)), o, 1e-12, "YCxCz round trip");
  const Color rgb = {0.2, 0.7, 0.4};
  ExpectColorNear(flip::XyzToLinearRgb(LinearRgbToXyz(rgb)), rgb, 1e-15, "RGB round trip");
}

TEST(FlipColor, LabOfKnownColoursMatchesPublishedValues) {
  auto lab = [](Color rgb) { return flip::XyzToLab(flip::LinearRgbToXyz(rgb)); };
  ExpectColorNear(lab({0, 0, 0}), {0, 0, 0}, 0.0, "black");
  ExpectColorNear(lab({1, 1, 1}), {100, 0, 0}, 1e-6, "white");
  // Published CIELAB (D65) of the sRGB primaries (e.g. B. Lindbloom's CIE colour
  // calculator): red (53.2408, 80.0925, 67.2032), green (87.7347, −86.1827, 83.1793),
  // blue (32.2970, 79.1875, −107.8602). FLIP's RGB→XYZ matrix (image-engineering.de
  // rational form) differs in the 4th digit from Lindbloom's, so agreement is ≈ 0.006.
  ExpectColorNear(lab({1, 0, 0}), {53.2408, 80.0925, 67.2032}, 0.01, "red");
  ExpectColorNear(lab({0, 1, 0}), {87.7347, -86.1827, 83.1793}, 0.01, "green");
  ExpectColorNear(lab({0, 0, 1}), {32.2970, 79.1875, -107.8602}, 0.01, "blue");
}

TEST(FlipColor, HuntHyAbAndCmax) {
  // Hunt: a, b scaled by L/100.
  ExpectColorNear(flip::HuntAdjust({50, 10, 20}), {50, 5, 10}, 0.0, "hunt");
  // HyAB: |50 − 40| + sqrt(3² + 4²) = 10 + 5 = 15.
  EXPECT_DOUBLE_EQ(flip::HyAB({50, 10, 20}, {40, 13, 24}), 15.0);
  // cmax by hand from our Lab of green (87.73621, −86.17871, 83.18257) and blue
  // (32.29817, 79.19360, −107.85864): Hunt → green (87.73621, −75.60993, 72.98123),
  // blue (32.29817, 25.57808, −34.83637); HyAB = 55.43804 + sqrt(101.18801² + 107.81760²)
  // = 55.43804 + 147.86362 = 203.30165; ^0.7 = exp(0.7·ln 203.30165) = 41.27610.
  EXPECT_NEAR(flip::Cmax(), 41.2760984, 1e-6);
}

TEST(FlipColor, Remap) {
  const double cmax = flip::Cmax(), knee = 0.4 * cmax;
  EXPECT_EQ(flip::RemapColorError(0.0), 0.0);
  EXPECT_NEAR(flip::RemapColorError(0.5 * knee), 0.475, 1e-15);  // linear to 0.95 at the knee
  EXPECT_NEAR(flip::RemapColorError(knee), 0.95, 1e-15);
  EXPECT_NEAR(flip::RemapColorError(cmax), 1.0, 1e-15);
  EXPECT_NEAR(flip::RemapColorError(knee + 0.5 * (cmax - knee)), 0.975, 1e-15);
}

TEST(FlipKernels, RadiiAndNormalisation) {
  // CSF: ceil(3·sqrt(0.04/(2π²))·67) = ceil(9.0482) = 10. Features: σ = 0.5·0.082·67 =
  // 2.747, ceil(3σ) = ceil(8.241) = 9.
  EXPECT_EQ(flip::SpatialFilterRadius(67.0), 10);
  EXPECT_EQ(flip::FeatureFilterRadius(67.0), 9);
  const auto s = flip::MakeSpatialKernels(67.0);
  ASSERT_EQ(s.y.size(), 21u);
  auto sum = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); };
  EXPECT_NEAR(sum(s.y), 1.0, 1e-15);
  EXPECT_NEAR(sum(s.cx), 1.0, 1e-15);
  // 2-D Cz kernel cz1(x)cz1(y) + cz2(x)cz2(y) sums to (Σcz1)² + (Σcz2)² = 1.
  EXPECT_NEAR(sum(s.cz1) * sum(s.cz1) + sum(s.cz2) * sum(s.cz2), 1.0, 1e-15);
  // Relative weight of the two Cz Gaussians at the centre tap: their 2-D peaks are in the
  // ratio (34.1·sqrt(π/0.04)) : (13.5·sqrt(π/0.025)) = 302.21 : 151.33.
  EXPECT_NEAR((s.cz1[10] * s.cz1[10]) / (s.cz2[10] * s.cz2[10]),
              (34.1 * std::sqrt(M_PI / 0.04)) / (13.5 * std::sqrt(M_PI / 0.025)), 1e-12);
  const auto f = flip::MakeFeatureKernels(67.0);
  ASSERT_EQ(f.g.size(), 19u);
  double dpos = 0, dneg = 0, ddpos = 0, ddneg = 0;
  for (size_t i = 0; i < f.g.size(); ++i) {
    (f.dg[i] > 0 ? dpos : dneg) += f.dg[i];
    (f.ddg[i] > 0 ? ddpos : ddneg) += f.ddg[i];
  }
  EXPECT_NEAR(sum(f.g), 1.0, 1e-15);
  EXPECT_NEAR(dpos, 1.0, 1e-15);
  EXPECT_NEAR(dneg, -1.0, 1e-15);
  EXPECT_NEAR(ddpos, 1.0, 1e-15);
  EXPECT_NEAR(ddneg, -1.0, 1e-15);
}

// ---- Whole pipelines on tiny images ----

TEST(Flip, IdenticalImagesGiveExactlyZero) {
  const auto [a, b] = testimg::MakePair(23, 17, 5);
  for (double v : flip::ErrorValues(a, a, 67.0)) ASSERT_EQ(v, 0.0);
  for (double v : flip::ErrorValues(b, b, 30.0)) ASSERT_EQ(v, 0.0);
}

// Constant black vs constant white: a constant image passes the CSF filters unchanged (unit
// sum, replicated borders) and has no features, so ΔEf = 0 exactly and ΔE = ΔEc.
// By hand: Lab black (0,0,0), white (100,0,0); Hunt leaves both; HyAB = 100;
// 100^0.7 = 10^1.4 = 25.1188643; knee = 0.4·41.2760984 = 16.5104394 < 25.1188643, so
// ΔEc = 0.95 + (25.1188643 − 16.5104394)/(41.2760984 − 16.5104394)·0.05 = 0.9673798.
TEST(Flip, ConstantPairIsPureColourError) {
  for (auto [w, h] : {std::pair{4, 3}, std::pair{1, 1}, std::pair{1, 9}, std::pair{9, 1}}) {
    ImageF black(w, h, 3, 0.0f), white(w, h, 3, 1.0f);
    const auto feature = flip::FeatureErrorValues(black, white, 67.0);
    const auto color = flip::ColorErrorValues(black, white, 67.0);
    const auto full = flip::ErrorValues(black, white, 67.0);
    for (size_t i = 0; i < full.size(); ++i) {
      EXPECT_EQ(feature[i], 0.0);
      EXPECT_NEAR(color[i], 0.9673797615, 1e-9);
      // The production path computes in float32 (flip_fast.cpp): 0.9673798 to a few ulp.
      EXPECT_NEAR(full[i], 0.9673797615, 1e-6);
    }
  }
  // A chromatic pair: constant red vs constant blue, by hand from Lab (see LabOf...):
  // red (53.23688, 80.09347, 67.20052), blue (32.29817, 79.19360, −107.85864); Hunt:
  // red (53.23688, 42.63927, 35.77546), blue (32.29817, 25.57808, −34.83637).
  // HyAB = 20.93871 + sqrt(17.06118² + 70.61183²) = 20.93871 + 72.64374 = 93.58245;
  // ^0.7 = 23.97928 > knee → 0.95 + (23.97928 − 16.51044)/24.76566·0.05 = 0.9650790.
  ImageF red(5, 5, 3, 0.0f), blue(5, 5, 3, 0.0f);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) {
      red.At(x, y, 0) = 1.0f;
      blue.At(x, y, 2) = 1.0f;
    }
  for (double v : flip::ErrorValues(red, blue, 67.0)) EXPECT_NEAR(v, 0.9650790, 1e-7);
}

// Feature pipeline on a vertical step (Ŷ = 0 left of column c, 1 from c on; black/white)
// against a constant grey (no features at all). The image is constant along y, so dy = 0
// and the vertical Gaussian leaves dx unchanged. At x = c − 1 and x = c the first-derivative
// kernel sees only its negative taps on white: |dx| = 1 (they sum to −1). The point
// response there is |Σ_{i>0} ddg(i)| = 0.5/N with N = Σ_{|i|<σ} (1 − i²/σ²) g(i) (half the
// off-centre taps, which sum to −ddg(0) = 1/N), below 1. So ΔEf = (1/√2)^0.5 = 2^−1/4.
// One pixel further right, |dx| = 1 − g(1)/S with S = Σ_{i=1..R} i·g(i), and the point
// response is (0.5 + (1 − 1/σ²)·g(1))/N. Far from the step (> R pixels) ΔEf = 0 exactly.
TEST(Flip, FeaturePipelineOnAStepEdge) {
  const double ppd = 67.0, sigma = 0.5 * 0.082 * ppd;  // 2.747 px
  const int r = 9, w = 48, h = 3, c = 24;
  ImageF step(w, h, 3, 0.0f), grey(w, h, 3, 0.5f);
  for (int y = 0; y < h; ++y)
    for (int x = c; x < w; ++x)
      for (int k = 0; k < 3; ++k) step.At(x, y, k) = 1.0f;
  auto g = [&](double i) { return std::exp(-i * i / (2 * sigma * sigma)); };
  double S = 0, N = 0;
  for (int i = 1; i <= r; ++i) S += i * g(i);
  for (int i = -r; i <= r; ++i)
    if (std::abs(i) < sigma) N += (1 - i * i / (sigma * sigma)) * g(i);
  // N = 1 + 2·0.86748·0.93590 + 2·0.46993·0.76714 = 3.3447; S = 7.4442.
  EXPECT_NEAR(N, 3.3447, 1e-4);
  EXPECT_NEAR(S, 7.4442, 1e-4);
  const double at_step = std::pow(2.0, -0.25);  // 0.8408964
  const double next = std::sqrt(std::max(1 - g(1) / S, (0.5 + (1 - 1 / (sigma * sigma)) * g(1)) / N) /
                                std::sqrt(2.0));  // sqrt(0.87428/√2) = 0.78626
  const auto f = flip::FeatureErrorValues(step, grey, ppd);
  for (int y = 0; y < h; ++y) {
    EXPECT_NEAR(f[y * w + c - 1], at_step, 1e-14);
    EXPECT_NEAR(f[y * w + c], at_step, 1e-14);
    EXPECT_NEAR(f[y * w + c + 1], next, 1e-14);
    EXPECT_EQ(f[y * w + 0], 0.0);
    EXPECT_EQ(f[y * w + c - r - 2], 0.0);
    EXPECT_EQ(f[y * w + w - 1], 0.0);
  }
  // The same step in both images: no feature difference anywhere.
  for (double v : flip::FeatureErrorValues(step, step, ppd)) EXPECT_EQ(v, 0.0);
}

TEST(Flip, FinalErrorCombinesPipelines) {
  const auto [a, b] = testimg::MakePair(30, 22, 9);
  const auto color = flip::ColorErrorValues(a, b, 67.0);
  const auto feature = flip::FeatureErrorValues(a, b, 67.0);
  const auto full = flip::ErrorValues(a, b, 67.0);
  const ImageF map = FlipErrorMap(a, b, 67.0);
  ASSERT_EQ(map.Channels(), 1);
  const auto full_double = flip::ErrorValuesUncached(a, b, 67.0);
  double worst = 0.0;
  for (size_t i = 0; i < full.size(); ++i) {
    EXPECT_EQ(full_double[i], std::pow(color[i], 1.0 - feature[i]));
    // The production path is float32 (flip_fast.cpp); see FastPath.FlipFloatPathAgainstDouble
    // for the bound on real frames.
    worst = std::max(worst, std::abs(full[i] - full_double[i]));
    EXPECT_EQ(map.Data()[i], static_cast<float>(full[i]));
    EXPECT_GE(full[i], 0.0);
    EXPECT_LE(full[i], 1.0);
  }
  std::printf("FinalErrorCombinesPipelines: worst |float - double| %.3g\n", worst);
  EXPECT_LE(worst, 1e-5);
}

TEST(Flip, Pooling) {
  // Sorted 0.1, 0.2, 0.3, 0.4 (total 1.0): running sums 0.1, 0.3, 0.6 → first > 0.5 is 0.3.
  FlipPooled p = PoolFlip({0.4, 0.1, 0.3, 0.2});
  EXPECT_DOUBLE_EQ(p.mean, 0.25);
  EXPECT_EQ(p.weighted_median, 0.3);
  EXPECT_EQ(p.max, 0.4);
  // One hot pixel carries all the weight.
  p = PoolFlip({0.0, 0.0, 1.0, 0.0});
  EXPECT_EQ(p.weighted_median, 1.0);
  EXPECT_EQ(p.mean, 0.25);
  // All zero: defined as 0.
  p = PoolFlip({0.0, 0.0});
  EXPECT_EQ(p.weighted_median, 0.0);
  EXPECT_EQ(p.max, 0.0);
}

// The value-weighted median as PoolFlip's doc block defines it, written plainly: std::sort,
// the total in sorted order, then the first value whose running sum exceeds half of it.
double SortedWeightedMedian(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  double total = 0.0;
  for (double x : v) total += x;
  if (!(total > 0.0)) return 0.0;
  double running = 0.0;
  for (double x : v) {
    running += x;
    if (running > 0.5 * total) return x;
  }
  return 0.0;
}

// Deterministic pseudo-random floats in [0, 1) (a 64-bit LCG, top 24 bits).
std::vector<double> LcgFloats(size_t n, uint64_t seed, int levels = 0) {
  std::vector<double> v(n);
  uint64_t s = seed;
  for (auto& x : v) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u = static_cast<double>(s >> 40) / 16777216.0;
    x = levels > 0 ? std::floor(u * levels) / levels : u;
  }
  return v;
}

TEST(Flip, WeightedMedianEqualsTheSortBasedOneOnRandomAndAdversarialInputs) {
  std::vector<std::pair<std::string, std::vector<double>>> cases;
  // Several sort chunks (2^15 keys) and median blocks (4096): 200003 values.
  cases.emplace_back("uniform", LcgFloats(200003, 7));
  {  // FLIP-like: most pixels tiny, a few large (errors cube-shaped toward 0), floats.
    auto v = LcgFloats(150001, 11);
    for (auto& x : v) x = static_cast<double>(static_cast<float>(x * x * x * x));
    cases.emplace_back("skewed", v);
  }
  cases.emplace_back("ties (16 levels)", LcgFloats(100000, 3, 16));
  {  // exponents from 2^-126 up: every 11-bit digit of the key varies
    auto v = LcgFloats(70000, 5);
    for (size_t i = 0; i < v.size(); ++i)
      v[i] = std::ldexp(static_cast<double>(static_cast<float>(v[i])), -static_cast<int>(i % 120));
    cases.emplace_back("wide exponents", v);
  }
  cases.emplace_back("all equal", std::vector<double>(90000, 0.375));
  cases.emplace_back("all zero", std::vector<double>(50000, 0.0));
  {
    std::vector<double> v(80000, 0.0);
    v[123] = 0.25;
    cases.emplace_back("one non-zero", v);
  }
  {  // two values, the crossing exactly at a tie between them and at a block edge
    std::vector<double> v(8192, 0.5);
    for (size_t i = 0; i < 4096; ++i) v[i] = 0.25;
    cases.emplace_back("two levels", v);
  }
  {  // doubles that are not floats: the std::sort path
    auto v = LcgFloats(40000, 9);
    for (auto& x : v) x += 1e-12;
    cases.emplace_back("not floats", v);
  }
  cases.emplace_back("one value", std::vector<double>{0.7});
  for (const auto& [name, v] : cases) {
    const double expected = SortedWeightedMedian(v);
    // The mean and max as the doc block defines them: one plain pass in the given order.
    double sum = 0.0, max = v[0];
    for (double x : v) sum += x, max = std::max(max, x);
    const double mean = sum / static_cast<double>(v.size());
    for (int threads : {1, 2, 3}) {
      SetThreadCount(threads);
      const FlipPooled p = PoolFlip(v);
      EXPECT_EQ(p.weighted_median, expected) << name << ", " << threads << " threads";
      EXPECT_EQ(p.mean, mean) << name << ", " << threads << " threads";
      EXPECT_EQ(p.max, max) << name << ", " << threads << " threads";
    }
  }
  SetThreadCount(0);
  // Hand-worked: the two-levels case's total is 4096·0.25 + 4096·0.5 = 3072, half 1536; the
  // 0.25s sum to 1024, so the crossing is among the 0.5s.
  EXPECT_EQ(SortedWeightedMedian(cases[7].second), 0.5);
}

// ErrorValues' output is not zero-filled before the chunks write it: with the test poison on
// (every such buffer filled with 0xFF bytes, a NaN, or 0x00 first), the values must be the
// same bits as without it, at 1 and 2 threads, on a size of several 48-row chunks with a
// short last one (130x101: 3 chunks), so a pixel some chunk forgot would show.
TEST(Flip, ErrorValuesWriteEveryValue) {
  const auto [a, b] = testimg::MakePair(130, 101, 21);
  const auto side = flip::PrepareReference(a, 67.0);
  const FlipValues plain = flip::ErrorValues(*side, b);
  for (int threads : {1, 2}) {
    SetThreadCount(threads);
    for (int poison : {0xFF, 0x00}) {
      SetUninitializedPoison(poison);
      const FlipValues v = flip::ErrorValues(*side, b);
      SetUninitializedPoison(-1);
      ASSERT_EQ(v.size(), plain.size());
      EXPECT_EQ(std::memcmp(v.data(), plain.data(), v.size() * sizeof(double)), 0)
          << "poison " << poison << ", " << threads << " threads";
    }
  }
  SetThreadCount(0);
}

// flip_planes.cpp decodes a row whose every value is an exact 8-bit code (float(k) / 255) in
// vector lanes, and any other row per pixel. A 4-channel copy of the same image takes the
// per-pixel decode on every row: the two must give the same bits. The images are exact
// codes except three rows of the test image (a non-code value, one above 1, one below 0),
// and the reference's last row (a non-code value), so both paths run inside one image.
TEST(Flip, EightBitRowsInLanesEqualThePerPixelDecode) {
  const int w = 75, h = 58;  // a 16-lane block and a tail per row; two chunks (48 rows)
  ImageF a3(w, h, 3), b3(w, h, 3), a4(w, h, 4), b4(w, h, 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const int ka = (x * 7 + y * 3 + c * 50 + (x > 40 && y > 20 ? 90 : 0)) % 256;
        const int kb = std::clamp(ka + static_cast<int>((x * 13 + y * 5 + c) % 11) - 5, 0, 255);
        a3.At(x, y, c) = a4.At(x, y, c) = static_cast<float>(ka) / 255.0f;
        b3.At(x, y, c) = b4.At(x, y, c) = static_cast<float>(kb) / 255.0f;
      }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) a4.At(x, y, 3) = b4.At(x, y, 3) = 1.0f;
  b3.At(10, 5, 1) = b4.At(10, 5, 1) = 0.3f;     // not k/255 for any k
  b3.At(70, 30, 0) = b4.At(70, 30, 0) = 1.25f;  // above 1
  b3.At(3, 49, 2) = b4.At(3, 49, 2) = -0.1f;    // below 0
  a3.At(w - 1, h - 1, 0) = a4.At(w - 1, h - 1, 0) = 0.5f;
  for (int threads : {1, 2}) {
    SetThreadCount(threads);
    const FlipValues lanes = flip::ErrorValues(a3, b3, 67.0);
    const FlipValues per_pixel = flip::ErrorValues(a4, b4, 67.0);
    ASSERT_EQ(lanes.size(), per_pixel.size());
    EXPECT_EQ(std::memcmp(lanes.data(), per_pixel.data(), lanes.size() * sizeof(double)), 0) << threads << " threads";
    // and the image is not trivial: errors well above zero, and zero where nothing differs
    EXPECT_GT(*std::max_element(lanes.begin(), lanes.end()), 0.05);
  }
  SetThreadCount(0);
}

// flip_fast.cpp skips std::pow(e, 1 - ef) where ef = 0 and 0 <= e <= 1, returning e: this
// holds for the pow linked here on every float in [0, 1] (every value the skip takes).
TEST(Flip, PowOfOneIsTheValueOnEveryFloatInTheUnitInterval) {
  const uint32_t last = std::bit_cast<uint32_t>(1.0f);
  volatile float one_v = 1.0f;  // a run-time exponent, as in flip_fast.cpp (no constant folding)
  const float one = one_v;
  constexpr int kBlocks = 256;  // in parallel over blocks of bit patterns (ParallelFor)
  std::vector<uint32_t> wrong_in(kBlocks, 0), first_in(kBlocks, 0);
  ParallelFor(kBlocks, [&](int blk) {
    const uint64_t b0 = (uint64_t{last} + 1) * blk / kBlocks, b1 = (uint64_t{last} + 1) * (blk + 1) / kBlocks;
    for (uint64_t b = b0; b < b1; ++b) {
      const uint32_t bits = static_cast<uint32_t>(b);
      if (std::bit_cast<uint32_t>(std::pow(std::bit_cast<float>(bits), one)) != bits && wrong_in[blk]++ == 0) {
        first_in[blk] = bits;
      }
    }
  });
  uint32_t wrong = 0, first_wrong = 0;
  for (int blk = kBlocks - 1; blk >= 0; --blk) {
    wrong += wrong_in[blk];
    if (wrong_in[blk] > 0) first_wrong = first_in[blk];
  }
  EXPECT_EQ(wrong, 0u) << "first at bits 0x" << std::hex << first_wrong;
}

TEST(Flip, BadInputsAreUserErrors) {
  ImageF a(4, 4, 3), b(5, 4, 3), grey(4, 4, 1);
  EXPECT_THROW(FlipErrorMap(a, b), UserError);
  EXPECT_THROW(FlipErrorMap(grey, grey), UserError);
  EXPECT_THROW(FlipErrorMap(a, a, 0.0), UserError);
  EXPECT_THROW(FlipErrorMap(a, a, std::nan("")), UserError);
}

TEST(Flip, BitIdenticalAcrossThreadCounts) {
  const auto [a, b] = testimg::MakePair(130, 70, 4);
  SetThreadCount(1);
  const ImageF one = FlipErrorMap(a, b);
  const auto vone = flip::ErrorValues(a, b, 67.0);
  SetThreadCount(2);
  const ImageF two = FlipErrorMap(a, b);
  const auto vtwo = flip::ErrorValues(a, b, 67.0);
  SetThreadCount(0);
  EXPECT_TRUE(one == two);
  EXPECT_TRUE(vone == vtwo);
}

}  // namespace
}  // namespace aalab
