// TAA's per-frame cost against fxaa311-p39 on the same 1080p frame (bench/bench_taa.cpp).
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace aalab {

/// Markdown lines for the bench table and JSON figures for bench.json.
struct TaaBench {
  std::vector<std::string> lines;
  nlohmann::ordered_json figures = nlohmann::ordered_json::array();
  double ratio = 0.0;         ///< median TAA step time / median fxaa311-p39 time
  double minmax_ratio = 0.0;  ///< the same for taa:clip=minmax (min/max box, no sums)
  double none_ratio = 0.0;    ///< the same for taa:clip=none (no box: fetch, blend, encode)
  double floor_ratio = 0.0;   ///< TAA's bandwidth floor (its reads and writes alone) / fxaa311-p39
};

/// Renders frames 0 and 1 of the motion-pan scene at 1920x1080 (jittered, with exact motion
/// vectors), then times, at `threads` threads, one untimed warm-up and `reps` timed runs of:
/// TAA's temporal step on frame 1 (reprojection, YCoCg variance clip, blend, 8-bit output;
/// each run on a fresh copy of the state after frame 0, the copy not timed), fxaa311-p39's
/// post filter on the same scene's 1x frame, and the motion vectors (PreviousPositions).
/// Also the step of taa:clip=minmax and taa:clip=none (lower bounds on the default step's
/// time, whatever its variance box costs), and TAA's bandwidth floor: a plain pass reading
/// its inputs and writing its outputs. Goal: TAA ≤ 2× fxaa311-p39.
TaaBench RunTaaBench(int reps, int threads);

}  // namespace aalab
