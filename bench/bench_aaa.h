/// Analytical-AA figures for `make bench` (bench/bench_aaa.cpp).
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace aalab {

/// Times (wall clock, one untimed warm-up, then `reps` repetitions; median/min/max) the aaa
/// render against `none` on sdf-circles at 960x540, and the exact reference of sdf-circles at
/// 1920x1080 against a 256-spp sampled reference. Appends a markdown section to `table` and
/// returns the figures for bench.json.
std::vector<nlohmann::ordered_json> BenchAnalyticAa(int reps, std::string* table);

}  // namespace aalab
