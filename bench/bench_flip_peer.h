/// FLIP against NVIDIA's own FLIP tool (C++ CPU version, built from its public source; not
/// part of this repository) on the bench's 1080p pair: the tool's evaluation time at 1 and 2
/// OpenMP threads and its mean, beside aalab's mean on the same 8-bit pair. Where the tool
/// is: $AALAB_NVIDIA_FLIP, else kNvidiaFlipDefaultPath; docs/performance.md says how to
/// build it. Used by bench/bench_metrics.cpp (make bench) and bench/bench_metrics_main.cpp (aalab_bench_metrics).
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"

namespace aalab::bench {

/// Where make bench looks for NVIDIA's FLIP tool when $AALAB_NVIDIA_FLIP is not set.
inline constexpr const char* kNvidiaFlipDefaultPath = "/opt/nvidia-flip/flip";

/// The tool's figures on one pair.
struct NvidiaFlipRun {
  std::string path;                           ///< the tool looked for
  std::string error;                          ///< non-empty: not measured, and why
  std::map<int, std::vector<double>> eval_s;  ///< threads → evaluation times it printed (s)
  double tool_mean = 0.0;                     ///< its mean (printed to 6 decimals)
  double aalab_mean = 0.0;                    ///< aalab's flip_mean on the same 8-bit pair
};

/// Runs the tool on `reference` and `test` (written as PNG under `tmp_dir`) with `reps`
/// evaluations per thread count (one process each: the tool evaluates every -t file in turn,
/// after one untimed warm-up), at 67 pixels per degree as aalab's default.
NvidiaFlipRun RunNvidiaFlip(const Image8& reference, const Image8& test, int reps, const std::string& tmp_dir);

/// One row of the goals table.
struct BenchGoal {
  std::string goal, measured;
  bool met = false;
};

/// The table rows of the comparison (through `line`) and its goals: `aalab_ms(threads)` is
/// aalab's FLIP as in a run (reference half reused) on the bench pair, median ms.
std::vector<BenchGoal> ReportNvidiaFlip(const NvidiaFlipRun& run, const std::function<double(int)>& aalab_ms,
                                        const std::function<void(const std::string&)>& line,
                                        nlohmann::ordered_json* figures);

}  // namespace aalab::bench
