#include <gtest/gtest.h>

#include "core/error.h"
#include "metrics/error_stats.h"
#include "metrics/families.h"

namespace aalab {
namespace {

TEST(AbsError, PerPixelIsChannelMean) {
  // Errors (0.375, 0, 0) and (0.25, 0.25, 0.25): e = 0.125 and 0.25 (exact in binary).
  ImageF a(2, 1, 3, 0.5f), b(2, 1, 3, 0.5f);
  b.At(0, 0, 0) = 0.125f;
  for (int c = 0; c < 3; ++c) b.At(1, 0, c) = 0.75f;
  const ImageF map = AbsErrorMap(a, b);
  ASSERT_EQ(map.Channels(), 1);
  EXPECT_EQ(map.At(0, 0, 0), 0.125f);
  EXPECT_EQ(map.At(1, 0, 0), 0.25f);
  EXPECT_EQ(AbsErrorMap(b, a), map);  // symmetric
}

TEST(AbsError, NearestRankRule) {
  EXPECT_EQ(NearestRankPercentile({5.0}, 50), 5.0);
  EXPECT_EQ(NearestRankPercentile({5.0}, 0), 5.0);
  // N = 3: p50 → rank ceil(1.5) = 2; p0 → rank 1; p34 → ceil(1.02) = 2; p100 → 3.
  const std::vector<double> v = {1.0, 2.0, 3.0};
  EXPECT_EQ(NearestRankPercentile(v, 50), 2.0);
  EXPECT_EQ(NearestRankPercentile(v, 0), 1.0);
  EXPECT_EQ(NearestRankPercentile(v, 33), 1.0);  // ceil(0.99) = 1
  EXPECT_EQ(NearestRankPercentile(v, 34), 2.0);
  EXPECT_EQ(NearestRankPercentile(v, 100), 3.0);
}

// 200 pixels (20×10) with errors i/256, i = 0..199, equal on R, G, B (exact in float and
// in the channel mean), placed in a scrambled order. Sorted: e(k) = (k − 1)/256.
// p50: rank ceil(0.50·200) = 100 → 99/256; p95: rank 190 → 189/256; p99: rank 198 →
// 197/256; max: 199/256.
TEST(AbsError, PercentilesOfAKnownDistribution) {
  ImageF ref(20, 10, 3, 0.0f), img(20, 10, 3, 0.0f);
  for (int i = 0; i < 200; ++i) {
    const int pos = (i * 77) % 200;  // 77 is coprime with 200: a permutation
    for (int c = 0; c < 3; ++c) img.At(pos % 20, pos / 20, c) = i / 256.0f;
  }
  MetricInput in;
  in.image = &img;
  in.reference = &ref;
  const auto v = AbsErrorMetrics().at(0).compute(in);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0].name, "abs_err_p50");
  EXPECT_EQ(*v[0].value, 99 / 256.0);
  EXPECT_EQ(v[1].name, "abs_err_p95");
  EXPECT_EQ(*v[1].value, 189 / 256.0);
  EXPECT_EQ(v[2].name, "abs_err_p99");
  EXPECT_EQ(*v[2].value, 197 / 256.0);
  EXPECT_EQ(v[3].name, "abs_err_max");
  EXPECT_EQ(*v[3].value, 199 / 256.0);
}

TEST(AbsError, IdenticalIsZeroNotNull) {
  ImageF a(3, 2, 3, 0.4f);
  MetricInput in;
  in.image = &a;
  in.reference = &a;
  for (const auto& m : AbsErrorMetrics().at(0).compute(in)) EXPECT_EQ(*m.value, 0.0) << m.name;
}

TEST(AbsError, ShapeMismatchIsUserError) {
  ImageF a(3, 2, 3), b(2, 3, 3);
  EXPECT_THROW(AbsErrorMap(a, b), UserError);
}

}  // namespace
}  // namespace aalab
