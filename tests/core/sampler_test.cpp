#include "core/sampler.h"

#include <gtest/gtest.h>

#include <cmath>

namespace aalab {
namespace {

Image8 Ramp2x2() {
  Image8 img(2, 2, 4, 255);
  // texel (0,0)=0, (1,0)=100, (0,1)=200, (1,1)=50 in every colour channel
  const uint8_t v[4] = {0, 100, 200, 50};
  for (int i = 0; i < 4; ++i) {
    for (int c = 0; c < 3; ++c) img.At(i % 2, i / 2, c) = v[i];
  }
  return img;
}

TEST(Sampler, TexelCentresAreExact) {
  Image8 img = Ramp2x2();
  BilinearSampler s(img);
  EXPECT_FLOAT_EQ(s.Sample(0.5f, 0.5f).r, 0.0f);
  EXPECT_FLOAT_EQ(s.Sample(1.5f, 0.5f).r, 100.0f / 255.0f);
  EXPECT_FLOAT_EQ(s.Sample(0.5f, 1.5f).g, 200.0f / 255.0f);
  EXPECT_FLOAT_EQ(s.Texel(1, 1).b, 50.0f / 255.0f);
  EXPECT_FLOAT_EQ(s.Sample(1.5f, 1.5f).a, 1.0f);
}

TEST(Sampler, MidpointAveragesFourTexels) {
  Image8 img = Ramp2x2();
  BilinearSampler s(img);
  // At the shared corner (1, 1) all four weights are 1/4: (0+100+200+50)/4 = 87.5.
  EXPECT_NEAR(s.Sample(1.0f, 1.0f).r, 87.5f / 255.0f, 1e-6);
  // Halfway between (0,0) and (1,0): 50.
  EXPECT_NEAR(s.Sample(1.0f, 0.5f).r, 50.0f / 255.0f, 1e-6);
  // A quarter of the way: 25.
  EXPECT_NEAR(s.Sample(0.75f, 0.5f).r, 25.0f / 255.0f, 1e-6);
}

TEST(Sampler, ClampToEdge) {
  Image8 img = Ramp2x2();
  BilinearSampler s(img);
  // Outside the image the border texels repeat.
  EXPECT_FLOAT_EQ(s.Sample(-5.0f, 0.5f).r, 0.0f);
  EXPECT_FLOAT_EQ(s.Sample(10.0f, 0.5f).r, 100.0f / 255.0f);
  EXPECT_FLOAT_EQ(s.Sample(0.0f, 0.0f).r, 0.0f);  // corner: all four clamped to texel (0,0)
  EXPECT_FLOAT_EQ(s.Texel(-1, 5).r, 200.0f / 255.0f);
}

TEST(Sampler, NormalizedAndTaps) {
  Image8 img = Ramp2x2();
  BilinearSampler s(img);
  EXPECT_FLOAT_EQ(s.SampleNormalized(0.75f, 0.25f).r, 100.0f / 255.0f);
  s.Texel(0, 0);
  EXPECT_EQ(s.Taps(), 2u);
}

TEST(Sampler, UnormReadIsTimesRoundedReciprocal) {
  // llvmpipe converts UNORM8 texels as k · fl(1/255) (one float multiply), which is not
  // k / 255 correctly rounded for every k: e.g. 3 · fl(1/255) rounds up past 3/255.
  int differ = 0;
  for (int k = 0; k < 256; ++k) {
    const float expected = static_cast<float>(k) * (1.0f / 255.0f);
    EXPECT_EQ(UnormToFloat(static_cast<uint8_t>(k)), expected);
    differ += expected != static_cast<float>(k) / 255.0f;
  }
  EXPECT_GT(differ, 0);
  EXPECT_EQ(UnormToFloat(0), 0.0f);
  EXPECT_EQ(UnormToFloat(255), 1.0f);
}

TEST(Sampler, StoreRoundsHalfToEven) {
  // Where v·255 is exactly k + 0.5 in float, GL (llvmpipe) stores the even neighbour.
  int ties = 0;
  for (int k = 0; k < 255; ++k) {
    const float v = (static_cast<float>(k) + 0.5f) / 255.0f;
    if (v * 255.0f != static_cast<float>(k) + 0.5f) continue;
    ++ties;
    EXPECT_EQ(StoreUnorm8(v), (k % 2 == 0) ? k : k + 1) << k;
  }
  EXPECT_GT(ties, 10);
  EXPECT_EQ(StoreUnorm8(-0.25f), 0);
  EXPECT_EQ(StoreUnorm8(1.5f), 255);
  EXPECT_EQ(StoreUnorm8(std::nanf("")), 0);
}

TEST(Sampler, ClampToEdgeIsExactAtAnyFraction) {
  // Between the border texel and its clamped copy the filter must return the texel itself
  // (lerp(a, a, f) = a for every f); a sum of weighted copies need not.
  Image8 img = Ramp2x2();
  BilinearSampler s(img);
  for (int i = 0; i <= 64; ++i) {
    const float u = 0.5f * static_cast<float>(i) / 64.0f;  // left of texel 0's centre
    EXPECT_EQ(s.Sample(u, 1.5f).r, UnormToFloat(200)) << u;
    EXPECT_EQ(s.Sample(1.5f + u, 0.5f).r, UnormToFloat(100)) << u;  // right of the last
  }
}

TEST(Sampler, LerpOrderOfTheFilter) {
  // lerp(lerp(a, b, fx), lerp(c, d, fx), fy) with lerp(p, q, w) = p + w·(q − p).
  Image8 img = Ramp2x2();
  BilinearSampler s(img);
  const float fx = 0.3f, fy = 0.7f;
  const float a = UnormToFloat(0), b = UnormToFloat(100), c = UnormToFloat(200), d = UnormToFloat(50);
  const float top = a + fx * (b - a), bottom = c + fx * (d - c);
  EXPECT_EQ(s.Sample(0.5f + fx, 0.5f + fy).r, top + fy * (bottom - top));
}

TEST(Sampler, OffsetSamplesAddTheOffsetInTexelSpace) {
  // textureLodOffset: at a texel centre of a power-of-two frame the offset tap is the texel.
  Image8 img(4, 4, 4);
  for (int i = 0; i < 64; ++i) img.Data()[static_cast<size_t>(i)] = static_cast<uint8_t>(i * 4);
  BilinearSampler s(img);
  EXPECT_EQ(s.SampleNormalizedOffset(1.5f / 4, 2.5f / 4, 1, -1).g, s.Texel(2, 1).g);
  EXPECT_EQ(s.SampleNormalizedOffset(0.5f / 4, 0.5f / 4, -1, -1).b, s.Texel(0, 0).b);  // clamped
  // Half a texel right of a centre: the midpoint of the two offset texels.
  const float m = s.SampleNormalizedOffset(2.0f / 4, 1.5f / 4, 1, 0).r;
  EXPECT_EQ(m, s.Texel(2, 1).r + 0.5f * (s.Texel(3, 1).r - s.Texel(2, 1).r));
}

TEST(Sampler, FloatImage) {
  ImageF img(2, 1, 3);
  img.At(1, 0, 0) = 1.0f;
  EXPECT_NEAR(SampleBilinear(img, 1.25f, 0.5f).r, 0.75f, 1e-6);
}

}  // namespace
}  // namespace aalab
