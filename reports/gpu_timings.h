/// The JSON that gpu/aalab_gpu writes (timings and fidelity of the post filters' CUDA
/// twins), read back and merged into a report's rows as their `gpu` block (docs/gpu.md,
/// reports/SCHEMA.md).
#pragma once
#include <string>
#include <vector>

#include "reports/result.h"

namespace aalab {

/// One result line of the GPU file: a method (or a copy floor) on one scene at one size.
struct GpuResult {
  std::string scene, size, method, kernels;
  bool timed = false;
  double median_ms = 0, min_ms = 0, max_ms = 0, ratio_to_copy = 0;
  bool has_fidelity = false;
  double identical_share = 0;
  int max_diff = 0;
};

/// A whole GPU file.
struct GpuTimingsFile {
  std::string device, driver, cuda_runtime, generated_utc;
  std::vector<GpuResult> results;
  /// Scene names with results, in first-seen order.
  std::vector<std::string> Scenes() const;
};

/// Reads and validates a file written by `aalab_gpu --json`. Throws UserError naming the path
/// for a missing file, invalid JSON, another schema or version, or a missing field.
GpuTimingsFile ReadGpuTimingsFile(const std::string& path);

/// Sets `row.gpu` for every row whose scene and spec have timed results in `gpu` (one
/// GpuTimingAt per size, in file order; copy_ms from the file's "copy" result for that scene
/// and size) and records the source in report.context["gpu_timings"]. Rows without results
/// are left as they are. A row that already has a block from the same setup (device, driver,
/// CUDA runtime, kernels) keeps it and gains this file's sizes, a size in both taking this
/// file's timing (so a 1080p file and a 4K file merged one after the other put both sizes on
/// the row, each size with its own `measured_utc` and the block's listing the times of the
/// files its sizes come from, "; "-separated); a block from another
/// setup is replaced. report.context["gpu_timings"] lists every merged file's source once.
/// Returns the number of rows that got or extended a block.
int MergeGpuTimings(Report& report, const GpuTimingsFile& gpu);

}  // namespace aalab
