// The production FXAA paths (luma plane, row-wise early exit, edge pixels only) against the
// simple per-pixel reference implementations: same bytes and same tap counts, on rendered
// library frames and adversarial synthetic frames, for every registered preset and for
// parameter settings that reach the edge cases (thresholds 0, every luma mode, both orders).
#include <gtest/gtest.h>

#include <cstring>

#include "core/parallel.h"
#include "methods/fxaa1.h"
#include "methods/fxaa311.h"
#include "methods/registry.h"
#include "methods/rescale.h"
#include "tests/equivalence/frames.h"

namespace aalab {
namespace {

using perf_test::NamedFrame;

std::vector<NamedFrame> AllFrames() {
  std::vector<NamedFrame> f = perf_test::SyntheticFrames();
  for (const auto& s : perf_test::SceneFrames()) f.push_back(s);
  return f;
}

// First differing byte, or -1.
long FirstDifference(const Image8& a, const Image8& b) {
  if (a.Width() != b.Width() || a.Height() != b.Height() || a.Channels() != b.Channels()) return 0;
  for (size_t i = 0; i < a.Data().size(); ++i) {
    if (a.Data()[i] != b.Data()[i]) return static_cast<long>(i);
  }
  return -1;
}

void ExpectFxaa311Same(const Image8& img, const Fxaa311Params& p, const std::string& what) {
  PostStats fast_stats, ref_stats;
  const Image8 fast = Fxaa311(img, p, &fast_stats);
  const Image8 ref = Fxaa311Reference(img, p, &ref_stats);
  const long d = FirstDifference(fast, ref);
  EXPECT_EQ(d, -1) << what << ": first differing byte " << d << " (pixel " << (d / 4) % img.Width() << ","
                   << (d / 4) / std::max(1, img.Width()) << ")";
  EXPECT_EQ(fast_stats.taps, ref_stats.taps) << what;
}

// Every registered FXAA 3.11 post filter at its defaults, with the typed parameters its
// post filter runs with (MethodPlan::config), named as in the registry; then settings that
// reach the edge cases.
std::vector<std::pair<std::string, Fxaa311Params>> Fxaa311Settings() {
  std::vector<std::pair<std::string, Fxaa311Params>> out;
  for (const auto& e : MethodRegistry()) {
    const MethodPlan plan = MakeMethod(e.name);
    if (const auto* p = plan.Config<Fxaa311Params>(); p && plan.IsPostOnly()) out.push_back({plan.name, *p});
  }
  // Every luma mode with both orders, thresholds 0 (range = 0 pixels reach the guard), and
  // extreme subpix values.
  const Fxaa311Params::Luma lumas[] = {Fxaa311Params::Luma::kRec601, Fxaa311Params::Luma::kRec601Rgb,
                                       Fxaa311Params::Luma::kGreen, Fxaa311Params::Luma::kSqrtLuminance};
  for (auto luma : lumas) {
    for (auto order : {Fxaa311Params::Order::kFxaa311, Fxaa311Params::Order::kSeed003Glsl}) {
      Fxaa311Params p;
      p.steps = Fxaa311PresetSteps(12);
      p.luma = luma;
      p.order = order;
      p.edge_threshold = 0.0f;
      p.edge_threshold_min = 0.0f;
      p.subpix = 1.0f;
      out.push_back({"luma" + std::to_string(static_cast<int>(luma)) + "-order" +
                         std::to_string(static_cast<int>(order)) + "-thr0",
                     p});
      p.edge_threshold = 0.063f;
      p.edge_threshold_min = 0.0312f;
      p.subpix = 0.0f;
      out.push_back({"luma" + std::to_string(static_cast<int>(luma)) + "-order" +
                         std::to_string(static_cast<int>(order)) + "-low-thr",
                     p});
    }
  }
  return out;
}

TEST(FastPath, Fxaa311EqualsReferenceOnEveryFrameAndSetting) {
  const auto frames = AllFrames();
  for (const auto& [name, p] : Fxaa311Settings()) {
    for (const auto& f : frames) ExpectFxaa311Same(f.img, p, name + " on " + f.name);
  }
}

// Off-centre 3x3 taps: the fast path decides near-tie early exits with the real taps and
// falls back to the reference when a frame is so wide or tall that the taps' deviation from
// the texel centres nears an 8-bit step (10000 wide: just below; 40000: above). Noise strips,
// a preset, the tutorial's luma, iter12 and the threshold-0 settings (every pixel an edge).
TEST(FastPath, Fxaa311EqualsReferenceOnVeryWideAndTallFrames) {
  uint64_t seed = 99;
  for (auto [w, h] : std::vector<std::pair<int, int>>{{10000, 2}, {2, 10000}, {40000, 1}, {1, 40000}}) {
    Image8 img(w, h, 4);
    for (auto& b : img.Data()) b = static_cast<uint8_t>((perf_test::NextRandom(seed) & 0x3f) * 4);
    for (const auto& [name, p] : Fxaa311Settings()) {
      const bool row = !name.starts_with("luma");  // a registry row, not an edge-case setting
      if ((row && !MakeMethod(name).in_default_list) || (!row && name.find("thr0") == std::string::npos)) continue;
      ExpectFxaa311Same(img, p, name + " noise " + std::to_string(w) + "x" + std::to_string(h));
    }
  }
}

TEST(FastPath, Fxaa311EqualsReferenceAtOneAndTwoThreads) {
  Fxaa311Params p;
  p.steps = Fxaa311PresetSteps(39);
  for (int threads : {1, 2}) {
    SetThreadCount(threads);
    for (const auto& f : perf_test::SceneFrames()) {
      ExpectFxaa311Same(f.img, p, f.name + " threads " + std::to_string(threads));
    }
  }
  SetThreadCount(0);
}

void ExpectFxaa1Same(const Image8& img, const Fxaa1Params& p, const std::string& what) {
  PostStats fast_stats, ref_stats;
  const Image8 fast = Fxaa1(img, p, "", &fast_stats);
  const Image8 ref = Fxaa1Reference(img, p, "", &ref_stats);
  const long d = FirstDifference(fast, ref);
  EXPECT_EQ(d, -1) << what << ": first differing byte " << d;
  EXPECT_EQ(fast_stats.taps, ref_stats.taps) << what;
}

TEST(FastPath, Fxaa1EqualsReferenceOnEveryFrameAndSetting) {
  std::vector<std::pair<std::string, Fxaa1Params>> settings;
  for (int preset = 0; preset <= 5; ++preset) settings.push_back({"p" + std::to_string(preset), Fxaa1Preset(preset)});
  Fxaa1Params zero = Fxaa1Preset(3);
  zero.edge_threshold = 0.0f;
  zero.edge_threshold_min = 0.0f;  // range = 0 pixels pass the check and take the guards
  settings.push_back({"thr0", zero});
  Fxaa1Params wide = Fxaa1Preset(2);
  wide.search_acceleration = 4;
  wide.search_steps = 64;
  wide.subpix_trim = 0.0f;
  wide.subpix_cap = 1.0f;
  wide.edge_threshold = 1.0f / 16.0f;
  settings.push_back({"wide", wide});
  const auto frames = AllFrames();
  for (const auto& [name, p] : settings) {
    for (const auto& f : frames) ExpectFxaa1Same(f.img, p, name + " on " + f.name);
  }
}

TEST(FastPath, Fxaa1DebugViewsStillComeFromTheReference) {
  const Image8& img = perf_test::SceneFrames()[0].img;
  for (const auto& view : Fxaa1DebugViews()) {
    EXPECT_TRUE(Fxaa1(img, Fxaa1Preset(3), view, nullptr) == Fxaa1Reference(img, Fxaa1Preset(3), view, nullptr))
        << view;
  }
}

TEST(FastPath, RescaleEqualsReferenceOnEveryFrameAndSize) {
  for (const auto& f : AllFrames()) {
    const int w = f.img.Width(), h = f.img.Height();
    const std::vector<std::pair<int, int>> sizes = {
        {w, h},         {1, 1}, {std::max(1, w * 3 / 4), std::max(1, h * 3 / 4)}, {w * 4 / 3 + 1, h * 4 / 3 + 1},
        {w * 2, h * 2}, {7, 5}};
    for (auto [ow, oh] : sizes) {
      for (Rescale kind : {Rescale::kBilinear, Rescale::kBicubic}) {
        PostStats a, b;
        const Image8 fast = RescaleFrame(f.img, ow, oh, kind, &a);
        const Image8 ref = RescaleFrameReference(f.img, ow, oh, kind, &b);
        EXPECT_EQ(FirstDifference(fast, ref), -1)
            << f.name << " -> " << ow << "x" << oh << " kind " << static_cast<int>(kind);
        EXPECT_EQ(a.taps, b.taps);
      }
    }
  }
}

}  // namespace
}  // namespace aalab
