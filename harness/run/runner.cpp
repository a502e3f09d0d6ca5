#include "harness/run/runner.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>

#include "harness/core/color.h"
#include "harness/core/error.h"
#include "harness/core/parallel.h"
#include "harness/core/params.h"
#include "harness/core/timer.h"
#include "harness/io/image_io.h"
#include "metrics/crops.h"
#include "metrics/metric.h"
#include "methods/registry.h"
#include "reports/report_json.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace aalab {
namespace fs = std::filesystem;

std::vector<std::string> DefaultMethods() {
  return {"none", "ssaa-2x2", "ssaa-4x4", "ssaa-rgss", "ssaa-jitter", "fxaa1-p0", "fxaa1-p1", "fxaa1-p2",
          "fxaa1-p3", "fxaa1-p4"};
}

void ParseSize(const std::string& text, int* width, int* height) {
  const auto x = text.find('x');
  auto fail = [&]() {
    throw UserError("--size '" + text + "' is not WxH with 1 <= W, H <= 16384 and W*H <= 64 Mpx (e.g. 960x540)");
  };
  if (x == std::string::npos || x == 0 || x + 1 >= text.size()) fail();
  for (size_t i = 0; i < text.size(); ++i) {
    if (i != x && (text[i] < '0' || text[i] > '9')) fail();
  }
  if (x > 6 || text.size() - x - 1 > 6) fail();
  const long w = std::stol(text.substr(0, x)), h = std::stol(text.substr(x + 1));
  if (w < 1 || h < 1 || w > 16384 || h > 16384 || w * h > 64L * 1024 * 1024) fail();
  *width = static_cast<int>(w);
  *height = static_cast<int>(h);
}

namespace {

/// Progress with ETA on stderr.
class Progress {
 public:
  Progress(int total, bool quiet) : total_(total), quiet_(quiet) {}
  void Step(const std::string& what) {
    ++done_;
    if (quiet_) return;
    const double elapsed = clock_.ElapsedMs() / 1000.0;
    const double eta = done_ > 0 ? elapsed / done_ * (total_ - done_) : 0.0;
    std::fprintf(stderr, "[%3d/%d] %-40s elapsed %6.1fs  eta %6.1fs\n", done_, total_, what.c_str(), elapsed, eta);
    std::fflush(stderr);
  }

 private:
  int total_;
  int done_ = 0;
  bool quiet_;
  Stopwatch clock_;
};

/// Runs `body` once as a warm-up, then `repeat` times timed.
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

Timing ZeroTiming(int repeat) {
  Timing t;
  t.samples_ms.assign(static_cast<size_t>(repeat), 0.0);
  t.Summarize();
  return t;
}

std::string FileSafe(const std::string& spec) {
  std::string s = spec;
  for (char& c : s) {
    if (c == ':' || c == ',') c = '_';
    if (c == '=') c = '-';
  }
  return s;
}

/// Display-linear float image (decoded) of an sRGB-encoded float image, for EXR output.
ImageF DecodeToLinear(const ImageF& encoded) {
  ImageF out(encoded.Width(), encoded.Height(), encoded.Channels());
  for (size_t i = 0; i < encoded.Data().size(); ++i) out.Data()[i] = SrgbDecode(encoded.Data()[i]);
  return out;
}

struct SceneRun {
  const Scene* scene;
  std::string dir;  // images/<scene>
};

}  // namespace

Report RunSuite(const RunSettings& s) {
  SetThreadCount(s.threads);
  // Validate every input before any work.
  if (s.repeat < 1 || s.repeat > 1000) throw UserError("--repeat " + std::to_string(s.repeat) + " is out of range (1..1000)");
  const int grid = ReferenceGridForSpp(s.ref_spp);
  const std::vector<std::string> scene_names = s.scenes.empty() ? SuiteScenes(s.suite) : s.scenes;
  if (scene_names.empty()) throw UserError("no scenes to run");
  std::vector<std::unique_ptr<Scene>> scenes;
  for (const auto& n : scene_names) {
    scenes.push_back(std::make_unique<Scene>(LoadScene(n)));
    for (size_t i = 0; i + 1 < scenes.size(); ++i) {
      if (scenes[i]->name == scenes.back()->name) throw UserError("scene '" + n + "' is listed twice");
    }
  }
  const std::vector<std::string> method_specs = s.methods.empty() ? DefaultMethods() : s.methods;
  std::vector<MethodPlan> plans;
  for (const auto& m : method_specs) {
    plans.push_back(MakeMethod(m));
    for (size_t i = 0; i + 1 < plans.size(); ++i) {
      if (plans[i].spec == plans.back().spec) throw UserError("method '" + m + "' is listed twice");
    }
    const MethodPlan& p = plans.back();
    if (p.render.scale != 1.0 && p.rescale == Rescale::kNone) {
      throw InternalError("method '" + p.spec + "' renders at scale " + FormatNumber(p.render.scale) + " but does not rescale");
    }
  }
  if (s.out_dir.empty()) throw UserError("--out must not be empty");
  const fs::path out(s.out_dir);
  if (fs::exists(out)) {
    if (!fs::is_directory(out)) throw UserError("--out '" + s.out_dir + "' exists and is not a folder");
    if (!fs::is_empty(out) && !fs::exists(out / "report.json")) {
      throw UserError("--out '" + s.out_dir + "' is a non-empty folder without a report.json; refusing to replace it");
    }
  }
  const fs::path tmp = out.string() + ".partial";
  fs::remove_all(tmp);
  fs::create_directories(tmp / "images");

  Report report;
  for (const auto& [k, v] : ContextFacts()) report.context[k] = v;
  report.settings = {{"suite", s.scenes.empty() ? s.suite : "(custom)"},
                     {"scenes", JoinNames(scene_names)},
                     {"methods", JoinNames(method_specs)},
                     {"size", std::to_string(s.width) + "x" + std::to_string(s.height)},
                     {"ref_spp", std::to_string(s.ref_spp)},
                     {"seed", std::to_string(s.seed)},
                     {"threads", std::to_string(ThreadCount())},
                     {"repeat", std::to_string(s.repeat)},
                     {"warmup", "1"},
                     {"debug_views", s.debug_views ? "true" : "false"}};

  const int W = s.width, H = s.height;
  const double px = static_cast<double>(W) * H;
  Progress progress(static_cast<int>(scenes.size() * (plans.size() + 1)), s.quiet);
  for (const auto& scene_ptr : scenes) {
    const Scene& scene = *scene_ptr;
    const std::string rel_dir = "images/" + scene.name;
    fs::create_directories(tmp / rel_dir);
    SceneResult sr;
    sr.name = scene.name;
    sr.description = scene.description;
    sr.source = scene.path;
    sr.effects = scene.EffectNames();
    sr.width = W;
    sr.height = H;
    sr.ref_spp = s.ref_spp;

    Stopwatch bvh_clock;
    Tracer tracer(scene);
    sr.bvh_build_ms = bvh_clock.ElapsedMs();

    Stopwatch ref_clock;
    TraceCounters ref_counters;
    const Reference ref = RenderReference(tracer, W, H, grid, s.seed, &ref_counters);
    sr.reference_ms = ref_clock.ElapsedMs();
    sr.ref_primary_rays_per_px = static_cast<double>(ref_counters.primary_rays) / px;
    sr.ref_shadow_rays_per_px = static_cast<double>(ref_counters.shadow_rays) / px;
    sr.ref_texture_lookups_per_px = static_cast<double>(ref_counters.texture_lookups) / px;
    sr.ref_halves_psnr_db = PsnrFromMse(MeanSquaredError(ref.half_a, ref.half_b).mse);
    if (sr.ref_halves_psnr_db) sr.ref_floor_psnr_db = *sr.ref_halves_psnr_db + 10.0 * std::log10(4.0);
    size_t edge_px = 0;
    for (float v : ref.edge_mask.Data()) edge_px += v > 0.5f ? 1 : 0;
    sr.edge_pixel_fraction = static_cast<double>(edge_px) / px;
    WriteImageF((tmp / rel_dir / "reference.exr").string(), DecodeToLinear(ref.image));
    WriteImage8((tmp / rel_dir / "reference.png").string(), ToUnorm8(ref.image));
    WriteImage8((tmp / rel_dir / "edge_mask.png").string(), ToUnorm8(ref.edge_mask));
    sr.images = {{"reference_exr", rel_dir + "/reference.exr"},
                 {"reference_png", rel_dir + "/reference.png"},
                 {"edge_mask", rel_dir + "/edge_mask.png"}};
    progress.Step(scene.name + " reference");

    // The 1x frame: rendered once (timed) and shared by `none` and every post-only method.
    Image8 frame1x;
    TraceCounters counters1x;
    const Timing render1x = TimeRepeats(s.repeat, [&] {
      TraceCounters c;
      frame1x = RenderFrame(tracer, W, H, RenderSpec{}, s.seed, &c);
      counters1x = c;
    });
    const ImageF none_f = ToFloat(frame1x, 3);
    const int crop_size = std::max(8, std::min(32, std::min(W, H) / 4));
    for (const auto& c : PickCrops(CropScore(none_f, ref.image, &ref.edge_mask), crop_size, 4)) {
      sr.crops.push_back({c.x, c.y, c.w, c.h});
    }

    for (const MethodPlan& plan : plans) {
      ResultRow row;
      row.scene = scene.name;
      row.method = plan.name;
      row.spec = plan.spec;
      row.params = plan.params.Ordered();
      row.samples_per_pixel = plan.render.SamplesPerPixel();
      const bool shared = plan.render.pattern == SamplePattern::kCenter && plan.render.scale == 1.0;
      Image8 frame;
      TraceCounters counters;
      if (shared) {
        frame = frame1x;
        counters = counters1x;
        row.render = render1x;
        row.render_shared = plan.post != nullptr;
        row.render_width = W;
        row.render_height = H;
      } else {
        const int rw = std::max(1, static_cast<int>(std::lround(plan.render.scale * W)));
        const int rh = std::max(1, static_cast<int>(std::lround(plan.render.scale * H)));
        row.render_width = rw;
        row.render_height = rh;
        row.render = TimeRepeats(s.repeat, [&] {
          TraceCounters c;
          frame = RenderFrame(tracer, rw, rh, plan.render, s.seed, &c);
          counters = c;
        });
      }
      PostStats post_stats;
      if (plan.post) {
        Image8 filtered;
        row.post = TimeRepeats(s.repeat, [&] {
          PostStats st;
          filtered = plan.post(frame, PostOptions{}, &st);
          post_stats = st;
        });
        if (s.debug_views) {
          for (const auto& view : plan.debug_views) {
            PostOptions opt;
            opt.debug_view = view;
            const std::string rel = rel_dir + "/" + FileSafe(plan.spec) + ".debug-" + view + ".png";
            WriteImage8((tmp / rel).string(), plan.post(frame, opt, nullptr));
            row.images["debug_" + view] = rel;
          }
        }
        frame = std::move(filtered);
      } else {
        row.post = ZeroTiming(s.repeat);
      }
      if (plan.rescale != Rescale::kNone) {
        throw InternalError("rescaling methods are not wired into the runner yet");
      }
      row.resample = ZeroTiming(s.repeat);
      for (size_t i = 0; i < row.render.samples_ms.size(); ++i) {
        row.total.samples_ms.push_back(row.render.samples_ms[i] + row.post.samples_ms[i] + row.resample.samples_ms[i]);
      }
      row.total.Summarize();
      AALAB_CHECK(frame.Width() == W && frame.Height() == H, "method output size must equal the frame size");
      row.primary_rays_per_px = static_cast<double>(counters.primary_rays) / px;
      row.shadow_rays_per_px = static_cast<double>(counters.shadow_rays) / px;
      row.texture_lookups_per_px = static_cast<double>(counters.texture_lookups) / px;
      row.taps_per_px = static_cast<double>(post_stats.taps) / px;
      row.output_hash = HashBytes(frame.Data().data(), frame.Data().size());

      const ImageF out_f = ToFloat(frame, 3);
      MetricInput in;
      in.image = &out_f;
      in.reference = &ref.image;
      in.edge_mask = &ref.edge_mask;
      in.none_image = &none_f;
      for (const auto& entry : MetricRegistry()) {
        for (const auto& v : entry.compute(in)) row.metrics.push_back({v.name, v.value, v.null_reason});
      }
      const std::string rel = rel_dir + "/" + FileSafe(plan.spec) + ".png";
      WriteImage8((tmp / rel).string(), frame);
      row.images["output"] = rel;
      report.rows.push_back(std::move(row));
      progress.Step(scene.name + " " + plan.spec);
    }
    report.scenes.push_back(std::move(sr));
  }

  WriteTextFile((tmp / "report.json").string(), ReportToJson(report).dump(2) + "\n");
  fs::remove_all(out);
  fs::rename(tmp, out);
  return report;
}

}  // namespace aalab
