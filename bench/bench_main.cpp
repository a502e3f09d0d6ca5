// aalab_bench — `make bench`: what the harness costs, measured against limits measured in the
// same run on the same machine. One file per concern; this file parses the command line,
// calls them in order and writes the table and bench.json.
//
//   post filters   Mpix/s on a rendered 1920x1080 1x frame (real content) and on an
//                  edge-dense frame, at 1 and 2 threads; limit: a plain read+write pass over
//                  the same frame at the same thread count (the memory-bandwidth floor).
//                  Rescale and SSAA resolve the same way (bench/bench_post.cpp).
//   tracing        reference rendering of every library scene in Mrays/s; limit: the bare
//                  Embree loop (Tracer::BareTrace: rtcIntersect16, coherent primary rays, no
//                  shading) on the same scene, size and samples per pixel; the 1M-triangle
//                  torus (bench/bench_tracing.cpp, bench/bench_bigmesh.cpp).
//   metrics        ms per 1080p pair; side by side with scikit-image (SSIM, PSNR) and
//                  OpenImageIO's idiff when installed, timed the same way (bench/bench_metrics.cpp).
//   aaa, taa       analytical AA and TAA's temporal step (bench/bench_aaa.cpp, bench/bench_taa.cpp).
//   suite          wall time of `aalab run` at three sizes and at 1 vs 2 threads, and the
//                  default run (bench/bench_suite.cpp).
//   msaa           msaa-4x vs ssaa-rgss per library scene (bench/bench_msaa.cpp).
//   goals          each concern adds its rows to the goals table (SMAA's: bench/bench_smaa.cpp).
//
// Timing: Google Benchmark runs each figure (wall clock, UseRealTime) as `repetitions`
// repetitions after one untimed warm-up call; every figure reports the median, min and max
// over the repetitions (bench/bench_common.cpp). Suite runs are timed directly (one process
// per repetition). Every optimised post filter is also run through its reference
// implementation and the outputs compared byte for byte: any difference fails the benchmark (exit 2).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>

#include "bench/bench_memory.h"
#include "bench/bench_aaa.h"
#include "bench/bench_common.h"
#include "bench/bench_metrics.h"
#include "bench/bench_msaa.h"
#include "bench/bench_post.h"
#include "bench/bench_smaa.h"
#include "bench/bench_suite.h"
#include "bench/bench_taa.h"
#include "bench/bench_tracing.h"
#include "core/format.h"
#include "harness/run/context.h"
#include "core/parallel.h"

namespace aalab::bench {
namespace {

std::string Now() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&t));
  return buf;
}

std::string LoadAverage() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return a + " " + b + " " + c;
}

// Parses the command line into `cfg`; returns an exit code when the program is done (usage
// error, or --only-aaa), -1 to go on.
int ParseArgs(int argc, char** argv, Settings& cfg) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(1);
      }
      return argv[++i];
    };
    if (a == "--json")
      cfg.json_path = next();
    else if (a == "--aalab")
      cfg.aalab_bin = next();
    else if (a == "--reps")
      cfg.reps = std::stoi(next());
    else if (a == "--quick")
      cfg.quick = true;
    else if (a == "--only-aaa") {  // bench/bench_aaa.cpp's figures alone, printed as markdown
      std::string table;
      const auto figs = BenchAnalyticAa(i + 1 < argc ? std::stoi(argv[++i]) : 5, &table);
      std::printf("%s\n%s\n", table.c_str(), Json(figs).dump(1).c_str());
      return 0;
    } else {
      std::fprintf(stderr, "usage: aalab_bench [--json FILE] [--aalab BIN] [--reps N] [--quick] | --only-aaa [REPS]\n");
      return 1;
    }
  }
  if (cfg.quick) {
    cfg.reps = 3;
    cfg.trace_reps = 2;
    cfg.suite_reps = 1;
    cfg.min_time = 0.01;
  }
  return -1;
}

Json Context(const Settings& cfg) {
  Json ctx;  // ordered_json is vector-backed: keep no reference into `report` while adding keys
  ctx["date"] = Now();
  ctx["cpu"] = CpuModel();
  ctx["hardware_threads"] = ThreadCount();
  ctx["load_average_at_start"] = LoadAverage();
  ctx["git_commit"] = RunCapture("git -C " AALAB_SOURCE_DIR " rev-parse --short=12 HEAD 2>/dev/null");
  if (!ctx["git_commit"].get<std::string>().empty() && ctx["git_commit"].get<std::string>().back() == '\n') {
    std::string c = ctx["git_commit"];
    c.pop_back();
    ctx["git_commit"] = c;
  }
  ctx["timing"] = "wall clock; one untimed warm-up call, then " + std::to_string(cfg.reps) + " repetitions (tracing " +
                  std::to_string(cfg.trace_reps) + ", suite " + std::to_string(cfg.suite_reps) +
                  "); median, min, max over repetitions";
  return ctx;
}

int Main(int argc, char** argv) {
  Settings cfg;
  if (const int rc = ParseArgs(argc, argv, cfg); rc >= 0) return rc;
  const auto wall_start = std::chrono::steady_clock::now();
  Json report;
  report["schema_version"] = 1;
  Json ctx = Context(cfg);
  std::fprintf(stderr, "aalab_bench: %s, %s, load %s\n", ctx["date"].get<std::string>().c_str(),
               ctx["cpu"].get<std::string>().c_str(), LoadAverage().c_str());

  // Figures timed by Google Benchmark: registered first, run together.
  const PostBench post = RegisterPostFigures(cfg, report);  // writes report["bit_identity"]
  TracingBench tracing = RegisterTracingFigures(cfg);
  MetricsBench metrics = RegisterMetricFigures(cfg, post.frames[0].img);
  RunRegistered();
  // Figures timed here directly.
  RunExternalTools(cfg, metrics);
  SuiteBench suite;
  if (!RunSuiteFigures(cfg, suite)) return 3;

  // The table, section by section.
  BenchOutput out;
  PostTable(post, out);
  TracingTable(cfg, tracing, out);
  BigMeshTable(out);
  MetricsTable(metrics, out);
  {  // analytical AA (bench/bench_aaa.cpp)
    std::string aaa_table;
    for (auto& f : BenchAnalyticAa(cfg.reps, &aaa_table)) out.figures.push_back(f);
    out.table << aaa_table;
  }
  double taa_ratio = 0.0, taa_minmax = 0.0, taa_none = 0.0, taa_floor = 0.0;
  {  // TAA vs fxaa311-p39 (bench/bench_taa.cpp)
    const TaaBench taa = RunTaaBench(cfg.reps, 2);
    out.Line("");
    for (const auto& l : taa.lines) out.Line(l);
    for (const auto& f : taa.figures) out.figures.push_back(f);
    taa_ratio = taa.ratio;
    taa_minmax = taa.minmax_ratio;
    taa_none = taa.none_ratio;
    taa_floor = taa.floor_ratio;
  }
  SuiteTable(suite, out);
  AppendMsaaBench(cfg.quick, out.table, report);  // bench/bench_msaa.cpp

  // The goals: each concern adds its rows.
  out.Line("");
  out.Line("## Goals");
  out.Line("");
  out.Line("| goal | measured | met |");
  out.Line("|---|---|---|");
  PostFloorGoals(out);
  TracingRatioGoal(tracing, out);
  MetricsGoals(metrics, out);
  out.Goal("TAA temporal step ≤ 2× fxaa311-p39's time (1080p, 2 threads)",
           FormatDouble("%.2f×", taa_ratio) +
               FormatDouble("; the same step with the min/max box only %.2f×", taa_minmax) +
               FormatDouble(", with no box at all %.2f×", taa_none) +
               FormatDouble("; TAA's bandwidth floor alone (its reads and writes) %.2f×", taa_floor) +
               FormatDouble(", the step %.1f× its floor", taa_floor > 0 ? taa_ratio / taa_floor : 0.0),
           taa_ratio > 0 && taa_ratio <= 2.0);
  TracingScalingGoal(tracing, out);
  PostScalingGoal(post, out);
  SmaaGoals(
      [](const std::string& a, const std::string& b) { return PairedRatio(a, b); },
      [&out](const std::string& g, const std::string& m, bool met) { out.Goal(g, m, met); });  // bench/bench_smaa.cpp
  SuiteGoals(suite, out);
  DefaultRunGoal(suite, out);

  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  ctx["load_average_at_end"] = LoadAverage();
  ctx["bench_wall_s"] = total_s;
  out.Line("");
  out.Line("Machine: " + ctx["cpu"].get<std::string>() + ", " + std::to_string(ctx["hardware_threads"].get<int>()) +
           " hardware threads; " + ctx["date"].get<std::string>() + "; load average " +
           ctx["load_average_at_start"].get<std::string>() + " at start, " +
           ctx["load_average_at_end"].get<std::string>() + " at end; bench wall time " +
           FormatDouble("%.0f s", total_s) + ".");
  report["context"] = ctx;
  report["figures"] = out.figures;
  report["external"] = metrics.external;
  report["goals"] = out.goals;
  report["table_markdown"] = out.table.str();
  std::ofstream(cfg.json_path) << report.dump(2) << "\n";
  std::printf("%s\nwrote %s\n", out.table.str().c_str(), cfg.json_path.c_str());
  return 0;
}

}  // namespace
}  // namespace aalab::bench

int main(int argc, char** argv) {
  std::fprintf(stderr, "aalab_bench: %s\n", aalab::bench::ApplyBenchMemoryPolicy());
  try {
    return aalab::bench::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aalab_bench: %s\n", e.what());
    return 3;
  }
}
