/// Distribution of the per-pixel absolute error: percentiles and maximum. Definitions in
/// metrics/error_stats.cpp and METRICS.md.
#pragma once
#include <vector>

#include "core/image.h"

namespace aalab {

/// Per-pixel absolute error of two same-size RGB images (channels 0..2): the mean over R, G, B
/// of |a − b| on the stored (sRGB-encoded) values, computed in double and rounded to float.
/// 1 channel. Throws UserError on a shape mismatch or fewer than 3 channels.
ImageF AbsErrorMap(const ImageF& a, const ImageF& b);

/// The same per-pixel values in double, row-major (what the statistics are computed from).
std::vector<double> AbsErrorValues(const ImageF& a, const ImageF& b);

/// Nearest-rank percentile of values sorted ascending (non-empty): the value of 1-based rank
/// max(1, ceil(percent · N / 100)), with `percent` an integer in [0, 100] (exact integer
/// arithmetic). It is always one of the values, never an interpolation; percent 100 is the
/// maximum.
double NearestRankPercentile(const std::vector<double>& sorted, int percent);

}  // namespace aalab
