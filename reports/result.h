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

/// A row's post filter timed on a GPU by its CUDA twin (gpu/aalab_gpu, docs/gpu.md), at one
/// frame size of the same scene: CUDA events, median/min/max over the timed launches.
struct GpuTimingAt {
  std::string size;  ///< "1920x1080"
  double median_ms = 0, min_ms = 0, max_ms = 0;
  double copy_ms = 0;        ///< the copy floor's median in the same run, same size
  double ratio_to_copy = 0;  ///< median_ms / copy_ms
  std::optional<double> identical_share;  ///< share of pixels equal to the CPU output
  std::optional<int> max_diff;            ///< largest rgb difference to the CPU output, 8-bit levels
};

/// The GPU block of a row: where and when it was measured, and the timings per size.
struct GpuTiming {
  std::string device, driver, cuda_runtime, measured_utc;
  std::string kernels;  ///< the kernels launched, in order
  std::vector<GpuTimingAt> sizes;
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
  double coverage_rays_per_px = 0;  ///< camera rays that decide visibility at a sample position
  double shading_evals_per_px = 0;  ///< surface shading evaluations (MSAA: one per primitive and pixel)
  std::vector<MetricResult> metrics;
  std::string output_hash;  ///< FNV-1a 64 of the output's RGBA8 bytes, hex
  std::map<std::string, std::string> images;  ///< role → path relative to the report folder
  std::optional<GpuTiming> gpu;  ///< set by `aalab merge-gpu` / `run --gpu-timings`
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

/// A whole run.
struct Report {
  int schema_version = 1;
  std::map<std::string, std::string> context;       ///< tool/git/build/library/machine facts
  std::vector<std::pair<std::string, std::string>> settings;  ///< run settings, as given
  std::vector<SceneResult> scenes;
  std::vector<ResultRow> rows;
};

}  // namespace aalab
