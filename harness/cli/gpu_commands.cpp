// `aalab export-frames`, `aalab export-geometry` and `aalab merge-gpu`: the CPU side of the GPU
// timings (docs/gpu.md). export-frames renders the frames the post filters see, for the
// stand-alone GPU tool (gpu/aalab_gpu), which needs no Embree; export-geometry writes the
// triangle scenes for the raster tool (gpu/raster/aalab_raster); merge-gpu (and run
// --gpu-timings) attaches one or more of the GPU tools' JSON files (aalab_gpu's and aalab_vk's
// schema aalab-gpu-timings, aalab_raster's aalab-raster-timings) to a report.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "harness/cli/commands.h"
#include "core/error.h"
#include "core/input_files.h"
#include "core/exit_code.h"
#include "core/params.h"
#include "core/parallel.h"
#include "io/image_io.h"
#include "io/ppm.h"
#include "harness/run/out_folder.h"
#include "harness/run/pipeline.h"
#include "harness/run/runner.h"
#include "methods/registry.h"
#include "reports/gpu_timings.h"
#include "reports/raster_timings.h"
#include "reports/html_report.h"
#include "reports/report_json.h"
#include "scenes/library.h"
#include "scenes/motion.h"
#include "scenes/motion_render.h"
#include "scenes/raster_export.h"
#include "scenes/render.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

struct ExportArgs {
  std::string suite = "default", scenes, sizes = "1920x1080,3840x2160", out;
  uint64_t seed = 1;
  int threads = 0;
  bool no_scaled = false;
  int taa_frames = 0;
  std::string render_methods;  ///< render-time methods whose frames to write too (for aalab_raster --compare)
};

// TAA's inputs for frames 0..n-1 of `scene` at w × h, as `aalab run --frames n --methods taa`
// renders them (pipeline.cpp RunMethod): frame t is the jittered one-sample render of the
// scene at t (FrameJitterAt of taa's default jitter spec) and, from t = 1, the previous
// positions of its pixel centres (PreviousPositions). Written as BASE-taa-f<t>.ppm and
// BASE-taa-f<t>.prev, listed as role taa-<t>.
void ExportTaaSequence(const Scene& scene, const Tracer& still_tracer, int w, int h, int n, const std::string& base,
                       const fs::path& dir, std::ostringstream& tsv) {
  const JitterSpec jitter_spec = MakeMethod("taa").render.jitter;
  for (int t = 0; t < n; ++t) {
    std::unique_ptr<Scene> frame_scene;
    std::unique_ptr<Tracer> frame_tracer;
    if (scene.animation.Moves()) {
      frame_scene = std::make_unique<Scene>(SceneAtFrame(scene, t));
      frame_tracer = std::make_unique<Tracer>(*frame_scene);
    }
    const Tracer& tracer = frame_tracer ? *frame_tracer : still_tracer;
    const FrameJitter jitter = FrameJitterAt(jitter_spec, t);
    const SurfaceFrame sf = RenderSurfaceFrame(tracer, w, h, jitter, nullptr);
    const std::string stem = base + "-taa-f" + std::to_string(t);
    WritePpm((dir / (stem + ".ppm")).string(), sf.image);
    if (t > 0) {
      const std::vector<glm::vec2> prev = PreviousPositions(scene, t, sf, jitter);
      std::vector<float> flat(2 * prev.size());
      for (size_t i = 0; i < prev.size(); ++i) {
        flat[2 * i] = prev[i].x;
        flat[2 * i + 1] = prev[i].y;
      }
      WritePreviousPositions((dir / (stem + ".prev")).string(), w, h, flat);
    }
    tsv << scene.name << "\ttaa-" << t << "\t" << w << "\t" << h << "\t" << stem << ".ppm\n";
  }
}

// Writes DIR/<scene>-<W>x<H>.ppm (the 1x frame every post-only method filters, rendered as
// `aalab run` renders it: one sample at each pixel centre, same seed) and, unless
// --no-scaled, DIR/<scene>-<W>x<H>-scaled.ppm (the frame scale43 renders before its
// rescale), listed in DIR/frames.tsv. Everything goes to DIR.partial first.
int ExportFrames(const ExportArgs& a) {
  SetThreadCount(a.threads);
  std::vector<std::pair<int, int>> sizes;
  for (const auto& s : SplitCommaList(a.sizes, "--sizes")) {
    int w = 0, h = 0;
    ParseSize(s, &w, &h);
    sizes.emplace_back(w, h);
  }
  if (sizes.empty()) throw UserError("--sizes is empty (give e.g. 1920x1080,3840x2160)");
  const std::vector<std::string> names = a.scenes.empty() ? SuiteScenes(a.suite) : SplitCommaList(a.scenes, "--scenes");
  // Render-time methods (MSAA, SSAA) whose frames aalab_raster --compare checks against.
  std::vector<std::pair<std::string, RenderSpec>> render_methods;
  if (!a.render_methods.empty()) {
    for (const auto& spec : SplitCommaList(a.render_methods, "--render-methods")) {
      const MethodPlan plan = MakeMethod(spec);
      // Also the render-size frame of the FSR 1 rows (scale < 1): what aalab_vk's EASU reads.
      const bool reduced = plan.rescale == Rescale::kEasu && plan.render.scale < 1.0;
      if (!plan.render.msaa.On() && plan.render.pattern != SamplePattern::kOrderedGrid && !reduced) {
        throw UserError("--render-methods '" + spec +
                        "' is not an MSAA or ordered-grid SSAA method nor an EASU upscale (allowed: msaa-2x, "
                        "msaa-4x, msaa-8x, msaa-16x, ssaa-2x2, ssaa-4x4: what aalab_raster draws; scale43-easu, "
                        "scale43-easu-rcas: the render-size frame aalab_vk upscales)");
      }
      render_methods.emplace_back(spec, plan.render);
    }
  }
  std::vector<std::unique_ptr<Scene>> scenes = LoadScenes(names);
  if (a.taa_frames < 0 || a.taa_frames > 256) {
    throw UserError("--taa-frames " + std::to_string(a.taa_frames) + " is out of range (allowed: 0..256)");
  }
  for (const auto& scene : scenes) {
    if (scene->animation.Moves() && a.taa_frames > scene->animation.frames) {
      throw UserError("--taa-frames " + std::to_string(a.taa_frames) + " runs past scene '" + scene->name +
                      "' (it declares /animation/frames = " + std::to_string(scene->animation.frames) + ")");
    }
  }
  // The output folder rule (harness/run/out_folder.h): only an earlier frames folder is replaced.
  std::vector<std::string> inputs = names;  // with every file the scenes were built from (input_files.h)
  for (const auto& file : InputFilesRead()) inputs.push_back(file);
  OutFolder out(a.out, "frames", inputs);
  const fs::path tmp = out.Begin();
  // The render request of scale43 at its defaults: the scaled frame is what it renders.
  const RenderSpec scaled = MakeMethod("scale43").render;
  std::ostringstream tsv;
  tsv << "# aalab export-frames: scene, role (1x | scaled | taa-<frame>), output width, output height, file "
         "(binary PPM; taa-<t> with t >= 1 also has its previous positions in the same name with .prev)\n";
  for (const auto& scene : scenes) {
    const Tracer tracer(*scene);
    for (const auto& [w, h] : sizes) {
      const std::string base = scene->name + "-" + std::to_string(w) + "x" + std::to_string(h);
      WritePpm((tmp / (base + ".ppm")).string(), RenderFrame(tracer, w, h, RenderSpec{}, a.seed, nullptr));
      tsv << scene->name << "\t1x\t" << w << "\t" << h << "\t" << base << ".ppm\n";
      if (!a.no_scaled) {
        const int rw = std::max(1, static_cast<int>(std::lround(scaled.scale * w)));
        const int rh = std::max(1, static_cast<int>(std::lround(scaled.scale * h)));
        WritePpm((tmp / (base + "-scaled.ppm")).string(), RenderFrame(tracer, rw, rh, scaled, a.seed, nullptr));
        tsv << scene->name << "\tscaled\t" << w << "\t" << h << "\t" << base << "-scaled.ppm\n";
      }
      if (a.taa_frames > 0) ExportTaaSequence(*scene, tracer, w, h, a.taa_frames, base, tmp, tsv);
      for (const auto& [spec, render] : render_methods) {
        // At the method's render size, as the run renders it (harness/run/pipeline.cpp).
        const int rw = std::max(1, static_cast<int>(std::lround(render.scale * w)));
        const int rh = std::max(1, static_cast<int>(std::lround(render.scale * h)));
        WritePpm((tmp / (base + "-" + spec + ".ppm")).string(), RenderFrame(tracer, rw, rh, render, a.seed, nullptr));
        tsv << scene->name << "\t" << spec << "\t" << w << "\t" << h << "\t" << base << "-" << spec << ".ppm\n";
      }
      std::fprintf(stderr, "exported %s\n", base.c_str());
    }
  }
  WriteTextFile((tmp / "frames.tsv").string(), tsv.str());
  out.Commit();
  std::printf("wrote %zu scene(s) x %zu size(s) to %s (frames.tsv)\n", scenes.size(), sizes.size(), a.out.c_str());
  return ToInt(ExitCode::kOk);
}

struct GeometryArgs {
  std::string suite = "default", scenes, out;
  bool skip_unsupported = false;
};

// Writes DIR/<scene>.geom (core/raster_geometry.h) for each scene, listed in DIR/geometry.tsv,
// for the raster tool (gpu/raster/aalab_raster). A scene the raster path cannot draw is an
// error naming it and why, unless --skip-unsupported (then it is listed on stderr and in
// the TSV's comment lines). Everything goes to DIR.partial first.
int ExportGeometry(const GeometryArgs& a) {
  const std::vector<std::string> names = a.scenes.empty() ? SuiteScenes(a.suite) : SplitCommaList(a.scenes, "--scenes");
  std::vector<std::unique_ptr<Scene>> scenes = LoadScenes(names);
  std::vector<const Scene*> drawn;
  std::string skipped;
  for (const auto& scene : scenes) {
    const std::string why = RasterUnsupported(*scene);
    if (why.empty()) {
      drawn.push_back(scene.get());
    } else if (a.skip_unsupported) {
      skipped += "# skipped " + scene->name + ": " + why + "\n";
      std::fprintf(stderr, "skipped %s: %s\n", scene->name.c_str(), why.c_str());
    } else {
      RasterSceneOf(*scene);  // throws the one message naming the scene and the reason
    }
  }
  if (drawn.empty()) {
    throw UserError(
        "the raster path can draw none of the scenes given (it draws still triangle scenes with unlit or "
        "lambert solid colours or procedural textures, disks, lights and shadows, and glTF metallic-roughness "
        "materials; of the synthetic suite: wedges, mesh, checker-plane, detail-texture, circle, hdr-edges, "
        "sdf-circles, shadow-stipple; the whole default suite)");
  }
  std::vector<std::string> inputs = names;
  for (const auto& file : InputFilesRead()) inputs.push_back(file);
  OutFolder out(a.out, "geometry", inputs);
  const fs::path tmp = out.Begin();
  std::ostringstream tsv;
  tsv << "# aalab export-geometry: scene, triangles, file (core/raster_geometry.h; docs/gpu.md)\n" << skipped;
  for (const Scene* scene : drawn) {
    const RasterScene r = RasterSceneOf(*scene);
    WriteTextFile((tmp / (scene->name + ".geom")).string(), RasterSceneBytes(r));
    tsv << scene->name << "\t" << r.triangles.size() << "\t" << scene->name << ".geom\n";
  }
  WriteTextFile((tmp / "geometry.tsv").string(), tsv.str());
  out.Commit();
  std::printf("wrote %zu scene(s) to %s (geometry.tsv)\n", drawn.size(), a.out.c_str());
  return ToInt(ExitCode::kOk);
}

int MergeGpu(const std::string& dir, const std::vector<std::string>& gpu_jsons) {
  std::printf("%s\n", AttachGpuTimings(dir, gpu_jsons).c_str());
  return ToInt(ExitCode::kOk);
}

}  // namespace

void CheckGpuTimingsFile(const std::string& path) {
  RequireRegularFile(path, "GPU timings", "a JSON file written by aalab_gpu --json or aalab_raster --json is expected");
  if (IsRasterTimingsFile(path)) {
    ReadRasterTimingsFile(path);
  } else {
    ReadGpuTimingsFile(path);
  }
}

std::string AttachGpuTimings(const std::string& dir, const std::vector<std::string>& gpu_jsons) {
  const fs::path report_path = fs::path(dir) / "report.json";
  Report report = ReadReportFile(report_path.string());
  for (const auto& gpu_json : gpu_jsons) CheckGpuTimingsFile(gpu_json);
  // Every file is merged into the report in memory, in the order given (a later CUDA file of
  // the same setup adds its sizes to a row's block, one of another setup or a later raster
  // file replaces it); the report is written once, after all
  // of them matched, so a file that matches nothing leaves the report as it was.
  std::string lines;
  for (const auto& gpu_json : gpu_jsons) {
    std::string what;
    int matched = 0;
    std::vector<std::string> scenes;
    if (IsRasterTimingsFile(gpu_json)) {
      const RasterTimingsFile raster = ReadRasterTimingsFile(gpu_json);
      matched = MergeRasterTimings(report, raster);
      for (const auto& r : raster.results) {
        if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
      }
      what = "GPU raster timings (" + raster.device + ", " + raster.gl_version + ")";
    } else {
      const GpuTimingsFile gpu = ReadGpuTimingsFile(gpu_json);
      matched = MergeGpuTimings(report, gpu);
      scenes = gpu.Scenes();
      what = "GPU timings (" + gpu.device + ", driver " + gpu.driver + ")";
    }
    if (matched == 0) {
      throw UserError("'" + gpu_json +
                      "' has timings for none of the report's rows (rows are matched by scene and "
                      "method spec; the GPU file covers scenes " +
                      JoinNames(scenes) + "); the report was left unchanged");
    }
    lines += (lines.empty() ? "" : "\n") +
             ("merged " + what + " from " + gpu_json + " into " + std::to_string(matched) + " of " +
              std::to_string(report.rows.size()) + " rows of " + report_path.string());
  }
  WriteTextFile(report_path.string(), ReportToJson(report).dump(2) + "\n");
  WriteTextFile((fs::path(dir) / "index.html").string(), RenderHtmlReport(report));
  return lines;
}

void RegisterGpuCommands(CLI::App& app, Commands& commands) {
  auto* ex = app.add_subcommand(
      "export-frames", "render the 1x (and render-scale) frames of scenes as PPM for the GPU tool (docs/gpu.md)");
  auto ea = std::make_shared<ExportArgs>();
  ex->add_option("--suite", ea->suite, "suite name (see aalab list scenes)")->capture_default_str();
  ex->add_option("--scenes", ea->scenes, "comma-separated scene names or files (overrides --suite)");
  ex->add_option("--sizes", ea->sizes, "comma-separated output sizes WxH")->capture_default_str();
  ex->add_option("--seed", ea->seed, "jitter seed (as aalab run)")->capture_default_str();
  ex->add_option("--threads", ea->threads, "worker threads (0 = all)")->capture_default_str();
  ex->add_flag("--no-scaled", ea->no_scaled, "skip the frames rendered at scale43's render scale");
  ex->add_option("--taa-frames", ea->taa_frames,
                 "also export taa's inputs for frames 0..N-1 (jittered renders + previous positions; 0 = none)")
      ->capture_default_str();
  ex->add_option("--render-methods", ea->render_methods,
                 "also write these MSAA / SSAA methods' frames (<base>-<spec>.ppm), for aalab_raster --compare, "
                 "or scale43-easu's render-size frame, for aalab_vk")
      ->capture_default_str();
  ex->add_option("--out", ea->out, "output folder (frames.tsv + PPM files)")->required();
  ex->callback([&commands, ea] { commands.action = [ea] { return ExportFrames(*ea); }; });

  auto* eg = app.add_subcommand(
      "export-geometry", "write the triangle scenes' geometry, camera and shading for the raster tool (docs/gpu.md)");
  auto ga = std::make_shared<GeometryArgs>();
  eg->add_option("--suite", ga->suite, "suite name (see aalab list scenes)")->capture_default_str();
  eg->add_option("--scenes", ga->scenes, "comma-separated scene names or files (overrides --suite)");
  eg->add_flag("--skip-unsupported", ga->skip_unsupported,
               "skip (and list) the scenes the raster path cannot draw instead of refusing them");
  eg->add_option("--out", ga->out, "output folder (geometry.tsv + one .geom file per scene)")->required();
  eg->callback([&commands, ga] { commands.action = [ga] { return ExportGeometry(*ga); }; });

  auto* mg =
      app.add_subcommand("merge-gpu",
                         "attach GPU timings (aalab_gpu's, aalab_raster's or aalab_vk's JSON) to a report's rows and "
                         "redraw its page");
  auto dir = std::make_shared<std::string>();
  auto files = std::make_shared<std::vector<std::string>>();
  mg->add_option("report_dir", *dir, "report folder (holds report.json)")->required();
  mg->add_option("gpu_json", *files,
                 "one or more JSON files written by aalab_gpu --json, aalab_raster --json or aalab_vk --json, "
                 "merged in the order given")
      ->required();
  mg->callback([&commands, dir, files] { commands.action = [dir, files] { return MergeGpu(*dir, *files); }; });
}

}  // namespace aalab
