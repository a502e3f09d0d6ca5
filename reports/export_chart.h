/// `aalab export`'s quality-vs-time chart as a stand-alone SVG: the HTML report's suite chart
/// (mean metric against mean time per frame on a log axis, Pareto front) drawn for print:
/// every point labelled, no script, fonts named, one series per report.
#pragma once
#include <string>
#include <vector>

#include "reports/export_source.h"

namespace aalab {

/// The chart of `sel.metric` over the chosen scenes of every source. `provenance` goes into a
/// comment and <metadata>. Points without a value or a time > 0 are listed in <desc>.
std::string QualityTimeChartSvg(const std::vector<ExportSource>& sources, const ExportSelection& sel,
                                const std::vector<std::string>& provenance);

}  // namespace aalab
