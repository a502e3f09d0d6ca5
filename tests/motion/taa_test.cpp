// TAA on a still scene converges towards the reference: a bound derived from the blend.
//
// The bound. With clip=none the output is an exponential moving average (EMA) of the
// jittered samples, weights α(1−α)^k. For a pixel crossed by one straight edge between
// colours 0 and 1 (linear), each sample is 1 with probability c (the pixel's coverage,
// which the box-filtered reference is) if the jitter were independent and uniform; the EMA
// then has variance c(1−c)·Σw² = c(1−c)·α/(2−α) (Σw² of the EMA weights). Averaged over
// edge offsets spread uniformly (a slanted edge), E[c(1−c)] = 1/6, so E[err²] = α/(6(2−α)).
// `none` samples the centre: err = min(c, 1−c), E[err²] = 1/12. Ratio: 2α/(2−α) = 0.105 at
// α = 0.1. Halton points are stratified (one per 1/16 column in 16 frames), whose error is
// at most that of independent points for a step function, so the measured ratio of the
// edge pixels' mean squared linear error must stay below 2α/(2−α) — with 1.5× room for the
// finite number of edge pixels (~100) and the reference's own error (256 spp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "harness/core/color.h"
#include "harness/core/parallel.h"
#include "methods/registry.h"
#include "methods/taa.h"
#include "scenes/motion_render.h"
#include "scenes/render.h"
#include "../scenes/scene_test_util.h"

namespace aalab {
namespace {

struct Result {
  double taa_mse = 0, none_mse = 0;
  size_t edge_pixels = 0;
  bool interior_exact = true;
};

Result RunStill(const std::string& method, int frames) {
  const Scene s = testing::ParseText(R"({"name": "edge", "effects": ["unlit"],
    "camera": {"type": "orthographic", "position": [0,0,10], "look_at": [0,0,0], "height": 4},
    "materials": {"w": {"shading": "unlit", "color": [1, 1, 1]}},
    "objects": [{"shape": "quad", "size": [4, 8], "material": "w", "transform": {"translate": [-1.6, 0, 0], "rotate": [0, 0, 7]}}]})");
  const int W = 64, H = 48;
  const Tracer tracer(s);
  const Reference ref = RenderReference(tracer, W, H, 16, 1, nullptr);
  const Image8 none = RenderFrame(tracer, W, H, RenderSpec{}, 1, nullptr);
  const MethodPlan plan = MakeMethod(method);
  auto state = plan.make_state();
  Image8 out;
  for (int k = 0; k < frames; ++k) {
    const FrameJitter j = FrameJitterAt(plan.render.jitter, k);
    const SurfaceFrame sf = RenderSurfaceFrame(tracer, W, H, j, nullptr);
    std::vector<float> prev;
    if (k > 0) {
      for (const glm::vec2& p : PreviousPositions(s, k, sf, j)) {
        prev.push_back(p.x);
        prev.push_back(p.y);
      }
    }
    TemporalInput in;
    in.frame = &sf.image;
    in.previous = k > 0 ? &prev : nullptr;
    in.frame_index = k;
    out = state->Step(in, nullptr);
  }
  Result r;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      if (ref.edge_mask.At(x, y, 0) < 0.5f) {
        r.interior_exact &= out.At(x, y, 0) == none.At(x, y, 0);
        continue;
      }
      if (ref.edge_mask_raw.At(x, y, 0) < 0.5f) continue;
      const double c = SrgbDecode(ref.image.At(x, y, 0));  // coverage (linear)
      const double t = SrgbDecode8(out.At(x, y, 0)), n = SrgbDecode8(none.At(x, y, 0));
      r.taa_mse += (t - c) * (t - c);
      r.none_mse += (n - c) * (n - c);
      ++r.edge_pixels;
    }
  }
  r.taa_mse /= static_cast<double>(r.edge_pixels);
  r.none_mse /= static_cast<double>(r.edge_pixels);
  return r;
}

TEST(Taa, StillSceneConvergesWithinTheEmaBound) {
  const double alpha = 0.1;
  const Result r = RunStill("taa:clip=none", 64);
  ASSERT_GT(r.edge_pixels, 40u);
  std::printf("taa:clip=none, 64 frames: edge MSE ratio to none %.4f (bound %.4f, %zu edge pixels)\n",
              r.taa_mse / r.none_mse, 2 * alpha / (2 - alpha), r.edge_pixels);
  EXPECT_LT(r.taa_mse, 1.5 * 2 * alpha / (2 - alpha) * r.none_mse) << r.taa_mse << " vs none " << r.none_mse;
  EXPECT_TRUE(r.interior_exact);  // flat areas are exact: every sample is the same colour
}

TEST(Taa, DefaultClippingStillConverges) {
  // Variance clipping may pull the history toward the current sample (a bias the bound
  // above does not cover); it must still remove most of the 1x frame's edge error.
  const Result r = RunStill("taa", 64);
  std::printf("taa (variance clip), 64 frames: edge MSE ratio to none %.4f\n", r.taa_mse / r.none_mse);
  EXPECT_LT(r.taa_mse, 0.5 * r.none_mse) << r.taa_mse << " vs none " << r.none_mse;
  EXPECT_TRUE(r.interior_exact);
}

}  // namespace
}  // namespace aalab

namespace aalab {
namespace {

TEST(Taa, FastEncodeIsTheDirectEncodeBitForBit) {
  // 2^22 + 1 evenly spaced values over [0, 1] and the 64 floats around every code boundary.
  constexpr int kSteps = 1 << 22;
  for (int i = 0; i <= kSteps; ++i) {
    const float v = static_cast<float>(i) / kSteps;
    ASSERT_EQ(EncodeSrgb8(v), QuantizeUnorm8(SrgbEncode(v))) << v;
  }
  for (int k = 1; k < 256; ++k) {
    float v = SrgbDecode((static_cast<float>(k) - 0.5f) / 255.0f);  // near the boundary of code k
    for (int d = 0; d < 32; ++d) v = std::nextafter(v, 0.0f);
    for (int d = 0; d < 64; ++d, v = std::nextafter(v, 1.0f)) ASSERT_EQ(EncodeSrgb8(v), QuantizeUnorm8(SrgbEncode(v))) << v;
  }
}

// The production temporal step against the simple one (TaaReferenceCopy), bit for bit: every
// output byte, the taps and (through the later frames) the history, over sequences of random
// frames with random previous positions (inside, on the border, outside, NaN, exact texel
// centres), for every clip mode, odd sizes from 1x1, at 1 and 2 threads.
uint64_t Next(uint64_t& s) {
  s ^= s << 13;
  s ^= s >> 7;
  s ^= s << 17;
  return s;
}

TEST(Taa, FastStepIsTheReferenceStepBitForBit) {
  for (int threads : {1, 2}) {
    SetThreadCount(threads);
    for (const char* spec : {"taa", "taa:clip=minmax", "taa:clip=none", "taa:gamma=0.25,alpha=0.5", "taa:alpha=1"}) {
      for (auto [W, H] : std::vector<std::pair<int, int>>{{1, 1}, {2, 3}, {7, 5}, {33, 17}, {64, 48}}) {
        const MethodPlan plan = MakeMethod(spec);
        auto fast = plan.make_state();
        auto ref = TaaReferenceCopy(*fast);
        uint64_t seed = 0x9e3779b97f4a7c15ull ^ (static_cast<uint64_t>(W) << 20) ^ static_cast<uint64_t>(H);
        for (int k = 0; k < 5; ++k) {
          Image8 frame(W, H, 4);
          // Smooth areas (small differences, where the variance box is tight) and jumps.
          for (size_t i = 0; i < frame.Data().size(); ++i) {
            const uint64_t r = Next(seed);
            frame.Data()[i] = static_cast<uint8_t>((r & 3) == 0 ? r >> 56 : 100 + ((r >> 60) & 7));
          }
          std::vector<float> prev(2 * static_cast<size_t>(W) * H);
          for (size_t i = 0; i < prev.size(); ++i) {
            const uint64_t r = Next(seed);
            const float extent = static_cast<float>(i % 2 == 0 ? W : H);
            switch (r & 7) {
              case 0: prev[i] = std::nanf(""); break;
              case 1: prev[i] = (r & 8) ? -0.25f : extent + 0.25f; break;  // outside
              case 2: prev[i] = (r & 8) ? 0.0f : extent; break;             // on the border
              case 3: prev[i] = std::floor(static_cast<float>((r >> 8) % 1000) / 1000.0f * extent) + 0.5f; break;
              default: prev[i] = static_cast<float>((r >> 8) % 100000) / 100000.0f * extent; break;
            }
          }
          TemporalInput in;
          in.frame = &frame;
          in.previous = k > 0 ? &prev : nullptr;
          in.frame_index = k;
          PostStats sf, sr;
          const Image8 a = fast->Step(in, &sf);
          const Image8 b = ref->Step(in, &sr);
          const std::string what = std::string(spec) + " " + std::to_string(W) + "x" + std::to_string(H) + " frame " +
                                   std::to_string(k) + " threads " + std::to_string(threads);
          ASSERT_TRUE(a == b) << what;
          EXPECT_EQ(sf.taps, sr.taps) << what;
        }
      }
    }
  }
  SetThreadCount(0);
}

}  // namespace
}  // namespace aalab
