// FSR 1 (methods/fsr1.h) on hand-worked values: ffx_a.h's bit-trick approximations, the
// constants FsrEasuCon / FsrRcasCon write, EASU's behaviour on flat and stepped frames, and
// RCAS against its formula as ffx_fsr1.h's comment states it, evaluated here in double.
// The bit-for-bit comparison with the original shader is tests/oracle/fsr1_oracle_test.cpp.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "core/error.h"
#include "methods/fsr1.h"
#include "methods/registry.h"

namespace aalab {
namespace {

Image8 Fill(int w, int h, uint8_t (*f)(int x, int y, int c)) {
  Image8 img(w, h, 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) img.Pixel(x, y)[c] = f(x, y, c);
      img.Pixel(x, y)[3] = 255;
    }
  }
  return img;
}

TEST(Fsr1, ApproximationsAreTheBitTricks) {
  // bits(1.0f) = 0x3f800000; 0x7ef07ebb - 0x3f800000 = 0x3f707ebb.
  EXPECT_EQ(std::bit_cast<uint32_t>(Fsr1PrxLoRcp(1.0f)), 0x3f707ebbu);
  // bits(4.0f) = 0x40800000, >> 1 = 0x20400000; 0x5f347d74 - 0x20400000 = 0x3ef47d74 (~0.477, 1/sqrt(4) = 0.5).
  EXPECT_EQ(std::bit_cast<uint32_t>(Fsr1PrxLoRsq(4.0f)), 0x3ef47d74u);
  // Medium rcp of 2: b = bits 0x7ef19fff - 0x40000000 = 0x3ef19fff (0.47192), b·(2 − 2b).
  const float b = std::bit_cast<float>(0x3ef19fffu);
  EXPECT_EQ(Fsr1PrxMedRcp(2.0f), b * (-b * 2.0f + 2.0f));
  EXPECT_NEAR(Fsr1PrxMedRcp(2.0f), 0.49842342734336853, 1e-7);  // 0.3 % low: one Newton step
  // The low rcp of 0 is finite (bits 0x7ef07ebb), as in the shader.
  EXPECT_TRUE(std::isfinite(Fsr1PrxLoRcp(0.0f)));
}

TEST(Fsr1, EasuConstantsForA360x270To480x360Upscale) {
  const Fsr1EasuConst k = Fsr1EasuCon(360.0f, 270.0f, 480.0f, 360.0f);
  auto f = [](uint32_t u) { return std::bit_cast<float>(u); };
  EXPECT_EQ(f(k.con0[0]), 360.0f * (1.0f / 480.0f));  // ~0.75
  EXPECT_NEAR(f(k.con0[0]), 0.75, 1e-7);
  EXPECT_NEAR(f(k.con0[2]), 0.5 * 0.75 - 0.5, 1e-7);  // -0.125: output centre -> input texel
  EXPECT_NEAR(f(k.con0[3]), 0.5 * 0.75 - 0.5, 1e-7);
  EXPECT_EQ(f(k.con1[0]), 1.0f / 360.0f);
  EXPECT_EQ(f(k.con1[3]), -1.0f / 270.0f);
  EXPECT_EQ(f(k.con2[0]), -1.0f / 360.0f);
  EXPECT_EQ(f(k.con2[1]), 2.0f / 270.0f);
  EXPECT_EQ(f(k.con3[1]), 4.0f / 270.0f);
  EXPECT_EQ(k.con3[2], 0u);
  EXPECT_EQ(Fsr1RcasCon(0.0f), std::bit_cast<uint32_t>(1.0f));
  EXPECT_EQ(Fsr1RcasCon(1.0f), std::bit_cast<uint32_t>(0.5f));
}

// A flat frame stays flat (the dering clamp to the 2×2 neighbourhood makes it exact), at every
// factor, in every channel (asymmetric colour).
TEST(Fsr1, EasuKeepsAFlatFrame) {
  const Image8 in = Fill(13, 7, [](int, int, int c) { return static_cast<uint8_t>(40 + 70 * c); });
  for (auto [w, h] : {std::pair{17, 9}, {26, 14}, {13, 7}}) {
    const Image8 out = Fsr1Easu(in, w, h, nullptr);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        ASSERT_EQ(out.Pixel(x, y)[0], 40);
        ASSERT_EQ(out.Pixel(x, y)[1], 110);
        ASSERT_EQ(out.Pixel(x, y)[2], 180);
      }
    }
  }
}

// A vertical step (dark left, light right, at x = 5 of 11) upscaled 2×: every output stays
// inside [dark, light] (no ringing), rows agree (the frame does not vary along y), and the
// output's step sits where the input's does (output x < 9 is dark-ish, x >= 12 light).
TEST(Fsr1, EasuStepHasNoRingingAndStaysInPlace) {
  const Image8 in = Fill(11, 6, [](int x, int, int c) { return static_cast<uint8_t>(x < 5 ? 20 + c : 230 - c); });
  PostStats st;
  const Image8 out = Fsr1Easu(in, 22, 12, &st);
  EXPECT_EQ(st.taps, 12u * 22u * 12u);
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 22; ++x) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_GE(out.Pixel(x, y)[c], 20 + c);
        ASSERT_LE(out.Pixel(x, y)[c], 230 - c);
        ASSERT_EQ(out.Pixel(x, y)[c], out.Pixel(x, 0)[c]) << x << "," << y;
      }
    }
  }
  // Output pixel X maps to input x = 0.5·X - 0.25: X = 8 -> 3.75 (two texels left of the
  // step), X = 12 -> 5.75 (past it).
  EXPECT_LE(out.Pixel(8, 3)[0], 21);
  EXPECT_GE(out.Pixel(12, 3)[0], 229);
  EXPECT_GT(out.Pixel(10, 3)[0], 21);  // the step's pixels are in between
  EXPECT_LT(out.Pixel(9, 3)[0], out.Pixel(10, 3)[0]);
}

// RCAS against ffx_fsr1.h's stated formula, evaluated in double: per channel
// hitMin = min(mn4, e)/(4·mx4), hitMax = (1 − max(mx4, e))/(4·mn4 − 4), lobe =
// max(−(1/4 − 1/16), min(max over channels of max(−hitMin, hitMax), 0))·2^−sharpness, out =
// (lobe·(n + w + e + s) + m)/(4·lobe + 1). The shader's medium-precision rcp (up to ~0.3 %
// off) makes the float result differ slightly: within one 8-bit level on this frame.
TEST(Fsr1, RcasFollowsItsFormula) {
  const Image8 in = Fill(9, 7, [](int x, int y, int c) {
    return static_cast<uint8_t>((x * 37 + y * 91 + c * 53 + (x * y) % 7 * 20) % 200 + 30);
  });
  for (double stops : {0.0, 0.2, 1.5}) {
    const Image8 out = Fsr1Rcas(in, static_cast<float>(stops), nullptr);
    for (int y = 0; y < 7; ++y) {
      for (int x = 0; x < 9; ++x) {
        auto v = [&](int xx, int yy, int c) {
          xx = std::clamp(xx, 0, 8);
          yy = std::clamp(yy, 0, 6);
          return in.Pixel(xx, yy)[c] / 255.0;
        };
        double lobe = -1e9;
        for (int c = 0; c < 3; ++c) {
          const double n = v(x, y - 1, c), w = v(x - 1, y, c), e = v(x + 1, y, c), s = v(x, y + 1, c), m = v(x, y, c);
          const double mn4 = std::min({n, w, e, s}), mx4 = std::max({n, w, e, s});
          const double hit_min = std::min(mn4, m) / (4 * mx4), hit_max = (1 - std::max(mx4, m)) / (4 * mn4 - 4);
          lobe = std::max(lobe, std::max(-hit_min, hit_max));
        }
        lobe = std::max(-(0.25 - 1.0 / 16.0), std::min(lobe, 0.0)) * std::exp2(-stops);
        for (int c = 0; c < 3; ++c) {
          const double sum = v(x, y - 1, c) + v(x - 1, y, c) + v(x + 1, y, c) + v(x, y + 1, c);
          const double want = (lobe * sum + v(x, y, c)) / (4 * lobe + 1);
          const int want8 = static_cast<int>(std::lround(std::clamp(want, 0.0, 1.0) * 255));
          ASSERT_NEAR(out.Pixel(x, y)[c], want8, 1) << x << "," << y << " c" << c << " stops " << stops;
        }
      }
    }
  }
}

// A channel that is 0 all around gives hitMin = 0·(1/0) = NaN; GLSL's max picks the other
// operand (IEEE maxNum), so RCAS still sharpens the other channels and never outputs NaN:
// a red dot of 200 on (0, 100, 0) with green varying.
TEST(Fsr1, RcasNanOfABlackChannelPicksTheOtherOperand) {
  const Image8 in = Fill(5, 5, [](int x, int y, int c) {
    if (c == 0) return static_cast<uint8_t>(x == 2 && y == 2 ? 200 : 0);
    if (c == 1) return static_cast<uint8_t>(x == 2 && y == 2 ? 150 : 100);
    return static_cast<uint8_t>(0);
  });
  const Image8 out = Fsr1Rcas(in, 0.0f, nullptr);
  // Red: ring 0, centre 200/255: hitMin = NaN, hitMax = (1 − 200/255)/(0 − 4) = −0.0539;
  // green: mn4 = mx4 = 100/255, m = 150/255: hitMin = 0.25, hitMax = (1 − 150/255)/(4·100/255 − 4) = −0.1709;
  // blue: all 0: hitMin = NaN, hitMax = −0.25. lobe = max(−0.0539, −0.25, −0.1709) = −0.0539.
  const double lobe = (1 - 200.0 / 255) / -4;
  const double red = (0 + 200.0 / 255) / (4 * lobe + 1),
               green = (lobe * 4 * 100.0 / 255 + 150.0 / 255) / (4 * lobe + 1);
  EXPECT_NEAR(out.Pixel(2, 2)[0], std::lround(std::min(1.0, red) * 255), 1);
  EXPECT_NEAR(out.Pixel(2, 2)[1], std::lround(green * 255), 1);
  EXPECT_EQ(out.Pixel(2, 2)[2], 0);
  EXPECT_EQ(out.Pixel(0, 0)[0], 0);
}

TEST(Fsr1, RegistryRows) {
  const MethodPlan easu = MakeMethod("scale43-easu");
  EXPECT_EQ(easu.rescale, Rescale::kEasu);
  EXPECT_DOUBLE_EQ(easu.render.scale, 0.75);
  EXPECT_FALSE(easu.post);
  EXPECT_FALSE(easu.sharpen);
  const MethodPlan er = MakeMethod("scale43-easu-rcas:upscale=2,sharpness=1");
  EXPECT_DOUBLE_EQ(er.render.scale, 0.5);
  ASSERT_TRUE(er.sharpen);
  const Image8 in =
      Fill(6, 5, [](int x, int y, int c) { return static_cast<uint8_t>((x * 40 + y * 17 + c * 60) % 256); });
  EXPECT_EQ(er.sharpen(in, PostOptions{}, nullptr).Data(), Fsr1Rcas(in, 1.0f, nullptr).Data());
  const MethodPlan fx = MakeMethod("scale43-fxaa-high-easu-rcas");
  EXPECT_TRUE(fx.post);
  EXPECT_TRUE(fx.sharpen);
  const MethodPlan rcas = MakeMethod("rcas");
  EXPECT_TRUE(rcas.IsPostOnly());
  EXPECT_EQ(rcas.post(in, PostOptions{}, nullptr).Data(), Fsr1Rcas(in, 0.2f, nullptr).Data());
  try {
    MakeMethod("scale43-easu:upscale=3");
    FAIL() << "upscale 3 was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("upscale"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace aalab
