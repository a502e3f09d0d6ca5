/// Preset tuning (`aalab sweep`): one method over a grid of parameter values, each scene's
/// reference and 1x frame rendered once (PrepareScene) and reused for every grid point
/// (RunMethod). Writes DIR/sweep.json and DIR/index.html (Pareto front of quality vs time,
/// heatmap per parameter pair; inline SVG, offline: reports/sweep_page.h) and returns the
/// summary (reports/sweep_result.h).
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/run/runner.h"
#include "harness/run/shard.h"
#include "methods/method.h"
#include "reports/compare.h"
#include "reports/result.h"
#include "reports/sweep_result.h"

namespace aalab {

/// The largest grid `sweep` accepts (points = product of the axes' value counts).
constexpr size_t kMaxSweepPoints = 1024;

struct SweepSettings {
  std::vector<std::string> scenes;      ///< names or paths (required)
  std::string method;                   ///< base spec; may override parameters not in the grid
  std::vector<std::string> grid;        ///< one "name=v1,v2,..." per --grid
  std::vector<std::string> objectives;  ///< empty: flip_mean then edge_psnr_db (psnr_db when edge PSNR is not computed)
  int width = 960, height = 540;
  /// `run`'s defaults (harness/run/runner.h), so a sweep and a run at their defaults measure
  /// the same way and their reports can be compared.
  int ref_spp = RunSettings{}.ref_spp;
  std::string reference = "sampled";  ///< "sampled" or "exact" (as `run --reference`)
  uint64_t seed = 1;
  int repeat = RunSettings{}.repeat;
  int threads = 0;
  std::string out_dir = "sweep";
  bool quiet = false;
  ShardSpec shard;        ///< --shard K/N: this process's share of the grid points (docs/cluster.md)
  std::string ref_cache;  ///< --ref-cache DIR: shared reference cache ("" = none)
  std::string viewing;    ///< --viewing PRESET[:key=value,...] (metrics/viewing.h); "" = default
};

/// Parses the --grid arguments: "name=v1,v2,..." each, non-empty names and values; a
/// parameter given twice (in two --grid, or in --grid and the base spec `base_spec`), or a
/// value repeated within an axis, is a UserError. Values are not checked here.
std::vector<GridAxis> ParseGrid(const std::vector<std::string>& args, const std::string& base_spec);

/// Every grid point's method spec (base overrides, then the axes in order; the last axis
/// varies fastest). Checks the point count against kMaxSweepPoints first (UserError naming
/// the count), then resolves each axis value through MakeMethod, so an unknown parameter or
/// out-of-range value gets the method's own error; values that resolve to the same number
/// are a UserError. Replaces each axis value with its canonical text.
std::vector<std::string> ExpandGrid(const std::string& base_spec, std::vector<GridAxis>* axes);

/// Indices of the Pareto-optimal points (no other point is at least as fast and at least as
/// good, and strictly better in one), sorted by time then index. Points with an empty quality
/// are excluded; +inf quality (identical) is the best possible. With `noise` (one time spread
/// per point), two times within the sum of their points' spreads count as equal: j dominates
/// i when t_j <= t_i + n and q_j is at least as good, and t_j < t_i − n or q_j is better. A
/// NaN spread (unknown: one repeat) makes n = 0 and never lets time alone rank two equally
/// good points (both stay on the front).
std::vector<size_t> ParetoFront(const std::vector<double>& time_ms, const std::vector<std::optional<double>>& quality,
                                Better better, const std::vector<double>& noise = {});

/// How far a point lies from the method's defaults: over its swept parameters, |value −
/// default| divided by the span of the axis's values and the default (numbers), or 0 / 1
/// (other values: equal or not); summed. Ties of the best mean go to the smallest distance.
double DistanceFromDefaults(const SweepPoint& pt, const std::vector<GridAxis>& axes,
                            const std::vector<std::pair<std::string, std::string>>& defaults);

/// Runs the sweep (validating every input before any rendering), writes DIR/sweep.json and
/// DIR/index.html through DIR.partial (a non-empty DIR without sweep.json is never replaced).
/// A shard (settings.shard) runs its share of the points on every scene and writes a
/// sweep.json with its rows and a "shard" block but no summary (points, best, Pareto front)
/// and no page: `aalab merge` writes those for the whole grid.
SweepResult RunSweep(const SweepSettings& settings);

/// `sweep --references-only`: this shard's share of the scenes' references into the cache, as
/// `run --references-only` with the same scenes, size, samples, seed and reference kind (a
/// sweep's references are a still run's: the same cache keys). Returns the number rendered;
/// `*cached` gets the number already cached.
int RenderSweepReferences(const SweepSettings& settings, int* cached = nullptr);

/// Fills points, the noise-aware Pareto front, every objective's best, the suggested point
/// (the first objective's best; ties: faster beyond the time spreads, then closest to the
/// defaults), the default point, the objectives' disagreements and the per-scene change of
/// the suggestion against the default, from result->report.rows and row_point; `plans[p]` is
/// grid point p (its spec and parameters).
void SummarizeSweep(SweepResult* result, const std::vector<MethodPlan>& plans);

/// sweep.json: the summary (absent for a shard), then scenes and rows in the report schema,
/// each row with its point, plus "specs" and, for a shard, its "shard" block.
nlohmann::ordered_json SweepToJson(const SweepResult& result);

/// Mean of per-scene values of `metric` for one point (rules in ObjectiveMean).
ObjectiveMean MeanOverScenes(const std::vector<const ResultRow*>& rows, const std::string& metric);

/// The summary printed by the CLI: best setting per objective, the Pareto front and the
/// suggested preset line.
std::string SweepSummaryText(const SweepResult& result);

}  // namespace aalab
