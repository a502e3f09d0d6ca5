// sweep's pure parts: grid parsing/expansion, Pareto front, objective means.
#include "harness/run/sweep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"

namespace aalab {
namespace {

TEST(Sweep, ParsesAndExpandsTheGridLastAxisFastest) {
  std::vector<GridAxis> axes = ParseGrid({"subpix_cap=0,0.5", "edge_threshold=0.25,0.125,0.0625"}, "fxaa1-p3");
  ASSERT_EQ(axes.size(), 2u);
  EXPECT_EQ(axes[1].values, (std::vector<std::string>{"0.25", "0.125", "0.0625"}));
  const std::vector<std::string> specs = ExpandGrid("fxaa1-p3:search_steps=8", &axes);
  ASSERT_EQ(specs.size(), 6u);
  // Canonical specs: overrides in the method's definition order.
  EXPECT_EQ(specs[0], "fxaa1-p3:edge_threshold=0.25,search_steps=8,subpix_cap=0");
  EXPECT_EQ(specs[1], "fxaa1-p3:edge_threshold=0.125,search_steps=8,subpix_cap=0");
  EXPECT_EQ(specs[5], "fxaa1-p3:edge_threshold=0.0625,search_steps=8,subpix_cap=0.5");
  // Values become their canonical text.
  axes = ParseGrid({"edge_threshold=.5"}, "fxaa1-p3");
  ExpandGrid("fxaa1-p3", &axes);
  EXPECT_EQ(axes[0].values, std::vector<std::string>{"0.5"});
  EXPECT_THROW(ParseGrid({}, "fxaa1-p3"), UserError);
  EXPECT_THROW(ParseGrid({"a=1,,2"}, "fxaa1-p3"), UserError);
  EXPECT_THROW(ParseGrid({"=1"}, "fxaa1-p3"), UserError);
}

TEST(Sweep, ParetoFrontByHand) {
  // time:    1    2    3    4    5    2
  // quality: 20   25   24   30   30   25 (a tie with point 1)
  const std::vector<double> t = {1, 2, 3, 4, 5, 2};
  std::vector<std::optional<double>> q = {20.0, 25.0, 24.0, 30.0, 30.0, 25.0};
  // 2 is dominated by 1 (faster, better); 4 by 3 (same quality, faster); 1 and 5 tie: both stay.
  EXPECT_EQ(ParetoFront(t, q, Better::kHigher), (std::vector<size_t>{0, 1, 5, 3}));
  // Lower is better: only the fastest at the lowest value survive.
  EXPECT_EQ(ParetoFront(t, q, Better::kLower), (std::vector<size_t>{0}));
  // Nulls are left out; +inf (identical) is the best possible.
  q[0] = std::nullopt;
  q[4] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ParetoFront(t, q, Better::kHigher), (std::vector<size_t>{1, 5, 3, 4}));
}

TEST(Sweep, ParetoFrontCountsTimesWithinTheSpreadsAsEqual) {
  // time 1.0, 1.1, 2.0; quality 30, 31, 31; spreads 0.2, 0.2, 0.1.
  const std::vector<double> t = {1.0, 1.1, 2.0}, noise = {0.2, 0.2, 0.1};
  const std::vector<std::optional<double>> q = {30.0, 31.0, 31.0};
  // Exact: 0 is the fastest, 1 the best; 2 is dominated by 1.
  EXPECT_EQ(ParetoFront(t, q, Better::kHigher), (std::vector<size_t>{0, 1}));
  // With noise: 1 is better and slower than 0 by 0.1 ms < 0.2 + 0.2, so it dominates 0; 2 is
  // slower than 1 by 0.9 > 0.3.
  EXPECT_EQ(ParetoFront(t, q, Better::kHigher, noise), (std::vector<size_t>{1}));
  // With larger spreads 2 is as fast as 1 (0.9 < 0.5 + 0.5): both stay.
  EXPECT_EQ(ParetoFront(t, q, Better::kHigher, {0.2, 0.5, 0.5}), (std::vector<size_t>{1, 2}));
  // Unknown spreads (one repeat): time ranks points of different quality (exactly), never
  // two equally good ones.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ParetoFront(t, q, Better::kHigher, {nan, nan, nan}), (std::vector<size_t>{0, 1, 2}));
}

TEST(Sweep, DefaultsAreRuns) {
  // One set of default reference spp and repeats for run and sweep.
  EXPECT_EQ(SweepSettings{}.ref_spp, RunSettings{}.ref_spp);
  EXPECT_EQ(SweepSettings{}.repeat, RunSettings{}.repeat);
}

TEST(Sweep, MeanOverScenes) {
  ResultRow a, b;
  a.scene = "wedges";
  b.scene = "circle";
  a.metrics = {{"psnr_db", 20.0, ""}};
  b.metrics = {{"psnr_db", 30.0, ""}};
  EXPECT_DOUBLE_EQ(*MeanOverScenes({&a, &b}, "psnr_db").mean, 25.0);
  b.metrics = {{"psnr_db", std::nullopt, "identical"}};
  EXPECT_TRUE(std::isinf(*MeanOverScenes({&a, &b}, "psnr_db").mean));
  b.metrics = {{"psnr_db", std::nullopt, "empty mask"}};
  const ObjectiveMean m = MeanOverScenes({&a, &b}, "psnr_db");
  EXPECT_FALSE(m.mean);
  EXPECT_EQ(m.null_reason, "null on scene circle: empty mask");
  EXPECT_FALSE(MeanOverScenes({&a, &b}, "ssim").mean);
}

}  // namespace
}  // namespace aalab
