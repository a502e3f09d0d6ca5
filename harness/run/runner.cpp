#include "harness/run/runner.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>

#include "core/color.h"
#include "core/error.h"
#include "core/input_files.h"
#include "core/parallel.h"
#include "core/params.h"
#include "core/timer.h"
#include "io/image_io.h"
#include "metrics/metric.h"
#include "metrics/viewing.h"
#include "methods/registry.h"
#include "reports/html_report.h"
#include "reports/report_json.h"
#include "harness/run/image_scene.h"
#include "harness/run/out_folder.h"
#include "harness/run/pipeline.h"
#include "harness/run/reference_cache.h"
#include "harness/run/score_rows.h"
#include "harness/run/sequence.h"
#include "harness/run/stage_clock.h"
#include "scenes/library.h"
#include "scenes/motion.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace aalab {
namespace fs = std::filesystem;

std::vector<std::string> DefaultMethods() {
  // The registry rows marked in_default_list (by their family files), in registry order: what
  // the first run of `make run` compares. `--methods all` runs every registered method.
  std::vector<std::string> names;
  for (const auto& e : MethodRegistry()) {
    if (e.in_default_list) names.push_back(e.name);
  }
  return names;
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

/// A run's scenes, loaded and checked against its settings before any work: the reference
/// samples, the frame count, the reference kind and each sequence's length.
struct RunScenes {
  std::vector<std::string> names;  ///< as given (a suite's, or --scenes)
  std::vector<SceneSource> sources;
  int grid = 0;
  bool exact = false;
};

RunScenes LoadRunScenes(const RunSettings& s) {
  RunScenes r;
  r.grid = ReferenceGridForSpp(s.ref_spp);
  r.names = s.scenes.empty() ? SuiteScenes(s.suite) : s.scenes;
  if (s.frames < 1 || s.frames > kMaxFrames) {
    throw UserError("--frames " + std::to_string(s.frames) + " is out of range (1.." + std::to_string(kMaxFrames) + ")");
  }
  r.sources = LoadSceneSources(r.names);
  r.exact = CheckReferenceKind(s.reference, r.sources);
  for (const auto& src : r.sources) {
    if (src.scene) CheckSequenceLength(*src.scene, s.frames);
    if (src.view && src.view->frames > 1 && s.frames > src.view->frames) {
      throw UserError("--frames " + std::to_string(s.frames) + " runs past the sequence of view '" + src.Name() +
                      "' of image scene '" + src.view->manifest + "', which has " +
                      std::to_string(src.view->frames) + " frames (allowed: 1.." + std::to_string(src.view->frames) +
                      "; without --frames a sequence view runs all its frames)");
    }
  }
  return r;
}

}  // namespace

Report RunSuite(const RunSettings& s) {
  StageClock clock({"load_scenes", "references", "method_renders_filters", "metrics", "image_writing", "html"});
  clock.Enter("load_scenes");
  SetThreadCount(s.threads);
  // Validate every input before any work.
  if (s.repeat < 1 || s.repeat > 1000) throw UserError("--repeat " + std::to_string(s.repeat) + " is out of range (1..1000)");
  RunScenes loaded = LoadRunScenes(s);
  if (s.frame_exr && s.frames < 2) throw UserError("--frame-exr writes each frame's reference of a motion run: it needs --frames N > 1");
  const ViewingCondition viewing = ResolveViewing(s.viewing);
  const int grid = loaded.grid;
  const bool exact = loaded.exact;
  const std::vector<std::string>& scene_names = loaded.names;
  std::vector<SceneSource> scenes = std::move(loaded.sources);
  // A shard keeps its share of the scenes (whole sequences: a method's memory and the
  // temporal metrics chain a sequence's frames); the settings still describe the whole run.
  std::optional<ShardInfo> shard_info;
  if (s.shard.Active()) {
    ShardInfo info{s.shard.index, s.shard.count, "scene", static_cast<int>(scenes.size()), {}};
    std::vector<SceneSource> mine;
    for (size_t i : ShardShare(scenes.size(), s.shard)) {
      info.units.push_back(scenes[i].Name());
      mine.push_back(std::move(scenes[i]));
    }
    scenes = std::move(mine);
    shard_info = info;
  }
  // A sequence view runs its own frames (all of them, or the first --frames); everything
  // else runs --frames.
  auto frames_of = [&s](const SceneSource& src) { return src.Frames() > 1 && s.frames == 1 ? src.Frames() : s.frames; };
  bool any_sequence = false;
  for (const auto& src : scenes) any_sequence = any_sequence || frames_of(src) > 1;
  const bool all = s.methods.size() == 1 && s.methods[0] == "all";
  std::vector<std::string> method_specs = s.methods.empty() ? DefaultMethods() : all ? MethodNames() : s.methods;
  std::vector<MethodPlan> plans = ResolveMethods(method_specs);
  if ((s.methods.empty() || all) && !any_sequence) {
    // Methods with memory need a sequence: a still run's default list leaves them out (a
    // still run is unchanged by their existence); name them with --methods to see frame 0.
    for (size_t i = plans.size(); i-- > 0;) {
      if (!plans[i].NeedsHistory()) continue;
      plans.erase(plans.begin() + static_cast<std::ptrdiff_t>(i));
      method_specs.erase(method_specs.begin() + static_cast<std::ptrdiff_t>(i));
    }
  }
  // The user's own AA outputs (image scenes' `outputs`): rows after aalab's methods.
  const std::vector<std::string> supplied = SuppliedOutputNames(scenes);
  for (const auto& name : supplied) {
    for (const auto& p : plans) {
      if (p.spec == name) throw UserError("output '" + name + "' of an image scene has the name of a method of this run");
    }
  }
  int total_steps = 0;
  for (const auto& src : scenes) total_steps += static_cast<int>(plans.size() + supplied.size() + 1) * frames_of(src);
  // A run that fails half-way (an exception from any stage) removes its partial output.
  std::vector<std::string> inputs = {s.ref_cache};
  for (const auto& name : s.scenes) {
    if (fs::exists(name)) inputs.push_back(name);  // a scene file or manifest (not a library name)
  }
  // Every file the scenes were built from: meshes, glTF buffers and textures, image-scene
  // frames and captures (core/input_files.h).
  for (const auto& file : InputFilesRead()) inputs.push_back(file);
  OutFolder out(s.out_dir, "run", inputs);
  std::optional<ReferenceCache> cache;  // created once every input has been checked
  if (!s.ref_cache.empty()) cache.emplace(s.ref_cache);
  const fs::path tmp = out.Begin();
  fs::create_directories(tmp / "images");

  Report report;
  for (const auto& [k, v] : ContextFacts()) report.context[k] = v;
  // What applied: --size, --ref-spp and --seed apply to rendered scenes only; an image-scene
  // view has its images' size and the user's reference.
  bool any_rendered = false;
  std::vector<std::string> view_sizes;
  for (const auto& src : scenes) {
    if (src.scene) any_rendered = true;
    if (!src.view) continue;
    const std::string sz = std::to_string(src.view->width) + "x" + std::to_string(src.view->height);
    if (std::find(view_sizes.begin(), view_sizes.end(), sz) == view_sizes.end()) view_sizes.push_back(sz);
  }
  std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
  std::string ref_spp = exact ? std::string("exact") : std::to_string(s.ref_spp);
  std::string seed = std::to_string(s.seed);
  if (!view_sizes.empty()) {
    const std::string views = JoinNames(view_sizes);
    size = any_rendered ? size + " (rendered scenes; image-scene views: " + views + ")" : views + " (the views' own size)";
    ref_spp = any_rendered ? ref_spp + " (rendered scenes; image-scene views: the user's own)" : "the user's own";
    if (!any_rendered) seed = "(not used: image scenes only)";
  }
  report.settings = {{"suite", s.scenes.empty() ? s.suite : "(custom)"},
                     {"scenes", JoinNames(scene_names)},
                     {"methods", JoinNames(method_specs)},
                     {"size", size},
                     {"ref_spp", ref_spp},
                     {"seed", seed},
                     {"threads", std::to_string(ThreadCount())},
                     {"repeat", std::to_string(s.repeat)},
                     {"warmup", "1"},
                     {"debug_views", s.debug_views ? "true" : "false"}};
  if (s.frames > 1) report.settings.emplace_back("frames", std::to_string(s.frames));
  if (s.frame_exr) report.settings.emplace_back("frame_exr", "true");
  if (s.sampler != SamplerArithmetic::kGl) report.settings.emplace_back("sampler", SamplerArithmeticName(s.sampler));
  for (auto& kv : viewing.Settings()) report.settings.push_back(std::move(kv));
  if (!supplied.empty()) report.settings.emplace_back("supplied", JoinNames(supplied));
  report.shard = shard_info;

  const int W = s.width, H = s.height;
  const size_t rows_per_frame = plans.size() + supplied.size();
  Progress progress(total_steps, s.quiet);
  for (auto& source : scenes) {
    const std::string name = source.Name();
    const int F = frames_of(source);
    const std::string rel_dir = "images/" + name;
    fs::create_directories(tmp / rel_dir);
    // A sequence per (scene, method): methods with memory keep their state from frame to
    // frame; a still run is a sequence of one frame. Image-scene views are still scenes.
    const std::shared_ptr<const Scene> sequence(std::move(source.scene));
    // A captured sequence (a view with N frames) is read anew at every frame, as a moving
    // scene is rendered anew.
    const bool captured = source.view && source.view->frames > 1;
    const bool moves = (sequence && sequence->animation.Moves()) || captured;
    std::vector<std::unique_ptr<TemporalState>> states(plans.size());
    std::vector<SequenceTrack> tracks;
    for (size_t m = 0; m < rows_per_frame; ++m) tracks.emplace_back(viewing.ppd, viewing.fps, F);
    std::unique_ptr<PreparedScene> prepared;
    SceneResult sr;
    std::vector<std::string> reference_frames, reference_frames_exr;
    double scene_ms = 0, reference_ms = 0;
    std::vector<std::string> scene_warnings;
    int more_warnings = 0;
    // The last frame's image files are independent: queued and written in parallel at the
    // scene's end; a bit-identical output is stored once.
    std::vector<std::function<void()>> writes;
    std::map<std::string, std::string> file_of_hash;
    for (int k = 0; k < F; ++k) {
      const bool last = k == F - 1;
      const std::string tag = F > 1 ? ".f" + std::to_string(k) : "";
      // A moving scene is built, traced and referenced anew at every frame; a still one once.
      if (!prepared || moves) {
        Stopwatch build;
        if (captured) {
          prepared = PrepareSource(source, W, H, grid, s.seed, s.repeat, exact, &clock, nullptr, k, viewing.ppd);
        } else if (moves) {
          clock.Enter("references");
          auto frame_scene = std::make_unique<Scene>(SceneAtFrame(*sequence, k));
          const double scene_build_ms = build.ElapsedMs();
          prepared = PrepareScene(std::move(frame_scene), W, H, grid, s.seed, s.repeat, exact, &clock,
                                  cache ? &*cache : nullptr, viewing.ppd);
          scene_ms += scene_build_ms;
        } else {
          if (sequence) source.scene = std::make_unique<Scene>(*sequence);
          prepared = PrepareSource(source, W, H, grid, s.seed, s.repeat, exact, &clock,
                                   cache ? &*cache : nullptr, 0, viewing.ppd);
        }
        prepared->sequence_scene = sequence;
        // A capture's mismatch warnings (image scenes): said now, kept for the report (the
        // first frames that have any, then a count).
        for (const auto& w : prepared->info.warnings) {
          std::fprintf(stderr, "aalab: warning: scene '%s': %s\n", name.c_str(), w.c_str());
          if (scene_warnings.size() < 3) scene_warnings.push_back(w); else ++more_warnings;
        }
        scene_ms += prepared->info.bvh_build_ms;
        reference_ms += prepared->info.reference_ms;
      }
      prepared->frame = k;
      const Reference& ref = prepared->ref;
      clock.Enter("image_writing");
      if (F > 1) {
        const std::string rel = rel_dir + "/reference" + tag + ".png";
        WriteImage8((tmp / rel).string(), ToUnorm8(ref.image));
        reference_frames.push_back(rel);
        if (s.frame_exr) {
          const std::string exr = rel_dir + "/reference" + tag + ".exr";
          WriteImageF((tmp / exr).string(), DecodeToLinear(ref.image));
          reference_frames_exr.push_back(exr);
        }
      }
      if (last) {  // `prepared` (and so `ref`) lives until the scene's writes are done
        sr = prepared->info;
        sr.warnings = scene_warnings;
        if (more_warnings) sr.warnings.push_back(std::to_string(more_warnings) + " more frame(s) with such warnings");
        writes.push_back([&tmp, &rel_dir, &ref] {
          WriteImageF((tmp / rel_dir / "reference.exr").string(), DecodeToLinear(ref.image));
        });
        writes.push_back([&tmp, &rel_dir, &ref] { WriteImage8((tmp / rel_dir / "reference.png").string(), ToUnorm8(ref.image)); });
        writes.push_back([&tmp, &rel_dir, &ref] { WriteImage8((tmp / rel_dir / "edge_mask.png").string(), ToUnorm8(ref.edge_mask)); });
        sr.images = {{"reference_exr", rel_dir + "/reference.exr"},
                     {"reference_png", rel_dir + "/reference.png"},
                     {"edge_mask", rel_dir + "/edge_mask.png"}};
      }
      progress.Step(name + tag + " reference");

      const int fw = prepared->info.width, fh = prepared->info.height;  // a view's own size
      // aalab's methods, rendered and timed one after another, then scored concurrently
      // (harness/run/score_rows.h).
      const auto method_rows = RunAndScoreRows(*prepared, plans, s.seed, s.repeat, &states, &clock, s.sampler,
                                               last && s.debug_views);
      for (size_t m = 0; m < rows_per_frame; ++m) {
        // aalab's methods, then the user's supplied outputs (scored, not run).
        const MethodPlan* plan = m < plans.size() ? &plans[m] : nullptr;
        const std::string spec = plan ? plan->spec : supplied[m - plans.size()];
        auto mo = plan ? method_rows[m]
                       : std::make_shared<MethodOutput>(SuppliedOutputRow(*prepared, spec, s.repeat, &clock));
        ResultRow& row = mo->row;
        if (!row.not_applicable.empty()) {  // a renderer-side method on an image scene: no images
          if (last) report.rows.push_back(std::move(row));
          progress.Step(name + tag + " " + spec + " (not applicable)");
          continue;
        }
        clock.Enter("image_writing");
        if (F > 1) {
          const std::string rel = rel_dir + "/" + FileSafe(spec) + tag + ".png";
          WriteImage8((tmp / rel).string(), mo->output);
          tracks[m].AddFrame(*mo, *prepared, rel);
        }
        progress.Step(name + tag + " " + spec);
        if (!last) continue;
        if (s.debug_views && plan && plan->post) {
          for (const auto& view : plan->debug_views) {
            PostOptions opt;
            opt.debug_view = view;
            opt.sampler = s.sampler;
            const std::string rel = rel_dir + "/" + FileSafe(spec) + ".debug-" + view + ".png";
            WriteImage8((tmp / rel).string(), plan->post(mo->input, opt, nullptr));
            row.images["debug_" + view] = rel;
          }
        }
        mo->input = Image8();  // only the output and FLIP map wait for the scene's writes
        const auto [it, fresh] = file_of_hash.emplace(row.output_hash, rel_dir + "/" + FileSafe(spec));
        const std::string base = it->second;
        if (fresh) {
          writes.push_back([&tmp, base, mo] { WriteImage8((tmp / (base + ".png")).string(), mo->output); });
          writes.push_back([&tmp, base, mo, fw, fh] { WriteGrey8((tmp / (base + ".flip.png")).string(), fw, fh, mo->flip_grey); });
        }
        row.images["output"] = base + ".png";
        row.images["flip_map"] = base + ".flip.png";
        if (F > 1) tracks[m].Finish(&row);
        report.rows.push_back(row);
      }
    }
    // The per-sequence states end with their sequence; the metrics' reference sides (FLIP's
    // and SSIM's, ~50 MB at 960x540) are not needed by the scene's writes: freed before them.
    states.clear();
    if (prepared) {
      prepared->flip_reference.reset();
      prepared->ssim_reference.reset();
    }
    if (F > 1) {
      sr.frames = F;
      sr.moves = moves;
      sr.frame_images = reference_frames;
      sr.frame_exr_images = reference_frames_exr;
      sr.sequence_scene_ms = scene_ms;
      sr.sequence_reference_ms = reference_ms;
    }
    clock.Enter("image_writing");
    ParallelFor(static_cast<int>(writes.size()), [&](int i) { writes[static_cast<size_t>(i)](); });
    report.scenes.push_back(std::move(sr));
  }

  clock.Enter("html");
  // A shard's page shows its own scenes; one without scenes (N above the scene count) has
  // nothing to show, and `aalab merge` writes the page of the whole run.
  // The page shows the time breakdown too, so it is built once inside the clock (what the
  // html stage measures) and, once the breakdown is complete, built again with it and written
  // after the clock has stopped, like report.json (one more build: ~0.1% of a default run).
  if (!report.scenes.empty()) (void)RenderHtmlReport(report);
  report.time_breakdown = clock.Finish();
  if (!report.scenes.empty()) WriteTextFile((tmp / "index.html").string(), RenderHtmlReport(report));
  WriteTextFile((tmp / "report.json").string(), ReportToJson(report).dump(2) + "\n");
  out.Commit();
  return report;
}

int RenderReferencesOnly(const RunSettings& s, int* cached) {
  SetThreadCount(s.threads);
  if (s.ref_cache.empty()) throw UserError("--references-only needs --ref-cache DIR (the folder the shards share)");
  const RunScenes loaded = LoadRunScenes(s);
  ResolveViewing(s.viewing);  // checked like the run's other settings (references do not depend on it)
  const std::vector<SceneSource>& sources = loaded.sources;
  const int grid = loaded.grid;
  const bool exact = loaded.exact;
  const ReferenceCache cache(s.ref_cache);
  // The units: every reference the run renders, in run order (a moving scene: one per frame,
  // as RunSuite builds them; a still scene: one).
  struct Unit {
    const Scene* scene;
    int frame;  ///< -1: the scene as it is (a still scene)
  };
  std::vector<Unit> units;
  for (const auto& src : sources) {
    if (!src.scene) continue;
    if (src.scene->animation.Moves()) {
      for (int k = 0; k < s.frames; ++k) units.push_back({src.scene.get(), k});
    } else {
      units.push_back({src.scene.get(), -1});
    }
  }
  int rendered = 0, found = 0;
  const std::vector<size_t> share = ShardShare(units.size(), s.shard);
  Progress progress(static_cast<int>(share.size()), s.quiet);
  for (size_t i : share) {
    const Unit& u = units[i];
    const Scene scene = u.frame >= 0 ? SceneAtFrame(*u.scene, u.frame) : *u.scene;
    const Tracer tracer(scene);
    bool hit = false;
    ObtainReference(scene, tracer, s.width, s.height, grid, s.seed, exact, &cache, &hit);
    (hit ? found : rendered) += 1;
    progress.Step(scene.name + (u.frame >= 0 ? ".f" + std::to_string(u.frame) : "") + (hit ? " (cached)" : " reference"));
  }
  if (cached) *cached = found;
  return rendered;
}

}  // namespace aalab
