/// Registry rows of each metric family, one function per family file.
#pragma once
#include <vector>

#include "metrics/metric.h"

namespace aalab {

/// `psnr` (metrics/psnr.cpp).
std::vector<MetricEntry> PsnrMetrics();

}  // namespace aalab
