// FXAA 3.11's edge pixels eight at a time (methods/fxaa311_search.h) against the scalar
// production path (the kernel switched off) and the reference implementation (ShadePixel per
// pixel through BilinearSampler): same bytes and same tap counts. Frames with edges in both
// directions, at the borders (clamped taps and search ends past the frame), long edges (the
// search runs to its last step), and edge counts that leave a partial batch; every 8-bit luma
// mode, both orders, presets with short and long step tables, 1 and 2 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "methods/fxaa311.h"
#include "methods/fxaa311_search.h"

namespace aalab {
namespace {

using fxaa311_internal::EdgePixelsX8Available;
using fxaa311_internal::SetEdgePixelsX8Enabled;
using Luma = Fxaa311Params::Luma;
using Order = Fxaa311Params::Order;

uint64_t Next(uint64_t& s) {
  s = s * 6364136223846793005ULL + 1442695040888963407ULL;
  return s >> 33;
}

// w x h: a bright slanted band (long, nearly horizontal edges: searches of many steps), a
// steep dark wedge (nearly vertical edges), a few random blocks and single-pixel specks
// (short searches, ends in both directions), colours that differ per channel so the final rgb
// tap's three channels differ. Edges touch every border.
Image8 TestFrame(int w, int h, uint64_t seed) {
  Image8 img(w, h, 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.Pixel(x, y);
      const bool band = (y * 37 + x * 3) % (h * 37) < h * 12;  // slope 3/37
      const bool wedge = (x * 41 + y * 5) % (w * 41) < w * 9;  // slope 41/5
      p[0] = static_cast<uint8_t>(band ? 230 : 40);
      p[1] = static_cast<uint8_t>(wedge ? 20 : (band ? 200 : 90));
      p[2] = static_cast<uint8_t>(wedge ? 60 : 150);
      p[3] = static_cast<uint8_t>(x * 7 + y);  // alpha is ignored
    }
  }
  for (int k = 0; k < w * h / 40; ++k) {
    const int x = static_cast<int>(Next(seed) % static_cast<uint64_t>(w));
    const int y = static_cast<int>(Next(seed) % static_cast<uint64_t>(h));
    const uint64_t r = Next(seed);
    const int bw = 1 + static_cast<int>(r % 5), bh = 1 + static_cast<int>((r >> 8) % 4);
    for (int yy = y; yy < std::min(h, y + bh); ++yy) {
      for (int xx = x; xx < std::min(w, x + bw); ++xx) {
        uint8_t* p = img.Pixel(xx, yy);
        p[0] = static_cast<uint8_t>(r >> 16);
        p[1] = static_cast<uint8_t>(r >> 24);
        p[2] = static_cast<uint8_t>(r >> 3);
      }
    }
  }
  return img;
}

struct Setting {
  std::string name;
  Fxaa311Params p;
};

// prefix + the decimal n (built by appending: GCC 12 warns, wrongly, on "literal" + string).
std::string Name(const char* prefix, int n) {
  std::string s(prefix);
  s += std::to_string(n);
  return s;
}

std::vector<Setting> Settings() {
  std::vector<Setting> out;
  for (int preset : {10, 12, 29, 39}) {
    Fxaa311Params p;
    p.steps = Fxaa311PresetSteps(preset);
    out.push_back({Name("p", preset), p});
  }
  for (Luma luma : {Luma::kRec601, Luma::kGreen, Luma::kSqrtLuminance}) {
    for (Order order : {Order::kFxaa311, Order::kSeed003Glsl}) {
      Fxaa311Params p;
      p.steps = Fxaa311PresetSteps(39);
      p.luma = luma;
      p.order = order;
      p.subpix = 1.0f;
      p.edge_threshold = 0.063f;
      p.edge_threshold_min = 0.0312f;
      out.push_back({Name("luma", static_cast<int>(luma)) + Name("-order", static_cast<int>(order)), p});
    }
  }
  Fxaa311Params tutorial = FxaaTutorialHighParams();
  out.push_back({"tutorial-high", tutorial});
  Fxaa311Params zero;
  zero.steps = Fxaa311PresetSteps(20);
  zero.edge_threshold = 0.0f;
  zero.edge_threshold_min = 0.0f;  // nearly every pixel goes through the search
  out.push_back({"thr0", zero});
  return out;
}

struct Result {
  Image8 img;
  uint64_t taps = 0;
};

Result RunFilter(const Image8& in, const Fxaa311Params& p, bool x8) {
  SetEdgePixelsX8Enabled(x8);
  PostStats s;
  Result r{Fxaa311(in, p, &s), 0};
  r.taps = s.taps;
  SetEdgePixelsX8Enabled(true);
  return r;
}

// Number of pixels whose bytes differ.
long DifferingPixels(const Image8& a, const Image8& b) {
  long n = 0;
  for (int y = 0; y < a.Height(); ++y) {
    for (int x = 0; x < a.Width(); ++x) n += std::memcmp(a.Pixel(x, y), b.Pixel(x, y), 4) != 0;
  }
  return n;
}

TEST(Fxaa311Search, EightAtATimeEqualsScalarAndReference) {
  if (!EdgePixelsX8Available()) GTEST_SKIP() << "no AVX2 on this CPU: only the scalar path runs";
  const std::vector<std::pair<int, int>> sizes = {{173, 67}, {61, 130}, {9, 5}, {3, 1}, {1, 11}};
  uint64_t seed = 7;
  for (auto [w, h] : sizes) {
    const Image8 in = TestFrame(w, h, seed++);
    for (const Setting& s : Settings()) {
      const std::string what = s.name + Name(" ", w) + Name("x", h);
      const Result x8 = RunFilter(in, s.p, true);
      const Result scalar = RunFilter(in, s.p, false);
      PostStats rs;
      const Image8 ref = Fxaa311Reference(in, s.p, &rs);
      EXPECT_EQ(DifferingPixels(x8.img, scalar.img), 0) << what;
      EXPECT_EQ(DifferingPixels(x8.img, ref), 0) << what;
      EXPECT_EQ(x8.taps, scalar.taps) << what;
      EXPECT_EQ(x8.taps, rs.taps) << what;
      // The frame must exercise the search: many edge pixels moved (more than the 5 taps each
      // of an all-exit frame), unless the frame is a single row or column.
      if (w > 3 && h > 3) {
        EXPECT_GT(x8.taps, 5u * static_cast<uint64_t>(w) * h + 100u) << what;
        EXPECT_GT(DifferingPixels(x8.img, in), w * h / 20) << what;
      }
    }
  }
}

TEST(Fxaa311Search, SameBitsAtOneAndTwoThreads) {
  if (!EdgePixelsX8Available()) GTEST_SKIP() << "no AVX2 on this CPU: only the scalar path runs";
  const Image8 in = TestFrame(320, 181, 3);
  Fxaa311Params p;
  p.steps = Fxaa311PresetSteps(39);
  SetThreadCount(1);
  const Result one = RunFilter(in, p, true);
  SetThreadCount(2);
  const Result two = RunFilter(in, p, true);
  SetThreadCount(0);
  const Result scalar = RunFilter(in, p, false);
  EXPECT_EQ(DifferingPixels(one.img, two.img), 0);
  EXPECT_EQ(DifferingPixels(one.img, scalar.img), 0);
  EXPECT_EQ(one.taps, two.taps);
  EXPECT_EQ(one.taps, scalar.taps);
}

}  // namespace
}  // namespace aalab
