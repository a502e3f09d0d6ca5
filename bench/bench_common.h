/// What the `make bench` figures share (bench/bench_common.cpp): the settings, registering a
/// timed figure with Google Benchmark and reading its repetitions back, the formatting of the
/// table, and the table, figures and goals being written (BenchOutput). Each concern's file
/// (bench_post, bench_tracing, bench_metrics, bench_suite, bench_msaa, bench_smaa, bench_taa,
/// bench_aaa, bench_bigmesh) uses these; bench_main.cpp calls the concerns in order.
#pragma once
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_stats.h"
#include "bench/run_capture.h"
#include "core/image.h"

namespace aalab::bench {

using Json = nlohmann::ordered_json;
using Stats = SampleStats;  ///< samples: seconds per operation, one per repetition

/// The command line's settings.
struct Settings {
  std::string json_path = "bench.json";
  std::string aalab_bin = AALAB_BIN_PATH;
  std::string python = "/usr/bin/python3";
  std::string script_dir = AALAB_BENCH_DIR;
  int reps = 5;            ///< repetitions for post filters and metrics
  int trace_reps = 3;      ///< repetitions for tracing
  int suite_reps = 2;      ///< repetitions per suite configuration
  double min_time = 0.05;  ///< Google Benchmark min time per repetition, seconds
  int trace_w = 320, trace_h = 180, trace_grid = 8;
  bool quick = false;  ///< a small subset, for checking the benchmark itself
};

/// The size of the post-filter and metric frames.
inline constexpr int kFrameW = 1920, kFrameH = 1080;

/// Registers `body` as one figure: `threads` worker threads, one warm-up call, then `reps`
/// repetitions of at least `min_time` seconds each (wall clock), recording the cores used.
void Register(const std::string& name, int threads, int reps, double min_time, std::function<void()> body);

/// One figure of a group that RegisterRounds measures in rounds.
struct RoundFigure {
  std::string name;
  int threads = 1;
  std::function<void()> body;
};

/// Registers groups of figures that goals compare with each other, measured in `reps` rounds:
/// round r runs one repetition (≥ `min_time` s) of every figure of every group, each group's
/// figures in order, so the r-th samples of two figures of a group were taken seconds apart and
/// pair up (PairedRatio); each figure gets one untimed warm-up call before its first round. On a
/// machine whose speed drifts from one minute to the next, the drift then cancels in each pair
/// instead of biasing one figure; and since round r of every group runs before round r + 1, a
/// group's rounds lie minutes apart, so a slow stretch a few seconds long reaches one round of a
/// group (which the median over rounds then drops) instead of all of them.
void RegisterRounds(const std::vector<std::vector<RoundFigure>>& groups, int reps, double min_time);

/// The median over rounds of figure a's r-th sample / figure b's r-th sample (both registered by
/// one RegisterRounds group); exits 3 when either is missing or their counts differ.
double PairedRatio(const std::string& a, const std::string& b);

/// Figure a's fastest sample / figure b's fastest sample: the same ratio with the machine's
/// slow stretches left out (other load and a host that slows a vCPU only add time), shown
/// beside PairedRatio where a goal reads the machine's 2-core scaling.
double FastestRatio(const std::string& a, const std::string& b);

/// Runs every registered figure (Google Benchmark), collecting seconds per operation.
void RunRegistered();

/// The repetitions of figure `name`; exits 3 when it was not measured.
const Stats& Figure(const std::string& name);

/// Median cores the process got while figure `name` ran (CPU seconds / wall seconds); 0 if unknown.
double CoresUsed(const std::string& name);

/// Process CPU time (all threads, user + system), seconds.
double ProcessCpuSeconds();

/// A 1x frame of library scene `scene_name` at w × h.
Image8 RenderFrame1x(const std::string& scene_name, int w, int h);

/// The memory-bandwidth floor: a plain read+write pass, input rgb to output with alpha 255
/// (what an FXAA early exit writes), rows in parallel chunks as the filters use.
void PlainPass(const Image8& in, Image8& out);

/// Prints the bit-identity failure and exits 2.
[[noreturn]] void FailIdentity(const std::string& what);

/// "median (min–max)" of `s` scaled by `scale`, each with format `f`.
std::string Range(const Stats& s, double scale, const char* f);
/// Rates mp / t for each sample t (Mpix/s from seconds).
Stats Mpix(const Stats& s, double mp);
/// {median, min, max, repeats} of `v` scaled by `scale`.
Json StatsJson(const std::vector<double>& v, double scale);

/// The standard output of a shell command.

/// What the bench writes: the markdown table, bench.json's figures and the goals.
struct BenchOutput {
  std::ostringstream table;
  Json figures = Json::array();
  Json goals = Json::array();
  /// Appends one line to the table.
  void Line(const std::string& s) { table << s << "\n"; }
  /// Appends one goal row (to the table and to `goals`).
  void Goal(const std::string& goal, const std::string& measured, bool met);
};

}  // namespace aalab::bench
