// Outputs made with kUninitialized (core/image.h) are written whole: every post filter that
// makes its output that way gives the same bytes as the zero-initialised path, on frames
// whose every pixel it writes. SetUninitializedPoison fills such images with a chosen byte
// instead of leaving them unset; a byte the filter forgot to write then differs between the
// poisons 0x00 (what Image(w, h, c) gives), 0xA5 and 0x5A. Planted bug: drop the alpha store
// of TAA's encode loop (methods/taa.cpp) or skip one row of SMAA's copy, and these tests fail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/parallel.h"
#include "methods/cmaa2.h"
#include "methods/fxaa1.h"
#include "methods/fxaa311.h"
#include "methods/registry.h"
#include "methods/smaa.h"
#include "tests/equivalence/frames.h"

namespace aalab {
namespace {

/// Resets the poison when a test ends, even on failure.
struct PoisonGuard {
  ~PoisonGuard() { SetUninitializedPoison(-1); }
};

using Filter = std::function<Image8(const Image8&)>;

/// The filter's output under poisons 0x00, 0xA5 and 0x5A, at 1 and 2 threads: all equal.
void ExpectWrittenWhole(const std::string& what, const Filter& filter, const Image8& in) {
  PoisonGuard guard;
  SetUninitializedPoison(0);
  SetThreadCount(1);
  const Image8 zero = filter(in);
  ASSERT_EQ(zero.Width(), in.Width()) << what;
  for (int threads : {1, 2}) {
    SetThreadCount(threads);
    for (int poison : {0xA5, 0x5A}) {
      SetUninitializedPoison(poison);
      const Image8 out = filter(in);
      ASSERT_EQ(out.Data().size(), zero.Data().size()) << what;
      size_t first = out.Data().size();
      for (size_t i = 0; i < out.Data().size(); ++i) {
        if (out.Data()[i] != zero.Data()[i]) {
          first = i;
          break;
        }
      }
      EXPECT_EQ(first, out.Data().size())
          << what << ": byte " << first << " (pixel " << first / 4 << ", channel " << first % 4
          << ") not written; poison " << poison << ", " << threads << " thread(s)";
    }
  }
  SetThreadCount(0);
}

/// Frames with every pixel written by each filter: odd sizes, noise with random alpha, flat
/// areas (early exits and copies) and edges (the filters' own writes), real scenes.
std::vector<perf_test::NamedFrame> Frames() {
  std::vector<perf_test::NamedFrame> out;
  for (auto& f : perf_test::SyntheticFrames()) {
    if (f.img.Width() >= 17 && f.img.Height() >= 9) out.push_back(std::move(f));
  }
  const auto& scenes = perf_test::SceneFrames();
  out.push_back(scenes[1]);  // mesh
  out.push_back(scenes[3]);  // thin-wires
  return out;
}

TEST(UninitializedOutput, PoisonFillsAndZeroPathIsTheFillConstructor) {
  PoisonGuard guard;
  SetUninitializedPoison(0xA5);
  const Image8 a(5, 3, 4, kUninitialized);
  for (uint8_t v : a.Data()) EXPECT_EQ(v, 0xA5);
  const ImageF f(3, 2, 3, kUninitialized);
  for (float v : f.Data()) {
    uint32_t bits = 0;
    std::memcpy(&bits, &v, 4);
    EXPECT_EQ(bits, 0xA5A5A5A5u);
  }
  SetUninitializedPoison(0);
  EXPECT_EQ(Image8(5, 3, 4, kUninitialized), Image8(5, 3, 4));
  EXPECT_THROW(SetUninitializedPoison(256), std::exception);
}

TEST(UninitializedOutput, Fxaa311WritesEveryByte) {
  for (int preset : {12, 39}) {
    Fxaa311Params p;
    p.steps = Fxaa311PresetSteps(preset);
    for (const auto& f : Frames()) {
      ExpectWrittenWhole(
          "fxaa311-p" + std::to_string(preset) + " " + f.name,
          [&](const Image8& in) { return Fxaa311(in, p, nullptr); }, f.img);
    }
  }
}

TEST(UninitializedOutput, Fxaa1WritesEveryByte) {
  const Fxaa1Params p;
  for (const auto& f : Frames()) {
    ExpectWrittenWhole(
        "fxaa1 " + f.name, [&](const Image8& in) { return Fxaa1(in, p, "", nullptr); }, f.img);
  }
}

TEST(UninitializedOutput, SmaaWritesEveryByte) {
  for (const char* preset : {"low", "ultra"}) {
    const SmaaParams p = SmaaPreset(preset);
    for (const auto& f : Frames()) {
      ExpectWrittenWhole(
          std::string("smaa-") + preset + " " + f.name, [&](const Image8& in) { return Smaa(in, p, "", nullptr); },
          f.img);
    }
  }
}

TEST(UninitializedOutput, Cmaa2WritesEveryByte) {
  const Cmaa2Params p;
  for (const auto& f : Frames()) {
    ExpectWrittenWhole(
        "cmaa2 " + f.name, [&](const Image8& in) { return Cmaa2(in, p, nullptr); }, f.img);
  }
}

/// Two steps of a temporal method: frame 0 (no history) and frame 1 over `in` with motion
/// (-1.3, +0.6) px and a column of pixels without history (NaN); the outputs one above the
/// other (the stacking image is zero-filled: only the steps' outputs can carry the poison).
Image8 TwoSteps(const std::string& method, const Image8& in) {
  const MethodPlan plan = MakeMethod(method);
  auto state = plan.make_state();
  const int w = in.Width(), h = in.Height();
  TemporalInput in0;
  in0.frame = &in;
  const Image8 a = state->Step(in0, nullptr);
  std::vector<float> prev(2 * static_cast<size_t>(w) * static_cast<size_t>(h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = 2 * (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x));
      prev[i] = x == w / 2 ? NAN : static_cast<float>(x) + 0.5f - 1.3f;
      prev[i + 1] = static_cast<float>(y) + 0.5f + 0.6f;
    }
  }
  TemporalInput in1;
  in1.frame = &in;
  in1.previous = &prev;
  in1.frame_index = 1;
  const Image8 b = state->Step(in1, nullptr);
  Image8 both(w, 2 * h, 4);
  for (int y = 0; y < h; ++y) {
    std::copy(a.Row(y), a.Row(y) + 4 * w, both.Row(y));
    std::copy(b.Row(y), b.Row(y) + 4 * w, both.Row(h + y));
  }
  return both;
}

TEST(UninitializedOutput, TaaWritesEveryByte) {
  for (const char* method : {"taa", "taa-prod"}) {
    for (const auto& f : Frames()) {
      ExpectWrittenWhole(
          std::string(method) + " " + f.name, [&](const Image8& in) { return TwoSteps(method, in); }, f.img);
    }
  }
}

}  // namespace
}  // namespace aalab
