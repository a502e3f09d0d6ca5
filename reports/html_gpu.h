/// The HTML report's GPU parts (docs/gpu.md): a "GPU ms" column in each scene table and a
/// summary table in the suite overview, shown only when rows carry a `gpu` block
/// (aalab merge-gpu / run --gpu-timings).
#pragma once
#include <string>

#include "reports/result.h"

namespace aalab::html {

/// True when any row has GPU timings.
bool AnyGpu(const Report& r);
/// The scene table's "GPU ms" header cell ("" when no row has GPU timings).
std::string GpuHeader(const Report& r);
/// One row's "GPU ms" cell: median ms per size ("1080p / 4K"), device and ratios in the title;
/// a dash with the reason when the row has none.
std::string GpuCell(const ResultRow& row);
/// The suite overview's table: every GPU-timed method, mean over scenes of the median ms and
/// of the ratio to the copy floor at each size, and the worst identical share ("" when none).
std::string GpuSummary(const Report& r);

}  // namespace aalab::html
