#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "metrics/metric.h"

namespace aalab {
namespace {

TEST(Psnr, ConstantOffset) {
  // A constant offset d on every channel gives MSE d² and PSNR −20·log10(d).
  // Offsets are powers of two so that 0.25 + d is exact in float32.
  for (float d : {0.5f, 0.125f, 0.0078125f}) {
    ImageF a(7, 5, 3, 0.25f), b(7, 5, 3, 0.25f + d);
    const auto r = MeanSquaredError(a, b);
    EXPECT_DOUBLE_EQ(r.mse, static_cast<double>(d) * d);
    EXPECT_NEAR(*PsnrFromMse(r.mse), -20.0 * std::log10(static_cast<double>(d)), 1e-9);
  }
}

TEST(Psnr, HandComputedMixedError) {
  // 2 pixels: errors (0.1, 0.2, 0.3) and (0, 0, 0). MSE = (0.01+0.04+0.09)/3/2 = 0.02333...
  ImageF a(2, 1, 3, 0.0f), b(2, 1, 3, 0.0f);
  b.At(0, 0, 0) = 0.1f;
  b.At(0, 0, 1) = 0.2f;
  b.At(0, 0, 2) = 0.3f;
  const auto r = MeanSquaredError(a, b);
  EXPECT_NEAR(r.mse, 0.14 / 6.0, 1e-8);
  EXPECT_NEAR(*PsnrFromMse(r.mse), 10.0 * std::log10(6.0 / 0.14), 1e-5);
}

TEST(Psnr, IdenticalIsNullAndSymmetric) {
  ImageF a(3, 3, 3, 0.5f);
  EXPECT_FALSE(PsnrFromMse(MeanSquaredError(a, a).mse).has_value());
  ImageF b(3, 3, 3, 0.2f);
  b.At(1, 1, 0) = 0.9f;
  EXPECT_EQ(MeanSquaredError(a, b).mse, MeanSquaredError(b, a).mse);
}

TEST(Psnr, MaskSelectsPixels) {
  ImageF a(2, 1, 3, 0.0f), b(2, 1, 3, 0.0f), mask(2, 1, 1, 0.0f);
  b.At(1, 0, 0) = 0.3f;
  b.At(1, 0, 1) = 0.3f;
  b.At(1, 0, 2) = 0.3f;
  mask.At(1, 0, 0) = 1.0f;
  auto on = MeanSquaredError(a, b, &mask, false);
  auto off = MeanSquaredError(a, b, &mask, true);
  EXPECT_EQ(on.pixels, 1u);
  EXPECT_NEAR(on.mse, 0.09, 1e-7);
  EXPECT_EQ(off.pixels, 1u);
  EXPECT_EQ(off.mse, 0.0);
}

TEST(Psnr, ShapeMismatchIsUserError) {
  ImageF a(2, 2, 3), b(3, 2, 3);
  EXPECT_THROW(RequireSameShape(a, b, "pair"), UserError);
}

}  // namespace
}  // namespace aalab
