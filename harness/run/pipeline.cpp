#include "harness/run/pipeline.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>

#include "core/error.h"
#include "core/hash.h"
#include "core/params.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "metrics/crops.h"
#include "metrics/metric.h"
#include "metrics/metrics.h"
#include "methods/registry.h"
#include "methods/rescale.h"
#include "scenes/analytic.h"
#include "scenes/exact_reference.h"
#include "scenes/library.h"
#include "scenes/motion.h"
#include "scenes/motion_render.h"

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
    // A temporal upscaler (make_state) resolves at the output size itself.
    if (p.render.scale != 1.0 && p.rescale == Rescale::kNone && !p.make_state) {
      throw InternalError("method '" + p.spec + "' renders at scale " + FormatNumber(p.render.scale) +
                          " but does not rescale");
    }
  }
  return plans;
}

bool CheckReferenceKind(const std::string& kind, const std::vector<const Scene*>& scenes) {
  if (kind != "sampled" && kind != "exact") {
    throw UserError("--reference '" + kind + "' is not allowed (allowed: sampled, exact)");
  }
  if (kind == "sampled") return false;
  for (const auto& s : scenes) {
    const std::string why = ExactReferenceRefusal(*s);
    if (!why.empty()) throw UserError("scene '" + s->name + "' cannot have --reference exact: " + why);
  }
  return true;
}

std::unique_ptr<PreparedScene> PrepareScene(std::unique_ptr<Scene> scene, int W, int H, int grid, uint64_t seed,
                                            int repeat, bool exact_reference, StageClock* clock,
                                            const ReferenceCache* cache, double flip_ppd) {
  if (clock) clock->Enter("references");
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
  sr.ref_spp = exact_reference ? 0 : grid * grid;
  sr.ref_exact = exact_reference;

  Stopwatch bvh_clock;
  p->tracer = std::make_unique<Tracer>(sc);
  sr.bvh_build_ms = bvh_clock.ElapsedMs();
  bool gltf = !sc.images.empty();
  for (const Material& m : sc.materials) gltf |= m.gltf.has_value();
  if (gltf) {
    SceneResult::Content c;
    for (const Shape& shape : sc.shapes) c.triangles += shape.triangles.size();
    c.textures = static_cast<int>(sc.images.size());
    for (const auto& img : sc.images) {
      c.texture_bytes += img->Bytes();
      c.texture_bytes_rgba8 += img->Bytes8();
    }
    for (const Scene::FileLoad& f : sc.load) c.load_ms += f.seconds * 1e3;
    sr.content = c;
  }

  CachedReference cr = ObtainReference(sc, *p->tracer, W, H, grid, seed, exact_reference, cache, nullptr);
  p->ref = std::move(cr.ref);
  sr.reference_ms = cr.render_ms;
  sr.ref_primary_rays_per_px = static_cast<double>(cr.primary_rays) / px;
  sr.ref_shadow_rays_per_px = static_cast<double>(cr.shadow_rays) / px;
  sr.ref_texture_lookups_per_px = static_cast<double>(cr.texture_lookups) / px;
  sr.ref_halves_psnr_db = PsnrFromMse(cr.halves_mse);
  if (sr.ref_halves_psnr_db) sr.ref_floor_psnr_db = *sr.ref_halves_psnr_db + 10.0 * std::log10(4.0);
  size_t edge_px = 0;
  for (float v : p->ref.edge_mask.Data()) edge_px += v > 0.5f ? 1 : 0;
  sr.edge_pixel_fraction = static_cast<double>(edge_px) / px;

  if (clock) clock->Enter("method_renders_filters");
  p->render1x = TimeRepeats(repeat, [&] {
    TraceCounters c;
    p->frame1x = RenderFrame(*p->tracer, W, H, RenderSpec{}, seed, &c);
    p->counters1x = c;
  });
  if (clock) clock->Enter("references");
  p->flip_ppd = flip_ppd;
  // The reference's metric sides, the coverage probes and the crops: four independent, untimed
  // jobs run side by side (each a pure function of the reference, the scene and the 1x frame,
  // so the same values at any thread count), so that one job's serial parts (its buffers'
  // first touch, the crops' pick) overlap another's parallel loops.
  std::vector<DiskProbe> disks;
  const std::function<void()> jobs[] = {
      [&] { p->flip_reference = flip::PrepareReference(p->ref.image, flip_ppd); },
      [&] { p->ssim_reference = PrepareSsimReference(p->ref.image); },
      [&] { disks = DiskProbes(sc, W, H, p->ref.image); },
      [&] {
        p->none_f = ToFloat(p->frame1x, 3);
        const int crop_size = std::max(8, std::min(32, std::min(W, H) / 4));
        for (const auto& c : PickCrops(CropScore(p->none_f, p->ref.image, &p->ref.edge_mask), crop_size, 4)) {
          sr.crops.push_back({c.x, c.y, c.w, c.h});
        }
      }};
  ParallelFor(static_cast<int>(std::size(jobs)), [&](int i) { jobs[i](); });
  for (const DiskProbe& d : disks) {
    CoverageProbe c;
    c.x0 = d.x0;
    c.y0 = d.y0;
    c.x1 = d.x1;
    c.y1 = d.y1;
    c.radius_px = d.radius_px;
    c.area_px = d.area_px;
    for (int k = 0; k < 3; ++k) {
      c.inside[k] = d.inside[static_cast<size_t>(k)];
      c.outside[k] = d.outside[static_cast<size_t>(k)];
    }
    p->coverage_probes.push_back(c);
  }
  return p;
}

bool RunsOnImageScenes(const MethodPlan& plan, bool has_motion) {
  if (plan.IsPostOnly() || plan.IsIdentity()) return true;
  // TAA: a jittered one-sample 1x render plus a temporal step, all of which a captured
  // sequence with motion vectors and jitter supplies.
  return has_motion && plan.NeedsHistory() && plan.render.jitter.samples > 0 && plan.render.scale == 1.0 &&
         plan.rescale == Rescale::kNone;
}

namespace {

// What every row of `plan` on scene `p` says about itself before anything runs.
ResultRow RowHeader(const PreparedScene& p, const MethodPlan& plan) {
  ResultRow row;
  row.scene = p.info.name;
  row.method = plan.name;
  row.spec = plan.spec;
  row.params = plan.params.Ordered();
  row.samples_per_pixel = plan.render.SamplesPerPixel();
  row.analytic_costs = plan.render.aaa.enabled;
  return row;
}

}  // namespace

ResultRow NotApplicableRow(const PreparedScene& p, const MethodPlan& plan) {
  ResultRow row = RowHeader(p, plan);
  row.render_width = p.info.width;
  row.render_height = p.info.height;
  row.not_applicable = "needs the renderer (it renders its own frame";
  if (plan.render.SamplesPerPixel() > 1) {
    row.not_applicable += ", " + std::to_string(plan.render.SamplesPerPixel()) + " samples per pixel";
  }
  if (plan.render.scale != 1.0) row.not_applicable += ", at scale " + FormatNumber(plan.render.scale);
  row.not_applicable += "); image scene '" + p.info.source + "' has only the 1x frame";
  for (const std::string& name : ImageMetricKeys()) {
    row.metrics.push_back({name, std::nullopt, "not applicable: " + row.not_applicable});
  }
  return row;
}

MethodOutput RunMethod(const PreparedScene& p, const MethodPlan& plan, const MethodRunSettings& run,
                       std::unique_ptr<TemporalState>* state, bool score) {
  const uint64_t seed = run.seed;
  const int repeat = run.repeat;
  const SamplerArithmetic sampler = run.sampler;
  StageClock* const clock = run.clock;
  if (!p.tracer && !RunsOnImageScenes(plan, p.captured_motion))
    return MethodOutput{NotApplicableRow(p, plan), {}, {}, {}};
  if (clock) clock->Enter("method_renders_filters");
  const int W = p.info.width, H = p.info.height;
  const double px = static_cast<double>(W) * H;
  MethodOutput out;
  out.row = RowHeader(p, plan);
  ResultRow& row = out.row;
  const bool jittered = plan.render.jitter.samples > 0;
  const bool shared = plan.render.IsPlain1x();  // false for jittered renders
  Image8 frame;
  TraceCounters counters;
  std::vector<float> previous;  // motion vectors of a jittered render (frame >= 1)
  std::vector<float> depth;     // view depth of a jittered render (+Inf: background)
  FrameJitter jitter;           // the jittered render's offset
  if (jittered && !p.tracer) {
    // A captured sequence (image scene with motion vectors and jitter): the 1x frame is the
    // engine's jittered frame, the previous positions come from its motion vectors; the
    // plan's own jitter pattern does not apply (the engine chose the jitter).
    frame = p.frame1x;
    row.render = p.render1x;
    row.render_shared = true;
    row.render_width = W;
    row.render_height = H;
    if (p.frame > 0) previous = p.captured_previous;
    jitter = p.captured_jitter;
  } else if (jittered) {
    AALAB_CHECK(plan.render.pattern == SamplePattern::kCenter, "jitter applies to a one-sample render");
    jitter = FrameJitterAt(plan.render.jitter, p.frame);
    // Temporal upscaling (methods/taau.cpp) renders its jittered frame at the plan's scale.
    const int rw = std::max(1, static_cast<int>(std::lround(plan.render.scale * W)));
    const int rh = std::max(1, static_cast<int>(std::lround(plan.render.scale * H)));
    row.render_width = rw;
    row.render_height = rh;
    // The render stage includes the motion vectors (a rasterizer writes its velocity buffer
    // while it renders).
    row.render = TimeRepeats(repeat, [&] {
      TraceCounters c;
      SurfaceFrame sf = RenderSurfaceFrame(*p.tracer, rw, rh, jitter, &c);
      if (p.sequence_scene) depth = SurfaceDepth(CameraAtFrame(*p.sequence_scene, p.frame), sf);
      if (p.frame > 0 && p.sequence_scene) {
        const std::vector<glm::vec2> prev = PreviousPositions(*p.sequence_scene, p.frame, sf, jitter);
        previous.resize(2 * prev.size());
        for (size_t i = 0; i < prev.size(); ++i) {
          previous[2 * i] = prev[i].x;
          previous[2 * i + 1] = prev[i].y;
        }
      }
      frame = std::move(sf.image);
      counters = c;
    });
  } else if (shared) {
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
      if (plan.render.aaa.enabled) {
        AnalyticCounters ac;
        frame = RenderAnalyticFrame(*p.tracer, rw, rh, plan.render.aaa, &c, &ac);
        row.analytic_edge_share =
            ac.edge_pixels ? std::optional<double>(static_cast<double>(ac.analytic_edge_pixels) / ac.edge_pixels)
                           : std::nullopt;
        row.analytic_pixels_per_px = static_cast<double>(ac.analytic_pixels) / (static_cast<double>(rw) * rh);
        row.distance_evals_per_px = static_cast<double>(ac.distance_evals) / (static_cast<double>(rw) * rh);
      } else {
        frame = RenderFrame(*p.tracer, rw, rh, plan.render, seed, &c);
      }
      counters = c;
    });
  }
  PostStats post_stats;
  if (plan.make_state) {
    // The temporal step runs on copies of the state (warm-up and repeats must not advance
    // the sequence more than once); the last copy becomes the state of the next frame.
    std::unique_ptr<TemporalState> local;
    std::unique_ptr<TemporalState>& st = state ? *state : local;
    if (!st) st = plan.make_state();
    TemporalInput tin;
    tin.frame = &frame;
    tin.previous = previous.empty() ? nullptr : &previous;
    tin.frame_index = p.frame;
    tin.depth = depth.empty() ? nullptr : &depth;
    tin.jitter = jitter;
    if (p.tracer && p.scene && p.scene->camera.type == CameraType::kPerspective) {               // FSR 2's depth clip
      tin.fov_y_radians = static_cast<float>(p.scene->camera.fov_y_deg * 0.017453292519943295);  // the frame's
    }
    tin.output_width = W;
    tin.output_height = H;
    Image8 filtered;
    std::unique_ptr<TemporalState> advanced;
    for (int r = 0; r <= repeat; ++r) {  // r = 0: the untimed warm-up, as TimeRepeats
      advanced = st->Clone();            // the copy is not part of the method's cost
      PostStats ps;
      Stopwatch w;
      filtered = advanced->Step(tin, &ps);
      if (r > 0) row.post.samples_ms.push_back(w.ElapsedMs());
      post_stats = ps;
    }
    row.post.Summarize();
    st = std::move(advanced);
    out.input = std::move(frame);
    frame = std::move(filtered);
  } else if (plan.post) {
    Image8 filtered;
    row.post = TimeRepeats(repeat, [&] {
      PostStats st;
      PostOptions opt;
      opt.sampler = sampler;
      filtered = plan.post(frame, opt, &st);
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
      scaled = RescaleFrame(frame, W, H, plan.rescale, &st, sampler);
      if (plan.sharpen) {
        PostOptions opt;
        opt.sampler = sampler;
        scaled = plan.sharpen(scaled, opt, &st);
      }
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
  if (!score) {  // the caller hashes (RunAndScoreRows: every row's hash in parallel, untimed)
    out.output = std::move(frame);
    return out;
  }
  ScoreOutput(p, std::move(frame), &out, clock);
  return out;
}

void ScoreOutput(const PreparedScene& p, Image8 frame, MethodOutput* out, StageClock* clock) {
  ResultRow& row = out->row;
  row.output_hash = HashBytes(frame.Data().data(), frame.Data().size());
  if (clock) clock->Enter("metrics");
  const auto seen = p.scored_by_hash.find(row.output_hash);
  if (seen != p.scored_by_hash.end()) {
    row.metrics = seen->second.metrics;
    out->flip_grey = seen->second.flip_grey;
    out->output = std::move(frame);
    return;
  }
  PreparedScene::Scored scored = ScoreFrame(p, frame);
  row.metrics = scored.metrics;
  out->flip_grey = scored.flip_grey;
  p.scored_by_hash[row.output_hash] = std::move(scored);
  out->output = std::move(frame);
}

PreparedScene::Scored ScoreFrame(const PreparedScene& p, const Image8& frame) {
  PreparedScene::Scored scored;
  const ImageF out_f = ToFloat(frame, 3);
  const FlipValues flip_values = flip::ErrorValues(*p.flip_reference, out_f);
  MetricInput in;
  in.image = &out_f;
  in.reference = &p.ref.image;
  in.edge_mask = &p.ref.edge_mask;
  in.none_image = &p.none_f;
  in.coverage_probes = &p.coverage_probes;
  in.flip_values = &flip_values;
  in.flip_ppd = p.flip_ppd;
  in.ssim_reference = p.ssim_reference.get();
  for (const auto& v : ComputeAllMetrics(in)) scored.metrics.push_back({v.name, v.value, v.null_reason});
  // The FLIP map for the page, 8 bits: round(255 · v), v in [0, 1].
  // Per pixel, so rows in parallel give the same bytes.
  scored.flip_grey.resize(flip_values.size());
  const int w = std::max(1, frame.Width());
  ParallelForChunks(static_cast<int>(flip_values.size() / static_cast<size_t>(w)), 64, [&](int y0, int y1) {
    for (size_t i = static_cast<size_t>(y0) * w; i < static_cast<size_t>(y1) * w; ++i) {
      scored.flip_grey[i] = static_cast<uint8_t>(std::lround(std::clamp(flip_values[i], 0.0, 1.0) * 255.0));
    }
  });
  return scored;
}

}  // namespace aalab
