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
using perf_test::NextRandom;

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

// The fused pass cuts a 32-row band that holds many of the frame's edge pixels into column
// pieces (methods/smaa_fused.cpp, FusedJobs: at most width / 128 of them), which the frames
// above, narrower than 256 pixels, never are. Frames of 4 to 6 pieces with edges in every
// column (a fine checker, diagonals, thin features), so that pieces' borders fall on edge
// pixels, against the reference at 1, 2 and 3 threads.
TEST(SmaaFast, ColumnPiecesIdenticalToReference) {
  std::vector<NamedFrame> frames;
  {
    const Scene scene = LoadScene("checker-plane");
    const Tracer tracer(scene);
    frames.push_back({"checker-plane 700x90", RenderFrame(tracer, 700, 90, RenderSpec{}, 1, nullptr)});
  }
  uint64_t seed = 777;
  for (auto [w, h] : std::vector<std::pair<int, int>>{{513, 41}, {769, 35}, {512, 70}}) {
    Image8 img(w, h, 4);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        uint8_t* p = img.Pixel(x, y);
        const int m = x % 256;
        const bool border = m <= 1 || m >= 254;          // thin features on the piece borders
        const bool diag = (x + 2 * y) % 37 < 2;          // long diagonal and orthogonal searches
        const bool cell = ((x / 3) + (y / 2)) % 2 == 0;  // a fine checker elsewhere
        const uint64_t r = NextRandom(seed);
        const uint8_t v = border ? ((x + y) % 3 == 0 ? 250 : 10) : diag ? 230 : cell ? 40 : 170;
        p[0] = v;
        p[1] = static_cast<uint8_t>(v ^ ((r & 1) ? 8 : 0));
        p[2] = static_cast<uint8_t>(255 - v);
        p[3] = static_cast<uint8_t>(r >> 8);
      }
    }
    frames.push_back({"borders " + std::to_string(w) + "x" + std::to_string(h), std::move(img)});
  }
  for (int threads : {1, 2, 3}) {
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
