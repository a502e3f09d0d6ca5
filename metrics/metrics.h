/// The metrics module's front door: run every registered metric on one image pair, plus the
/// per-metric entry points (SSIM, FLIP, absolute-error statistics, heatmaps). Definitions of
/// every value: metrics/METRICS.md.
#pragma once
#include <vector>

#include "metrics/error_stats.h"
#include "metrics/flip.h"
#include "metrics/heatmap.h"
#include "metrics/metric.h"
#include "metrics/ssim.h"

namespace aalab {

/// Runs every MetricRegistry() row in listing order and returns their values in that order
/// (each row's `outputs`, in order). `in.image` and `in.reference` are required and must
/// have the same shape (UserError otherwise). Rows that need the edge mask report each of
/// their outputs as null with reason "no edge mask" when `in.edge_mask` is absent. A value
/// that comes out NaN or infinite (only possible from non-finite input pixels) is reported
/// as null with reason "non-finite result (input has NaN/Inf pixels)", so the result never
/// holds NaN or Inf. Deterministic: same inputs, same bits, at any thread count.
std::vector<MetricValue> ComputeAllMetrics(const MetricInput& in);

}  // namespace aalab
