// CMAA2 (methods/cmaa2.h): the colour conversions and the R11G11B10 "E4" packing against
// values worked out by hand (IEEE half bit patterns, the sRGB formulas in double), a frame
// whose result follows from the shader by hand (a flat frame: only the four corners are
// candidates, because the shader's loads outside the frame return black), determinism at
// 1 and 2 threads, and the registry rows. The original shader itself: tests/oracle/cmaa2_oracle_test.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "methods/cmaa2.h"
#include "methods/registry.h"

namespace aalab {
namespace {

TEST(Cmaa2, SrgbConversionsMatchTheFormulas) {
  EXPECT_EQ(Cmaa2SrgbToLinear(0), 0.0f);
  EXPECT_EQ(Cmaa2SrgbToLinear(255), 1.0f);
  // 10/255 is on the linear segment: /12.92; 128 and 188 on the power segment (python, double).
  EXPECT_EQ(Cmaa2SrgbToLinear(10), static_cast<float>(0.003035269835488375));
  EXPECT_EQ(Cmaa2SrgbToLinear(128), static_cast<float>(0.21586050011389926));
  EXPECT_EQ(Cmaa2SrgbToLinear(188), static_cast<float>(0.5028864580325687));
  EXPECT_NEAR(Cmaa2LinearToSrgb(0.5f), 0.7353569830524495, 2e-7);
  EXPECT_FLOAT_EQ(Cmaa2LinearToSrgb(0.002f), 0.002f * 12.92f);  // below 0.0031308: linear
}

TEST(Cmaa2, PackingKeepsSevenAndSixMantissaBits) {
  // 1.0 = half 0x3C00: exact in every channel.
  EXPECT_EQ(Cmaa2PackUnpack({1.0f, 1.0f, 1.0f}), (std::array<float, 3>{1.0f, 1.0f, 1.0f}));
  // 0.31 = half 0x34F6 (1.2402 x 2^-2, mantissa 246). r, g: (0x34F6 + 4) >> 3 = 0x69F -> 0x34F8
  // = 0.310546875; b: (0x34F6 + 8) >> 4 = 0x34F -> 0x34F0 = 0.30859375.
  EXPECT_EQ(Cmaa2PackUnpack({0.31f, 0.31f, 0.31f}), (std::array<float, 3>{0.310546875f, 0.310546875f, 0.30859375f}));
  // Clamped to [0, 2): negative -> 0.
  EXPECT_EQ(Cmaa2PackUnpack({-0.5f, 0.0f, 0.0f}), (std::array<float, 3>{0.0f, 0.0f, 0.0f}));
}

// The value the packing gives for v in [0.25, 0.5), worked out without the port: f32tof16
// rounds to the half's 10 mantissa bits (nearest), then "+ 4 >> 3" (r, g: 7 bits kept) or
// "+ 8 >> 4" (b: 6 bits) rounds those half up: two roundings (0.369 in blue: 487.55 -> 488
// -> 30.5 -> 31 sixty-fourths, where one rounding would give 30).
double Quantize(double v, int bits) {
  const double unit = 0.25 / 1024;  // one step of the half's mantissa in [0.25, 0.5)
  const double m10 = std::floor(v / unit + 0.5);
  const double k = static_cast<double>(1 << (10 - bits));
  return std::floor((m10 + k / 2) / k) * k * unit;
}
uint8_t Srgb8(double lin) {
  const double s = lin < 0.0031308 ? lin * 12.92 : 1.055 * std::pow(lin, 1.0 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::floor(s * 255.0 + 0.5));
}

TEST(Cmaa2, FlatFrameChangesOnlyTheCornersAgainstTheBlackOutside) {
  // A flat 7x5 frame. Outside the frame the shader's loads return 0, so each border has an
  // edge; only a corner pixel has two edges meeting (a candidate). Its simple shape: two
  // edges -> blur 0.10·0.75 = 0.075 from each of the two outside neighbours (black); edges
  // all around = 2 -> saturate(1.3 − 2/10) = 1; no Z shape. Its one sample, weight 0.8, is
  // the colour times 1 − 2·0.075 = 0.85, packed to 7/7/6 mantissa bits.
  const uint8_t code[3] = {188, 200, 176};
  Image8 in(7, 5, 4);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      for (int c = 0; c < 3; ++c) in.Pixel(x, y)[c] = code[c];
      in.Pixel(x, y)[3] = 255;
    }
  }
  Cmaa2Stats stats;
  const Image8 out = Cmaa2(in, Cmaa2Params{}, &stats);
  EXPECT_EQ(stats.candidates, 4u);
  EXPECT_EQ(stats.z_shapes, 0u);
  EXPECT_EQ(stats.pixels_written, 4u);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      const bool corner = (x == 0 || x == 6) && (y == 0 || y == 4);
      for (int c = 0; c < 3; ++c) {
        const double lin = std::pow((code[c] / 255.0 + 0.055) / 1.055, 2.4) * 0.85;
        const uint8_t want = corner ? Srgb8(Quantize(lin, c == 2 ? 6 : 7)) : code[c];
        EXPECT_EQ(out.Pixel(x, y)[c], want) << "(" << x << "," << y << ") channel " << c;
      }
      EXPECT_EQ(out.Pixel(x, y)[3], 255);
    }
  }
}

Image8 Pattern(int w, int h) {
  // Hard-edged shapes: a slanted edge, a disc and a 1-px grid corner, in colour.
  Image8 img(w, h, 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const bool a = y * 7 > x * 2 + 10,
                 b = (x - 40) * (x - 40) + (y - 20) * (y - 20)<150, g = x> 60 && (x + y) % 2 == 0;
      uint8_t* p = img.Pixel(x, y);
      p[0] = a ? 230 : 20;
      p[1] = b ? 40 : (g ? 250 : 120);
      p[2] = a != b ? 200 : 30;
      p[3] = 255;
    }
  }
  return img;
}

TEST(Cmaa2, SameBytesAtOneAndTwoThreads) {
  const Image8 in = Pattern(83, 45);
  for (int preset = 0; preset < 4; ++preset) {
    Cmaa2Params p;
    p.preset = preset;
    SetThreadCount(1);
    const Image8 one = Cmaa2(in, p);
    SetThreadCount(2);
    const Image8 two = Cmaa2(in, p);
    SetThreadCount(0);
    EXPECT_EQ(one.Data(), two.Data()) << "preset " << preset;
    EXPECT_NE(one.Data(), in.Data()) << "preset " << preset << " changed nothing";
  }
}

TEST(Cmaa2, LowerThresholdsChangeMorePixels) {
  const Image8 in = Pattern(83, 45);
  uint64_t last = 0;
  for (int preset = 0; preset < 4; ++preset) {
    Cmaa2Params p;
    p.preset = preset;
    Cmaa2Stats s;
    Cmaa2(in, p, &s);
    EXPECT_GE(s.candidates, last) << "preset " << preset;
    last = s.candidates;
  }
}

TEST(Cmaa2, RegistryRowsAndParameters) {
  const MethodPlan high = MakeMethod("cmaa2-high");
  ASSERT_NE(high.Config<Cmaa2Params>(), nullptr);
  EXPECT_EQ(high.Config<Cmaa2Params>()->preset, 2);
  EXPECT_TRUE(high.in_default_list);
  EXPECT_TRUE(high.IsPostOnly());
  const MethodPlan sharp = MakeMethod("cmaa2-low:extra_sharpness=1,edges=color");
  EXPECT_EQ(sharp.Config<Cmaa2Params>()->preset, 0);
  EXPECT_TRUE(sharp.Config<Cmaa2Params>()->extra_sharpness);
  EXPECT_TRUE(sharp.Config<Cmaa2Params>()->color_edges);
  EXPECT_FALSE(MakeMethod("cmaa2-ultra").in_default_list);
  EXPECT_THROW(MakeMethod("cmaa2-high:extra_sharpness=2"), UserError);
  EXPECT_THROW(MakeMethod("cmaa2-high:edges=rgb"), UserError);
}

}  // namespace
}  // namespace aalab
