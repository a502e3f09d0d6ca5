// RunAndScoreRows (harness/run/score_rows.h): a frame's rows rendered one after another and
// scored concurrently equal the rows RunMethod renders and scores one at a time, bit for bit
// (metrics, FLIP map, output, hash), at 1, 2 and 3 threads, with outputs that repeat within
// one call and across calls (the shared scores by hash).
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "core/parallel.h"
#include "harness/run/pipeline.h"
#include "harness/run/score_rows.h"
#include "scenes/library.h"

namespace aalab {
namespace {

void ExpectSameRow(const MethodOutput& got, const MethodOutput& want, const std::string& where) {
  EXPECT_EQ(got.row.output_hash, want.row.output_hash) << where;
  EXPECT_TRUE(got.output == want.output) << where;
  EXPECT_EQ(got.flip_grey, want.flip_grey) << where;
  ASSERT_EQ(got.row.metrics.size(), want.row.metrics.size()) << where;
  for (size_t i = 0; i < want.row.metrics.size(); ++i) {
    const auto& g = got.row.metrics[i];
    const auto& w = want.row.metrics[i];
    EXPECT_EQ(g.name, w.name) << where;
    EXPECT_EQ(g.value.has_value(), w.value.has_value()) << where << " " << w.name;
    if (g.value && w.value) {
      EXPECT_EQ(*g.value, *w.value) << where << " " << w.name;  // same bits
    }
    EXPECT_EQ(g.null_reason, w.null_reason) << where << " " << w.name;
  }
  EXPECT_EQ(got.row.not_applicable, want.row.not_applicable) << where;
}

TEST(ScoreRows, ConcurrentScoresEqualOneAtATimeAtAnyThreadCount) {
  // Rendering methods, post filters (on a dark scene several leave the 1x frame as it is, so
  // outputs repeat within one call: `none`'s hash), a rescaling one.
  const auto plans = ResolveMethods({"none", "ssaa-2x2", "fxaa311-p39", "smaa-high", "fxaa1-p3", "scale43-easu-rcas"});
  int repeated = 0;
  for (const char* name : {"wedges", "hard-dark"}) {
    // Expected: RunMethod scoring each row as it goes, one thread (W ≠ H, both > 11 for SSIM).
    SetThreadCount(1);
    auto serial = PrepareScene(std::make_unique<Scene>(LoadScene(name)), 72, 40, 2, 1, 1);
    std::vector<MethodOutput> want;
    for (const auto& plan : plans) want.push_back(RunMethod(*serial, plan, MethodRunSettings{1, 1}));
    std::set<std::string> hashes;
    for (const auto& w : want) hashes.insert(w.row.output_hash);
    repeated += static_cast<int>(want.size() - hashes.size());
    for (int threads : {1, 2, 3}) {
      SetThreadCount(threads);
      auto prepared = PrepareScene(std::make_unique<Scene>(LoadScene(name)), 72, 40, 2, 1, 1);
      std::vector<std::unique_ptr<TemporalState>> states(plans.size());
      // Twice on one prepared frame: the second call finds every output already scored.
      for (int call = 0; call < 2; ++call) {
        const auto got = RunAndScoreRows(*prepared, plans, MethodRunSettings{1, 1}, &states, true);
        ASSERT_EQ(got.size(), plans.size());
        for (size_t m = 0; m < plans.size(); ++m) {
          ExpectSameRow(*got[m], want[m],
                        std::string(name) + " " + plans[m].spec + ", " + std::to_string(threads) + " threads, call " +
                            std::to_string(call));
        }
      }
      EXPECT_EQ(prepared->scored_by_hash.size(), hashes.size()) << name;
    }
  }
  SetThreadCount(0);
  EXPECT_GT(repeated, 0) << "no output repeated: the shared-score path was not exercised";
}

TEST(ScoreRows, InputsKeptOnlyWhenAsked) {
  const auto plans = ResolveMethods({"fxaa311-p39"});
  auto prepared = PrepareScene(std::make_unique<Scene>(LoadScene("wedges")), 40, 24, 2, 1, 1);
  std::vector<std::unique_ptr<TemporalState>> states(plans.size());
  EXPECT_TRUE(RunAndScoreRows(*prepared, plans, MethodRunSettings{1, 1}, &states, true)[0]->input == prepared->frame1x);
  EXPECT_TRUE(RunAndScoreRows(*prepared, plans, MethodRunSettings{1, 1}, &states, false)[0]->input.Empty());
}

}  // namespace
}  // namespace aalab
