#include "harness/core/sampler.h"

#include <gtest/gtest.h>

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

TEST(Sampler, FloatImage) {
  ImageF img(2, 1, 3);
  img.At(1, 0, 0) = 1.0f;
  EXPECT_NEAR(SampleBilinear(img, 1.25f, 0.5f).r, 0.75f, 1e-6);
}

}  // namespace
}  // namespace aalab
