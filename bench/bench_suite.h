/// The suite figures of `make bench` (bench/bench_suite.cpp): wall and CPU time of
/// `aalab run --suite quick` at three sizes and at 1 vs 2 threads (one process per
/// repetition), and the default run (`aalab run` with its defaults: wall, CPU, peak memory).
#pragma once
#include <string>
#include <tuple>
#include <vector>

#include "bench/bench_common.h"

namespace aalab::bench {

/// One suite configuration and its repetitions.
struct SuiteRun {
  std::string size;
  int w, h, threads;
  std::vector<double> secs;
  std::vector<double> cpu;  ///< child CPU seconds (user + system)
  /// The last repetition's report.json time_breakdown: stage name, wall s, CPU s (in stage
  /// order; "total" last), so that the table shows which stages do not scale.
  std::vector<std::tuple<std::string, double, double>> stages;
  /// Per run, its parallel loops (AALAB_LOOP_STATS, docs/cli.md): wall s inside
  /// top-level loops and thread-s inside chunk bodies, so that a 2-thread run's shortfall splits
  /// into serial time (the run's wall − in loops), idle time in loops (threads × in loops − busy)
  /// and work that costs more thread time than at 1 thread (busy against the 1-thread run's).
  std::vector<double> in_loops_s, busy_s;
};

/// The default run, as `make run` does it with the binary prebuilt (not in --quick).
struct DefaultRun {
  bool ok = false;
  double wall_s = 0, cpu_s = 0, max_rss_mb = 0;
  double folder_mb = 0;           ///< the output folder: sum of its files' sizes (MB, 10^6 bytes)
  double folder_disk_mb = 0;      ///< the same folder's disk usage in 4 KiB blocks, as `du` counts
  std::vector<std::string> real;  ///< the default suite's scenes with glTF content (a real asset)
  int scenes = 0;                 ///< scenes in the default suite
};

/// What the suite figures measured, for their table and goals.
struct SuiteBench {
  std::vector<SuiteRun> runs;
  DefaultRun default_run;
  /// The machine's own two-core throughput for this work: two 1-thread 960x540 runs started
  /// together (separate output folders), once a round right after the 1-thread run alone.
  /// Wall s until both ended, and the CPU s of both.
  std::vector<double> pair_secs, pair_cpu;
  /// `aalab --version`: the process's start and exit alone (dynamic loading), minimum of 3.
  double start_wall_s = 0, start_cpu_s = 0;
  // Filled by SuiteTable:
  double per_mpix_1080 = 0.0;                         ///< wall s per Mpix at 1080p, 2 threads
  double linear_worst = 0.0, linear_worst_cpu = 0.0;  ///< worst deviation from per_mpix_1080 (wall, CPU)
  double t1 = 0, t2 = 0;                              ///< 960x540 wall s at 1 and 2 threads (medians)
  double t1_min = 0, t2_min = 0;                      ///< the same, fastest runs
  /// 960x540, 2 threads (AALAB_LOOP_STATS medians): busy thread-s / the 1-thread run's, idle
  /// thread-s inside loops, wall s outside loops (0 when not measured).
  double busy_ratio = 0, idle2_s = 0, outside2_s = 0;
};

/// Repetitions of a suite configuration `width` pixels wide, `suite_reps` given: 1080p (~30 s
/// a run) once, 480x270 (~2 s) 2 × suite_reps, the others suite_reps.
int SuiteReps(int width, int suite_reps);

/// Runs the suite configurations and the default run; false (with a message) when a run failed.
bool RunSuiteFigures(const Settings& cfg, SuiteBench& suite);

/// The "## Suite" and "## Default run" sections; fills the linearity and thread figures.
void SuiteTable(SuiteBench& suite, BenchOutput& out);

/// Goals: suite time linear in pixel count, 2 threads at 960x540 (the "## Goals" rows after SMAA's).
void SuiteGoals(const SuiteBench& suite, BenchOutput& out);

/// Goal: the default run ≤ 30 s wall and ≤ 300 MB peak memory (when it ran).
void DefaultRunGoal(const SuiteBench& suite, BenchOutput& out);

}  // namespace aalab::bench
