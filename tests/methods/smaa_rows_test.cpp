// SMAA's pass-1 rows in SIMD (methods/smaa_rows.h) against the reference shader's arithmetic:
// LumaRow for every one of the 2^24 rgb colours against SMAA.hlsl's dot (rgb of the UNORM
// texels, float32, in dot's order), with row lengths and starts that reach the AVX2 blocks (8
// pixels), the SSE2 blocks (4) and the scalar tail, and the padding of the clamped
// neighbours; EdgeRowLuma against its scalar form; Quantize8 against QuantizeUnorm8; ListNonZero against a plain scan
// on rows with set bytes at both ends, in every 16-byte lane and in the tail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "core/color.h"
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

// EdgeRowLuma (SSE2/AVX2 blocks and the early exit) against its scalar form, on luma rows drawn
// from a few values whose differences hit the threshold and the local-contrast limit exactly
// (binary fractions: k/16 with threshold 1/8; and decimal ones near 0.1), sparse and dense,
// with widths that leave tails after the 8- and 4-column blocks.
TEST(SmaaRows, EdgeRowLumaMatchesTheScalarForm) {
  uint32_t s = 777;
  auto next = [&] { return (s = s * 1664525u + 1013904223u) >> 8; };
  struct Case {
    float thr, lcf;
    std::vector<float> values;
  };
  const std::vector<Case> cases = {{0.125f, 2.0f, {0.0f, 0.0625f, 0.125f, 0.25f, 0.375f, 0.5f, 1.0f}},
                                   {0.1f, 2.0f, {0.05f, 0.1f, 0.15f, 0.2f, 0.3f, 0.7f}},
                                   {0.0f, 0.0f, {0.0f, 0.5f}},
                                   {0.05f, 1.5f, {0.2f, 0.25f, 0.3f, 0.45f}}};
  long diff = 0, kept_diff = 0, any_diff = 0, rows = 0;
  for (const Case& c : cases) {
    for (int w : {1, 3, 4, 7, 8, 9, 13, 37, 1925}) {
      for (int dense : {2, 10, 100}) {  // percent of columns that change value
        std::vector<std::vector<float>> l(4, std::vector<float>(w + 3));
        for (auto& row : l) {
          float v = c.values[next() % c.values.size()];
          for (int x = 0; x < w; ++x) {
            if (static_cast<int>(next() % 100) < dense) v = c.values[next() % c.values.size()];
            row[x + 2] = v;
          }
          row[0] = row[1] = row[2];
          row[w + 2] = row[w + 1];
        }
        std::vector<uint8_t> a(w, 0xAA), b(w, 0x55);
        uint8_t any_a = 7, any_b = 9;
        const int ka = smaa_internal::EdgeRowLuma(l[0].data(), l[1].data(), l[2].data(), l[3].data(), w, c.thr, c.lcf,
                                                  a.data(), &any_a);
        const int kb = smaa_internal::EdgeRowLumaScalar(l[0].data(), l[1].data(), l[2].data(), l[3].data(), w, c.thr,
                                                        c.lcf, b.data(), &any_b);
        diff += a != b;
        kept_diff += ka != kb;
        any_diff += (any_a != 0) != (any_b != 0);
        ++rows;
      }
    }
  }
  EXPECT_EQ(diff, 0) << "of " << rows << " rows";
  EXPECT_EQ(kept_diff, 0);
  EXPECT_EQ(any_diff, 0);
}

// Quantize8 against QuantizeUnorm8: every float in [0, 1] whose v·255 lies within 64 ulps of a
// half-integer k + 0.5 (the rounding boundaries), a stride through all floats in [0, 1], and
// negative, zero, one, above one, NaN and infinity.
TEST(SmaaRows, Quantize8IsQuantizeUnorm8) {
  long diff = 0, n = 0;
  auto check = [&](float v) {
    diff += smaa_internal::Quantize8(v) != QuantizeUnorm8(v);
    ++n;
  };
  for (int k = 0; k < 255; ++k) {
    float v = (static_cast<float>(k) + 0.5f) / 255.0f;
    for (int i = 0; i < 64; ++i) v = std::nextafter(v, 0.0f);
    for (int i = 0; i < 129; ++i, v = std::nextafter(v, 2.0f)) check(v);
  }
  for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 997) {
    float v;
    std::memcpy(&v, &bits, 4);
    check(v);
  }
  for (float v : {-1.0f, -0.0f, 0.0f, 1.0f, 1.5f, 1e30f, std::nanf(""), std::numeric_limits<float>::infinity(),
                  -std::numeric_limits<float>::infinity(), 1e-45f, 0.99999994f}) {
    check(v);
  }
  EXPECT_EQ(diff, 0) << "of " << n;
}

TEST(SmaaRows, ListNonZeroListsEverySetByteInOrder) {
  uint32_t s = 12345;
  auto next = [&] { return s = s * 1664525u + 1013904223u; };
  for (int w : {1, 2, 15, 16, 17, 31, 33, 100, 1920}) {
    for (int fill : {0, 1, 5, 50, 100}) {                       // percent of set bytes
      std::vector<uint8_t> row(static_cast<size_t>(w) + 1, 0);  // one spare byte: never listed
      for (int x = 0; x < w; ++x)
        row[x] = (next() >> 8) % 100 < static_cast<uint32_t>(fill) ? (next() >> 8) % 3 + 1 : 0;
      row[static_cast<size_t>(w) - 1] = 2;   // the last column (in the tail for most widths)
      row[static_cast<size_t>(w)] = 1;       // past the end: must not be read as a column
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
