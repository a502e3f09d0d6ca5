/// Registry rows of each metric family, one function per family file.
#pragma once
#include <vector>

#include "metrics/metric.h"

namespace aalab {

/// `psnr` (metrics/psnr.cpp): psnr_db, mse.
std::vector<MetricEntry> PsnrMetrics();
/// `edge` (metrics/edge_error.cpp): edge_psnr_db, edge_rmse, interior_psnr_db,
/// edge_error_removed. Needs the edge mask.
std::vector<MetricEntry> EdgeErrorMetrics();
/// `ssim` (metrics/ssim.cpp): ssim.
std::vector<MetricEntry> SsimMetrics();
/// `flip` (metrics/flip.cpp): flip_mean, flip_median_weighted, flip_max.
std::vector<MetricEntry> FlipMetrics();
/// `abs_error` (metrics/error_stats.cpp): abs_err_p50, abs_err_p95, abs_err_p99, abs_err_max.
std::vector<MetricEntry> AbsErrorMetrics();
/// `coverage_bias` (metrics/coverage_bias.cpp): area_bias_px2, area_bias_abs_rel and
/// area_bias_rel_r* per radius bin. Needs MetricInput::coverage_probes.
std::vector<MetricEntry> CoverageBiasMetrics();
/// `temporal` (metrics/temporal.cpp, a sequence row): temporal_rmse, temporal_psnr_db,
/// temporal_edge_rmse. Computed by TemporalError.
std::vector<MetricEntry> TemporalMetrics();
/// `temporal_perceptual` (metrics/temporal_perceptual.cpp, a sequence row):
/// temporal_perceptual, temporal_csf_rmse. Computed by PerceptualTemporalError.
std::vector<MetricEntry> PerceptualTemporalMetrics();

}  // namespace aalab
