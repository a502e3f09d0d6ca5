// Every registered post filter's production path against the reference implementation the
// registry puts beside it (MethodPlan::post_reference): same bytes and same tap counts on the
// adversarial synthetic frames and rendered library frames, at the defaults (the family
// tests beside this one vary parameters and thread counts). A new post filter with a fast
// path is covered here without a line of its own.
#include <gtest/gtest.h>

#include "methods/registry.h"
#include "tests/equivalence/frames.h"

namespace aalab {
namespace {

TEST(PostReference, EveryRegisteredFastPathEqualsItsReference) {
  std::vector<perf_test::NamedFrame> frames = perf_test::SyntheticFrames();
  for (const auto& s : perf_test::SceneFrames()) frames.push_back(s);
  int filters = 0;
  for (const auto& e : MethodRegistry()) {
    const MethodPlan plan = MakeMethod(e.name);
    if (!plan.post_reference) continue;
    ASSERT_TRUE(plan.post) << e.name << ": a reference implementation without a production path";
    ++filters;
    for (const auto& f : frames) {
      PostStats fast_stats, ref_stats;
      const Image8 fast = plan.post(f.img, PostOptions{}, &fast_stats);
      const Image8 ref = plan.post_reference(f.img, PostOptions{}, &ref_stats);
      EXPECT_TRUE(fast == ref) << e.name << " on " << f.name;
      EXPECT_EQ(fast_stats.taps, ref_stats.taps) << e.name << " on " << f.name;
    }
  }
  // fxaa1-p0..p5, 21 FXAA 3.11 rows, scale43-fxaa-high's FXAA, 4 SMAA presets.
  EXPECT_GE(filters, 6 + 21 + 1 + 4);
}

}  // namespace
}  // namespace aalab
