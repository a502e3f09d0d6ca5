// The production SMAA path (luma plane, edge/blend neighbourhood skipping, plane reader of
// the edge texture) against the plain per-pixel reference: same bytes and same tap counts,
// debug views included, on rendered library frames and adversarial synthetic frames, for
// every preset and for settings that reach other branches (colour detection, exact
// sub-texel fetches, zero thresholds and steps), at 1 and 2 threads.
#include <gtest/gtest.h>

#include "core/parallel.h"
#include "methods/smaa.h"
#include "tests/equivalence/frames.h"

namespace aalab {
namespace {

using perf_test::NamedFrame;

std::vector<std::pair<std::string, SmaaParams>> Settings() {
  std::vector<std::pair<std::string, SmaaParams>> out;
  for (const char* preset : {"low", "medium", "high", "ultra"}) out.push_back({preset, SmaaPreset(preset)});
  SmaaParams color = SmaaPreset("high");
  color.detection = SmaaParams::Detection::kColor;
  out.push_back({"high-color", color});
  SmaaParams exact = SmaaPreset("ultra");
  exact.subtexel = SubTexel::kExact;
  out.push_back({"ultra-exact", exact});
  SmaaParams edge_case = SmaaPreset("high");
  edge_case.threshold = 0.0f;
  edge_case.max_search_steps = 0;
  edge_case.max_search_steps_diag = 0;
  edge_case.corner_rounding = 100;
  edge_case.local_contrast_factor = 0.0f;
  out.push_back({"thr0-steps0", edge_case});
  SmaaParams long_search = SmaaPreset("ultra");
  long_search.max_search_steps = 112;
  long_search.max_search_steps_diag = 20;
  long_search.corner_rounding = 0;
  long_search.detection = SmaaParams::Detection::kColor;
  long_search.subtexel = SubTexel::kExact;
  out.push_back({"steps112-color-exact", long_search});
  return out;
}

void ExpectSame(const Image8& img, const SmaaParams& p, const std::string& view, const std::string& what) {
  PostStats fs, rs;
  const Image8 fast = Smaa(img, p, view, &fs);
  const Image8 ref = SmaaReference(img, p, view, &rs);
  ASSERT_EQ(fast.Width(), ref.Width()) << what;
  size_t first = fast.Data().size();
  for (size_t i = 0; i < fast.Data().size(); ++i) {
    if (fast.Data()[i] != ref.Data()[i]) {
      first = i;
      break;
    }
  }
  EXPECT_EQ(first, fast.Data().size()) << what << ": first differing byte at pixel "
                                       << (first / 4) % std::max(1, img.Width()) << ","
                                       << (first / 4) / std::max(1, img.Width());
  EXPECT_EQ(fs.taps, rs.taps) << what;
}

TEST(SmaaFast, BitIdenticalToReference) {
  std::vector<NamedFrame> frames = perf_test::SyntheticFrames();
  for (const auto& s : perf_test::SceneFrames()) frames.push_back(s);
  for (int threads : {1, 2}) {
    SetThreadCount(threads);
    for (const auto& [name, p] : Settings()) {
      for (const auto& f : frames) {
        ExpectSame(f.img, p, "", name + " on " + f.name + " t" + std::to_string(threads));
      }
    }
  }
  SetThreadCount(0);
}

TEST(SmaaFast, DebugViewsIdentical) {
  const auto& frames = perf_test::SceneFrames();
  for (const char* view : {"edges", "weights"}) {
    for (const auto& f : frames) ExpectSame(f.img, SmaaPreset("ultra"), view, std::string(view) + " on " + f.name);
  }
}

}  // namespace
}  // namespace aalab
