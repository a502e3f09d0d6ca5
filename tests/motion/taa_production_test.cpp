// The production TAA (methods/taa_production.cpp) and temporal upscaling (methods/taau.cpp),
// each technique against a hand-worked case:
//  - Catmull-Rom weights at t = 0, 1/4, 1/2 (worked by hand from the cubic);
//  - RGBA16F rounding against IEEE half values (Python's struct 'e', round to nearest even);
//  - closest-depth dilation on a two-depth edge: the background pixel beside a moving
//    foreground takes the foreground's vector, so its history comes from where the
//    foreground was (and without dilation from its own position);
//  - disocclusion: history from a nearer surface is dropped (depth), a jump of the motion
//    vector drops it when no depth is given, and, with depth, where a background pixel took
//    a moving object's dilated vector (the depth test alone keeps it);
//  - a still edge converges: after one Halton cycle (16 frames) the edge pixels' mean squared
//    error is below a quarter of `none`'s (bound derived below);
//  - 1 vs 2 threads give the same bytes (taa-prod and taau-50);
//  - TAAU: render scale, jitter phases ⌊8·ratio²⌋ (FSR 2), output size.
#include <gtest/gtest.h>

#include <cmath>

#include "core/color.h"
#include "core/parallel.h"
#include "methods/families.h"
#include "methods/registry.h"
#include "methods/taa.h"
#include "methods/taa_production.h"
#include "reports/html_speed.h"
#include "scenes/motion.h"
#include "scenes/motion_render.h"
#include "scenes/render.h"
#include "../scenes/scene_test_util.h"
#include "taa_test_util.h"

namespace aalab {
namespace {

TEST(TaaProd, CatmullRomWeightsByHand) {
  // w0 = −t³/2 + t² − t/2, w1 = 3t³/2 − 5t²/2 + 1, w2 = −3t³/2 + 2t² + t/2, w3 = t³/2 − t²/2.
  const auto w0 = CatmullRomWeights(0.0f);
  EXPECT_EQ(w0[0], 0.0f);
  EXPECT_EQ(w0[1], 1.0f);
  EXPECT_EQ(w0[2], 0.0f);
  EXPECT_EQ(w0[3], 0.0f);
  const auto wq = CatmullRomWeights(0.25f);  // −9/128, 111/128, 29/128, −3/128
  EXPECT_FLOAT_EQ(wq[0], -9.0f / 128.0f);
  EXPECT_FLOAT_EQ(wq[1], 111.0f / 128.0f);
  EXPECT_FLOAT_EQ(wq[2], 29.0f / 128.0f);
  EXPECT_FLOAT_EQ(wq[3], -3.0f / 128.0f);
  const auto wh = CatmullRomWeights(0.5f);  // −1/16, 9/16, 9/16, −1/16
  EXPECT_FLOAT_EQ(wh[0], -0.0625f);
  EXPECT_FLOAT_EQ(wh[1], 0.5625f);
  EXPECT_FLOAT_EQ(wh[2], 0.5625f);
  EXPECT_FLOAT_EQ(wh[3], -0.0625f);
}

TEST(TaaProd, HalfRoundingMatchesIeeeHalf) {
  EXPECT_EQ(RoundToHalf(1.0f / 3.0f), 0.333251953125f);
  EXPECT_EQ(RoundToHalf(0.1f), 0.0999755859375f);
  EXPECT_EQ(RoundToHalf(2049.0f), 2048.0f);  // tie to even
  EXPECT_EQ(RoundToHalf(2051.0f), 2052.0f);  // tie to even (up)
  EXPECT_EQ(RoundToHalf(65519.0f), 65504.0f);
  EXPECT_TRUE(std::isinf(RoundToHalf(65520.0f)));
  EXPECT_EQ(RoundToHalf(1e-7f), 1.1920928955078125e-07f);  // subnormal half 2^-23
  EXPECT_EQ(RoundToHalf(-0.5f), -0.5f);
  EXPECT_EQ(RoundToHalf(0.75f), 0.75f);
}

TEST(TaaProd, ClosestDepthPicksTheForeground) {
  // 5 × 3, columns 3..4 near (depth 2), columns 0..2 far (10); one far pixel nearer still.
  const int w = 5, h = 3;
  std::vector<float> d(w * h, 10.0f);
  for (int y = 0; y < h; ++y) d[y * w + 3] = d[y * w + 4] = 2.0f;
  EXPECT_EQ(ClosestDepthPixel(d.data(), w, h, 2, 1), 0 * w + 3);  // first near one, row-major
  EXPECT_EQ(ClosestDepthPixel(d.data(), w, h, 1, 1), 1 * w + 1);  // all far: the centre
  EXPECT_EQ(ClosestDepthPixel(d.data(), w, h, 3, 1), 1 * w + 3);  // a tie: the centre wins
  d[2 * w + 0] = 1.0f;
  EXPECT_EQ(ClosestDepthPixel(d.data(), w, h, 0, 2), 2 * w + 0);  // clamped corner
  EXPECT_EQ(ClosestDepthPixel(d.data(), w, h, 1, 1), 2 * w + 0);
}

// A W × H frame whose pixel (x, y) has grey code codes[x] (+ 7y so rows differ).
Image8 Ramp(int W, int H, const std::vector<int>& codes) {
  Image8 im(W, H, 4, 255);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      for (int c = 0; c < 3; ++c) im.Pixel(x, y)[c] = static_cast<uint8_t>(codes[static_cast<size_t>(x)] + 7 * y);
    }
  }
  return im;
}

ParamValues Params(const std::string& overrides_spec) {
  const MethodPlan plan = MakeMethod("taa-prod" + overrides_spec);
  return plan.params;
}

// Previous positions: every pixel moved by (dx(x), 0).
std::vector<float> Shifted(int W, int H, const std::vector<float>& dx) {
  std::vector<float> p(2 * static_cast<size_t>(W) * H);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const size_t i = static_cast<size_t>(y) * W + x;
      p[2 * i] = static_cast<float>(x) + 0.5f + dx[static_cast<size_t>(x)];
      p[2 * i + 1] = static_cast<float>(y) + 0.5f;
    }
  }
  return p;
}

// One frame of a hand-made sequence: the image, its previous positions and depth (null: none).
struct FrameIn {
  const Image8* image;
  const std::vector<float>* previous;
  const std::vector<float>* depth;
};

// Steps `st` through `frames` (frame indices 0, 1, ...; zero jitter) and returns the last output.
Image8 Feed(TemporalState& st, const std::vector<FrameIn>& frames) {
  Image8 out;
  for (size_t k = 0; k < frames.size(); ++k) {
    TemporalInput in;
    in.frame = frames[k].image;
    in.previous = frames[k].previous;
    in.depth = frames[k].depth;
    in.frame_index = static_cast<int>(k);
    out = st.Step(in, nullptr);
  }
  return out;
}

TEST(TaaProd, DilationTakesTheForegroundVector) {
  // Background columns 0..3 (depth 10, still), foreground columns 4..7 (depth 1) moving +2 px
  // per frame (previous = x − 2). Fixed α = 1/2, no clip, bilinear, box: the output is
  // (history + current) / 2 in linear light, with the history fetched at an integer shift.
  const int W = 8, H = 3;
  const std::vector<int> f0 = {10, 40, 70, 100, 130, 160, 190, 220}, f1 = {20, 50, 80, 110, 140, 170, 200, 230};
  std::vector<float> depth(W * H, 10.0f);
  for (int y = 0; y < H; ++y) {
    for (int x = 4; x < W; ++x) depth[static_cast<size_t>(y) * W + x] = 1.0f;
  }
  const std::vector<float> prev = Shifted(W, H, {0, 0, 0, 0, -2, -2, -2, -2});
  for (const bool dilate : {true, false}) {
    const std::string spec =
        std::string(":feedback=fixed,alpha=0.5,clip=none,history=bilinear,disocclusion=off,dilate=") +
        (dilate ? "on" : "off");
    auto st = MakeTaaProdState(TaaProdParamsFrom(Params(spec)));
    const Image8 a = Ramp(W, H, f0), b = Ramp(W, H, f1);
    const Image8 out = Feed(*st, {{&a, nullptr, &depth}, {&b, &prev, &depth}});
    // Pixel (3, 1): background, its right neighbour is foreground. Dilated: history at x = 1.
    const int hist_x = dilate ? 1 : 3;
    const float expect =
        0.5f * (SrgbDecode8(static_cast<uint8_t>(f0[hist_x] + 7)) + SrgbDecode8(static_cast<uint8_t>(f1[3] + 7)));
    EXPECT_EQ(out.Pixel(3, 1)[0], EncodeSrgb8(expect)) << "dilate " << dilate;
    // Pixel (1, 1): far from the edge, still either way.
    const float still =
        0.5f * (SrgbDecode8(static_cast<uint8_t>(f0[1] + 7)) + SrgbDecode8(static_cast<uint8_t>(f1[1] + 7)));
    EXPECT_EQ(out.Pixel(1, 1)[0], EncodeSrgb8(still));
  }
}

TEST(TaaProd, DisocclusionDropsHistory) {
  // Frame 0: a near surface (depth 1) everywhere; frame 1: the far background (depth 10) is
  // uncovered, nothing moved. With the test on, the output is the current frame itself.
  const int W = 6, H = 4;
  const Image8 a = Ramp(W, H, {200, 200, 200, 200, 200, 200}), b = Ramp(W, H, {30, 60, 90, 120, 150, 180});
  std::vector<float> near(W * H, 1.0f), far(W * H, 10.0f);
  const std::vector<float> still = Shifted(W, H, std::vector<float>(W, 0.0f));
  for (const bool on : {true, false}) {
    auto st =
        MakeTaaProdState(TaaProdParamsFrom(Params(std::string(":clip=none,disocclusion=") + (on ? "on" : "off"))));
    const Image8 out = Feed(*st, {{&a, nullptr, &near}, {&b, &still, &far}});
    if (on) {
      EXPECT_EQ(out.Data(), b.Data());
    } else {
      EXPECT_NE(out.Pixel(2, 1)[0], b.Pixel(2, 1)[0]);  // the old surface bleeds in
    }
  }
  // Without depth: frame 1 still (vectors 0), frame 2 every pixel jumps by −3 px: the
  // previous vector at the reprojected position (0) differs by 3 px > 1 px → dropped.
  auto st = MakeTaaProdState(TaaProdParamsFrom(Params(":clip=none")));
  std::vector<float> moved = Shifted(W, H, std::vector<float>(W, -3.0f));
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < 3; ++x) moved[2 * (static_cast<size_t>(y) * W + x)] += 3.0f;  // columns 0..2 stay still
  }
  const Image8 out = Feed(*st, {{&a, nullptr, nullptr}, {&a, &still, nullptr}, {&b, &moved, nullptr}});
  EXPECT_EQ(out.Pixel(4, 1)[0], b.Pixel(4, 1)[0]);  // jumped: current only
  EXPECT_NE(out.Pixel(1, 1)[0], b.Pixel(1, 1)[0]);  // still: history blends in
}

TEST(TaaProd, DilatedBackgroundBesideAMovingObjectIsDropped) {
  // A near bar (depth 1) 4 px wide moves right by 2 px a frame over a still far background
  // (depth 10): at frame t it covers columns 2t + 2 .. 2t + 5; its previous positions are
  // x − 2, the background's x. Frame 2: column 5 is background just uncovered (the bar
  // covered 4..7 at frame 1); its 3×3 holds the bar (column 6), so dilation gives it the
  // bar's vector: h = 5.5 − 2, column 3, background at frame 1 too, so the depth test (10
  // is not nearer than 1) keeps that history — background from 2 px away. The motion test
  // compares the bar's −2 px with frame 1's vector at column 3 (0, background): 2 px > 1 px,
  // dropped; the output is the current frame's pixel. Column 9 (the bar; frame 1's vector
  // at column 7, the bar's, matches) and column 1 (still background) keep their history.
  const int W = 14, H = 3;
  std::vector<Image8> img;
  std::vector<std::vector<float>> depth, prev;
  for (int t = 0; t < 3; ++t) {
    std::vector<int> codes(W);
    std::vector<float> d(static_cast<size_t>(W) * H, 10.0f), shift(W, 0.0f);
    for (int x = 0; x < W; ++x) {
      const bool bar = x >= 2 * t + 2 && x <= 2 * t + 5;
      codes[static_cast<size_t>(x)] = bar ? 200 + 10 * t : 20 + 9 * x + 30 * t;
      if (bar) {
        shift[static_cast<size_t>(x)] = -2.0f;
        for (int y = 0; y < H; ++y) d[static_cast<size_t>(y) * W + x] = 1.0f;
      }
    }
    img.push_back(Ramp(W, H, codes));
    depth.push_back(d);
    prev.push_back(Shifted(W, H, shift));
  }
  for (const bool on : {true, false}) {
    auto st = MakeTaaProdState(TaaProdParamsFrom(
        Params(std::string(":clip=none,feedback=fixed,alpha=0.5,disocclusion=") + (on ? "on" : "off"))));
    const Image8 out =
        Feed(*st, {{&img[0], nullptr, &depth[0]}, {&img[1], &prev[1], &depth[1]}, {&img[2], &prev[2], &depth[2]}});
    if (on) {
      EXPECT_EQ(out.Pixel(5, 1)[0], img[2].Pixel(5, 1)[0]);  // dropped by the motion test
    } else {
      EXPECT_NE(out.Pixel(5, 1)[0], img[2].Pixel(5, 1)[0]);  // the history from column 3 blends in
    }
    EXPECT_NE(out.Pixel(9, 1)[0], img[2].Pixel(9, 1)[0]) << on;  // the bar keeps its history
    EXPECT_NE(out.Pixel(1, 1)[0], img[2].Pixel(1, 1)[0]) << on;  // still background too
  }
}

// Runs `method` for `frames` frames on a still slanted edge (unlit, orthographic) and returns
// the mean squared linear error over pixels the reference shows partly covered, and `none`'s.
struct StillResult {
  double mse = 0, none_mse = 0;
};
StillResult RunStillEdge(const std::string& method, int frames, int W, int H, Image8* image = nullptr) {
  const testing::StillEdge edge(W, H);
  const MethodPlan plan = MakeMethod(method);
  auto state = plan.make_state();
  Image8 out;
  const int rw = static_cast<int>(std::lround(plan.render.scale * W)),
            rh = static_cast<int>(std::lround(plan.render.scale * H));
  for (int k = 0; k < frames; ++k) {
    const testing::TaaFrame f = testing::RenderTaaFrame(edge.scene, edge.tracer, plan.render.jitter, k, rw, rh);
    const std::vector<float> depth = SurfaceDepth(CameraAtFrame(edge.scene, k), f.sf);
    TemporalInput in = f.Input(k);
    in.depth = &depth;
    in.output_width = W;
    in.output_height = H;
    out = state->Step(in, nullptr);
  }
  EXPECT_EQ(out.Width(), W);
  EXPECT_EQ(out.Height(), H);
  if (image) *image = out;
  StillResult r;
  size_t n = 0;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const float t = edge.ref.image.At(x, y, 0);
      if (t < 0.02f || t > 0.98f) continue;  // edge pixels only
      const double e = SrgbDecode8(out.Pixel(x, y)[0]) - t, en = SrgbDecode8(edge.none.Pixel(x, y)[0]) - t;
      r.mse += e * e;
      r.none_mse += en * en;
      ++n;
    }
  }
  EXPECT_GT(n, 20u);
  r.mse /= static_cast<double>(n);
  r.none_mse /= static_cast<double>(n);
  return r;
}

TEST(TaaProd, StillEdgeConverges) {
  // Bound: while 1/(n+1) ≥ alpha_min (n < 24) the adaptive feedback is the running mean, so
  // after 16 frames (one Halton cycle) each pixel is the equal-weight mean of its 16
  // stratified samples (the variance clip only moves history that leaves the neighbourhood's
  // box). For a pixel of coverage c, independent uniform samples give E[err²] = c(1−c)/16,
  // 1/96 averaged over the offsets of a slanted edge; `none` gives 1/12: ratio 1/8. Halton
  // points are stratified (no worse for a step); a factor 2 of room for ~60 edge pixels and
  // the reference's own error: ratio < 1/4.
  const StillResult r = RunStillEdge("taa-prod", 16, 64, 48);
  EXPECT_LT(r.mse, 0.25 * r.none_mse) << r.mse << " vs none " << r.none_mse;
  // Gaussian reconstruction aims at a softer filter: still far better than none on this edge.
  const StillResult g = RunStillEdge("taa-prod:filter=gauss", 16, 64, 48);
  EXPECT_LT(g.mse, 0.5 * g.none_mse) << g.mse << " vs none " << g.none_mse;
}

TEST(TaaProd, TaauResolvesAtTheOutputSize) {
  for (const auto& [name, ratio, phases] : std::vector<std::tuple<std::string, double, int>>{
           {"taau-77", 1.3, 13}, {"taau-67", 1.5, 18}, {"taau-59", 1.7, 23}, {"taau-50", 2.0, 32}}) {
    const MethodPlan p = MakeMethod(name);
    EXPECT_DOUBLE_EQ(p.render.scale, 1.0 / ratio) << name;
    EXPECT_EQ(p.render.jitter.samples, phases) << name;  // ⌊8·ratio²⌋: 13.52, 18, 23.12, 32
    EXPECT_EQ(TaauJitterPhases(ratio), phases);
    EXPECT_TRUE(p.NeedsHistory());
  }
  // Rendering at 32 × 24 for a 64 × 48 output, one Halton(2,3) cycle of 32: the edge
  // converges to well below none's error at the full size.
  const StillResult r = RunStillEdge("taau-50", 32, 64, 48);
  EXPECT_LT(r.mse, 0.5 * r.none_mse) << r.mse << " vs none " << r.none_mse;
}

TEST(TaaProd, SameBytesAtOneAndTwoThreads) {
  for (const std::string method : {"taa-prod", "taa-prod:filter=gauss,precision=rgba16f,sharpen=0.5", "taau-50"}) {
    Image8 out[2];
    for (int t = 1; t <= 2; ++t) {
      SetThreadCount(t);
      RunStillEdge(method, 5, 37, 23, &out[t - 1]);
    }
    SetThreadCount(0);
    EXPECT_EQ(out[0].Data(), out[1].Data()) << method;
  }
}

}  // namespace
}  // namespace aalab

namespace aalab {
namespace {

ResultRow SweepRow(const std::string& scene, const std::string& spec, double tp, double flip) {
  ResultRow r;
  r.scene = scene;
  r.method = spec;
  r.spec = spec;
  r.metrics.push_back({"flip_mean", flip, ""});
  r.metrics.push_back({"temporal_perceptual", tp, ""});
  return r;
}

TEST(SpeedSweep, PointsCsvAndSectionFromSceneNames) {
  Report rep;
  rep.rows.push_back(SweepRow("motion-speed-zoom-2", "taa-prod", 0.5, 0.25));
  rep.rows.push_back(SweepRow("motion-speed-zoom-0p25", "taa-prod", 0.125, 0.75));
  rep.rows.push_back(SweepRow("motion-speed-rotate-8", "none", 1.5, 0.0625));
  rep.rows.push_back(SweepRow("wedges", "none", 1.0, 1.0));                  // not in the family
  rep.rows.push_back(SweepRow("motion-speed-zoom-fast", "none", 1.0, 1.0));  // no speed
  ResultRow null_row = SweepRow("motion-speed-zoom-1", "taa", 0.0, 0.0);
  null_row.metrics[1].value.reset();  // a null measure: left out
  rep.rows.push_back(null_row);
  EXPECT_EQ(SpeedSweepCsv(rep),
            "kind,speed,method,temporal_perceptual,flip_mean\n"
            "zoom,0.25,taa-prod,0.125,0.75\n"
            "zoom,2,taa-prod,0.5,0.25\n"
            "rotate,8,none,1.5,0.0625\n");
  std::string html;
  AppendSpeedSection(html, rep);
  EXPECT_NE(html.find("id=\"speed-sweep\""), std::string::npos);
  EXPECT_NE(html.find("<h3>zoom</h3>"), std::string::npos);
  EXPECT_NE(html.find("<h3>rotate</h3>"), std::string::npos);
  // No sweep scene: nothing (existing pages unchanged).
  Report plain;
  plain.rows.push_back(SweepRow("wedges", "none", 1.0, 1.0));
  std::string none_html;
  AppendSpeedSection(none_html, plain);
  EXPECT_TRUE(none_html.empty());
}

}  // namespace
}  // namespace aalab
