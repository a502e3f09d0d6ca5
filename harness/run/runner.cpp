#include "harness/run/runner.h"

#include <filesystem>
#include <functional>
#include <iterator>
#include <optional>

#include "core/error.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "io/image_io.h"
#include "methods/registry.h"
#include "reports/html_report.h"
#include "reports/report_json.h"
#include "harness/run/out_folder.h"
#include "harness/run/pipeline.h"
#include "harness/run/reference_cache.h"
#include "harness/run/run_plan.h"
#include "harness/run/scene_pass.h"
#include "harness/run/stage_clock.h"
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

/// The writing stage: index.html and report.json into `tmp`. A shard's page shows its own
/// scenes; one without scenes (N above the scene count) has nothing to show, and `aalab merge`
/// writes the page of the whole run. The page shows the time breakdown too, so it is built
/// once inside the clock (what the html stage measures) and, once the breakdown is complete,
/// built again with it and written after the clock has stopped, like report.json (one more
/// build: ~0.1% of a default run). After the clock: report.json's document is built once for
/// both files, and the page and report.json are rendered and written side by side (each a
/// pure function of the finished report: the same bytes at any thread count).
void WriteRunReport(const fs::path& tmp, StageClock* clock, Report* report) {
  clock->Enter("html");
  if (!report->scenes.empty()) (void)RenderHtmlReport(*report);
  report->time_breakdown = clock->Finish();
  const nlohmann::ordered_json doc = ReportToJson(*report);
  const std::function<void()> files[] = {[&] {
                                           if (!report->scenes.empty())
                                             WriteTextFile((tmp / "index.html").string(),
                                                           RenderHtmlReport(*report, doc));
                                         },
                                         [&] { WriteTextFile((tmp / "report.json").string(), doc.dump(2) + "\n"); }};
  ParallelFor(static_cast<int>(std::size(files)), [&](int i) { files[i](); });
}

}  // namespace

Report RunSuite(const RunSettings& s) {
  StageClock clock({"load_scenes", "references", "method_renders_filters", "metrics", "image_writing", "html"});
  clock.Enter("load_scenes");
  SetThreadCount(s.threads);
  // 1. Resolve: every input checked before any work (scenes, methods, supplied outputs).
  RunPlan plan = ResolveRun(s);
  // A run that fails half-way (an exception from any stage) removes its partial output.
  OutFolder out(s.out_dir, "run", RunInputs(s));
  std::optional<ReferenceCache> cache;  // created once every input has been checked
  if (!s.ref_cache.empty()) cache.emplace(s.ref_cache);
  const fs::path tmp = out.Begin();
  fs::create_directories(tmp / "images");
  Report report;
  for (const auto& [k, v] : ContextFacts()) report.context[k] = v;
  report.settings = RunReportSettings(s, plan);
  report.shard = plan.shard;
  // 2-4. Per scene: prepare its references, run and score every row (ScoreFrameRows) frame
  // by frame, write its images (harness/run/scene_pass.h).
  Progress progress(plan.TotalSteps(), s.quiet);
  const ScenePass pass{s, plan, tmp, &clock, cache ? &*cache : nullptr, &progress};
  for (auto& source : plan.scenes.sources) report.scenes.push_back(RunScene(pass, source, &report.rows));
  // 5. Write the page and report.json, then move the folder into place.
  WriteRunReport(tmp, &clock, &report);
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
    progress.Step(scene.name + (u.frame >= 0 ? ".f" + std::to_string(u.frame) : "") +
                  (hit ? " (cached)" : " reference"));
  }
  if (cached) *cached = found;
  return rendered;
}

}  // namespace aalab
