// MemoSampler (methods/smaa_fast.h), the table the fused SMAA pass puts in front of its area
// and search fetches, against InlineSampler itself: on a small asymmetric RGBA8 texture, a
// long sequence of fetches drawn from a few coordinate pairs (pairs sharing s or t, texel
// centres, clamped borders, negative and past-the-end coordinates), through a 4-entry table so
// that entries collide and are evicted, in both sub-texel modes (one table kept across the
// modes, as the fused pass keeps one across calls): every returned Float4 has the bits of the
// direct fetch and the tap counts agree; and a table kept from one texture serves another of
// the same size at another address with that texture's values.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "core/image.h"
#include "methods/smaa_fast.h"

namespace aalab {
namespace {

bool SameBits(const Float4& a, const Float4& b) {
  return std::memcmp(&a.r, &b.r, 4) == 0 && std::memcmp(&a.g, &b.g, 4) == 0 && std::memcmp(&a.b, &b.b, 4) == 0 &&
         std::memcmp(&a.a, &b.a, 4) == 0;
}

TEST(SmaaMemo, MemoSamplerReturnsTheFetchBitForBit) {
  Image8 tex(7, 5, 4);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      for (int c = 0; c < 4; ++c)
        tex.Row(y)[4 * x + c] = static_cast<uint8_t>((37 * x + 91 * y + 53 * c + x * y) % 256);
    }
  }
  // (s, t) pairs in normalised coordinates; several share s or t, so a key that dropped one
  // coordinate would return another pair's value.
  const float pairs[][2] = {{0.1f, 0.3f},   {0.1f, 0.7f},   {0.6f, 0.3f},       {0.5f / 7, 0.5f / 5}, {-0.2f, 0.4f},
                            {1.3f, 0.9f},   {0.93f, 1.1f},  {0.3333f, 0.6667f}, {0.6f, 0.7f},         {0.0f, 0.0f},
                            {0.999f, 0.5f}, {0.5f, 0.999f}, {0.21f, 0.123456f}};
  constexpr int kPairs = sizeof pairs / sizeof pairs[0];
  smaa_internal::MemoTable<2> table;
  for (SubTexel mode : {SubTexel::kFixed8, SubTexel::kExact, SubTexel::kFixed8}) {
    smaa_internal::InlineSampler direct(smaa_internal::Tex8(tex), mode), inner(smaa_internal::Tex8(tex), mode);
    smaa_internal::MemoSampler<2> memo(inner, table);
    uint32_t state = 12345;
    for (int i = 0; i < 2000; ++i) {
      state = state * 1664525u + 1013904223u;
      const int k = static_cast<int>((state >> 16) % kPairs);
      const Float4 want = direct.SampleNormalized(pairs[k][0], pairs[k][1]);
      const Float4 got = memo.SampleNormalized(pairs[k][0], pairs[k][1]);
      ASSERT_TRUE(SameBits(want, got)) << "fetch " << i << " pair " << k;
    }
    EXPECT_EQ(inner.Taps(), direct.Taps());
    EXPECT_EQ(direct.Taps(), 2000u);
  }
  // Another texture of the same size: the kept table must not answer with the first one's.
  Image8 other(7, 5, 4);
  for (size_t i = 0; i < other.Data().size(); ++i) other.Data()[i] = static_cast<uint8_t>(255 - tex.Data()[i]);
  smaa_internal::InlineSampler direct(smaa_internal::Tex8(other), SubTexel::kFixed8);
  smaa_internal::InlineSampler inner(smaa_internal::Tex8(other), SubTexel::kFixed8);
  smaa_internal::MemoSampler<2> memo(inner, table);
  for (int k = 0; k < kPairs; ++k) {
    for (int rep = 0; rep < 2; ++rep) {
      ASSERT_TRUE(
          SameBits(direct.SampleNormalized(pairs[k][0], pairs[k][1]), memo.SampleNormalized(pairs[k][0], pairs[k][1])))
          << "pair " << k << " on the second texture";
    }
  }
}

}  // namespace
}  // namespace aalab
