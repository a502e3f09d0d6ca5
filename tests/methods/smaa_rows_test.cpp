// SMAA's pass-1 rows in SIMD (methods/smaa_rows.h) against the reference shader's arithmetic:
// LumaRow for every one of the 2^24 rgb colours against SMAA.hlsl's dot (rgb of the UNORM
// texels, float32, in dot's order), with row lengths and starts that reach the AVX2 blocks (8
// pixels), the SSE2 blocks (4) and the scalar tail, and the padding of the clamped
// neighbours; ListNonZero against a plain scan on rows with set bytes at both ends, in every
// 16-byte lane and in the tail.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "core/image.h"
#include "core/sampler.h"
#include "methods/smaa_rows.h"

namespace aalab {
namespace {

// SMAA.hlsl's luma of an RGBA8 texel: dot(rgb, (0.2126, 0.7152, 0.0722)), rgb = k/255 as the
// UNORM fetch returns it.
float ShaderLuma(const uint8_t* p) {
  return (UnormToFloat(p[0]) * 0.2126f + UnormToFloat(p[1]) * 0.7152f) + UnormToFloat(p[2]) * 0.0722f;
}

bool SameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(SmaaRows, LumaRowIsTheShadersDotForEveryColour) {
  Image8 frame(256, 256, 4);
  std::vector<float> l(256 + 3);
  long diff = 0, pad = 0;
  for (int r = 0; r < 256; ++r) {
    for (int y = 0; y < 256; ++y) {
      for (int x = 0; x < 256; ++x) {
        uint8_t* p = frame.Pixel(x, y);
        p[0] = static_cast<uint8_t>(r), p[1] = static_cast<uint8_t>(y), p[2] = static_cast<uint8_t>(x);
        p[3] = static_cast<uint8_t>(x ^ y);  // ignored
      }
    }
    for (int y = 0; y < 256; ++y) {
      smaa_internal::LumaRow(frame.Row(y), 256, l.data());
      for (int x = 0; x < 256; ++x) diff += !SameBits(l[x + 2], ShaderLuma(frame.Pixel(x, y)));
      // From pixel 5 on, 251 pixels: 31 AVX2 blocks (or 62 SSE2 ones) and a 3-pixel tail.
      smaa_internal::LumaRow(frame.Row(y) + 4 * 5, 251, l.data());
      for (int x = 0; x < 251; ++x) diff += !SameBits(l[x + 2], ShaderLuma(frame.Pixel(x + 5, y)));
      pad += !SameBits(l[0], l[2]) + !SameBits(l[1], l[2]) + !SameBits(l[251 + 2], l[251 + 1]);
    }
  }
  EXPECT_EQ(diff, 0);
  EXPECT_EQ(pad, 0);
}

TEST(SmaaRows, LumaRowShortRowsMatchTheScalarForm) {
  Image8 frame(13, 1, 4);
  for (int x = 0; x < 13; ++x) {
    for (int c = 0; c < 4; ++c) frame.Pixel(x, 0)[c] = static_cast<uint8_t>(37 * x + 91 * c + 11);
  }
  for (int w = 1; w <= 13; ++w) {
    std::vector<float> a(w + 3, -1.0f), b(w + 3, -2.0f);
    smaa_internal::LumaRow(frame.Row(0), w, a.data());
    smaa_internal::LumaRowScalar(frame.Row(0), w, b.data());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "width " << w;
    EXPECT_TRUE(SameBits(a[2 + w - 1], ShaderLuma(frame.Pixel(w - 1, 0)))) << "width " << w;
  }
}

TEST(SmaaRows, ListNonZeroListsEverySetByteInOrder) {
  uint32_t s = 12345;
  auto next = [&] { return s = s * 1664525u + 1013904223u; };
  for (int w : {1, 2, 15, 16, 17, 31, 33, 100, 1920}) {
    for (int fill : {0, 1, 5, 50, 100}) {  // percent of set bytes
      std::vector<uint8_t> row(w);
      for (int x = 0; x < w; ++x)
        row[x] = (next() >> 8) % 100 < static_cast<uint32_t>(fill) ? (next() >> 8) % 3 + 1 : 0;
      row[w - 1] = 2;                        // the last column (in the tail for most widths)
      if (w > 16) row[15] = 1, row[16] = 3;  // a lane's last byte and the next lane's first
      std::vector<uint16_t> expected, got(w, 0xFFFF);
      for (int x = 0; x < w; ++x) {
        if (row[x]) expected.push_back(static_cast<uint16_t>(x));
      }
      const int n = smaa_internal::ListNonZero(row.data(), w, got.data());
      got.resize(static_cast<size_t>(n));
      EXPECT_EQ(got, expected) << "width " << w << ", " << fill << " %";
    }
  }
}

}  // namespace
}  // namespace aalab
