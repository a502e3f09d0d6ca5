// FXAA 3.11's luma plane rows in SSE2 (methods/fxaa311_rows.h) against the luma pre-pass
// (Fxaa311LumaFrame, the scalar per-pixel code the reference path runs), for every one of the
// 2^24 rgb colours, in every 8-bit luma mode, with row lengths and starts that leave a scalar
// tail (the vector loop takes 16 pixels at a time).
#include <gtest/gtest.h>

#include <vector>

#include "methods/fxaa311.h"
#include "methods/fxaa311_rows.h"

namespace aalab {
namespace {

using Luma = Fxaa311Params::Luma;

// For each red value r: a 256x256 frame with green = row and blue = column (alpha varies too:
// it must be ignored), its pre-pass luma, and PlaneRow8 over each row, whole and from pixel 3
// on (253 pixels: 15 vectors and a 13-pixel tail). Returns the number of differing lumas.
long CountDifferences(Luma luma) {
  long diff = 0;
  Image8 frame(256, 256, 4);
  std::vector<uint8_t> plane(256);
  for (int r = 0; r < 256; ++r) {
    for (int y = 0; y < 256; ++y) {
      for (int x = 0; x < 256; ++x) {
        uint8_t* p = frame.Pixel(x, y);
        p[0] = static_cast<uint8_t>(r);
        p[1] = static_cast<uint8_t>(y);
        p[2] = static_cast<uint8_t>(x);
        p[3] = static_cast<uint8_t>(x ^ y ^ r);
      }
    }
    const Image8 pre = Fxaa311LumaFrame(frame, luma);
    for (int y = 0; y < 256; ++y) {
      const auto expected = [&](int x) { return luma == Luma::kGreen ? pre.Pixel(x, y)[1] : pre.Pixel(x, y)[3]; };
      fxaa311_internal::PlaneRow8(frame.Row(y), 256, luma, plane.data());
      for (int x = 0; x < 256; ++x) diff += plane[x] != expected(x);
      fxaa311_internal::PlaneRow8(frame.Row(y) + 4 * 3, 253, luma, plane.data());
      for (int x = 0; x < 253; ++x) diff += plane[x] != expected(x + 3);
    }
  }
  return diff;
}

// CountDifferences with PlaneRow8 capped at each instruction set in turn (each one the CPU
// lacks runs the next narrower one again).
long CountDifferencesEveryIsa(Luma luma) {
  using fxaa311_internal::PlaneIsa;
  long diff = 0;
  for (PlaneIsa cap : {PlaneIsa::kSse2, PlaneIsa::kAvx2, PlaneIsa::kAvx512}) {
    fxaa311_internal::SetPlaneRow8IsaCap(cap);
    const long d = CountDifferences(luma);
    EXPECT_EQ(d, 0) << "instruction set cap " << static_cast<int>(cap);
    diff += d;
  }
  fxaa311_internal::SetPlaneRow8IsaCap(PlaneIsa::kAvx512);
  return diff;
}

TEST(Fxaa311Rows, Rec601PlaneEqualsThePrePassForEveryColour) { EXPECT_EQ(CountDifferencesEveryIsa(Luma::kRec601), 0); }

TEST(Fxaa311Rows, SqrtLuminancePlaneEqualsThePrePassForEveryColour) {
  EXPECT_EQ(CountDifferencesEveryIsa(Luma::kSqrtLuminance), 0);
}

TEST(Fxaa311Rows, GreenPlaneIsTheGreenByte) { EXPECT_EQ(CountDifferencesEveryIsa(Luma::kGreen), 0); }

// Known values by hand: rec601 of (255, 0, 0) = 0.299·255 = 76.245 → 76; of (0, 255, 0) =
// 149.685 → 150; of (0, 0, 255) = 29.07 → 29; white → 255, black → 0. sqrt-luminance of
// mid grey 128: sqrt(SrgbDecode(128) ≈ 0.2158605) = 0.464608 → ·255 = 118.475 → 118. The
// six pixels open a row of 16 (the SSE2 loop) and of 32 (the AVX2 loop where the CPU has it).
TEST(Fxaa311Rows, KnownColoursByHand) {
  uint8_t px[32 * 4] = {255, 0, 0, 9, 0, 255, 0, 9, 0, 0, 255, 9, 255, 255, 255, 9, 0, 0, 0, 9, 128, 128, 128, 9};
  for (int w : {16, 32}) {
    uint8_t o[32] = {};
    fxaa311_internal::PlaneRow8(px, w, Luma::kRec601, o);
    EXPECT_EQ(o[0], 76) << w;
    EXPECT_EQ(o[1], 150) << w;
    EXPECT_EQ(o[2], 29) << w;
    EXPECT_EQ(o[3], 255) << w;
    EXPECT_EQ(o[4], 0) << w;
    fxaa311_internal::PlaneRow8(px, w, Luma::kSqrtLuminance, o);
    EXPECT_EQ(o[5], 118) << w;
  }
}

}  // namespace
}  // namespace aalab
