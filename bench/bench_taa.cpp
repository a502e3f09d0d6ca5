// TAA per-frame cost vs fxaa311-p39 at 1080p (issue #16's goal: within 2×). Called from
// bench/bench_main.cpp (`make bench`) and from aalab_bench_taa (this figure alone).
#include "bench/bench_stats.h"
#include "bench/bench_taa.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
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
  auto state = taa.make_state();
  TemporalInput in0;
  in0.frame = &f0.image;
  state->Step(in0, nullptr);
  TemporalInput in1;
  in1.frame = &f1.image;
  in1.previous = &prev;
  in1.frame_index = 1;
  std::unique_ptr<TemporalState> copy;
  Image8 out;
  const Times taa_t = Time(
      reps, [&] { copy = state->Clone(); }, [&] { out = copy->Step(in1, nullptr); });
  // The simple implementation of the same step (the reference the production path is tested
  // against, bit for bit): the speed-up of the production path.
  Image8 out_ref;
  const Times ref_t = Time(
      reps, [&] { copy = TaaReferenceCopy(*state); }, [&] { out_ref = copy->Step(in1, nullptr); });
  if (!(out_ref == out)) std::fprintf(stderr, "TAA: the production step differs from the reference step\n");

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
  const std::string th = std::to_string(threads);
  b.lines.push_back("## TAA — ms per 1920x1080 frame (motion-pan, frame 1), " + th +
                    " threads; goal: taa ≤ 2× fxaa311-p39");
  b.lines.push_back("");
  b.lines.push_back("| stage | median ms (min–max) | / fxaa311-p39 |");
  b.lines.push_back("|---|---|---|");
  b.lines.push_back("| taa temporal step (reproject, clip, blend) | " + Fmt(taa_t.Median()) + " (" + Fmt(taa_t.Min()) +
                    "–" + Fmt(taa_t.Max()) + ") | " + Fmt(ratio) + (ratio <= 2.0 ? " (goal met)" : " (goal missed)") +
                    " |");
  b.lines.push_back("| taa temporal step, simple implementation (the reference it is tested against) | " +
                    Fmt(ref_t.Median()) + " (" + Fmt(ref_t.Min()) + "–" + Fmt(ref_t.Max()) + ") | " +
                    Fmt(ref_t.Median() / fxaa_t.Median()) + " |");
  b.lines.push_back("| fxaa311-p39 post filter | " + Fmt(fxaa_t.Median()) + " (" + Fmt(fxaa_t.Min()) + "–" +
                    Fmt(fxaa_t.Max()) + ") | 1.00 |");
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
  fig("taa-step-reference", ref_t);
  fig("fxaa311-p39", fxaa_t);
  fig("motion-vectors", mv_t);
  SetThreadCount(0);  // back to the default for whatever runs next
  return b;
}

}  // namespace aalab
