/// The offline page of `aalab sweep` (DIR/index.html): the best setting per objective, the
/// Pareto front of the first objective against method time and a heatmap per parameter pair
/// (inline SVG), and every point; no scripts, no external files.
#pragma once
#include <string>

#include "reports/sweep_result.h"

namespace aalab {

/// The whole page. Pure: same result, same bytes.
std::string SweepHtml(const SweepResult& result);

}  // namespace aalab
