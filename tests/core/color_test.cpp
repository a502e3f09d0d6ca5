#include "core/color.h"

#include <gtest/gtest.h>

#include <bit>
#include <vector>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/error.h"

namespace aalab {
namespace {

TEST(Color, SrgbEncodeKnownValues) {
  // IEC 61966-2-1: linear segment below 0.0031308, 1.055 x^(1/2.4) − 0.055 above.
  EXPECT_FLOAT_EQ(SrgbEncode(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(SrgbEncode(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(SrgbEncode(0.001f), 0.01292f);
  // 0.5 linear → 0.735357 encoded (1.055·0.5^(1/2.4) − 0.055, computed by hand).
  EXPECT_NEAR(SrgbEncode(0.5f), 0.735357f, 1e-5);
  // 0.2140 linear is the value whose encoding is ~0.5 (display mid-grey code 128).
  EXPECT_NEAR(SrgbEncode(0.214041f), 0.5f, 1e-5);
}

// SrgbEncode computes x^(1/2.4) without libm (tables, a series, and powf only where the
// rounding is in doubt); it must give libm's bits for every input the tracer can pass. Every
// float in [0, 1] (bit patterns 0 .. 0x3F800000, 2^30 + 1 values, ~75 M of them on the
// power branch) is compared with the formula written with std::pow.
TEST(Color, SrgbEncodeSameBitsAsLibmOnEveryFloatInUnitInterval) {
  uint64_t differ = 0;
  uint32_t first = 0;
  for (uint32_t b = 0; b <= 0x3F800000u; ++b) {
    const float v = std::bit_cast<float>(b);
    const uint32_t fast = std::bit_cast<uint32_t>(SrgbEncode(v));
    const uint32_t libm = std::bit_cast<uint32_t>(SrgbEncodeLibm(v));
    if (fast != libm && differ++ == 0) first = b;
  }
  EXPECT_EQ(differ, 0u) << "first differing input: " << std::bit_cast<float>(first);
  // Outside [0, 1] both clamp; NaN gives 0.
  for (float v : {-0.0f, -1e-30f, -2.0f, 1.0000001f, 3.0f, std::numeric_limits<float>::infinity(),
                  std::numeric_limits<float>::quiet_NaN()}) {
    EXPECT_EQ(std::bit_cast<uint32_t>(SrgbEncode(v)), std::bit_cast<uint32_t>(SrgbEncodeLibm(v))) << v;
  }
}

// SrgbEncodeN (the reference's vectorised encode) against SrgbEncode, bit for bit: every float
// of the power branch and its lower boundary (0.003 .. 1, ~76 M values, where the tables and
// the powf fallback act), every 97th float below it, and the clamped and NaN inputs; in place
// and out of place, in batches whose lengths are not multiples of the 64-value block.
TEST(Color, SrgbEncodeNSameBitsAsSrgbEncode) {
  std::vector<float> in, out;
  uint64_t differ = 0, checked = 0;
  float first = 0.0f;
  auto check = [&](bool in_place) {
    const int n = static_cast<int>(in.size());
    out = in;
    SrgbEncodeN(in_place ? out.data() : in.data(), out.data(), n);
    for (int k = 0; k < n; ++k) {
      ++checked;
      if (std::bit_cast<uint32_t>(out[k]) != std::bit_cast<uint32_t>(SrgbEncode(in[k])) && differ++ == 0) {
        first = in[k];
      }
    }
    in.clear();
  };
  const uint32_t lo = std::bit_cast<uint32_t>(0.003f);
  for (uint32_t b = 0; b < lo; b += 97) {
    in.push_back(std::bit_cast<float>(b));
    if (in.size() == 1001) check(false);
  }
  for (uint32_t b = lo; b <= 0x3F800000u; ++b) {
    in.push_back(std::bit_cast<float>(b));
    if (in.size() == 4099) check((b & 1) != 0);
  }
  for (float v : {-0.0f, -1e-30f, -2.0f, 0.0031308f, 1.0000001f, 3.0f, std::numeric_limits<float>::infinity(),
                  -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
    in.push_back(v);
  }
  check(true);
  EXPECT_EQ(differ, 0u) << "first differing input: " << first;
  EXPECT_GT(checked, 76000000u);
}

TEST(Color, SrgbRoundTrip) {
  for (int i = 0; i <= 100; ++i) {
    const float v = static_cast<float>(i) / 100.0f;
    EXPECT_NEAR(SrgbDecode(SrgbEncode(v)), v, 2e-6f) << v;
  }
}

TEST(Color, ClampAndNan) {
  EXPECT_EQ(SrgbEncode(-1.0f), 0.0f);
  EXPECT_EQ(SrgbEncode(7.0f), 1.0f);
  EXPECT_EQ(SrgbEncode(std::numeric_limits<float>::quiet_NaN()), 0.0f);
  EXPECT_EQ(QuantizeUnorm8(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(Color, Quantize) {
  EXPECT_EQ(QuantizeUnorm8(0.0f), 0);
  EXPECT_EQ(QuantizeUnorm8(1.0f), 255);
  EXPECT_EQ(QuantizeUnorm8(0.5f), 128);  // 127.5 rounds half away from zero
  EXPECT_EQ(QuantizeUnorm8(100.0f / 255.0f), 100);
}

TEST(Color, Tonemaps) {
  EXPECT_FLOAT_EQ(ApplyTonemap(Tonemap::kReinhard, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(ApplyTonemap(Tonemap::kReinhard, 3.0f), 0.75f);
  EXPECT_FLOAT_EQ(ApplyTonemap(Tonemap::kNone, 3.0f), 3.0f);
  EXPECT_FLOAT_EQ(ApplyTonemap(Tonemap::kAces, 0.0f), 0.0f);
  // ACES fit saturates near 1 for large input (limit 2.51/2.43 = 1.033 before clamp).
  EXPECT_NEAR(ApplyTonemap(Tonemap::kAces, 1e6f), 2.51f / 2.43f, 1e-4);
  Display d{2.0f, Tonemap::kNone};
  auto out = DisplayLinear(d, {0.25f, 1.0f, -1.0f});
  EXPECT_FLOAT_EQ(out[0], 0.5f);
  EXPECT_FLOAT_EQ(out[1], 1.0f);
  EXPECT_FLOAT_EQ(out[2], 0.0f);
}

TEST(Color, ParseTonemapErrors) {
  EXPECT_EQ(ParseTonemap("aces"), Tonemap::kAces);
  try {
    ParseTonemap("filmic");
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("none, reinhard, aces"), std::string::npos);
  }
}

TEST(Color, TonemapsStayFiniteForHugeAndInfiniteRadiance) {
  // Radiance far above display white (an emitter times a bright light times exposure) used to
  // overflow inside the tonemap: ACES computed x*x = inf and returned inf/inf = NaN, Reinhard
  // inf/(1+inf) = NaN, and the display transform mapped that NaN to black.
  const float inf = std::numeric_limits<float>::infinity();
  for (float v : {1e10f, 1e15f, 1e19f, 1e20f, 1e30f, 3.4e38f, inf}) {
    for (Tonemap t : {Tonemap::kNone, Tonemap::kReinhard, Tonemap::kAces}) {
      EXPECT_FALSE(std::isnan(ApplyTonemap(t, v))) << TonemapName(t) << " " << v;
      Display d;
      d.tonemap = t;
      d.exposure = 1e9f;
      const auto out = DisplayLinear(d, {v, v, 0.5f});
      EXPECT_EQ(out[0], 1.0f) << TonemapName(t) << " " << v;
      EXPECT_EQ(out[1], 1.0f) << TonemapName(t) << " " << v;
    }
  }
  // Continuous at the ACES cut-off: the fit has reached its limit there.
  EXPECT_NEAR(ApplyTonemap(Tonemap::kAces, 1e15f / 0.6f * 0.999f), 2.51f / 2.43f, 1e-6f);
  EXPECT_EQ(ApplyTonemap(Tonemap::kReinhard, 3.4e38f), 1.0f);
}

}  // namespace
}  // namespace aalab
