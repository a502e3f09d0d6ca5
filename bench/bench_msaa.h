/// MSAA's cost against SSAA with the same four-sample budget (bench/bench_msaa.cpp).
#pragma once
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace aalab {

/// Renders `scenes` (library names) at width × height with msaa-4x and ssaa-rgss (the same four
/// positions), `reps` timed repetitions after one warm-up each (wall clock, median/min/max),
/// and returns the markdown table (per scene: shading evaluations, coverage and shadow rays
/// per pixel, render time, MSAA/SSAA ratios) and the same as JSON.
struct MsaaBenchResult {
  std::string markdown;
  nlohmann::ordered_json json;
};
MsaaBenchResult RunMsaaBench(int width, int height, int reps, const std::vector<std::string>& scenes);

/// The hook `make bench` calls: runs RunMsaaBench on every library scene (480x270, 5 repetitions; 160x90, 2 with
/// `quick`), appends its table to `table` and its JSON to report["msaa"].
void AppendMsaaBench(bool quick, std::ostringstream& table, nlohmann::ordered_json& report);

}  // namespace aalab
