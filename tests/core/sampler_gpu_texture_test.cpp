// The texture unit's arithmetic (SamplerArithmetic::kGpuTexture, core/sampler.h)
// against values worked out by hand from the rule the H100 probe found (docs/gpu.md), and
// the default arithmetic left as it was.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/sampler.h"

namespace aalab {
namespace {

// A w×1 RGBA8 texture whose red channel holds `codes` (other channels 0, alpha 255).
Image8 Row(std::initializer_list<int> codes) {
  Image8 img(static_cast<int>(codes.size()), 1, 4, 255);
  int x = 0;
  for (int k : codes) {
    img.At(x, 0, 0) = static_cast<uint8_t>(k);
    img.At(x, 0, 1) = img.At(x, 0, 2) = 0;
    ++x;
  }
  return img;
}

// q/65535 as the nearest float: written out as a double quotient (exact to 2^-53 relative,
// far inside the float's half-ulp), then rounded once.
float Q16(int q) { return static_cast<float>(q / 65535.0); }

TEST(GpuTextureSampler, TexelsAreCorrectlyRoundedK255) {
  int differ_from_gl = 0;
  for (int k = 0; k < 256; ++k) {
    const float v = HwUnorm8ToFloat(static_cast<uint8_t>(k));
    const long double exact = static_cast<long double>(k) / 255.0L;
    // Nearest float: no float strictly closer than v.
    const float up = std::nextafter(v, 2.0f), down = std::nextafter(v, -1.0f);
    EXPECT_LE(std::fabs(static_cast<long double>(v) - exact), std::fabs(static_cast<long double>(up) - exact)) << k;
    EXPECT_LE(std::fabs(static_cast<long double>(v) - exact), std::fabs(static_cast<long double>(down) - exact)) << k;
    if (v != UnormToFloat(static_cast<uint8_t>(k))) ++differ_from_gl;
    EXPECT_EQ(TexelValue(static_cast<uint8_t>(k), SamplerArithmetic::kGl), UnormToFloat(static_cast<uint8_t>(k)));
    EXPECT_EQ(TexelValue(static_cast<uint8_t>(k), SamplerArithmetic::kGpuTexture), v);
  }
  EXPECT_EQ(differ_from_gl, 126);  // k·fl(1/255) vs k/255: the count docs/gpu.md gives
  EXPECT_EQ(HwUnorm8ToFloat(0), 0.0f);
  EXPECT_EQ(HwUnorm8ToFloat(255), 1.0f);
}

TEST(GpuTextureSampler, HalfTexelBetweenCodesRoundsHalfUpIn16Bits) {
  // Halfway between codes a and b: S = 128·a + 128·b; the 16-bit value is (a + b)/2 · 257,
  // i.e. 128.5 for (0, 1) → 129 (ties upwards); 385.5 for (1, 2) → 386; 257 for (0, 2).
  const Image8 img = Row({0, 1, 2, 0, 2});
  BilinearSampler s(img, SubTexel::kExact, SamplerArithmetic::kGpuTexture);
  EXPECT_EQ(s.Sample(1.0f, 0.5f).r, Q16(129));
  EXPECT_EQ(s.Sample(2.0f, 0.5f).r, Q16(386));
  EXPECT_EQ(s.Sample(4.0f, 0.5f).r, HwUnorm8ToFloat(1));
  // The GL arithmetic gives 0.5·fl(1/255) for (0, 1), which is not 129/65535.
  BilinearSampler gl(img);
  EXPECT_NE(gl.Sample(1.0f, 0.5f).r, Q16(129));
  EXPECT_EQ(s.Taps(), 3u);
}

TEST(GpuTextureSampler, FractionOfOneThirdQuantisesTo85Over256) {
  // u − 0.5 = 1/3 (as a float): 1/3·256 = 85.33 → 85. Between codes 0 and 255 the value is
  // 85·255·257/256 = 21760.08 → 21760 (of 65535).
  const HwFootprint f = HwFootprintAt(0.5f + 1.0f / 3.0f, 0.5, 2, 1);
  EXPECT_EQ(f.x0, 0);
  EXPECT_EQ(f.kx, 85);
  EXPECT_EQ(f.ky, 0);
  const Image8 img = Row({0, 255});
  BilinearSampler s(img, SubTexel::kExact, SamplerArithmetic::kGpuTexture);
  EXPECT_EQ(s.Sample(0.5f + 1.0f / 3.0f, 0.5f).r, Q16(21760));
}

TEST(GpuTextureSampler, CoordinateTiesRoundUpwardsAlsoBelowZero) {
  // (u − 0.5)·256 = 0.5 → 1; −0.5 → 0; −1.5 → −1, i.e. texel −1 with fraction 255/256.
  HwFootprint f = HwFootprintAt(0.5 + 1.0 / 512.0, 0.5, 4, 4);
  EXPECT_EQ(f.x0, 0);
  EXPECT_EQ(f.kx, 1);
  f = HwFootprintAt(0.5 - 1.0 / 512.0, 0.5, 4, 4);
  EXPECT_EQ(f.x0, 0);
  EXPECT_EQ(f.kx, 0);
  f = HwFootprintAt(0.5 - 3.0 / 512.0, 0.5, 4, 4);
  EXPECT_EQ(f.x0, -1);
  EXPECT_EQ(f.kx, 255);
  // Just below a tie rounds down: (u − 0.5)·256 = 1.5 − 2^-14 → 1.
  f = HwFootprintAt(0.5 + 1.5 / 256.0 - 1.0 / 4194304.0, 0.5, 4, 4);
  EXPECT_EQ(f.kx, 1);
  // 255.5/256 rounds up to a whole texel: the next texel with fraction 0.
  f = HwFootprintAt(0.5 + 255.5 / 256.0, 1.5, 4, 4);
  EXPECT_EQ(f.x0, 1);
  EXPECT_EQ(f.kx, 0);
  EXPECT_EQ(f.y0, 1);
  // Far outside and NaN stay in range (the reads clamp to the edge anyway).
  f = HwFootprintAt(-1e9, std::nan(""), 4, 4);
  EXPECT_EQ(f.x0, -1);
  EXPECT_EQ(f.y0, -1);  // NaN reads as 0: (0 − 0.5)·256 = −128 → texel −1, fraction 128
  EXPECT_EQ(f.ky, 128);
  f = HwFootprintAt(1e9, 2.0, 4, 4);
  EXPECT_EQ(f.x0, 4);
}

TEST(GpuTextureSampler, NormalisedCoordinatesAreTruncatedTo21Bits) {
  // s = 5e-5 (float 4.99999987e-5) on a 1920-texel axis: s·2^21 = 104.86 → 104, so
  // u = 104·1920/2^21 = 0.09521484375, (u − 0.5)·256 = −103.625 → −103.125 → floor −104:
  // texel −1, fraction 152. The exact product 0.096 would give −102.92 → −103 → fraction 153.
  const HwFootprint f = HwFootprintNormalized(5e-5f, 0.5f, 1920, 1);
  EXPECT_EQ(f.x0, -1);
  EXPECT_EQ(f.kx, 152);
  EXPECT_EQ(HwFootprintAt(5e-5 * 1920.0, 0.5, 1920, 1).kx, 153);
  // On a power-of-two size the truncation changes nothing: s = 0.3 on 16 texels.
  const HwFootprint g = HwFootprintNormalized(0.3f, 0.5f, 16, 1);
  const HwFootprint h = HwFootprintAt(static_cast<double>(0.3f) * 16.0, 0.5, 16, 1);
  EXPECT_EQ(g.x0, h.x0);
  EXPECT_EQ(g.kx, h.kx);
}

TEST(GpuTextureSampler, QuadWeightsRoundTheCornerProduct) {
  // d = round(kx·ky/256) ties up, b = kx − d, c = ky − d, a = 256 − kx − ky + d.
  HwWeights w = HwWeightsOf(1, 43);  // 43/256 = 0.17 → 0
  EXPECT_EQ(w.a, 212);
  EXPECT_EQ(w.b, 1);
  EXPECT_EQ(w.c, 43);
  EXPECT_EQ(w.d, 0);
  w = HwWeightsOf(3, 127);  // 381/256 = 1.49 → 1
  EXPECT_EQ(w.a, 127);
  EXPECT_EQ(w.b, 2);
  EXPECT_EQ(w.c, 126);
  EXPECT_EQ(w.d, 1);
  w = HwWeightsOf(1, 128);  // 128/256 = 0.5 → 1 (tie upwards)
  EXPECT_EQ(w.d, 1);
  EXPECT_EQ(w.b, 0);
  EXPECT_EQ(w.a + w.b + w.c + w.d, 256);
  // A 2×2 fetch at the shared corner of codes 0, 100, 200, 50: weights 64 each, S = 64·350 =
  // 22400, and 257·22400/256 = 22487.5 exactly, a tie: q = 22488.
  Image8 img(2, 2, 4, 255);
  const int v[4] = {0, 100, 200, 50};
  for (int i = 0; i < 4; ++i) img.At(i % 2, i / 2, 0) = static_cast<uint8_t>(v[i]);
  BilinearSampler s(img, SubTexel::kExact, SamplerArithmetic::kGpuTexture);
  EXPECT_EQ(s.Sample(1.0f, 1.0f).r, Q16(22488));
  EXPECT_EQ(s.SampleNormalized(0.5f, 0.5f).r, Q16(22488));
  EXPECT_EQ(s.Texel(1, 0).r, HwUnorm8ToFloat(100));
}

TEST(GpuTextureSampler, FloatFilterRoundsTiesUpwards) {
  // Halfway between 1 and the next float 1 + 2^-23: exactly 1 + 2^-24, a tie; the texture
  // unit rounds it up (round-to-nearest-even would give 1).
  const float a = 1.0f, b = std::nextafter(1.0f, 2.0f);
  const HwWeights half = HwWeightsOf(128, 0);
  EXPECT_EQ(HwFilterFloat(a, b, a, b, half), b);
  // Not a tie: a quarter of the way rounds to nearest, 1 + 2^-25 → 1.
  EXPECT_EQ(HwFilterFloat(a, b, a, b, HwWeightsOf(64, 0)), a);
  // Weights 0: the texel itself.
  EXPECT_EQ(HwFilterFloat(0.3f, 0.7f, 0.1f, 0.9f, HwWeightsOf(0, 0)), 0.3f);
}

TEST(GpuTextureSampler, Names) {
  EXPECT_EQ(ParseSamplerArithmetic("gl"), SamplerArithmetic::kGl);
  EXPECT_EQ(ParseSamplerArithmetic("gpu-texture"), SamplerArithmetic::kGpuTexture);
  EXPECT_STREQ(SamplerArithmeticName(SamplerArithmetic::kGpuTexture), "gpu-texture");
  EXPECT_THROW(ParseSamplerArithmetic("hw"), UserError);
}

}  // namespace
}  // namespace aalab
