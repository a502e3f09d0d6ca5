/// The JSON that gpu/raster/aalab_raster writes (schema "aalab-raster-timings": GPU times of
/// the render-time methods drawn by the raster path), read back and merged into a report's
/// rows as their `gpu_raster` block (docs/gpu.md "The raster path", reports/SCHEMA.md).
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reports/result.h"

namespace aalab {

/// One row of the raster file: a method on one scene at one size.
struct RasterResult {
  std::string scene, size, method;
  std::string render_size;  ///< render_width x render_height when the row has them (scale43), else ""
  int samples = 1;
  double median_ms = 0, min_ms = 0, max_ms = 0, draw_ms = 0, resolve_ms = 0, encode_ms = 0;
};

struct RasterTimingsFile {
  std::string device, gl_version, egl_platform, target_format, msaa_resolve;
  std::vector<RasterResult> results;
};

/// True when the JSON file at `path` declares the raster schema (any other content: false).
bool IsRasterTimingsFile(const std::string& path);
/// Reads and validates a file written by `aalab_raster --json`. Throws UserError naming the
/// path for a missing file, invalid JSON, another schema or version, a missing field or
/// timings that are not 0 < min ≤ median ≤ max.
RasterTimingsFile ReadRasterTimingsFile(const std::string& path);
/// The report specs a raster method's rows time, and whether the raster row is only their
/// render: a method times its own spec (whole), except `scale43`, the render at 4/3, which is
/// the render part of both `scale43` and `scale43-fxaa-high` (their rescale and FXAA are
/// the CUDA twins'). Pure.
std::vector<std::string> RasterSpecsOf(const std::string& raster_method, bool* render_only);

/// Sets `row.gpu_raster` for every row whose scene and spec have results (RasterSpecsOf; one
/// RasterTimingAt per size; ratio_to_1x against the file's `none` on the same scene and size;
/// part "render" for a render-only row) and records the device in
/// report.context["gpu_raster_timings"]. Returns the rows matched.
int MergeRasterTimings(Report& report, const RasterTimingsFile& file);

/// The block as report.json holds it, and back.
nlohmann::ordered_json RasterTimingJson(const RasterTiming& t);
RasterTiming RasterTimingFrom(const nlohmann::ordered_json& j);

}  // namespace aalab
