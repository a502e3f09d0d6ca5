#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "metrics/ssim.h"
#include "tests/metrics/ssim_bound.h"
#include "tests/metrics/test_images.h"

namespace aalab {
namespace {

constexpr double kC1 = 0.01 * 0.01;  // (K1·L)², L = 1
constexpr double kC2 = 0.03 * 0.03;  // (K2·L)²

TEST(Ssim, IdenticalIsExactlyOne) {
  const auto [a, b] = testimg::MakePair(40, 30, 7);
  EXPECT_EQ(*ComputeSsim(a, a).ssim, 1.0);
  EXPECT_EQ(*ComputeSsim(b, b).ssim, 1.0);
}

TEST(Ssim, Symmetric) {
  const auto [a, b] = testimg::MakePair(40, 30, 7);
  const double ab = *ComputeSsim(a, b).ssim, ba = *ComputeSsim(b, a).ssim;
  EXPECT_EQ(ab, ba);
  EXPECT_LT(ab, 1.0);
}

// x constant μx (σx = 0, σxy = 0); y = μy + checkerboard ±d. With the separable 11-tap
// window w (σ = 1.5), the local mean of the checkerboard is ±d·A², A = Σ (−1)^i w_i
// = 1.39e-4, so μy is exact to 2e-9·d and σy² = d²(1 − A⁴) = d² to 4e-16. Eq. (13) then
// reduces to the closed form (2μxμy + C1)/(μx² + μy² + C1) · C2/(σy² + C2).
// All pixel values (0.5, 0.375 ± 0.0625) are exact in float.
TEST(Ssim, CheckerboardNoiseOnConstantMatchesClosedForm) {
  const double mx = 0.5, my = 0.375, d = 0.0625;
  ImageF x(32, 24, 3, static_cast<float>(mx)), y(32, 24, 3);
  for (int j = 0; j < 24; ++j)
    for (int i = 0; i < 32; ++i)
      for (int c = 0; c < 3; ++c) y.At(i, j, c) = static_cast<float>((i + j) % 2 ? my + d : my - d);
  // (2·0.5·0.375 + 1e-4)/(0.25 + 0.140625 + 1e-4) = 0.3751/0.390725 = 0.96001024
  // · 0.0009/(0.00390625 + 0.0009) = 0.18725618  →  0.17976784
  const double expected = (2 * mx * my + kC1) / (mx * mx + my * my + kC1) * kC2 / (d * d + kC2);
  EXPECT_NEAR(expected, 0.17976784, 1e-8);
  EXPECT_NEAR(*ComputeSsim(x, y).ssim, expected, 1e-12);
  EXPECT_NEAR(*ComputeSsim(y, x).ssim, expected, 1e-12);
}

// Random ±d signs on a constant μ: x = μ, y = μ + d·ε with ε = ±1 per pixel and channel.
// In a window with weights w (Σw = 1) let S = Σ w_i ε_i. Then, exactly,
//   μy = μ + d·S,  σy² = Σ w_i (y_i − μy)² = d²·Σ w_i (ε_i − S)² = d²(1 − S²)  (ε_i² = 1),
//   σx² = σxy = 0,
// so Eq. (13) of each window is (2μ·μy + C1)/(μ² + μy² + C1) · C2/(d²(1 − S²) + C2), and SSIM
// is its mean over the valid windows and the three channels. The expected value below is
// computed that way: S from the signs and the separable Gaussian (σ = 1.5, 11 taps,
// normalised), no second moments at all — an independent route to the same number. The
// implementation forms σy² = E[y²] − μy² in double: |E[y²]| ≤ 0.33, so each moment is off by
// at most ~121·0.33·2⁻⁵³ ≈ 4.4e-15, σy² (≈ 0.0038) by ~1e-14, and a window's SSIM, whose
// derivative in σy² is at most C2/C2² ≈ 1.1e3 in size, by ~1e-11: tolerance 1e-10.
// (The closed form C2/(d²(1 − Σw²) + C2) = 0.192802 used before is the expectation over sign
// patterns to first order; this image's mean, 0.19286, differs from it by its sampling noise,
// which the 1e-3 tolerance of that check had to absorb.)
TEST(Ssim, RandomNoiseOnConstantIsEq13OfEachWindow) {
  const double mu = 0.5, d = 0.0625;
  const int n = 96;
  ImageF x(n, n, 3, static_cast<float>(mu)), y(n, n, 3);
  auto sign = [](int i, int j, int c) { return testimg::Hash32(i + 1000u * j + 77777u * c) & 1u ? 1.0 : -1.0; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) y.At(i, j, c) = static_cast<float>(mu + d * sign(i, j, c));
  double w[11], wsum = 0.0;
  for (int k = 0; k < 11; ++k) wsum += w[k] = std::exp(-((k - 5) * (k - 5)) / (2.0 * 1.5 * 1.5));
  for (double& v : w) v /= wsum;
  double total = 0.0;
  for (int c = 0; c < 3; ++c) {
    for (int cy = 5; cy < n - 5; ++cy) {
      for (int cx = 5; cx < n - 5; ++cx) {
        double S = 0.0;
        for (int b = 0; b < 11; ++b)
          for (int a = 0; a < 11; ++a) S += w[a] * w[b] * sign(cx - 5 + a, cy - 5 + b, c);
        const double my = mu + d * S;
        total += (2 * mu * my + kC1) / (mu * mu + my * my + kC1) * kC2 / (d * d * (1.0 - S * S) + kC2);
      }
    }
  }
  const double expected = total / (3.0 * (n - 10) * (n - 10));
  EXPECT_NEAR(*ComputeSsimReference(x, y).ssim, expected, 1e-10);
  EXPECT_NEAR(*ComputeSsimReference(y, x).ssim, expected, 1e-10);  // symmetric: σx² and σy² swap roles
  // The production path sums in float32 (metrics/ssim_float.cpp): within its derived bound,
  // averaged over the map and the channels (≈ 1.0e-5 here: Q ≈ d² against D ≈ d² + C2).
  double bound = 0.0;
  for (int c = 0; c < 3; ++c) bound += testssim::MeasureDrift(x, y, c).mean_bound / 3.0;
  EXPECT_LT(bound, 2e-5);
  EXPECT_NEAR(*ComputeSsim(x, y).ssim, expected, bound);
  EXPECT_EQ(*ComputeSsim(x, y).ssim, *ComputeSsim(y, x).ssim);
}

TEST(Ssim, MeanOfChannels) {
  const auto [a, b] = testimg::MakePair(24, 20, 3);
  ImageF only_r = a;  // differs from `a` in the red channel only
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 24; ++x) only_r.At(x, y, 0) = b.At(x, y, 0);
  const SsimResult r = ComputeSsim(a, only_r);
  EXPECT_EQ(r.per_channel[1], 1.0);
  EXPECT_EQ(r.per_channel[2], 1.0);
  EXPECT_LT(r.per_channel[0], 1.0);
  EXPECT_EQ(*r.ssim, (r.per_channel[0] + 1.0 + 1.0) / 3.0);
}

TEST(Ssim, WindowLargerThanImageIsNull) {
  for (auto [w, h] : {std::pair{10, 40}, std::pair{40, 10}, std::pair{1, 1}, std::pair{1, 50}}) {
    ImageF a(w, h, 3, 0.2f), b(w, h, 3, 0.7f);
    const SsimResult r = ComputeSsim(a, b);
    EXPECT_FALSE(r.ssim.has_value());
    EXPECT_EQ(r.null_reason, "image smaller than the 11x11 SSIM window");
  }
  // 11×11: exactly one valid pixel. Constant 1 vs 0: (C1·C2)/((1 + C1)·C2) = C1/(1 + C1).
  ImageF white(11, 11, 3, 1.0f), black(11, 11, 3, 0.0f);
  EXPECT_NEAR(*ComputeSsim(white, black).ssim, kC1 / (1.0 + kC1), 1e-15);
}

TEST(Ssim, ShapeMismatchIsUserError) {
  ImageF a(20, 20, 3), b(20, 21, 3);
  EXPECT_THROW(ComputeSsim(a, b), UserError);
}

TEST(Ssim, BitIdenticalAcrossThreadCounts) {
  const auto [a, b] = testimg::MakePair(160, 120, 11);
  SetThreadCount(1);
  const SsimResult one = ComputeSsim(a, b);
  SetThreadCount(2);
  const SsimResult two = ComputeSsim(a, b);
  SetThreadCount(0);
  EXPECT_EQ(*one.ssim, *two.ssim);
  EXPECT_EQ(one.per_channel, two.per_channel);
}

}  // namespace
}  // namespace aalab
