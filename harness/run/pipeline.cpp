#include "harness/run/pipeline.h"

#include <cmath>

#include "harness/core/error.h"
#include "harness/core/params.h"
#include "harness/core/timer.h"
#include "harness/run/runner.h"
#include "metrics/crops.h"
#include "metrics/metric.h"
#include "metrics/metrics.h"
#include "methods/registry.h"
#include "methods/rescale.h"
#include "scenes/library.h"

namespace aalab {

namespace {

Timing ZeroTiming(int repeat) {
  Timing t;
  t.samples_ms.assign(static_cast<size_t>(repeat), 0.0);
  t.Summarize();
  return t;
}

}  // namespace

Timing TimeRepeats(int repeat, const std::function<void()>& body) {
  Timing t;
  body();
  for (int i = 0; i < repeat; ++i) {
    Stopwatch w;
    body();
    t.samples_ms.push_back(w.ElapsedMs());
  }
  t.Summarize();
  return t;
}

std::vector<std::unique_ptr<Scene>> LoadScenes(const std::vector<std::string>& names) {
  if (names.empty()) throw UserError("no scenes to run");
  std::vector<std::unique_ptr<Scene>> scenes;
  for (const auto& n : names) {
    scenes.push_back(std::make_unique<Scene>(LoadScene(n)));
    for (size_t i = 0; i + 1 < scenes.size(); ++i) {
      if (scenes[i]->name == scenes.back()->name) throw UserError("scene '" + n + "' is listed twice");
    }
  }
  return scenes;
}

std::vector<MethodPlan> ResolveMethods(const std::vector<std::string>& specs) {
  if (specs.empty()) throw UserError("no methods to run");
  std::vector<MethodPlan> plans;
  for (const auto& m : specs) {
    plans.push_back(MakeMethod(m));
    for (size_t i = 0; i + 1 < plans.size(); ++i) {
      if (plans[i].spec == plans.back().spec) throw UserError("method '" + m + "' is listed twice");
    }
    const MethodPlan& p = plans.back();
    if (p.render.scale != 1.0 && p.rescale == Rescale::kNone) {
      throw InternalError("method '" + p.spec + "' renders at scale " + FormatNumber(p.render.scale) +
                          " but does not rescale");
    }
  }
  return plans;
}

std::unique_ptr<PreparedScene> PrepareScene(std::unique_ptr<Scene> scene, int W, int H, int grid, uint64_t seed,
                                            int repeat) {
  auto p = std::make_unique<PreparedScene>();
  p->scene = std::move(scene);
  const Scene& sc = *p->scene;
  const double px = static_cast<double>(W) * H;
  SceneResult& sr = p->info;
  sr.name = sc.name;
  sr.description = sc.description;
  sr.source = sc.path;
  sr.effects = sc.EffectNames();
  sr.width = W;
  sr.height = H;
  sr.ref_spp = grid * grid;

  Stopwatch bvh_clock;
  p->tracer = std::make_unique<Tracer>(sc);
  sr.bvh_build_ms = bvh_clock.ElapsedMs();

  Stopwatch ref_clock;
  TraceCounters ref_counters;
  p->ref = RenderReference(*p->tracer, W, H, grid, seed, &ref_counters);
  sr.reference_ms = ref_clock.ElapsedMs();
  sr.ref_primary_rays_per_px = static_cast<double>(ref_counters.primary_rays) / px;
  sr.ref_shadow_rays_per_px = static_cast<double>(ref_counters.shadow_rays) / px;
  sr.ref_texture_lookups_per_px = static_cast<double>(ref_counters.texture_lookups) / px;
  sr.ref_halves_psnr_db = PsnrFromMse(MeanSquaredError(p->ref.half_a, p->ref.half_b).mse);
  if (sr.ref_halves_psnr_db) sr.ref_floor_psnr_db = *sr.ref_halves_psnr_db + 10.0 * std::log10(4.0);
  size_t edge_px = 0;
  for (float v : p->ref.edge_mask.Data()) edge_px += v > 0.5f ? 1 : 0;
  sr.edge_pixel_fraction = static_cast<double>(edge_px) / px;

  p->render1x = TimeRepeats(repeat, [&] {
    TraceCounters c;
    p->frame1x = RenderFrame(*p->tracer, W, H, RenderSpec{}, seed, &c);
    p->counters1x = c;
  });
  p->none_f = ToFloat(p->frame1x, 3);
  p->flip_reference = flip::PrepareReference(p->ref.image, kFlipDefaultPpd);
  const int crop_size = std::max(8, std::min(32, std::min(W, H) / 4));
  for (const auto& c : PickCrops(CropScore(p->none_f, p->ref.image, &p->ref.edge_mask), crop_size, 4)) {
    sr.crops.push_back({c.x, c.y, c.w, c.h});
  }
  return p;
}

MethodOutput RunMethod(const PreparedScene& p, const MethodPlan& plan, uint64_t seed, int repeat) {
  const int W = p.info.width, H = p.info.height;
  const double px = static_cast<double>(W) * H;
  MethodOutput out;
  ResultRow& row = out.row;
  row.scene = p.info.name;
  row.method = plan.name;
  row.spec = plan.spec;
  row.params = plan.params.Ordered();
  row.samples_per_pixel = plan.render.SamplesPerPixel();
  const bool shared = plan.render.IsPlain1x();
  Image8 frame;
  TraceCounters counters;
  if (shared) {
    frame = p.frame1x;
    counters = p.counters1x;
    row.render = p.render1x;
    row.render_shared = plan.post != nullptr;
    row.render_width = W;
    row.render_height = H;
  } else {
    const int rw = std::max(1, static_cast<int>(std::lround(plan.render.scale * W)));
    const int rh = std::max(1, static_cast<int>(std::lround(plan.render.scale * H)));
    row.render_width = rw;
    row.render_height = rh;
    row.render = TimeRepeats(repeat, [&] {
      TraceCounters c;
      frame = RenderFrame(*p.tracer, rw, rh, plan.render, seed, &c);
      counters = c;
    });
  }
  PostStats post_stats;
  if (plan.post) {
    Image8 filtered;
    row.post = TimeRepeats(repeat, [&] {
      PostStats st;
      filtered = plan.post(frame, PostOptions{}, &st);
      post_stats = st;
    });
    out.input = std::move(frame);
    frame = std::move(filtered);
  } else {
    row.post = ZeroTiming(repeat);
  }
  PostStats rescale_stats;
  if (plan.rescale != Rescale::kNone) {
    Image8 scaled;
    row.resample = TimeRepeats(repeat, [&] {
      PostStats st;
      scaled = RescaleFrame(frame, W, H, plan.rescale, &st);
      rescale_stats = st;
    });
    frame = std::move(scaled);
  } else {
    row.resample = ZeroTiming(repeat);
  }
  for (size_t i = 0; i < row.render.samples_ms.size(); ++i) {
    row.total.samples_ms.push_back(row.render.samples_ms[i] + row.post.samples_ms[i] + row.resample.samples_ms[i]);
  }
  row.total.Summarize();
  AALAB_CHECK(frame.Width() == W && frame.Height() == H, "method output size must equal the frame size");
  row.primary_rays_per_px = static_cast<double>(counters.primary_rays) / px;
  row.shadow_rays_per_px = static_cast<double>(counters.shadow_rays) / px;
  row.texture_lookups_per_px = static_cast<double>(counters.texture_lookups) / px;
  row.coverage_rays_per_px = static_cast<double>(counters.coverage_rays) / px;
  row.shading_evals_per_px = static_cast<double>(counters.shading_evals) / px;
  row.taps_per_px = static_cast<double>(post_stats.taps + rescale_stats.taps) / px;
  row.output_hash = HashBytes(frame.Data().data(), frame.Data().size());

  const ImageF out_f = ToFloat(frame, 3);
  const std::vector<double> flip_values = flip::ErrorValues(*p.flip_reference, out_f);
  MetricInput in;
  in.image = &out_f;
  in.reference = &p.ref.image;
  in.edge_mask = &p.ref.edge_mask;
  in.none_image = &p.none_f;
  in.flip_values = &flip_values;
  for (const auto& v : ComputeAllMetrics(in)) row.metrics.push_back({v.name, v.value, v.null_reason});
  // Heatmaps: per-pixel |error| (mean over RGB, viridis, full scale 0.25) and FLIP (magma,
  // full scale 1), both against the reference.
  out.error_heatmap = Heatmap(AbsErrorMap(out_f, p.ref.image), kErrorHeatmapMax, Colormap::kViridis);
  ImageF flip_map(W, H, 1);
  for (size_t i = 0; i < flip_values.size(); ++i) flip_map.Data()[i] = static_cast<float>(flip_values[i]);
  out.flip_heatmap = Heatmap(flip_map, 1.0f, Colormap::kMagma);
  out.output = std::move(frame);
  return out;
}

}  // namespace aalab
