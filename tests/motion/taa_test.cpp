// TAA on a still scene converges towards the reference (a bound derived from the blend);
// under motion it flickers less than `none` and leaves no ghost trail (below).
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
#include <cstring>
#include <cstdio>

#include "core/color.h"
#include "core/parallel.h"
#include "methods/registry.h"
#include "methods/taa.h"
#include "methods/taa_avx2.h"
#include "metrics/temporal.h"
#include "scenes/motion.h"
#include "scenes/motion_render.h"
#include "scenes/render.h"
#include "../scenes/scene_test_util.h"
#include "taa_test_util.h"

namespace aalab {
namespace {

struct Result {
  double taa_mse = 0, none_mse = 0;
  size_t edge_pixels = 0;
  bool interior_exact = true;
};

Result RunStill(const std::string& method, int frames) {
  const int W = 64, H = 48;
  const testing::StillEdge edge(W, H);
  const MethodPlan plan = MakeMethod(method);
  auto state = plan.make_state();
  Image8 out;
  for (int k = 0; k < frames; ++k) {
    const testing::TaaFrame f = testing::RenderTaaFrame(edge.scene, edge.tracer, plan.render.jitter, k, W, H);
    out = state->Step(f.Input(k), nullptr);
  }
  Result r;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      if (edge.ref.edge_mask.At(x, y, 0) < 0.5f) {
        r.interior_exact &= out.At(x, y, 0) == edge.none.At(x, y, 0);
        continue;
      }
      if (edge.ref.edge_mask_raw.At(x, y, 0) < 0.5f) continue;
      const double c = SrgbDecode(edge.ref.image.At(x, y, 0));  // coverage (linear)
      const double t = SrgbDecode8(out.At(x, y, 0)), n = SrgbDecode8(edge.none.At(x, y, 0));
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
  // Variance clipping may pull the history toward the current neighbourhood (a bias the
  // bound above does not cover). On a still scene the history is the converged average and
  // an edge pixel's 3×3 neighbourhood straddles the edge, so the box is wide and clipping is
  // rare: the default is held to the same bound as the plain accumulation, 1.5·2α/(2 − α) =
  // 0.158 of none's edge MSE (was a loose 0.5). That is a requirement, not a derivation of the
  // clipping's bias: measured 0.060 (clip=none: 0.036).
  const double alpha = 0.1;
  const Result r = RunStill("taa", 64);
  std::printf("taa (variance clip), 64 frames: edge MSE ratio to none %.4f (bound %.4f)\n", r.taa_mse / r.none_mse,
              1.5 * 2 * alpha / (2 - alpha));
  EXPECT_LT(r.taa_mse, 1.5 * 2 * alpha / (2 - alpha) * r.none_mse) << r.taa_mse << " vs none " << r.none_mse;
  EXPECT_TRUE(r.interior_exact);
}

// ---------------------------------------------------------------- under motion
//
// A white quad (12 × 24 px, rotated 7°: slanted edges) crosses a black background for 32
// frames at 64×48, run as `aalab run --frames 32` runs it (per-frame scene, jittered render,
// exact motion vectors, one state per sequence).
//
// Temporal error, at 0.37 px per frame. The 1x frame samples pixel centres, so as the slanted
// edges slide by a non-integer step the sampling phase changes every frame and the staircase
// crawls: an edge pixel's error jumps between −c and 1 − c (c its coverage) whenever the edge
// crosses its centre. TAA's edge pixels carry a reprojected average of ~1/α jittered samples,
// which follows the coverage instead, so the frame-to-frame change of its error
// (temporal_rmse, and temporal_edge_rmse on the edge masks: metrics/temporal.h) must be below
// none's. Measured when this test was written: 0.058 vs 0.074 (edge pixels 0.202 vs 0.258;
// at 0.25 and 0.5 px/frame too). Not at every speed: at 0.7 px/frame TAA's is above none's
// (about 0.08 vs 0.077; edge pixels 0.287 vs 0.261), and at exactly 1 px/frame, where none's
// frames are exact 1-px shifts of each other (the sampling phase never changes: no crawl),
// TAA's is higher still (0.099 vs 0.080). Why TAA changes more at these speeds (the
// neighbourhood clipping of edge pixels whose 3×3 box changes as the edge moves is the first
// suspect) is not analysed here; docs/motion.md's measurements are on the library scenes.
//
// Ghost trail, at 0.37 and 1 px per frame. Behind the quad, a pixel it covered in one of the
// last 15 frames whose 5×5 neighbourhood in the current reference is pure background: its 3×3
// neighbourhood's jittered samples (each inside its own pixel) can then only see background
// (the quad is convex and 12 px wide: a sample on it inside the 3×3 would put covered samples
// of the 64-spp reference into the 5×5), so the rectification box is the background colour
// ± 1e-8 (methods/taa.cpp's FLT_EPS extents), the reprojected white history is clipped onto
// it, and the output is the background's code exactly — what `none` shows. Without
// rectification (clip=none) the history there decays only as (1 − α)^k: 0.9^15 = 0.21 of
// white after 15 frames, sRGB code ~125: a trail, which the last test checks is seen (the
// check can fail).

struct MotionResult {
  double temporal_rmse = 0, temporal_edge_rmse = 0;            ///< the method's
  double none_temporal_rmse = 0, none_temporal_edge_rmse = 0;  ///< none's
  int trail_pixels = 0;  ///< pixels behind the quad checked for a ghost (frames 16..31)
  int ghosts = 0;        ///< of those, pixels whose output differs from the background's code
};

MotionResult RunMoving(const std::string& method, double px_per_frame) {
  // 12 px per scene unit (height 4 over 48 px): px_per_frame · 31 / 12 units in 31 frames.
  const std::string travel = std::to_string(px_per_frame * 31.0 / 12.0);
  const Scene s = testing::ParseText(R"({"name": "moving-quad", "effects": ["unlit"], "background": [0, 0, 0],
    "camera": {"type": "orthographic", "position": [0,0,10], "look_at": [0,0,0], "height": 4},
    "materials": {"w": {"shading": "unlit", "color": [1, 1, 1]}},
    "objects": [{"shape": "quad", "size": [1, 2], "material": "w",
                 "transform": {"translate": [-1.2, 0, 0], "rotate": [0, 0, 7]},
                 "motion": {"keys": [{"frame": 0}, {"frame": 31, "translate": [)" +
                                     travel + R"(, 0, 0]}]}}],
    "animation": {"frames": 32}})");
  const int W = 64, H = 48, F = 32;
  const MethodPlan plan = MakeMethod(method);
  auto state = plan.make_state();
  TemporalError taa_te, none_te;
  std::vector<ImageF> refs;  // every frame's reference, for the trail
  MotionResult r;
  for (int k = 0; k < F; ++k) {
    const Scene frame_scene = SceneAtFrame(s, k);
    const Tracer tracer(frame_scene);
    const Reference ref = RenderReference(tracer, W, H, 8, 1, nullptr);
    const Image8 none = RenderFrame(tracer, W, H, RenderSpec{}, 1, nullptr);
    const testing::TaaFrame f = testing::RenderTaaFrame(s, tracer, plan.render.jitter, k, W, H);
    const Image8 out = state->Step(f.Input(k), nullptr);
    taa_te.AddFrame(ToFloat(out, 3), ref.image, &ref.edge_mask);
    none_te.AddFrame(ToFloat(none, 3), ref.image, &ref.edge_mask);
    refs.push_back(ref.image);
    if (k < 16) continue;
    for (int y = 2; y < H - 2; ++y) {
      for (int x = 2; x < W - 2; ++x) {
        bool clear = true;
        for (int dy = -2; dy <= 2 && clear; ++dy) {
          for (int dx = -2; dx <= 2 && clear; ++dx) clear = ref.image.At(x + dx, y + dy, 0) == 0.0f;
        }
        bool was_covered = false;
        for (int back = 1; back <= 15; ++back) was_covered |= refs[static_cast<size_t>(k - back)].At(x, y, 0) == 1.0f;
        if (!clear || !was_covered) continue;
        ++r.trail_pixels;
        r.ghosts += out.At(x, y, 0) != none.At(x, y, 0) || none.At(x, y, 0) != 0;
      }
    }
  }
  auto value = [](const TemporalError& te, const char* name) {
    for (const auto& v : te.Values()) {
      if (v.name == name) return *v.value;
    }
    ADD_FAILURE() << "no " << name;
    return 0.0;
  };
  r.temporal_rmse = value(taa_te, "temporal_rmse");
  r.temporal_edge_rmse = value(taa_te, "temporal_edge_rmse");
  r.none_temporal_rmse = value(none_te, "temporal_rmse");
  r.none_temporal_edge_rmse = value(none_te, "temporal_edge_rmse");
  return r;
}

TEST(Taa, SlowMotionFlickersLessThanNoneAndLeavesNoTrail) {
  const MotionResult r = RunMoving("taa", 0.37);
  std::printf(
      "taa, quad moving 0.37 px/frame: temporal_rmse %.5f (none %.5f), temporal_edge_rmse %.5f (none %.5f); "
      "%d trail pixels, %d ghosts\n",
      r.temporal_rmse, r.none_temporal_rmse, r.temporal_edge_rmse, r.none_temporal_edge_rmse, r.trail_pixels, r.ghosts);
  EXPECT_LT(r.temporal_rmse, r.none_temporal_rmse);
  EXPECT_LT(r.temporal_edge_rmse, r.none_temporal_edge_rmse);
  // 16 frames × a strip ~2.5 px wide (15 frames · 0.37 px less the 5×5 margin) × ~20 px tall.
  EXPECT_GT(r.trail_pixels, 16 * 30);
  EXPECT_EQ(r.ghosts, 0);
}

TEST(Taa, FastMotionLeavesNoTrail) {
  const MotionResult r = RunMoving("taa", 1.0);
  std::printf("taa, quad moving 1 px/frame: temporal_rmse %.5f (none %.5f); %d trail pixels, %d ghosts\n",
              r.temporal_rmse, r.none_temporal_rmse, r.trail_pixels, r.ghosts);
  // 16 frames × a strip ~12 px wide (15 px of travel less the 5×5 margin) × ~20 px tall.
  EXPECT_GT(r.trail_pixels, 16 * 100);
  EXPECT_EQ(r.ghosts, 0);
}

TEST(Taa, WithoutRectificationTheTrailIsSeen) {
  // The same sequence with clip=none: the trail check above is able to fail.
  const MotionResult r = RunMoving("taa:clip=none", 1.0);
  std::printf("taa:clip=none: %d of %d trail pixels ghost\n", r.ghosts, r.trail_pixels);
  EXPECT_GT(r.ghosts, r.trail_pixels / 2);
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
    for (int d = 0; d < 64; ++d, v = std::nextafter(v, 1.0f))
      ASSERT_EQ(EncodeSrgb8(v), QuantizeUnorm8(SrgbEncode(v))) << v;
  }
}

// The row encode (where the CPU has them AVX-512 sixteen pixels at a time and AVX2 eight; SSE2
// four; the scalar tail) against the direct formula: around every code boundary and on a
// dense grid, each value in each channel position, with -0, 0 and 1, in rows whose width is
// not a multiple of 4 (31: one block of each width and a scalar tail; 13 and 15 without the
// AVX-512 block).
TEST(Taa, RowEncodeIsTheDirectEncodeBitForBit) {
  std::vector<float> values = {-0.0f, 0.0f, 1.0f, std::nextafter(1.0f, 0.0f), 1e-30f, 1e-7f};
  for (int i = 0; i <= (1 << 18); ++i) values.push_back(static_cast<float>(i) / (1 << 18));
  for (int k = 1; k < 256; ++k) {
    float v = SrgbDecode((static_cast<float>(k) - 0.5f) / 255.0f);
    for (int d = 0; d < 8; ++d) v = std::nextafter(v, 0.0f);
    for (int d = 0; d < 16; ++d, v = std::nextafter(v, 1.0f)) values.push_back(v);
  }
  const int n = static_cast<int>(values.size());
  for (int shift = 0; shift < 3; ++shift) {  // each value in R, G and B
    for (int w : {n, n - 1, 31, 15, 13, 7, 3}) {
      std::vector<float> ch[3];
      for (int c = 0; c < 3; ++c) {
        for (int x = 0; x < w; ++x) ch[c].push_back(values[static_cast<size_t>((x + 5 * c + shift * 11) % n)]);
      }
      std::vector<uint8_t> rgba(4 * static_cast<size_t>(w), 0);
      EncodeSrgb8Rgba(ch[0].data(), ch[1].data(), ch[2].data(), w, rgba.data());
      for (int x = 0; x < w; ++x) {
        for (int c = 0; c < 3; ++c) {
          const float v = ch[c][static_cast<size_t>(x)];
          ASSERT_EQ(rgba[4 * static_cast<size_t>(x) + c], QuantizeUnorm8(SrgbEncode(v))) << v << " x " << x;
        }
        ASSERT_EQ(rgba[4 * static_cast<size_t>(x) + 3], 255) << x;
      }
    }
  }
}

// The AVX-512 box's division by 9 (methods/taa_avx512.cpp Div9x16: a product with RN(1/9)
// and an FMA correction) against the division, bit for bit, for +0 and every float of
// magnitude from 2^-100 to 16: the box divides sums of nine YCoCg values of decoded 8-bit
// colours and their squares, which lie within ±9, are never −0 (they start from +0) and are
// 0 or far above 2^-100 (the smallest nonzero difference of decoded values is ~2^-37; the
// subnormal range, slow to divide, is left out). Without AVX-512 there is nothing to check.
TEST(Taa, BoxDivisionByNineIsTheDivisionBitForBit) {
  constexpr uint32_t kFirst = 0x0d800000u, kLast = 0x41800000u;  // 2^-100, 16.0f
  constexpr uint32_t kBlock = 1u << 14;
  std::vector<float> x(kBlock), q(kBlock), d(kBlock);
  std::vector<uint32_t> bits(kBlock);
  if (taa_detail::Div9Avx512(x.data(), 16, q.data()) == 0) GTEST_SKIP() << "no AVX-512";
  uint64_t checked = 0;
  for (uint32_t sign : {0u, 0x80000000u}) {
    for (uint32_t b0 = kFirst; b0 <= kLast; b0 += kBlock) {
      for (uint32_t i = 0; i < kBlock; ++i) bits[i] = sign | std::min(b0 + i, kLast);
      if (b0 == kFirst) bits[0] = 0;  // +0
      std::memcpy(x.data(), bits.data(), kBlock * sizeof(float));
      ASSERT_EQ(taa_detail::Div9Avx512(x.data(), static_cast<int>(kBlock), q.data()), static_cast<int>(kBlock));
      for (uint32_t i = 0; i < kBlock; ++i) d[i] = x[i] / 9.0f;
      if (std::memcmp(d.data(), q.data(), kBlock * sizeof(float)) != 0) {
        for (uint32_t i = 0; i < kBlock; ++i) ASSERT_EQ(std::memcmp(&d[i], &q[i], sizeof(float)), 0) << x[i];
      }
      checked += kBlock;
    }
  }
  EXPECT_GT(checked, 2ull * (kLast - kFirst));
}

// The production temporal step against the simple one (TaaReferenceCopy), bit for bit: every
// output byte, the taps and (through the later frames) the history, over sequences of random
// frames with random previous positions (inside, on the border, outside, NaN, exact texel
// centres), for every clip mode, odd sizes from 1x1, at 1 and 2 threads. Widths 29 and 47
// reach, in every row, the AVX-512 kernel (where the CPU has it: 16 pixels), the AVX2 kernel
// (where the CPU has it: 8), the SSE2 kernel (4) and the scalar tail; 13 the last three; 64
// the AVX-512 kernel only.
uint64_t Next(uint64_t& s) {
  s ^= s << 13;
  s ^= s >> 7;
  s ^= s << 17;
  return s;
}

// Steps the production state and its reference copy on `in`: the same output bytes, the same
// taps and the same float history (3 floats a pixel), bit for bit. The history shows a change
// below the 8-bit output's resolution (one ulp of the box, say) first.
::testing::AssertionResult StepsAgree(TemporalState& fast, TemporalState& ref, const TemporalInput& in) {
  PostStats sf, sr;
  const Image8 a = fast.Step(in, &sf);
  const Image8 b = ref.Step(in, &sr);
  if (!(a == b)) return ::testing::AssertionFailure() << "outputs differ";
  if (sf.taps != sr.taps) return ::testing::AssertionFailure() << "taps " << sf.taps << " vs " << sr.taps;
  const std::vector<float> hf = TaaHistory(fast), hr = TaaHistory(ref);
  const size_t n = 3 * static_cast<size_t>(in.frame->Width()) * static_cast<size_t>(in.frame->Height());
  if (hf.size() != n || hr.size() != n)
    return ::testing::AssertionFailure() << "history sizes " << hf.size() << ", " << hr.size();
  if (std::memcmp(hf.data(), hr.data(), n * sizeof(float)) != 0)
    return ::testing::AssertionFailure() << "histories differ";
  return ::testing::AssertionSuccess();
}

// StepsAgree over `frames` steps of every spec and size, at 1 and 2 threads: make(W, H, k,
// seed, frame, prev) fills step k's frame and previous positions from the running seed (step 0
// has no history), which starts at seed0 ^ (W << shift) ^ H for each spec and size.
template <class Make>
void ExpectFastStepIsReference(const std::vector<const char*>& specs, const std::vector<std::pair<int, int>>& sizes,
                               int frames, uint64_t seed0, int shift, Make make) {
  for (int threads : {1, 2}) {
    SetThreadCount(threads);
    for (const char* spec : specs) {
      for (auto [W, H] : sizes) {
        const MethodPlan plan = MakeMethod(spec);
        auto fast = plan.make_state();
        auto ref = TaaReferenceCopy(*fast);
        uint64_t seed = seed0 ^ (static_cast<uint64_t>(W) << shift) ^ static_cast<uint64_t>(H);
        for (int k = 0; k < frames; ++k) {
          Image8 frame(W, H, 4);
          std::vector<float> prev(2 * static_cast<size_t>(W) * H);
          make(W, H, k, seed, frame, prev);
          TemporalInput in;
          in.frame = &frame;
          in.previous = k > 0 ? &prev : nullptr;
          in.frame_index = k;
          ASSERT_TRUE(StepsAgree(*fast, *ref, in))
              << spec << " " << W << "x" << H << " frame " << k << " threads " << threads;
        }
      }
    }
  }
  SetThreadCount(0);
}

TEST(Taa, FastStepIsTheReferenceStepBitForBit) {
  ExpectFastStepIsReference({"taa", "taa:clip=minmax", "taa:clip=none", "taa:gamma=0.25,alpha=0.5", "taa:alpha=1"},
                            {{1, 1}, {2, 3}, {7, 5}, {13, 6}, {29, 9}, {33, 17}, {47, 35}, {64, 48}}, 5,
                            0x9e3779b97f4a7c15ull, 20,
                            [](int W, int H, int, uint64_t& seed, Image8& frame, std::vector<float>& prev) {
                              // Smooth areas (small differences, where the variance box is tight) and jumps.
                              for (size_t i = 0; i < frame.Data().size(); ++i) {
                                const uint64_t r = Next(seed);
                                frame.Data()[i] = static_cast<uint8_t>((r & 3) == 0 ? r >> 56 : 100 + ((r >> 60) & 7));
                              }
                              for (size_t i = 0; i < prev.size(); ++i) {
                                const uint64_t r = Next(seed);
                                const float extent = static_cast<float>(i % 2 == 0 ? W : H);
                                switch (r & 7) {
                                  case 0: prev[i] = std::nanf(""); break;
                                  case 1: prev[i] = (r & 8) ? -0.25f : extent + 0.25f; break;  // outside
                                  case 2:
                                    prev[i] = (r & 8) ? ((r & 16) ? -0.0f : 0.0f) : extent;
                                    break;  // on the border
                                  case 3:
                                    prev[i] = std::floor(static_cast<float>((r >> 8) % 1000) / 1000.0f * extent) + 0.5f;
                                    break;
                                  default: prev[i] = static_cast<float>((r >> 8) % 100000) / 100000.0f * extent; break;
                                }
                              }
                            });
}

// The motion the fast history fetch is for (taa_avx512.cpp FetchContiguous16): previous
// positions x + 0.5 + dx, y + 0.5 + dy with dx, dy varying slowly over the frame (an
// affine field: pan, slide, slight zoom and shear), so most 16-pixel groups have the
// footprint of the pixel before + 1 texel, and some do not (the integer part of dx changes
// inside the group, dy crosses a row inside it, the left or right border clamps, a NaN or
// an off-screen lane); the step against StepReference bit for bit, output and history.
TEST(Taa, FastStepUnderSmoothMotionIsTheReferenceStepBitForBit) {
  // Per step: offset x, offset y, d(dx)/dx, d(dx)/dy, d(dy)/dx, d(dy)/dy.
  // A shift of +0.3 puts the last pixel's x0 on the last texel (the clamp makes b = a).
  static constexpr float kMotion[6][6] = {{0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f},
                                          {0.3f, 0.7f, 0.0f, 0.0f, 0.0f, 0.0f},
                                          {-0.3f, -0.6f, 0.0f, 0.0f, 0.0f, 0.0f},
                                          {2.6f, -1.2f, -0.013f, 0.02f, 0.004f, -0.01f},
                                          {-3.4f, 0.25f, 0.021f, -0.03f, -0.007f, 0.015f},
                                          {0.5f, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f}};  // integer footprints
  ExpectFastStepIsReference(
      {"taa", "taa:clip=minmax", "taa:clip=none"}, {{77, 9}, {64, 48}, {130, 7}}, 6, 0x2545f4914f6cdd1dull, 16,
      [](int W, int H, int k, uint64_t& seed, Image8& frame, std::vector<float>& prev) {
        for (size_t i = 0; i < frame.Data().size(); ++i) {
          const uint64_t r = Next(seed);
          frame.Data()[i] = static_cast<uint8_t>((r & 3) == 0 ? r >> 56 : 100 + ((r >> 60) & 7));
        }
        const float* m = kMotion[k];
        for (int y = 0; y < H; ++y) {
          for (int x = 0; x < W; ++x) {
            float* p = &prev[2 * (static_cast<size_t>(y) * W + x)];
            p[0] = static_cast<float>(x) + 0.5f + m[0] + m[2] * static_cast<float>(x) + m[3] * static_cast<float>(y);
            p[1] = static_cast<float>(y) + 0.5f + m[1] + m[4] * static_cast<float>(x) + m[5] * static_cast<float>(y);
            const uint64_t r = Next(seed);
            if (k == 4 && (r & 255) == 0) p[r & 256 ? 0 : 1] = std::nanf("");
          }
        }
      });
}

// The AVX-512 box starts its min, max and sums from the first texel, and Cg is formed as
// 0.5 g − 0.25 r (taa_avx512.cpp Box16, ToYcc16): the same bits only because the planes
// hold no −0 and −0.25·0 + 0.5·0 is +0. Frames of 0, 1, 254 and 255 per channel (black,
// white, every zero combination of R, G and B, flat and noisy boxes) under a pan (the
// contiguous fetch) and under random motion: output and history against StepReference.
TEST(Taa, FastStepOnBlackAndWhiteIsTheReferenceStepBitForBit) {
  ExpectFastStepIsReference(
      {"taa", "taa:clip=minmax", "taa:gamma=0.25,alpha=0.5"}, {{64, 20}, {77, 9}}, 5, 0x6a09e667f3bcc909ull, 16,
      [](int W, int H, int k, uint64_t& seed, Image8& frame, std::vector<float>& prev) {
        constexpr uint8_t kLevels[4] = {0, 255, 1, 254};
        for (size_t i = 0; i < frame.Data().size(); ++i) {
          const uint64_t r = Next(seed);
          // Mostly 0 and 255, in patches of four pixels (flat boxes) where bit 40 says so.
          const uint64_t q = (r >> 40) & 1 ? (i / 16) * 0x9e3779b9u >> 7 : r >> 20;
          frame.Data()[i] = kLevels[(q & 7) == 0 ? 2 + ((q >> 3) & 1) : (q >> 3) & 1];
        }
        for (int y = 0; y < H; ++y) {
          for (int x = 0; x < W; ++x) {
            float* p = &prev[2 * (static_cast<size_t>(y) * W + x)];
            const uint64_t r = Next(seed);
            const bool pan = k % 2 == 1;
            p[0] = static_cast<float>(x) + (pan ? 1.3f : static_cast<float>((r >> 8) % 1000) / 250.0f - 1.5f);
            p[1] = static_cast<float>(y) + (pan ? 0.2f : static_cast<float>((r >> 24) % 1000) / 250.0f - 1.5f);
          }
        }
      });
}

}  // namespace
}  // namespace aalab
