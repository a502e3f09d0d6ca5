#include "harness/cli/commands.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "core/color.h"
#include "core/error.h"
#include "core/exit_code.h"
#include "core/params.h"
#include "core/parallel.h"
#include "io/image_io.h"
#include "harness/run/out_folder.h"
#include "harness/run/runner.h"
#include "metrics/viewing.h"
#include "harness/run/shard.h"
#include "metrics/metric.h"
#include "methods/registry.h"
#include "scenes/library.h"
#include "harness/run/stage_clock.h"
#include "reports/verdict.h"
#include "scenes/render.h"

namespace aalab {
namespace fs = std::filesystem;

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> out;
  std::string cur;
  // Commas separate items, except inside a method's parameter list ("a:x=1,y=2,b"): a
  // comma followed by "key=" continues the current spec.
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) throw UserError("empty item in list '" + text + "'");
    const bool continues = !cur.empty() && cur.find(':') != std::string::npos && item.find('=') != std::string::npos &&
                           item.find(':') == std::string::npos;
    if (continues) {
      cur += "," + item;
    } else {
      if (!cur.empty()) out.push_back(cur);
      cur = item;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

namespace {

int ListCommand(const std::string& what, bool markdown) {
  if (markdown && what != "methods" && what != "metrics") {
    throw UserError("--markdown is for `aalab list methods` and `aalab list metrics` only (not '" + what + "')");
  }
  if (what == "methods" && markdown) {
    std::printf("%s", MethodTableMarkdown().c_str());  // README.md's and docs/cli.md's table
    return 0;
  }
  if (what == "metrics" && markdown) {
    std::printf("%s", MetricTablesMarkdown().c_str());  // metrics/METRICS.md's tables
    return 0;
  }
  if (what == "scenes") {
    for (const auto& name : LibrarySceneNames()) {
      const Scene s = LoadScene(name);
      std::printf("%-18s [%s]\n    %s\n", name.c_str(), JoinNames(s.EffectNames()).c_str(), s.description.c_str());
    }
    std::printf("\nsuites:\n");
    for (const auto& suite : SuiteNames()) {
      std::printf("  %-10s %s\n", suite.c_str(), JoinNames(SuiteScenes(suite)).c_str());
    }
    return ToInt(ExitCode::kOk);
  }
  if (what == "methods") {
    for (const auto& e : MethodRegistry()) {
      std::printf("%-20s %s\n", e.name.c_str(), e.help.c_str());
      for (const auto& p : e.params) std::printf("    %-44s %s\n", p.Describe().c_str(), p.help.c_str());
    }
    return ToInt(ExitCode::kOk);
  }
  if (what == "metrics") {
    for (const auto& e : MetricRegistry()) {
      std::printf("%-14s %s\n    values: %s\n", e.name.c_str(), e.help.c_str(), JoinNames(OutputKeys(e)).c_str());
    }
    return ToInt(ExitCode::kOk);
  }
  if (what == "viewing") {
    for (const auto& p : ViewingPresets()) {
      std::printf("%-24s %s\n    %s\n", p.name, p.help, ResolveViewing(p.name).Describe().c_str());
    }
    std::printf("overrides (PRESET:key=value,...):\n");
    for (const auto& d : ViewingParams()) std::printf("    %-12s %s\n", d.name.c_str(), d.help.c_str());
    return ToInt(ExitCode::kOk);
  }
  throw UserError("unknown list '" + what + "' (allowed: scenes, methods, metrics, viewing)");
}

}  // namespace

void RegisterCommands(CLI::App& app, Commands& commands) {
  // list
  auto* list = app.add_subcommand("list", "list scenes (and suites), methods, metrics or viewing presets");
  auto list_what = std::make_shared<std::string>();
  auto list_markdown = std::make_shared<bool>(false);
  list->add_option("what", *list_what, "scenes | methods | metrics | viewing")->required();
  list->add_flag(
      "--markdown", *list_markdown,
      "methods: the family table of README.md and docs/cli.md; metrics: the tables of metrics/METRICS.md (Markdown)");
  list->callback([&commands, list_what, list_markdown] {
    commands.action = [list_what, list_markdown] { return ListCommand(*list_what, *list_markdown); };
  });

  // render
  auto* render = app.add_subcommand("render", "render one scene (reference-style stratified samples) to EXR or PNG");
  struct RenderArgs {
    std::string scene, size = "960x540", out;
    int spp = 1, threads = 0;
    uint64_t seed = 1;
  };
  auto ra = std::make_shared<RenderArgs>();
  render->add_option("--scene", ra->scene, "library scene name or path to a scene file")->required();
  render->add_option("--size", ra->size, "WxH")->capture_default_str();
  render->add_option("--spp", ra->spp, "samples per pixel: 1 (pixel centre) or n*n stratified")->capture_default_str();
  render->add_option("--seed", ra->seed, "jitter seed")->capture_default_str();
  render->add_option("--threads", ra->threads, "worker threads (0 = all)")->capture_default_str();
  render
      ->add_option("--out", ra->out,
                   "output file: .exr (display-linear float resolve, not quantised) or .png (sRGB 8-bit)")
      ->required();
  render->callback([&commands, ra] {
    commands.action = [ra] {
      int w = 0, h = 0;
      ParseSize(ra->size, &w, &h);
      SetThreadCount(ra->threads);
      int n = 0;
      while ((n + 1) * (n + 1) <= ra->spp) ++n;
      if (ra->spp < 1 || ra->spp > 4096 || n * n != ra->spp) {
        throw UserError("--spp " + std::to_string(ra->spp) +
                        " must be a square number from 1 to 4096 (1, 4, 9, 16, ..., 256)");
      }
      const std::string ext = fs::path(ra->out).extension().string();
      if (ext != ".exr" && ext != ".png") throw UserError("--out '" + ra->out + "' must end in .exr or .png");
      CheckOutFile(ra->out, {ra->scene});  // never onto the scene file, never a folder
      const Scene scene = LoadScene(ra->scene);
      Tracer tracer(scene);
      RenderSpec spec;
      if (n > 1) {
        spec.pattern = SamplePattern::kStratified;
        spec.grid = n;
      }
      TraceCounters counters;
      if (ext == ".png") {
        WriteImage8(ra->out, RenderFrame(tracer, w, h, spec, ra->seed, &counters));
      } else {  // the float resolve of the same samples, before sRGB encoding and quantisation
        WriteImageF(ra->out, RenderFrameLinear(tracer, w, h, spec, ra->seed, &counters));
      }
      std::printf("wrote %s (%dx%d, %d spp; %.2f primary rays/px, %.2f shadow rays/px, %.2f texture lookups/px)\n",
                  ra->out.c_str(), w, h, ra->spp, static_cast<double>(counters.primary_rays) / (w * h),
                  static_cast<double>(counters.shadow_rays) / (w * h),
                  static_cast<double>(counters.texture_lookups) / (w * h));
      return ToInt(ExitCode::kOk);
    };
  });

  // run
  auto* run = app.add_subcommand("run", "run the scene x method matrix; writes DIR/report.json and images");
  auto rs = std::make_shared<RunSettings>();
  auto run_scenes = std::make_shared<std::string>();
  auto run_methods = std::make_shared<std::string>();
  auto run_size = std::make_shared<std::string>("960x540");
  run->add_option("--suite", rs->suite, "suite name (see aalab list scenes)")->capture_default_str();
  run->add_option("--scenes", *run_scenes,
                  "comma-separated library scene names or scene file paths (overrides --suite)");
  run->add_option("--methods", *run_methods,
                  "comma-separated method specs, e.g. none,fxaa311-p39:subpix=0.5 (default: one or two of each family; "
                  "'all': every registered method)");
  run->add_option("--size", *run_size, "output size WxH")->capture_default_str();
  run->add_option("--ref-spp", rs->ref_spp, "reference samples per pixel: n*n, n even (4, 16, 64, 256, 1024)")
      ->capture_default_str();
  run->add_option(
         "--reference", rs->reference,
         "sampled (--ref-spp stratified samples) or exact (closed-form coverage; flat unlit orthographic scenes)")
      ->capture_default_str();
  run->add_option("--seed", rs->seed, "jitter seed")->capture_default_str();
  run->add_option("--threads", rs->threads, "worker threads (0 = all hardware threads)")->capture_default_str();
  run->add_option("--repeat", rs->repeat, "timed repeats after one warm-up")->capture_default_str();
  run->add_option("--frames", rs->frames,
                  "frames per scene (1..100000; 1 = a still frame; moving scenes allow up to their animation.frames)")
      ->capture_default_str();
  run->add_option("--out", rs->out_dir, "output folder")->capture_default_str();
  run->add_option("--viewing", rs->viewing,
                  "viewing condition PRESET[:key=value,...] for FLIP and the perceptual temporal error (default: "
                  "'default', 67 px/deg; see aalab list viewing)");
  run->add_flag("--frame-exr", rs->frame_exr,
                "motion runs: also write every frame's reference as display-linear float EXR (reference.f<t>.exr), for "
                "outside video metrics (docs/motion.md)");
  run->add_flag("--debug-views", rs->debug_views, "also save each post filter's debug views");
  auto run_sampler = std::make_shared<std::string>("gl");
  run->add_option("--sampler", *run_sampler,
                  "texel and bilinear arithmetic of the post filters: gl (llvmpipe's, the fidelity oracle) or "
                  "gpu-texture (the H100 texture unit's fixed-point filter; docs/gpu.md)")
      ->capture_default_str();
  run->add_flag("--quiet", rs->quiet, "no progress on stderr");
  auto run_shard = std::make_shared<std::string>();
  run->add_option("--shard", *run_shard,
                  "K/N: run shard K (0..N-1) of N, its share of the scenes, as a partial report for 'aalab merge' "
                  "(docs/cluster.md)");
  run->add_option("--ref-cache", rs->ref_cache,
                  "folder of cached references shared by shards and runs: read when present, written when rendered");
  run->add_flag("--references-only", rs->references_only,
                "only render this shard's share of the references into --ref-cache (scenes, and frames of moving "
                "scenes); write no report");
  auto run_gpu = std::make_shared<std::vector<std::string>>();
  run->add_option("--gpu-timings", *run_gpu,
                  "after the run, attach GPU timings (aalab_raster's, aalab_gpu's or aalab_vk's JSON) to the rows, as "
                  "merge-gpu does: FILE[,FILE...] or the option repeated, merged in that order (docs/gpu.md)")
      ->delimiter(',');
  run->callback([&commands, rs, run_scenes, run_methods, run_size, run_shard, run_sampler, run_gpu] {
    commands.action = [rs, run_scenes, run_methods, run_size, run_shard, run_sampler, run_gpu] {
      ParseSize(*run_size, &rs->width, &rs->height);
      rs->sampler = ParseSamplerArithmetic(*run_sampler);
      if (!run_scenes->empty()) rs->scenes = SplitList(*run_scenes);
      if (!run_methods->empty()) rs->methods = SplitList(*run_methods);
      if (!run_shard->empty()) rs->shard = ParseShard(*run_shard);
      if (!run_gpu->empty()) {
        if (rs->shard.Active() || rs->references_only) {
          throw UserError(
              "--gpu-timings needs a whole run (not --shard or --references-only); attach the timings to "
              "the merged report with aalab merge-gpu");
        }
        for (const auto& file : *run_gpu) CheckGpuTimingsFile(file);  // before any work
      }
      if (rs->references_only) {
        int cached = 0;
        const int rendered = RenderReferencesOnly(*rs, &cached);
        std::printf("references: %d rendered, %d already cached, in %s\n", rendered, cached,
                    fs::absolute(rs->ref_cache).string().c_str());
        return ToInt(ExitCode::kOk);
      }
      const Report report = RunSuite(*rs);
      if (report.shard) {
        std::printf("%s", FormatTimeBreakdown(report.time_breakdown).c_str());
        std::printf(
            "shard %d/%d: %zu of %d scenes, %zu results\npartial report: %s (merge the shards with aalab merge)\n",
            report.shard->index, report.shard->count, report.scenes.size(), report.shard->total_units,
            report.rows.size(), (fs::absolute(rs->out_dir) / "report.json").string().c_str());
        return ToInt(ExitCode::kOk);
      }
      std::printf("%s", FormatTimeBreakdown(report.time_breakdown).c_str());
      std::printf("%s", FormatVerdicts(Verdicts(report)).c_str());
      if (!run_gpu->empty()) std::printf("%s\n", AttachGpuTimings(rs->out_dir, *run_gpu).c_str());
      std::printf("wrote %zu results for %zu scenes\nhtml:   %s\nreport: %s\n", report.rows.size(),
                  report.scenes.size(), (fs::absolute(rs->out_dir) / "index.html").string().c_str(),
                  (fs::absolute(rs->out_dir) / "report.json").string().c_str());
      return ToInt(ExitCode::kOk);
    };
  });

  // apply
  auto* apply = app.add_subcommand("apply", "run a post-filter method on your own image");
  struct ApplyArgs {
    std::string method, debug, in, out, sampler = "gl";
    int threads = 0;
  };
  auto aa = std::make_shared<ApplyArgs>();
  apply->add_option("--method", aa->method, "method spec, e.g. fxaa311-p39:subpix=0.5")->required();
  apply->add_option("--debug", aa->debug, "debug view instead of the filtered image (see aalab list methods)");
  apply->add_option("--threads", aa->threads, "worker threads (0 = all)");
  apply
      ->add_option("--sampler", aa->sampler,
                   "texel and bilinear arithmetic: gl (llvmpipe's) or gpu-texture (the H100 texture unit's)")
      ->capture_default_str();
  apply->add_option("input", aa->in, "input image (PNG, JPEG, TIFF, EXR)")->required();
  apply->add_option("output", aa->out, "output image (.png, .jpg, .tif)")->required();
  apply->callback([&commands, aa] {
    commands.action = [aa] {
      SetThreadCount(aa->threads);
      const SamplerArithmetic sampler = ParseSamplerArithmetic(aa->sampler);
      const MethodPlan plan = MakeMethod(aa->method);
      if (!plan.IsPostOnly()) {
        throw UserError("method '" + plan.spec + "' is not a post filter on a finished frame (it renders " +
                        (plan.render.scale != 1.0 ? "at another scale" : "several samples per pixel") +
                        " and needs a scene); use it with 'aalab run'");
      }
      if (!aa->debug.empty()) {
        bool ok = false;
        for (const auto& v : plan.debug_views) ok = ok || v == aa->debug;
        if (!ok) {
          throw UserError("method '" + plan.name + "' has no debug view '" + aa->debug + "' (available: " +
                          (plan.debug_views.empty() ? std::string("none") : JoinNames(plan.debug_views)) + ")");
        }
      }
      const std::string ext = fs::path(aa->out).extension().string();
      if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".tif" && ext != ".tiff") {
        throw UserError("output '" + aa->out +
                        "' must end in .png, .jpg, .jpeg, .tif or .tiff (an 8-bit display image)");
      }
      CheckOutFile(aa->out, {aa->in});  // never onto its own input, never a folder
      const LoadedImage img = ReadImage(aa->in);
      Image8 frame(img.pixels.Width(), img.pixels.Height(), 4, 255);
      for (int y = 0; y < frame.Height(); ++y) {
        for (int x = 0; x < frame.Width(); ++x) {
          for (int c = 0; c < 3; ++c) {
            const float v = img.pixels.At(x, y, c);
            // Float (scene-linear) input: display transform (exposure 1, tonemap none = clamp)
            // then sRGB encode; 8-bit input is already display-encoded.
            frame.At(x, y, c) = QuantizeUnorm8(img.is_float ? SrgbEncode(v) : v);
          }
        }
      }
      if (img.is_float) {
        std::fprintf(stderr,
                     "aalab: '%s' holds float data: treated as scene-linear and passed through the display "
                     "transform (exposure 1, tonemap none = clamp to [0,1], sRGB encode, 8-bit) before filtering\n",
                     aa->in.c_str());
      }
      PostOptions opt;
      opt.debug_view = aa->debug;
      opt.sampler = sampler;
      PostStats stats;
      const Image8 result = plan.post(frame, opt, &stats);
      WriteImage8(aa->out, result);
      std::printf("wrote %s (%dx%d, %s%s, %.2f taps/px)\n", aa->out.c_str(), result.Width(), result.Height(),
                  plan.spec.c_str(), aa->debug.empty() ? "" : (", debug " + aa->debug).c_str(),
                  static_cast<double>(stats.taps) / static_cast<double>(result.PixelCount()));
      return ToInt(ExitCode::kOk);
    };
  });
  RegisterMetricsCommand(app, commands);
  RegisterCompareCommands(app, commands);
  RegisterSweepCommands(app, commands);
  RegisterGpuCommands(app, commands);
  RegisterClusterCommands(app, commands);
  RegisterExportCommand(app, commands);
  RegisterSceneCommand(app, commands);
}

}  // namespace aalab
