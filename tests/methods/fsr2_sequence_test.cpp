// FSR 2's sequence driver (methods/fsr2_sequence.h) and the fsr2-* rows' inputs
// (methods/fsr2_methods.cpp), against values worked out by hand from api/ffx_fsr2.cpp:
// which ping-pong side each frame reads and writes, the resets' clears, the constants' frame
// index; the jitter the rows render with and hand FSR 2 (Fsr2JitterOffset, signs); the colour,
// depth and motion conversions; and a still scene that converges (fsr2-native after 16 frames
// nearer the supersampled truth than the centre-sampled frame), which a wrong jitter sign
// spoils.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/color.h"
#include "methods/fsr2_sequence.h"
#include "methods/registry.h"
#include "methods/taa.h"

namespace aalab {
namespace {

// Fake passes that mark what they write with the frame number and record what they read.
struct Trace {
  int frame = 0;
  std::vector<float> history_read, lock_read, luma_hist_read, prev_motion_read;
  std::vector<float> exposure_seen_by_reconstruct;
  std::vector<uint32_t> prev_depth_at_reconstruct;
  std::vector<int> frame_index;
  std::vector<float> auto_exposure_before_pyramid;
};

Fsr2Passes FakePasses(Trace* tr) {
  Fsr2Passes p;
  p.pyramid = [tr](const Fsr2Constants& k, const Fsr2Options&, const Fsr2SpdDispatch&, const Fsr2Plane&,
                   Fsr2PyramidState* st) {
    tr->frame_index.push_back(k.frame_index);
    tr->auto_exposure_before_pyramid.push_back(st->auto_exposure[0]);
    st->auto_exposure[0] = 0.5f + static_cast<float>(tr->frame);
  };
  p.reconstruct = [tr](const Fsr2Constants& k, const Fsr2Options&, const Fsr2Plane&, const Fsr2Plane&, const Fsr2Plane&,
                       float exposure, Fsr2ReconstructOut* out) {
    tr->exposure_seen_by_reconstruct.push_back(exposure);
    tr->prev_depth_at_reconstruct.push_back(out->prev_depth.at(0));
    out->dilated_motion = Fsr2Plane(k.render_size[0], k.render_size[1], 2);
    for (float& v : out->dilated_motion.v) v = 10.0f + static_cast<float>(tr->frame);
    out->dilated_depth = Fsr2Plane(k.render_size[0], k.render_size[1], 1);
    out->lock_luma = Fsr2Plane(k.render_size[0], k.render_size[1], 1);
    out->prev_depth.assign(out->prev_depth.size(), 77u);  // reconstruct's pushes
  };
  p.depth_clip = [tr](const Fsr2Constants& k, const Fsr2Options&, const Fsr2DepthClipIn& in, Fsr2DepthClipOut* out) {
    tr->prev_motion_read.push_back(in.previous_dilated_motion->v.at(0));
    EXPECT_EQ(in.prev_depth->at(0), 77u);  // reads what reconstruct pushed this frame
    out->prepared_color = Fsr2Plane(k.render_size[0], k.render_size[1], 4);
    out->reactive_masks = Fsr2Plane(k.render_size[0], k.render_size[1], 2);
  };
  p.lock = [](const Fsr2Constants&, const Fsr2Options&, const Fsr2Plane&, Fsr2Plane*, std::vector<uint32_t>* pd) {
    pd->assign(pd->size(), 0u);  // reset to far (inverted depth)
  };
  p.accumulate = [tr](const Fsr2Constants& k, const Fsr2Options& o, const Fsr2AccumulateIn& in,
                      Fsr2AccumulateOut* out) {
    tr->history_read.push_back(in.history->v.at(0));
    tr->lock_read.push_back(in.lock_status->v.at(0));
    tr->luma_hist_read.push_back(in.luma_history->v.at(0));
    const int dw = k.display_size[0], dh = k.display_size[1];
    const float mark = 100.0f + static_cast<float>(tr->frame);
    out->internal_upscaled = Fsr2Plane(dw, dh, 4);
    out->lock_status = Fsr2Plane(dw, dh, 2);
    out->luma_history = Fsr2Plane(dw, dh, 4);
    for (Fsr2Plane* pl : {&out->internal_upscaled, &out->lock_status, &out->luma_history})
      for (float& v : pl->v) v = mark;
    out->output = o.apply_sharpening ? Fsr2Plane() : Fsr2Plane(dw, dh, 3);
  };
  p.rcas = [](const Fsr2Constants&, const Fsr2Plane& up, float, uint32_t) {
    return std::vector<float>(static_cast<size_t>(up.w) * up.h * 3, up.v.at(0));
  };
  return p;
}

Fsr2DispatchInput Input(const Fsr2Plane& color, const Fsr2Plane& depth, const Fsr2Plane& motion, bool reset) {
  Fsr2DispatchInput in;
  in.color = &color;
  in.depth = &depth;
  in.motion = &motion;
  in.dispatch.render_size[0] = in.dispatch.input_color_size[0] = 8;
  in.dispatch.render_size[1] = in.dispatch.input_color_size[1] = 6;
  in.dispatch.motion_vector_scale[0] = in.dispatch.motion_vector_scale[1] = 1.0f;
  in.dispatch.reset = reset;
  return in;
}

TEST(Fsr2Sequence, PingPongSidesAndResetsOverFourFrames) {
  Trace tr;
  Fsr2ContextParams cp;
  cp.max_render_size[0] = 8;
  cp.max_render_size[1] = 6;
  cp.display_size[0] = 12;
  cp.display_size[1] = 9;
  cp.inverted_depth = cp.infinite_depth = true;
  Fsr2Options o;
  o.inverted_depth = true;
  Fsr2Context ctx(cp, o, /*auto_exposure=*/true, FakePasses(&tr));
  EXPECT_EQ(ctx.Resources().prev_depth.at(0), 0u);  // far with inverted depth
  const Fsr2Plane color(8, 6, 4), depth(8, 6, 1), motion(8, 6, 2);
  std::vector<bool> odd, reset;
  for (int t = 0; t < 4; ++t) {
    tr.frame = t;
    const Fsr2DispatchResult r = ctx.Dispatch(Input(color, depth, motion, t == 3));
    odd.push_back(r.setup.odd);
    reset.push_back(r.setup.reset);
    // RCAS off: no sharpening asked; the output is accumulate's (3 floats per display pixel).
    EXPECT_EQ(r.output.size(), 12u * 9u * 3u);
    EXPECT_EQ(r.exposure, 0.5f + static_cast<float>(t));  // the pyramid's exposure, this frame's
  }
  // API: the resource frame index 0, 1, 2, 3 → even, odd, even, odd; reset on the first
  // dispatch and on the one that asks.
  EXPECT_EQ(odd, (std::vector<bool>{false, true, false, true}));
  EXPECT_EQ(reset, (std::vector<bool>{true, false, false, true}));
  EXPECT_EQ(tr.frame_index, (std::vector<int>{0, 1, 2, 0}));
  // Frame 0 (even) reads _1, cleared (0), writes _2 (100). Frame 1 (odd) reads _2 = 100, writes
  // _1 (101). Frame 2 reads _1 = 101, writes _2 (102). Frame 3 (odd, reset) reads _2, cleared by
  // the reset: 0 for the upscaled colour and lock status; the luma history is not cleared (102).
  EXPECT_EQ(tr.history_read, (std::vector<float>{0.0f, 100.0f, 101.0f, 0.0f}));
  EXPECT_EQ(tr.lock_read, (std::vector<float>{0.0f, 100.0f, 101.0f, 0.0f}));
  EXPECT_EQ(tr.luma_hist_read, (std::vector<float>{0.0f, 100.0f, 101.0f, 102.0f}));
  // Dilated motion: frame 0 writes _1 (10), reads _2 (0) as the previous; frame 1 writes _2
  // (11), reads _1 = 10; frame 2 writes _1, reads _2 = 11; frame 3 reads _1 = 12 (not cleared).
  EXPECT_EQ(tr.prev_motion_read, (std::vector<float>{0.0f, 10.0f, 11.0f, 12.0f}));
  // The pyramid starts from the reset's exposure −1 on frames 0 and 3, else from the last one.
  EXPECT_EQ(tr.auto_exposure_before_pyramid, (std::vector<float>{-1.0f, 0.5f, 1.5f, -1.0f}));
  // The previous depth reaches reconstruct as the lock pass left it (far = 0).
  EXPECT_EQ(tr.prev_depth_at_reconstruct, (std::vector<uint32_t>{0u, 0u, 0u, 0u}));
  // After frame 3 (odd) the _1 side holds what it wrote.
  EXPECT_EQ(ctx.Resources().internal_upscaled[0].v.at(0), 103.0f);
  EXPECT_EQ(ctx.Resources().internal_upscaled[1].v.at(0), 0.0f);
}

TEST(Fsr2Sequence, SharpeningRunsRcasOnTheColourJustWritten) {
  Trace tr;
  Fsr2ContextParams cp;
  cp.max_render_size[0] = 8;
  cp.max_render_size[1] = 6;
  cp.display_size[0] = 12;
  cp.display_size[1] = 9;
  Fsr2Context ctx(cp, Fsr2Options{}, /*auto_exposure=*/false, FakePasses(&tr));
  EXPECT_EQ(ctx.Resources().prev_depth.at(0), 0x3f800000u);  // far = 1.0 without inverted depth
  const Fsr2Plane color(8, 6, 4), depth(8, 6, 1), motion(8, 6, 2);
  for (int t = 0; t < 2; ++t) {
    tr.frame = t;
    Fsr2DispatchInput in = Input(color, depth, motion, false);
    in.sharpen = true;
    const Fsr2DispatchResult r = ctx.Dispatch(in);
    ASSERT_EQ(r.output.size(), 12u * 9u * 3u);
    EXPECT_EQ(r.output[0], 100.0f + static_cast<float>(t));  // this frame's upscaled colour
    EXPECT_EQ(r.exposure, 0.0f);                             // the API's default exposure texture
  }
  EXPECT_EQ(tr.exposure_seen_by_reconstruct, (std::vector<float>{0.0f, 0.0f}));
}

TEST(Fsr2Sequence, RefusesPlanesOfTheWrongSize) {
  Fsr2ContextParams cp;
  cp.max_render_size[0] = 8;
  cp.max_render_size[1] = 6;
  cp.display_size[0] = 12;
  cp.display_size[1] = 9;
  Fsr2Context ctx(cp, Fsr2Options{}, true);
  const Fsr2Plane color(8, 6, 4), depth(8, 5, 1), motion(8, 6, 2);
  try {
    ctx.Dispatch(Input(color, depth, motion, false));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("depth must be a 8x6 plane of 1 channel"), std::string::npos) << e.what();
  }
  cp.display_size[0] = 0;
  EXPECT_THROW(Fsr2Context(cp, Fsr2Options{}, true), std::invalid_argument);
}

TEST(Fsr2Sequence, RowsRenderWithTheNegatedFsr2JitterAndHandFsr2ItsOwn) {
  const struct {
    const char* name;
    int phases;
    double scale;
  } rows[] = {{"fsr2-native", 8, 1.0},
              {"fsr2-quality", 18, 1 / 1.5},
              {"fsr2-balanced", 23, 1 / 1.7},
              {"fsr2-performance", 32, 0.5},
              {"fsr2-ultra-performance", 72, 1 / 3.0}};
  for (const auto& r : rows) {
    const MethodPlan plan = MakeMethod(r.name);
    EXPECT_EQ(plan.render.jitter.samples, r.phases) << r.name;
    EXPECT_DOUBLE_EQ(plan.render.scale, r.scale) << r.name;
    EXPECT_TRUE(plan.NeedsHistory());
    EXPECT_EQ(plan.family, "fsr2");
    for (int t = 0; t < 2 * r.phases + 3; ++t) {
      const FrameJitter j = FrameJitterAt(plan.render.jitter, t);
      const Fsr2Jitter f = Fsr2JitterOffset(t, r.phases);
      EXPECT_EQ(j.x, -f.x) << r.name << " frame " << t;
      EXPECT_EQ(j.y, -f.y) << r.name << " frame " << t;
      const Fsr2Jitter back = Fsr2JitterFromFrame(j);
      EXPECT_EQ(back.x, f.x);
      EXPECT_EQ(back.y, f.y);
    }
  }
  // By hand: Halton index 1 is (1/2, 1/3), index 2 (1/4, 2/3); FSR 2's jitter subtracts 0.5,
  // the render's sample offset is its negative.
  const MethodPlan q = MakeMethod("fsr2-quality");
  EXPECT_EQ(FrameJitterAt(q.render.jitter, 0).x, 0.0f);
  EXPECT_NEAR(FrameJitterAt(q.render.jitter, 0).y, 1.0 / 6.0, 1e-7);
  EXPECT_EQ(FrameJitterAt(q.render.jitter, 1).x, 0.25f);
  EXPECT_NEAR(FrameJitterAt(q.render.jitter, 1).y, -1.0 / 6.0, 1e-7);
  EXPECT_EQ(FrameJitterAt(q.render.jitter, 18).x, FrameJitterAt(q.render.jitter, 0).x);  // 18 phases
}

TEST(Fsr2Sequence, ColourDepthAndMotionConversions) {
  Image8 f(3, 2, 4, 0);
  f.Pixel(1, 0)[0] = 188;  // sRGB 188 → linear 0.5029
  f.Pixel(2, 1)[2] = 255;
  const Fsr2Plane c = Fsr2ColorFromSrgb8(f);
  EXPECT_NEAR(c.At(1, 0, 0), 0.50289, 1e-4);
  EXPECT_EQ(c.At(2, 1, 2), 1.0f);
  EXPECT_EQ(c.At(0, 0, 0), 0.0f);
  EXPECT_EQ(c.At(0, 0, 3), 1.0f);
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> z = {2.0f, 4.0f, inf, 8.0f, 1.0f, inf};
  EXPECT_EQ(Fsr2NearPlane(&z), 0.5f);  // half the nearest
  EXPECT_EQ(Fsr2NearPlane(nullptr), 1.0f);
  const Fsr2Plane d = Fsr2DeviceDepth(&z, 3, 2, 0.5f);
  EXPECT_EQ(d.v, (std::vector<float>{0.25f, 0.125f, 0.0f, 0.0625f, 0.5f, 0.0f}));
  EXPECT_EQ(Fsr2DeviceDepth(nullptr, 3, 2, 0.5f).v, std::vector<float>(6, 0.0f));
  // previous positions (x then y) of a 3×2 frame; pixel (1, 0) moved from (2.75, 0.25): its
  // vector to the previous frame is (1.25, −0.25); pixel (0, 1) has no history (NaN).
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> prev = {0.5f, 0.5f, 2.75f, 0.25f, 2.5f, 0.5f, nan, nan, 1.5f, 1.5f, 3.0f, 2.0f};
  const Fsr2Plane m = Fsr2MotionFromPrevious(&prev, 3, 2);
  EXPECT_EQ(m.At(0, 0, 0), 0.0f);
  EXPECT_EQ(m.At(1, 0, 0), 1.25f);
  EXPECT_EQ(m.At(1, 0, 1), -0.25f);
  EXPECT_EQ(m.At(0, 1, 0), 6.0f);  // twice the render size: off screen
  EXPECT_EQ(m.At(0, 1, 1), 4.0f);
  EXPECT_EQ(m.At(2, 1, 0), 0.5f);
  EXPECT_EQ(m.At(2, 1, 1), 0.5f);
  EXPECT_EQ(Fsr2MotionFromPrevious(nullptr, 3, 2).v, std::vector<float>(12, 0.0f));
}

// A still scene in linear values: a disc and a slanted edge.
float Scene(float x, float y) {
  const float dx = x - 20.3f, dy = y - 15.7f;
  if (dx * dx + dy * dy < 9.2f * 9.2f) return 0.85f;
  if (x > 34.0f + 0.3f * (y - 16.0f)) return 0.7f;
  return 0.06f;
}

constexpr int kW = 48, kH = 32;

Image8 Render(FrameJitter j) {
  Image8 f(kW, kH, 4, 255);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const uint8_t v = EncodeSrgb8(Scene(static_cast<float>(x) + 0.5f + j.x, static_cast<float>(y) + 0.5f + j.y));
      for (int c = 0; c < 3; ++c) f.Pixel(x, y)[c] = v;
    }
  return f;
}

double Rmse(const Image8& img) {
  double s = 0.0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      double ref = 0.0;
      for (int sy = 0; sy < 16; ++sy)
        for (int sx = 0; sx < 16; ++sx)
          ref += Scene(static_cast<float>(x) + (static_cast<float>(sx) + 0.5f) / 16.0f,
                       static_cast<float>(y) + (static_cast<float>(sy) + 0.5f) / 16.0f);
      ref /= 256.0;
      const double e = SrgbDecode8(img.Pixel(x, y)[1]) - ref;
      s += e * e;
    }
  return std::sqrt(s / (kW * kH));
}

double StillSceneError(const std::string& spec, bool wrong_sign) {
  const MethodPlan plan = MakeMethod(spec);
  auto state = plan.make_state();
  const std::vector<float> depth(kW * kH, 4.0f);
  std::vector<float> previous(2 * kW * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      previous[2 * (y * kW + x)] = static_cast<float>(x) + 0.5f;
      previous[2 * (y * kW + x) + 1] = static_cast<float>(y) + 0.5f;
    }
  Image8 out;
  for (int t = 0; t < 16; ++t) {
    const FrameJitter j = FrameJitterAt(plan.render.jitter, t);
    const Image8 frame = Render(j);
    TemporalInput in;
    in.frame = &frame;
    in.previous = t ? &previous : nullptr;
    in.frame_index = t;
    in.depth = &depth;
    in.jitter = wrong_sign ? FrameJitter{-j.x, -j.y} : j;
    in.fov_y_radians = 0.8f;
    PostStats st;
    out = state->Step(in, &st);
  }
  return Rmse(out);
}

TEST(Fsr2Sequence, AStillSceneConvergesAndAWrongJitterSignSpoilsIt) {
  const double none = Rmse(Render(FrameJitter{}));
  const double right = StillSceneError("fsr2-native:sharpening=off", false);
  const double wrong = StillSceneError("fsr2-native:sharpening=off", true);
  const double sharp = StillSceneError("fsr2-native", false);
  std::printf(
      "still scene, RMSE (linear) after 16 frames: none %.5f, fsr2-native %.5f (sharpened %.5f), jitter sign "
      "wrong %.5f\n",
      none, right, sharp, wrong);
  EXPECT_LT(right, 0.8 * none);
  EXPECT_LT(sharp, none);
  EXPECT_GT(wrong, 1.3 * right);
}

}  // namespace
}  // namespace aalab
