// FSR 2's port (methods/fsr2.h), the parts checked without the shader: the 16-bit float store
// against the compiler's own binary16 conversion (GCC's _Float16, libgcc's round to nearest
// even) on a stride through every float bit pattern plus the boundary cases, and toward zero
// against "the nearest-even result, one step back if it is larger in magnitude"; the RCAS
// constant against exp2 of the API's remapped sharpness. The passes themselves are checked
// against the original shaders in tests/oracle/fsr2_oracle_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "methods/fsr2.h"

namespace aalab {
namespace {

float FromBits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

uint16_t ReferenceBits(float f, bool toward_zero) {
  _Float16 h = static_cast<_Float16>(f);
  uint16_t b;
  std::memcpy(&b, &h, 2);
  if (toward_zero && !std::isnan(f) && std::fabs(static_cast<float>(h)) > std::fabs(f)) --b;
  return b;
}

void Check(uint32_t u, long* bad) {
  const float f = FromBits(u);
  for (bool tz : {false, true}) {
    const uint16_t ours = Fsr2HalfBits(f, tz), ref = ReferenceBits(f, tz);
    const bool nan = std::isnan(f);
    if (nan ? (ours & 0x7c00u) != 0x7c00u || (ours & 0x3ffu) == 0 : ours != ref) {
      if (++*bad < 10)
        ADD_FAILURE() << std::hex << "float bits 0x" << u << (tz ? " toward zero" : " nearest") << ": ours 0x" << ours
                      << " reference 0x" << ref;
    }
    if (!nan) {
      _Float16 h;
      std::memcpy(&h, &ours, 2);
      const float back = Fsr2HalfToFloat(ours), want = static_cast<float>(h);
      if (std::memcmp(&back, &want, 4) != 0 && ++*bad < 10)
        ADD_FAILURE() << std::hex << "half 0x" << ours << " back to float";
    }
  }
}

TEST(Fsr2Half, MatchesTheCompilersConversionEverywhereSampled) {
  long bad = 0;
  for (uint64_t u = 0; u <= 0xffffffffull; u += 977) Check(static_cast<uint32_t>(u), &bad);
  // Boundaries: ties at the last mantissa bit, subnormal edges, 65504 / 65520 / 65536, ±0.
  for (float f : {65504.0f, 65519.996f, 65520.0f, 65535.0f, 65536.0f, 6.1035156e-05f, 6.0975552e-05f, 5.9604645e-08f,
                  2.9802322e-08f, 2.9802326e-08f, 1.0f + 0x1p-11f, 1.0f + 0x1p-11f + 0x1p-23f, 1.0f + 3 * 0x1p-11f,
                  0.0f, -0.0f}) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    Check(u, &bad);
    Check(u | 0x80000000u, &bad);
  }
  EXPECT_EQ(bad, 0);
  // Hand-worked: 1 + 2^-11 is a tie between 1 and 1 + 2^-10: even is 1 (0x3c00); 65520 ties
  // to infinity; toward zero 65536 is 65504 (0x7bff) and 1.9999 is 1.9990234 (0x3fff).
  EXPECT_EQ(Fsr2HalfBits(1.0f + 0x1p-11f), 0x3c00);
  EXPECT_EQ(Fsr2HalfBits(65520.0f), 0x7c00);
  EXPECT_EQ(Fsr2HalfBits(65536.0f, true), 0x7bff);
  EXPECT_EQ(Fsr2HalfBits(1.9999f, true), 0x3fff);
  EXPECT_EQ(Fsr2HalfBits(1.9999f), 0x4000);
}

TEST(Fsr2Rcas, ConstantIsExp2OfTheRemappedSharpness) {
  // ffx_fsr2.cpp: stops = -2·sharpness + 2; FsrRcasCon: con.x = bits of exp2(-stops).
  EXPECT_EQ(FromBits(Fsr2RcasCon(1.0f)), 1.0f);
  EXPECT_EQ(FromBits(Fsr2RcasCon(0.0f)), 0.25f);
  EXPECT_EQ(FromBits(Fsr2RcasCon(0.5f)), 0.5f);
  EXPECT_FLOAT_EQ(FromBits(Fsr2RcasCon(0.8f)), 0.757858283f);  // 2^-0.4
}

}  // namespace
}  // namespace aalab
