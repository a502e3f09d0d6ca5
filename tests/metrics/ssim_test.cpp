#include <gtest/gtest.h>

#include <cmath>

#include "harness/core/error.h"
#include "harness/core/parallel.h"
#include "metrics/ssim.h"
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

// Random ±d signs (zero mean, variance d²) on a constant μ. Within a window the sample
// variance estimates d²(1 − Σw²) on average (the weighted mean absorbs Σw² of it, with the
// 2-D Σw² = (Σ_i w_i²)² = 0.18813² = 0.035394), so the closed form uses
// σ² = d²(1 − 0.035394); the remaining spread of local variances (Jensen) and of local
// means moves the mean SSIM by a few 1e-5 here (naive σ² = d² would be off by 3%).
TEST(Ssim, RandomNoiseOnConstantNearClosedForm) {
  const double mu = 0.5, d = 0.0625;
  ImageF x(96, 96, 3, static_cast<float>(mu)), y(96, 96, 3);
  for (int j = 0; j < 96; ++j)
    for (int i = 0; i < 96; ++i)
      for (int c = 0; c < 3; ++c)
        y.At(i, j, c) = static_cast<float>(testimg::Hash32(i + 1000u * j + 77777u * c) & 1u ? mu + d : mu - d);
  const double var = d * d * (1.0 - 0.035394);
  const double expected = kC2 / (var + kC2);  // luminance term is 1 − O(1e-4) here
  EXPECT_NEAR(*ComputeSsim(x, y).ssim, expected, 1e-3);  // measured: 0.192858 vs 0.192802
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
