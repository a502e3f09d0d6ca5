// Temporal metrics against values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "metrics/temporal.h"

namespace aalab {
namespace {

ImageF Filled(int w, int h, int c, float v) {
  ImageF img(w, h, c);
  for (float& x : img.Data()) x = v;
  return img;
}

const MetricValue& Find(const std::vector<MetricValue>& v, const std::string& name) {
  for (const auto& m : v) {
    if (m.name == name) return m;
  }
  throw std::runtime_error("no metric " + name);
}

TEST(TemporalError, HandComputedTwoFrames) {
  // 2×1 RGB, reference 0. Frame 0: error 0.2 everywhere. Frame 1: pixel 0 unchanged, pixel 1
  // error 0.5 in all channels: Δe = 0.3 on 3 of 6 terms → mean Δe² = 3·0.09/6 = 0.045.
  const ImageF ref = Filled(2, 1, 3, 0.0f);
  ImageF f0 = Filled(2, 1, 3, 0.2f), f1 = Filled(2, 1, 3, 0.2f);
  for (int c = 0; c < 3; ++c) f1.At(1, 0, c) = 0.5f;
  ImageF mask0 = Filled(2, 1, 1, 0.0f), mask1 = Filled(2, 1, 1, 0.0f);
  mask0.At(1, 0, 0) = 1.0f;  // pixel 1 is an edge in frame 0 only: E0 ∪ E1 = {pixel 1}
  TemporalError te;
  te.AddFrame(f0, ref, &mask0);
  te.AddFrame(f1, ref, &mask1);
  const auto v = te.Values();
  EXPECT_NEAR(*Find(v, "temporal_rmse").value, std::sqrt(0.045), 1e-7);
  EXPECT_NEAR(*Find(v, "temporal_psnr_db").value, 10.0 * std::log10(1.0 / 0.045), 1e-5);
  EXPECT_NEAR(*Find(v, "temporal_edge_rmse").value, 0.3, 1e-7);
  ASSERT_EQ(te.PerFrameRmse().size(), 1u);
  EXPECT_NEAR(te.PerFrameRmse()[0], std::sqrt(0.045), 1e-7);
}

TEST(TemporalError, AStableErrorIsNoFlickerEvenWhenLarge) {
  // The reference moves (0.25 → 0.5) and the method moves with it, off by 0.25 both times
  // (values exact in binary, so the differences are exactly equal).
  TemporalError te;
  te.AddFrame(Filled(3, 2, 3, 0.5f), Filled(3, 2, 3, 0.25f), nullptr);
  te.AddFrame(Filled(3, 2, 3, 0.75f), Filled(3, 2, 3, 0.5f), nullptr);
  const auto v = te.Values();
  EXPECT_EQ(*Find(v, "temporal_rmse").value, 0.0);
  EXPECT_FALSE(Find(v, "temporal_psnr_db").value.has_value());
  EXPECT_FALSE(Find(v, "temporal_edge_rmse").value.has_value());  // no masks given
}

TEST(TemporalError, OneFrameIsNull) {
  TemporalError te;
  te.AddFrame(Filled(1, 1, 3, 0.4f), Filled(1, 1, 3, 0.1f), nullptr);
  for (const auto& m : te.Values()) EXPECT_FALSE(m.value.has_value()) << m.name;
}

TEST(PoolFrames, MeanOverFramesAndNullNamesTheFrame) {
  const std::vector<std::vector<MetricValue>> frames = {{{"a", 1.0, ""}, {"b", 2.0, ""}},
                                                        {{"a", 4.0, ""}, {"b", std::nullopt, "identical"}}};
  const auto pooled = PoolFrames(frames);
  EXPECT_DOUBLE_EQ(*pooled[0].value, 2.5);
  EXPECT_FALSE(pooled[1].value.has_value());
  EXPECT_EQ(pooled[1].null_reason, "null on frame 1: identical");
}

}  // namespace
}  // namespace aalab
