/// The result model: what a run produced, independent of how it is written (JSON, HTML).
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace aalab {

/// Median / min / max over the timed repeats (after a warm-up run), in milliseconds.
struct Timing {
  std::vector<double> samples_ms;
  double median_ms = 0, min_ms = 0, max_ms = 0;
  /// Fills median/min/max from samples_ms (median of an even count: mean of the middle two).
  void Summarize();
};

/// A metric value as it goes into the report: null (with a reason) when undefined.
struct MetricResult {
  std::string name;
  std::optional<double> value;
  std::string null_reason;
};

/// One scene × method result.
struct ResultRow {
  std::string scene;
  std::string method;  ///< registry name
  std::string spec;    ///< canonical spec (name plus overrides)
  std::vector<std::pair<std::string, std::string>> params;  ///< every parameter, resolved
  int render_width = 0, render_height = 0;
  int samples_per_pixel = 1;
  bool render_shared = false;  ///< the 1x frame is shared with `none` (post-only methods)
  Timing render, post, resample, total;
  // Cost counters, per output pixel.
  double primary_rays_per_px = 0, shadow_rays_per_px = 0, texture_lookups_per_px = 0, taps_per_px = 0;
  std::vector<MetricResult> metrics;
  std::string output_hash;  ///< FNV-1a 64 of the output's RGBA8 bytes, hex
  std::map<std::string, std::string> images;  ///< role → path relative to the report folder
};

/// Per-scene facts: the reference and its noise floor.
struct SceneResult {
  std::string name, description, source;
  std::vector<std::string> effects;
  int width = 0, height = 0;
  int ref_spp = 0;
  double bvh_build_ms = 0, reference_ms = 0;
  std::optional<double> ref_halves_psnr_db, ref_floor_psnr_db;
  double ref_primary_rays_per_px = 0, ref_shadow_rays_per_px = 0, ref_texture_lookups_per_px = 0;
  double edge_pixel_fraction = 0;
  std::map<std::string, std::string> images;
  /// Zoom windows [x, y, w, h] where `none` is furthest from the reference on edges.
  std::vector<std::array<int, 4>> crops;
};

/// Where a run's time went: one stage's wall-clock time and the process's CPU time (user +
/// system, all threads) while in it. A stage is entered many times; these are the sums.
struct StageTime {
  std::string stage;
  double wall_ms = 0, cpu_ms = 0;
};

/// A whole run.
struct Report {
  int schema_version = 1;
  std::map<std::string, std::string> context;       ///< tool/git/build/library/machine facts
  std::vector<std::pair<std::string, std::string>> settings;  ///< run settings, as given
  std::vector<SceneResult> scenes;
  std::vector<ResultRow> rows;
  /// `aalab run`'s stages in the order first entered, then "total" (empty in reports written
  /// before it existed, and from commands that do not time their stages).
  std::vector<StageTime> time_breakdown;
};

}  // namespace aalab
