// FSR 2's host-side tables and jitter (methods/fsr2_tables.h) against values worked out
// independently: Halton(2, 3) points by hand, the phase counts 8·ratio² for the quality
// modes, Lanczos-2 by its closed form sinc(x)·sinc(x/2) in double, the R16_SNORM codes by
// round(v·32767), and the maximum-bias table's corners and a few entries copied as numbers from
// api/ffx_fsr2_maximum_bias.h of FSR 2.2.1 (tests/oracle/fsr2_pyramid_oracle_test.cpp compares
// all 256 with the pinned file).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "methods/fsr2_tables.h"

namespace aalab {
namespace {

TEST(Fsr2Tables, HaltonPointsByHand) {
  // Base 2: 1/2, 1/4, 3/4, 1/8, 5/8, 3/8, 7/8 (exact in float).
  const float b2[] = {0.5f, 0.25f, 0.75f, 0.125f, 0.625f, 0.375f, 0.875f};
  for (int i = 1; i <= 7; ++i) EXPECT_EQ(Fsr2Halton(i, 2), b2[i - 1]) << "index " << i;
  // Base 3: 1/3, 2/3, 1/9, 4/9, 7/9, 2/9, 5/9, 8/9 (float: within two ulps of the fraction).
  const double b3[] = {1.0 / 3, 2.0 / 3, 1.0 / 9, 4.0 / 9, 7.0 / 9, 2.0 / 9, 5.0 / 9, 8.0 / 9};
  for (int i = 1; i <= 8; ++i) EXPECT_NEAR(Fsr2Halton(i, 3), b3[i - 1], 1.2e-7) << "index " << i;
  EXPECT_EQ(Fsr2Halton(0, 2), 0.0f);
}

TEST(Fsr2Tables, JitterOffsetsAreHaltonMinusAHalfAndWrapAtThePhaseCount) {
  // Frame i uses Halton index (i mod n) + 1: frame 0 → (1/2, 1/3), 1 → (1/4, 2/3), 2 → (3/4, 1/9),
  // 3 → (1/8, 4/9), each minus 1/2.
  const double want[4][2] = {{0.0, -1.0 / 6}, {-0.25, 1.0 / 6}, {0.25, -7.0 / 18}, {-0.375, -1.0 / 18}};
  for (int i = 0; i < 4; ++i) {
    const Fsr2Jitter j = Fsr2JitterOffset(i, 8);
    EXPECT_EQ(j.x, static_cast<float>(want[i][0])) << "frame " << i;
    EXPECT_NEAR(j.y, want[i][1], 1e-7) << "frame " << i;
  }
  // The float steps exactly: 1/3 rounds to 0.3333333432674408, minus 0.5 exactly (Sterbenz).
  EXPECT_EQ(Fsr2JitterOffset(0, 8).y, -0.1666666567325592f);
  // The sequence repeats every phase_count frames.
  for (int n : {8, 18, 23, 32, 72}) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(Fsr2JitterOffset(i + n, n).x, Fsr2JitterOffset(i, n).x);
      EXPECT_EQ(Fsr2JitterOffset(i + 2 * n, n).y, Fsr2JitterOffset(i, n).y);
    }
  }
  EXPECT_NE(Fsr2JitterOffset(8, 18).x, Fsr2JitterOffset(0, 18).x);  // 18 phases: frame 8 is new
  EXPECT_THROW(Fsr2JitterOffset(0, 0), std::invalid_argument);
  EXPECT_THROW(Fsr2JitterOffset(-1, 8), std::invalid_argument);
}

TEST(Fsr2Tables, PhaseCountsOfTheQualityModes) {
  EXPECT_EQ(Fsr2JitterPhaseCount(1280, 1920), 18);  // Quality 1.5×: 8·2.25
  EXPECT_EQ(Fsr2JitterPhaseCount(1129, 1920), 23);  // Balanced 1.7×: 8·1.70062² = 23.14
  EXPECT_EQ(Fsr2JitterPhaseCount(1000, 1700), 23);  // 1.7 exactly: 8·2.89 = 23.12
  EXPECT_EQ(Fsr2JitterPhaseCount(960, 1920), 32);   // Performance 2×
  EXPECT_EQ(Fsr2JitterPhaseCount(640, 1920), 72);   // Ultra performance 3×
  EXPECT_EQ(Fsr2JitterPhaseCount(1920, 1920), 8);   // native AA 1×
  EXPECT_EQ(Fsr2JitterPhaseCount(64, 96), 18);      // the oracle's 64×36 → 96×54
  EXPECT_THROW(Fsr2JitterPhaseCount(0, 1920), std::invalid_argument);
  EXPECT_THROW(Fsr2JitterPhaseCount(1280, -1), std::invalid_argument);
}

double Lanczos2Closed(double x) {
  if (x == 0.0) return 1.0;
  const double pi = 3.14159265358979323846;
  return (std::sin(pi * x) / (pi * x)) * (std::sin(pi * x / 2) / (pi * x / 2));
}

TEST(Fsr2Tables, Lanczos2AgainstTheClosedForm) {
  EXPECT_EQ(Fsr2Lanczos2(0.0f), 1.0f);
  EXPECT_NEAR(Fsr2Lanczos2(0.5f), 4.0 * std::sqrt(2.0) / (M_PI * M_PI), 1e-6);  // 0.5731592
  EXPECT_NEAR(Fsr2Lanczos2(1.0f), 0.0, 1e-6);
  EXPECT_NEAR(Fsr2Lanczos2(1.5f), -(std::sqrt(2.0) / 2) / (1.125 * M_PI * M_PI), 1e-6);  // −0.0636844
  EXPECT_NEAR(Fsr2Lanczos2(2.0f), 0.0, 1e-6);
  EXPECT_NEAR(Fsr2Lanczos2(-0.5f), Fsr2Lanczos2(0.5f), 0.0);  // even
}

TEST(Fsr2Tables, LanczosLutCodesAreTheClosedFormInSnorm16) {
  const auto codes = Fsr2LanczosLutCodes();
  const auto lut = Fsr2LanczosLut();
  ASSERT_EQ(codes.size(), 128u);
  EXPECT_EQ(codes[0], 32767);
  EXPECT_EQ(codes[1], 32750);   // x = 2/127: 0.99949 · 32767
  EXPECT_EQ(codes[32], 18601);  // x = 64/127: 0.56767
  EXPECT_EQ(codes[64], -162);   // x = 128/127, just past the first zero
  EXPECT_EQ(codes[96], -2014);  // x = 192/127: −0.061477
  EXPECT_EQ(codes[127], 0);     // x = 2
  int near_tie = 0;
  for (int i = 0; i < 128; ++i) {
    const double v = Lanczos2Closed(2.0 * i / 127.0) * 32767.0;
    const bool tie = std::fabs(v - std::floor(v) - 0.5) < 0.02;  // float and double may round apart
    near_tie += tie;
    if (tie) {
      EXPECT_NEAR(codes[i], v, 1.0) << "entry " << i;
    } else {
      EXPECT_EQ(codes[i], static_cast<int>(std::lround(v))) << "entry " << i;
    }
    EXPECT_EQ(lut[i], static_cast<float>(codes[i]) / 32767.0f);
  }
  EXPECT_EQ(near_tie, 6);  // entries 6, 26, 95, 99, 113, 114
  EXPECT_EQ(lut[0], 1.0f);
}

TEST(Fsr2Tables, Snorm16Conversion) {
  EXPECT_EQ(Fsr2Snorm16ToFloat(32767), 1.0f);
  EXPECT_EQ(Fsr2Snorm16ToFloat(0), 0.0f);
  EXPECT_EQ(Fsr2Snorm16ToFloat(-32767), -1.0f);
  EXPECT_EQ(Fsr2Snorm16ToFloat(-32768), -1.0f);  // clamped
  EXPECT_EQ(Fsr2Snorm16ToFloat(16384), static_cast<float>(16384.0 / 32767.0));
}

TEST(Fsr2Tables, MaximumBiasCornersAndEntriesFromTheApiFile) {
  // api/ffx_fsr2_maximum_bias.h of FSR 2.2.1: the table starts at line 28; row r is line 29 + r.
  const auto& t = Fsr2MaximumBiasTable();
  auto at = [&](int x, int y) { return t[static_cast<size_t>(y * 16 + x)]; };
  EXPECT_EQ(at(0, 0), 2.0f);      // line 29, first
  EXPECT_EQ(at(15, 0), 1.748f);   // line 29, last
  EXPECT_EQ(at(0, 15), 1.748f);   // line 44, first
  EXPECT_EQ(at(15, 15), 1.319f);  // line 44, last
  EXPECT_EQ(at(11, 0), 1.876f);   // line 29, 12th
  EXPECT_EQ(at(10, 4), 1.793f);   // line 33, 11th
  EXPECT_EQ(at(4, 12), 1.604f);   // line 41, 5th
  EXPECT_EQ(at(13, 4), 1.562f);   // line 33, 14th
  EXPECT_EQ(at(9, 5), 1.802f);    // line 34, 10th
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) EXPECT_EQ(at(x, y), at(y, x)) << x << "," << y;  // symmetric
  }
  // Uploaded as R16_SNORM of v/2: round(v/2 · 32767).
  const auto codes = Fsr2MaximumBiasCodes();
  const auto lut = Fsr2MaximumBiasLut();
  EXPECT_EQ(codes[0], 32767);            // 2.0
  EXPECT_EQ(codes[15], 28638);           // 1.748: 28638.36
  EXPECT_EQ(codes[255], 21610);          // 1.319: 21609.84
  EXPECT_EQ(codes[4 * 16 + 10], 29376);  // 1.793: 29375.62
  EXPECT_EQ(codes[12 * 16 + 4], 26279);  // 1.604: 26279.13
  EXPECT_EQ(codes[4 * 16 + 13], 25591);  // 1.562: 25591.03
  EXPECT_EQ(lut[0], 1.0f);
  EXPECT_EQ(2.0f * lut[255], 2.0f * (21610.0f / 32767.0f));  // what SampleUpsampleMaximumBias returns there
}

Fsr2ContextParams Context1080p() {
  Fsr2ContextParams c;
  c.max_render_size[0] = 1280;
  c.max_render_size[1] = 720;
  c.display_size[0] = 1920;
  c.display_size[1] = 1080;
  c.motion_vector_jitter_cancellation = true;
  return c;
}

Fsr2DispatchParams Frame(int render_w, int render_h, float jx, float jy) {
  Fsr2DispatchParams p;
  p.render_size[0] = p.input_color_size[0] = render_w;
  p.render_size[1] = p.input_color_size[1] = render_h;
  p.jitter[0] = jx;
  p.jitter[1] = jy;
  p.motion_vector_scale[0] = -640.0f;  // the app's vectors are in units of −2 and 2 pixels
  p.motion_vector_scale[1] = 360.0f;
  p.frame_time_delta_ms = 16.0f;
  return p;
}

TEST(Fsr2FrameConstants, FirstFrameResetsThenFramesCountAndPingPong) {
  const Fsr2ContextParams ctx = Context1080p();
  Fsr2ContextState st;
  Fsr2FrameSetup f = Fsr2NextFrameConstants(ctx, Frame(1280, 720, 0.25f, -0.125f), &st);
  const Fsr2Constants& k = st.constants;
  EXPECT_TRUE(f.reset);  // a fresh context
  EXPECT_FALSE(f.odd);
  EXPECT_EQ(k.frame_index, 0);
  EXPECT_EQ(k.jitter_sequence_length, 18.0f);  // 1920 / 1280 = 1.5: 8 · 2.25
  EXPECT_EQ(k.render_size[0], 1280);
  EXPECT_EQ(k.display_size[1], 1080);
  EXPECT_EQ(k.luma_mip_level, 4);
  EXPECT_EQ(k.luma_mip_size[0], 40);  // 1280 / 32
  EXPECT_EQ(k.luma_mip_size[1], 22);  // 720 / 32 = 22.5, truncated
  EXPECT_EQ(k.downscale_factor[0], 1280.0f / 1920.0f);
  EXPECT_EQ(k.motion_vector_scale[0], -0.5f);                           // −640 / 1280
  EXPECT_EQ(k.motion_vector_scale[1], 0.5f);                            // 360 / 720
  EXPECT_EQ(k.motion_vector_jitter_cancellation[0], -0.25f / 1280.0f);  // (0 − 0.25) / 1280
  EXPECT_EQ(k.motion_vector_jitter_cancellation[1], 0.125f / 720.0f);
  EXPECT_EQ(k.pre_exposure, 1.0f);  // 0 reads as 1
  EXPECT_EQ(k.delta_time, 0.016f);
  EXPECT_EQ(k.view_space_to_meters, 1.0f);
  EXPECT_EQ(k.jitter[0], 0.25f);

  Fsr2DispatchParams p2 = Frame(1280, 720, -0.25f, 0.375f);
  p2.pre_exposure = 1.5f;
  f = Fsr2NextFrameConstants(ctx, p2, &st);
  EXPECT_FALSE(f.reset);
  EXPECT_TRUE(f.odd);
  EXPECT_EQ(k.frame_index, 1);
  EXPECT_EQ(k.pre_exposure, 1.5f);
  EXPECT_EQ(k.previous_pre_exposure, 1.0f);
  EXPECT_EQ(k.motion_vector_jitter_cancellation[0], 0.5f / 1280.0f);  // (0.25 − (−0.25)) / 1280
  EXPECT_EQ(k.motion_vector_jitter_cancellation[1], -0.5f / 720.0f);  // (−0.125 − 0.375) / 720

  Fsr2DispatchParams p3 = Frame(1280, 720, 0, 0);
  p3.reset = true;
  f = Fsr2NextFrameConstants(ctx, p3, &st);
  EXPECT_TRUE(f.reset);
  EXPECT_FALSE(f.odd);
  EXPECT_EQ(k.frame_index, 0);
  EXPECT_EQ(k.previous_pre_exposure, 1.5f);
  // Sixteen queued frames: the index wraps at 16, an even number, so the sides keep alternating.
  for (int i = 3; i < 40; ++i) {
    f = Fsr2NextFrameConstants(ctx, Frame(1280, 720, 0, 0), &st);
    EXPECT_EQ(f.odd, (i % 2) == 1) << "frame " << i;
    EXPECT_EQ(k.frame_index, i - 2);
  }
  EXPECT_EQ(st.resource_frame_index, 40u % 16u);
}

TEST(Fsr2FrameConstants, PhaseCountMovesOneStepPerFrameUnlessReset) {
  const Fsr2ContextParams ctx = Context1080p();
  Fsr2ContextState st;
  Fsr2NextFrameConstants(ctx, Frame(1280, 720, 0, 0), &st);
  EXPECT_EQ(st.constants.jitter_sequence_length, 18.0f);
  for (float want : {19.0f, 20.0f, 21.0f}) {  // render 960: the target is 32
    Fsr2NextFrameConstants(ctx, Frame(960, 540, 0, 0), &st);
    EXPECT_EQ(st.constants.jitter_sequence_length, want);
  }
  Fsr2NextFrameConstants(ctx, Frame(1280, 720, 0, 0), &st);  // back toward 18
  EXPECT_EQ(st.constants.jitter_sequence_length, 20.0f);
  Fsr2DispatchParams p = Frame(960, 540, 0, 0);
  p.reset = true;
  Fsr2NextFrameConstants(ctx, p, &st);
  EXPECT_EQ(st.constants.jitter_sequence_length, 32.0f);
}

TEST(Fsr2FrameConstants, DepthParametersFieldOfViewAndClamps) {
  Fsr2ContextParams ctx = Context1080p();
  Fsr2DispatchParams p = Frame(1280, 720, 0, 0);
  p.camera_near = 0.1f;
  p.camera_far = 100.0f;
  p.camera_fov_vertical = 1.0471976f;  // 60°
  const double t30 = std::tan(M_PI / 6), aspect = 16.0 / 9.0;
  auto run = [&](bool inverted, bool infinite, bool swap) {
    ctx.inverted_depth = inverted;
    ctx.infinite_depth = infinite;
    Fsr2DispatchParams q = p;
    if (swap) std::swap(q.camera_near, q.camera_far);
    Fsr2ContextState st;
    Fsr2NextFrameConstants(ctx, q, &st);
    return st.constants;
  };
  // view depth = d1 / (depth − d0) from the projection's c and e (c = f/(n − f), e = c·n).
  Fsr2Constants k = run(false, false, false);
  EXPECT_NEAR(k.device_to_view_depth[0], 100.0 / 99.9, 1e-6);
  EXPECT_NEAR(k.device_to_view_depth[1], -100.0 / 99.9 * 0.1, 1e-7);
  EXPECT_NEAR(k.device_to_view_depth[2], t30 * aspect, 1e-6);  // 1/a = aspect · tan(fov/2)
  EXPECT_NEAR(k.device_to_view_depth[3], t30, 1e-6);
  EXPECT_NEAR(k.tan_half_fov, t30 * aspect, 1e-6);        // horizontal: tan(atan(tan 30° · 16/9))
  const Fsr2Constants swapped = run(false, false, true);  // near and far given the other way round
  for (int i = 0; i < 4; ++i) EXPECT_EQ(swapped.device_to_view_depth[i], k.device_to_view_depth[i]);
  k = run(true, false, false);  // inverted: near 100, far 0.1 in the formula
  EXPECT_NEAR(k.device_to_view_depth[0], -0.1 / 99.9, 1e-9);
  EXPECT_NEAR(k.device_to_view_depth[1], 0.1 / 99.9 * 100.0, 1e-7);
  const float eps = std::numeric_limits<float>::epsilon();
  k = run(false, true, false);  // infinite far plane
  EXPECT_EQ(k.device_to_view_depth[0], 1.0f + eps);
  EXPECT_EQ(k.device_to_view_depth[1], -0.1f - eps);
  k = run(true, true, false);  // inverted and infinite
  EXPECT_EQ(k.device_to_view_depth[0], -eps);
  EXPECT_EQ(k.device_to_view_depth[1], 0.1f);

  ctx = Context1080p();
  ctx.display_resolution_motion_vectors = true;  // scale divided by the display size
  Fsr2ContextState st;
  Fsr2DispatchParams q = Frame(1280, 720, 0.5f, 0);
  q.frame_time_delta_ms = 2500.0f;
  Fsr2NextFrameConstants(ctx, q, &st);
  EXPECT_EQ(st.constants.motion_vector_scale[0], -640.0f / 1920.0f);
  EXPECT_EQ(st.constants.motion_vector_jitter_cancellation[0], -0.5f / 1920.0f);
  EXPECT_EQ(st.constants.delta_time, 1.0f);  // clamped to 1 s
  q.frame_time_delta_ms = -3.0f;
  Fsr2NextFrameConstants(ctx, q, &st);
  EXPECT_EQ(st.constants.delta_time, 0.0f);
  ctx.display_size[0] = 0;
  EXPECT_THROW(Fsr2NextFrameConstants(ctx, q, &st), std::invalid_argument);
}

}  // namespace
}  // namespace aalab
