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
  double copy_ms = 0;                     ///< the copy floor's median in the same run, same size
  double ratio_to_copy = 0;               ///< median_ms / copy_ms
  std::optional<double> identical_share;  ///< share of pixels equal to the CPU output
  std::optional<int> max_diff;            ///< largest rgb difference to the CPU output, 8-bit levels
  std::string measured_utc;               ///< when the file that gave this size was written
};

/// The GPU block of a row: where and when it was measured, and the timings per size.
struct GpuTiming {
  std::string device, driver, cuda_runtime, measured_utc;
  std::string kernels;  ///< the kernels launched, in order
  std::vector<GpuTimingAt> sizes;
};

/// A row's render-time method drawn by the raster path (gpu/raster/aalab_raster, docs/gpu.md
/// "The raster path") at one frame size: GL_TIME_ELAPSED per stage, median/min/max of the
/// frame total over the timed frames, and the stages' medians.
struct RasterTimingAt {
  std::string size;  ///< "1920x1080"
  double median_ms = 0, min_ms = 0, max_ms = 0;
  double draw_ms = 0, resolve_ms = 0, encode_ms = 0;
  double ratio_to_1x = 0;   ///< median_ms / the same scene's `none` frame at this size (0: none not timed)
  std::string render_size;  ///< the frame drawn when it is not `size` (scale43's render: "2560x1440"), else ""
};

/// The raster block of a row (reports/raster_timings.h): the GL device and settings.
struct RasterTiming {
  std::string device, gl_version, egl_platform, target_format, msaa_resolve;
  /// "" when the block times the whole method; "render" when it times only the method's
  /// render (scale43 and scale43-fxaa-high: the 4/3 target), its rescale and post filter
  /// being the row's `gpu` block (the CUDA twin), so the method's GPU time is the two summed.
  std::string part;
  int samples = 1;  ///< samples per pixel the GL allocated
  std::vector<RasterTimingAt> sizes;
};

/// One scene × method result.
struct ResultRow {
  std::string scene;
  std::string method;                                       ///< registry name
  std::string spec;                                         ///< canonical spec (name plus overrides)
  std::vector<std::pair<std::string, std::string>> params;  ///< every parameter, resolved
  int render_width = 0, render_height = 0;
  int samples_per_pixel = 1;
  bool render_shared = false;  ///< the 1x frame is shared with `none` (post-only methods)
  Timing render, post, resample, total;
  // Cost counters, per output pixel.
  double primary_rays_per_px = 0, shadow_rays_per_px = 0, texture_lookups_per_px = 0, taps_per_px = 0;
  double coverage_rays_per_px = 0;  ///< camera rays that decide visibility at a sample position
  double shading_evals_per_px = 0;  ///< surface shading evaluations (MSAA: one per primitive and pixel)
  // Analytical AA (aaa methods only): share of the 1x frame's edge pixels (centre-sample
  // surface differs from a 4-neighbour's) within one pixel size of an analytic outline, i.e.
  // whose coverage came from the distance (null: not an aaa method, or no edge pixels);
  // pixels with a fractional alpha per pixel; signed-distance evaluations per pixel.
  bool analytic_costs = false;  ///< the method renders analytically (its plan says so): the three below are reported
  std::optional<double> analytic_edge_share;
  double analytic_pixels_per_px = 0, distance_evals_per_px = 0;
  std::vector<MetricResult> metrics;
  std::string output_hash;                    ///< FNV-1a 64 of the output's RGBA8 bytes, hex
  std::map<std::string, std::string> images;  ///< role → path relative to the report folder
  /// Motion runs (--frames > 1) only: per-frame series (name → one value per frame, null
  /// where undefined) and the output PNG of every frame. Empty for still runs.
  std::vector<std::pair<std::string, std::vector<std::optional<double>>>> frame_series;
  std::vector<std::string> frame_images;
  /// Non-empty when the method cannot run on this scene (a renderer-side method on an image
  /// scene): why. Such a row has every metric null with this reason, no timings, no images.
  std::string not_applicable;
  /// Non-empty for a row the user supplied (an image scene's `outputs`: frames anti-aliased by
  /// the user's own pipeline, scored like any method's output but not run by aalab): where the
  /// frames came from. Timings are the manifest's `ms` (render = total) or empty.
  std::string supplied;
  std::optional<GpuTiming> gpu;            ///< set by `aalab merge-gpu` / `run --gpu-timings`
  std::optional<RasterTiming> gpu_raster;  ///< set by `run --gpu-timings` / `merge-gpu` with a raster file
};

/// Per-scene facts: the reference and its noise floor.
struct SceneResult {
  std::string name, description, source;
  std::vector<std::string> effects;
  int width = 0, height = 0;
  int ref_spp = 0;         ///< 0 for the exact reference
  bool ref_exact = false;  ///< closed-form exact reference (scenes/exact_reference.h)
  double bvh_build_ms = 0, reference_ms = 0;
  /// Scenes with glTF content: triangles, image textures and their mip chains' memory.
  struct Content {
    uint64_t triangles = 0;
    int textures = 0;
    uint64_t texture_bytes = 0;        ///< mip chains as aalab stores them (RGBA8, or half for 16-bit/float images)
    uint64_t texture_bytes_rgba8 = 0;  ///< the same chains as RGBA8 GPU textures
    double load_ms = 0;                ///< wall time loading the scene's glTF files (a timing: not compared)
  };
  std::optional<Content> content;
  std::optional<double> ref_halves_psnr_db, ref_floor_psnr_db;
  double ref_primary_rays_per_px = 0, ref_shadow_rays_per_px = 0, ref_texture_lookups_per_px = 0;
  double edge_pixel_fraction = 0;
  std::map<std::string, std::string> images;
  /// Zoom windows [x, y, w, h] where `none` is furthest from the reference on edges.
  std::vector<std::array<int, 4>> crops;
  /// Motion runs (--frames > 1): the frame count, whether the scene moves, the reference PNG
  /// of every frame and the sequence's totals (the fields above describe the last frame).
  int frames = 1;
  bool moves = false;
  std::vector<std::string> frame_images;
  /// `run --frame-exr`: the reference of every frame as display-linear float EXR (empty otherwise).
  std::vector<std::string> frame_exr_images;
  double sequence_scene_ms = 0;      ///< building the scene at each frame + its BVH, summed
  double sequence_reference_ms = 0;  ///< the references of all frames, summed
  /// "rendered": a scene the tracer renders; "image": a view of an image scene (a user's own
  /// 1x frame and reference, harness/run/image_scene.h).
  std::string kind = "rendered";
  /// How the edge mask was made (the report shows it).
  std::string edge_mask_source =
      "geometry: the reference's samples see more than one surface, a shadow boundary "
      "or an alpha cut-out; dilated by 1 px";
  std::string reference_note;           ///< how an image scene's reference file was read ("" otherwise)
  std::string noise_floor_null_reason;  ///< why ref_floor_psnr_db is null, when it is ("" otherwise)
  /// Image scenes: whether the manifest gave the 1x frame's render time (`frame_ms`); the
  /// motion-vector convention of a captured sequence ("" when none).
  bool frame_ms_given = false;
  std::string motion_note;
  /// Image scenes: what the capture checks found that AA cannot explain (harness/run/
  /// capture_checks.h: a mean interior bias, interior error far above the edges'), with the
  /// likely causes; empty when nothing was found.
  std::vector<std::string> warnings;
};

/// Where a run's time went: one stage's wall-clock time and the process's CPU time (user +
/// system, all threads) while in it. A stage is entered many times; these are the sums.
struct StageTime {
  std::string stage;
  double wall_ms = 0, cpu_ms = 0;
};

/// The share of the work a partial report holds: written by `run --shard K/N` and
/// `sweep --shard K/N`, read by `aalab merge` (harness/run/shard.h). Absent in whole reports.
struct ShardInfo {
  int index = 0, count = 0;        ///< shard K of N
  std::string unit;                ///< what was split: "scene" or "grid point"
  int total_units = 0;             ///< the units of the whole run
  std::vector<std::string> units;  ///< this shard's units, in the run's order
};

/// A whole run.
struct Report {
  int schema_version = 1;
  std::map<std::string, std::string> context;                 ///< tool/git/build/library/machine facts
  std::vector<std::pair<std::string, std::string>> settings;  ///< run settings, as given
  std::vector<SceneResult> scenes;
  std::vector<ResultRow> rows;
  /// `aalab run`'s stages in the order first entered, then "total" (empty in reports written
  /// before it existed, and from commands that do not time their stages).
  std::vector<StageTime> time_breakdown;
  std::optional<ShardInfo> shard;  ///< set in a shard's partial report only
};

}  // namespace aalab
