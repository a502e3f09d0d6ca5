/// The offline page of `aalab sweep` (DIR/index.html): the best setting per objective, the
/// Pareto front of the first objective against method time and a heatmap per parameter pair
/// (inline SVG), every point, and per scene the crops of default / suggested / each objective's
/// pick / extremes as a table and in the shared A/B view (reports/html/abview.js: any two
/// columns, flip, the crop windows, pixel readout, |A − B|); no external files.
#pragma once
#include <string>

#include "reports/sweep_result.h"

namespace aalab {

/// The whole page. Pure: same result, same bytes.
std::string SweepHtml(const SweepResult& result);

}  // namespace aalab
