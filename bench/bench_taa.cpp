// TAA per-frame cost vs fxaa311-p39 at 1080p (issue #16's goal: within 2×). Called from
// bench/bench_main.cpp (`make bench`) and from aalab_bench_taa (this figure alone).
#include "bench/bench_stats.h"
#include "bench/bench_taa.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>

#include "core/format.h"
#include "core/parallel.h"
#include "methods/fxaa311.h"
#include "methods/registry.h"
#include "methods/taa.h"
#include "scenes/library.h"
#include "scenes/motion.h"
#include "scenes/motion_render.h"
#include "scenes/render.h"

namespace aalab {

namespace {

using Times = SampleStats;  // samples in ms

/// One untimed warm-up, then `reps` timed calls; `prepare` runs before each call, untimed.
Times Time(int reps, const std::function<void()>& prepare, const std::function<void()>& body) {
  Times t;
  for (int r = 0; r <= reps; ++r) {
    prepare();
    const auto a = std::chrono::steady_clock::now();
    body();
    const auto b = std::chrono::steady_clock::now();
    if (r > 0) t.samples.push_back(std::chrono::duration<double, std::milli>(b - a).count());
  }
  return t;
}

std::string Fmt(double v) { return FormatDouble("%.2f", v); }

/// TAA's bandwidth floor, as bench_common.cpp's PlainPass is FXAA's: every byte a step must
/// read (the frame, 4 bytes a pixel; the previous positions, 8; the history, 12) read once and
/// every byte it must write (the new history, 12; the output, 4) written once, with one
/// addition a float so that no read is dropped; the same row chunks as the step.
void TaaPlainPass(const Image8& frame, const std::vector<float>& prev, const std::vector<float>& hist,
                  std::vector<float>& next, Image8& out) {
  const int w = frame.Width();
  ParallelForChunks(frame.Height(), 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const size_t row = static_cast<size_t>(y) * static_cast<size_t>(w);
      const uint8_t* s = frame.Row(y);
      uint8_t* d = out.Row(y);
      const float* p = prev.data() + 2 * row;
      const float* h = hist.data() + 3 * row;
      float* n = next.data() + 3 * row;
      for (int x = 0; x < w; ++x) {
        uint32_t v;
        std::memcpy(&v, s + 4 * x, 4);
        v |= 0xFF000000u;
        std::memcpy(d + 4 * x, &v, 4);
        n[3 * x] = h[3 * x] + p[2 * x];
        n[3 * x + 1] = h[3 * x + 1] + p[2 * x + 1];
        n[3 * x + 2] = h[3 * x + 2];
      }
    }
  });
}

}  // namespace

TaaBench RunTaaBench(int reps, int threads) {
  const int W = 1920, H = 1080;
  SetThreadCount(threads);
  const Scene base = LoadScene("motion-pan");
  const Scene s0 = SceneAtFrame(base, 0), s1 = SceneAtFrame(base, 1);
  const Tracer t0(s0), t1(s1);
  const MethodPlan taa = MakeMethod("taa");
  const FrameJitter j0 = FrameJitterAt(taa.render.jitter, 0), j1 = FrameJitterAt(taa.render.jitter, 1);
  const SurfaceFrame f0 = RenderSurfaceFrame(t0, W, H, j0, nullptr);
  const SurfaceFrame f1 = RenderSurfaceFrame(t1, W, H, j1, nullptr);
  std::vector<float> prev;
  for (const glm::vec2& p : PreviousPositions(base, 1, f1, j1)) {
    prev.push_back(p.x);
    prev.push_back(p.y);
  }
  TemporalInput in0;
  in0.frame = &f0.image;
  TemporalInput in1;
  in1.frame = &f1.image;
  in1.previous = &prev;
  in1.frame_index = 1;
  std::unique_ptr<TemporalState> copy;
  Image8 out;
  // A method's state after frame 0; then its step on frame 1, timed on fresh copies.
  const auto after_frame0 = [&](const MethodPlan& m) {
    auto s = m.make_state();
    s->Step(in0, nullptr);
    return s;
  };
  const auto time_step = [&](const TemporalState& s) {
    return Time(
        reps, [&] { copy = s.Clone(); }, [&] { out = copy->Step(in1, nullptr); });
  };
  // The same step with a cheaper rectification (min/max box only) and with none: lower bounds
  // on the default step's time whatever its variance box costs (a variance box also takes the
  // min/max box; no box leaves the fetch, blend and encode every TAA does).
  const Times minmax_t = time_step(*after_frame0(MakeMethod("taa:clip=minmax")));
  const Times none_t = time_step(*after_frame0(MakeMethod("taa:clip=none")));
  const auto state = after_frame0(taa);
  const Times taa_t = time_step(*state);
  // The simple implementation of the same step (the reference the production path is tested
  // against, bit for bit): the speed-up of the production path.
  Image8 out_ref;
  const Times ref_t = Time(
      reps, [&] { copy = TaaReferenceCopy(*state); }, [&] { out_ref = copy->Step(in1, nullptr); });
  if (!(out_ref == out)) std::fprintf(stderr, "TAA: the production step differs from the reference step\n");

  std::vector<float> hist(3 * static_cast<size_t>(W) * H, 0.5f), next(hist.size());
  Image8 floor_out(W, H, 4);
  const Times floor_t = Time(
      reps, [] {}, [&] { TaaPlainPass(f1.image, prev, hist, next, floor_out); });

  const Image8 frame1x = RenderFrame(t1, W, H, RenderSpec{}, 1, nullptr);
  Fxaa311Params p39;
  p39.steps = Fxaa311PresetSteps(39);
  const Times fxaa_t = Time(
      reps, [] {}, [&] { out = Fxaa311(frame1x, p39, nullptr); });
  std::vector<glm::vec2> mv;
  const Times mv_t = Time(
      reps, [] {}, [&] { mv = PreviousPositions(base, 1, f1, j1); });

  TaaBench b;
  const double ratio = taa_t.Median() / fxaa_t.Median();
  b.ratio = ratio;
  b.minmax_ratio = minmax_t.Median() / fxaa_t.Median();
  b.none_ratio = none_t.Median() / fxaa_t.Median();
  b.floor_ratio = floor_t.Median() / fxaa_t.Median();
  const std::string th = std::to_string(threads);
  b.lines.push_back("## TAA — ms per 1920x1080 frame (motion-pan, frame 1), " + th +
                    " threads; goal: taa ≤ 2× fxaa311-p39");
  b.lines.push_back("");
  b.lines.push_back("| stage | median ms (min–max) | / fxaa311-p39 |");
  b.lines.push_back("|---|---|---|");
  b.lines.push_back("| taa temporal step (reproject, clip, blend) | " + Fmt(taa_t.Median()) + " (" + Fmt(taa_t.Min()) +
                    "–" + Fmt(taa_t.Max()) + ") | " + Fmt(ratio) + (ratio <= 2.0 ? " (goal met)" : " (goal missed)") +
                    " |");
  b.lines.push_back("| taa:clip=minmax step (min/max box only; a lower bound for the variance box) | " +
                    Fmt(minmax_t.Median()) + " (" + Fmt(minmax_t.Min()) + "–" + Fmt(minmax_t.Max()) + ") | " +
                    Fmt(minmax_t.Median() / fxaa_t.Median()) + " |");
  b.lines.push_back("| taa:clip=none step (no box: reproject, blend, encode) | " + Fmt(none_t.Median()) + " (" +
                    Fmt(none_t.Min()) + "–" + Fmt(none_t.Max()) + ") | " + Fmt(none_t.Median() / fxaa_t.Median()) +
                    " |");
  b.lines.push_back("| taa temporal step, simple implementation (the reference it is tested against) | " +
                    Fmt(ref_t.Median()) + " (" + Fmt(ref_t.Min()) + "–" + Fmt(ref_t.Max()) + ") | " +
                    Fmt(ref_t.Median() / fxaa_t.Median()) + " |");
  b.lines.push_back("| fxaa311-p39 post filter | " + Fmt(fxaa_t.Median()) + " (" + Fmt(fxaa_t.Min()) + "–" +
                    Fmt(fxaa_t.Max()) + ") | 1.00 |");
  b.lines.push_back(
      "| *taa's floor: plain read of its inputs (frame, previous positions, history), write of its "
      "outputs (history, frame)* | " +
      Fmt(floor_t.Median()) + " (" + Fmt(floor_t.Min()) + "–" + Fmt(floor_t.Max()) + ") | " +
      Fmt(floor_t.Median() / fxaa_t.Median()) + " |");
  b.lines.push_back("| motion vectors (exact, from the known motion) | " + Fmt(mv_t.Median()) + " (" + Fmt(mv_t.Min()) +
                    "–" + Fmt(mv_t.Max()) + ") | " + Fmt(mv_t.Median() / fxaa_t.Median()) + " |");
  auto fig = [&](const std::string& name, const Times& t) {
    b.figures.push_back({{"group", "taa"},
                         {"name", name},
                         {"frame", "motion-pan 1920x1080 frame 1"},
                         {"threads", threads},
                         {"unit", "ms"},
                         {"median", t.Median()},
                         {"min", t.Min()},
                         {"max", t.Max()},
                         {"samples", t.samples}});
  };
  fig("taa-step", taa_t);
  fig("taa-step-clip-minmax", minmax_t);
  fig("taa-step-clip-none", none_t);
  fig("taa-step-reference", ref_t);
  fig("taa-floor", floor_t);
  fig("fxaa311-p39", fxaa_t);
  fig("motion-vectors", mv_t);
  SetThreadCount(0);  // back to the default for whatever runs next
  return b;
}

}  // namespace aalab
