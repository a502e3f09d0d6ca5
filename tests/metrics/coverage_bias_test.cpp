// The signed coverage (area bias) metrics on hand-built images.
#include <gtest/gtest.h>

#include "metrics/metrics.h"

namespace aalab {
namespace {

std::optional<double> ValueOf(const std::vector<MetricValue>& v, const std::string& name) {
  for (const auto& m : v) {
    if (m.name == name) return m.value;
  }
  ADD_FAILURE() << name << " missing";
  return std::nullopt;
}

TEST(CoverageBias, GrowingAndShrinkingDisksHaveTheSignedArea) {
  // A white "disk" of 4 px on black in a 10 × 10 window; the method draws 5 px (grows by
  // 1 px², +25 %), then 3 px (shrinks by 1 px²). 0 and 1 are exact in 8 bits and in sRGB.
  ImageF ref(10, 10, 3, 0.0f), grown(10, 10, 3, 0.0f), shrunk(10, 10, 3, 0.0f);
  for (int c = 0; c < 3; ++c) {
    for (auto [x, y] : {std::pair{4, 4}, {5, 4}, {4, 5}, {5, 5}}) {
      ref.At(x, y, c) = 1.0f;
      grown.At(x, y, c) = 1.0f;
      shrunk.At(x, y, c) = 1.0f;
    }
    grown.At(6, 5, c) = 1.0f;
    shrunk.At(5, 5, c) = 0.0f;
  }
  CoverageProbe p;
  p.x1 = p.y1 = 10;
  p.radius_px = 1.13;  // bin 1–2 px
  p.area_px = 4.0;
  for (int c = 0; c < 3; ++c) p.inside[c] = 1.0f;
  std::vector<CoverageProbe> probes = {p};
  MetricInput in;
  in.reference = &ref;
  in.coverage_probes = &probes;
  in.image = &grown;
  auto v = ComputeAllMetrics(in);
  EXPECT_NEAR(*ValueOf(v, "area_bias_px2"), 1.0, 1e-6);
  EXPECT_NEAR(*ValueOf(v, "area_bias_rel_r1_2"), 0.25, 1e-6);
  EXPECT_NEAR(*ValueOf(v, "area_bias_abs_rel"), 0.25, 1e-6);
  EXPECT_FALSE(ValueOf(v, "area_bias_rel_r2_4").has_value());
  in.image = &shrunk;
  v = ComputeAllMetrics(in);
  EXPECT_NEAR(*ValueOf(v, "area_bias_px2"), -1.0, 1e-6);
  EXPECT_NEAR(*ValueOf(v, "area_bias_abs_rel"), 0.25, 1e-6);
  // Too little contrast to read coverage back: skipped, so the values are null.
  for (int c = 0; c < 3; ++c) probes[0].inside[c] = 0.01f;
  v = ComputeAllMetrics(in);
  EXPECT_FALSE(ValueOf(v, "area_bias_px2").has_value());
  // No probes at all (not a flat disk scene): null.
  in.coverage_probes = nullptr;
  v = ComputeAllMetrics(in);
  EXPECT_FALSE(ValueOf(v, "area_bias_px2").has_value());
}

}  // namespace
}  // namespace aalab
