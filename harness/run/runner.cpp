#include "harness/run/runner.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>

#include "harness/core/color.h"
#include "harness/core/error.h"
#include "harness/core/parallel.h"
#include "harness/core/params.h"
#include "harness/core/timer.h"
#include "harness/io/image_io.h"
#include "metrics/metric.h"
#include "methods/registry.h"
#include "reports/html_report.h"
#include "reports/report_json.h"
#include "harness/run/pipeline.h"
#include "harness/run/stage_clock.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace aalab {
namespace fs = std::filesystem;

std::vector<std::string> DefaultMethods() {
  // Every registered method at its defaults, in registry order.
  return MethodNames();
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

}  // namespace

Report RunSuite(const RunSettings& s) {
  StageClock clock;
  clock.Enter("load_scenes");
  SetThreadCount(s.threads);
  // Validate every input before any work.
  if (s.repeat < 1 || s.repeat > 1000) throw UserError("--repeat " + std::to_string(s.repeat) + " is out of range (1..1000)");
  const int grid = ReferenceGridForSpp(s.ref_spp);
  const std::vector<std::string> scene_names = s.scenes.empty() ? SuiteScenes(s.suite) : s.scenes;
  std::vector<std::unique_ptr<Scene>> scenes = LoadScenes(scene_names);
  const std::vector<std::string> method_specs = s.methods.empty() ? DefaultMethods() : s.methods;
  const std::vector<MethodPlan> plans = ResolveMethods(method_specs);
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
  // A run that fails half-way (an exception from any stage) removes its partial output.
  struct RemovePartial {
    fs::path dir;
    bool armed = true;
    ~RemovePartial() {
      std::error_code ec;
      if (armed) fs::remove_all(dir, ec);
    }
  } cleanup{tmp};

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
  Progress progress(static_cast<int>(scenes.size() * (plans.size() + 1)), s.quiet);
  for (auto& scene_ptr : scenes) {
    const std::string name = scene_ptr->name;
    const std::string rel_dir = "images/" + name;
    fs::create_directories(tmp / rel_dir);
    const auto prepared = PrepareScene(std::move(scene_ptr), W, H, grid, s.seed, s.repeat, &clock);
    SceneResult sr = prepared->info;
    const Reference& ref = prepared->ref;
    // Image files are independent: a scene's are queued and written in parallel at its end.
    std::vector<std::function<void()>> writes;
    writes.push_back([&tmp, &rel_dir, &ref] {
      WriteImageF((tmp / rel_dir / "reference.exr").string(), DecodeToLinear(ref.image));
    });
    writes.push_back([&tmp, &rel_dir, &ref] { WriteImage8((tmp / rel_dir / "reference.png").string(), ToUnorm8(ref.image)); });
    writes.push_back([&tmp, &rel_dir, &ref] { WriteImage8((tmp / rel_dir / "edge_mask.png").string(), ToUnorm8(ref.edge_mask)); });
    sr.images = {{"reference_exr", rel_dir + "/reference.exr"},
                 {"reference_png", rel_dir + "/reference.png"},
                 {"edge_mask", rel_dir + "/edge_mask.png"}};
    progress.Step(name + " reference");

    std::map<std::string, std::string> file_of_hash;  // a bit-identical output is stored once
    for (const MethodPlan& plan : plans) {
      auto mo = std::make_shared<MethodOutput>(RunMethod(*prepared, plan, s.seed, s.repeat, &clock));
      ResultRow& row = mo->row;
      clock.Enter("image_writing");
      if (s.debug_views && plan.post) {
        for (const auto& view : plan.debug_views) {
          PostOptions opt;
          opt.debug_view = view;
          const std::string rel = rel_dir + "/" + FileSafe(plan.spec) + ".debug-" + view + ".png";
          WriteImage8((tmp / rel).string(), plan.post(mo->input, opt, nullptr));
          row.images["debug_" + view] = rel;
        }
      }
      mo->input = Image8();  // only the output and FLIP map wait for the scene's writes
      const auto [it, fresh] = file_of_hash.emplace(row.output_hash, rel_dir + "/" + FileSafe(plan.spec));
      const std::string base = it->second;
      if (fresh) {
        writes.push_back([&tmp, base, mo] { WriteImage8((tmp / (base + ".png")).string(), mo->output); });
        writes.push_back([&tmp, base, mo, W, H] { WriteGrey8((tmp / (base + ".flip.png")).string(), W, H, mo->flip_grey); });
      }
      row.images["output"] = base + ".png";
      row.images["flip_map"] = base + ".flip.png";
      report.rows.push_back(row);
      progress.Step(name + " " + plan.spec);
    }
    clock.Enter("image_writing");
    ParallelFor(static_cast<int>(writes.size()), [&](int i) { writes[static_cast<size_t>(i)](); });
    report.scenes.push_back(std::move(sr));
  }

  clock.Enter("html");
  const std::string html = RenderHtmlReport(report);
  WriteTextFile((tmp / "index.html").string(), html);
  report.time_breakdown = clock.Finish();  // writing report.json itself is the only time not in it
  WriteTextFile((tmp / "report.json").string(), ReportToJson(report).dump(2) + "\n");
  fs::remove_all(out);
  fs::rename(tmp, out);
  cleanup.armed = false;
  return report;
}

}  // namespace aalab
