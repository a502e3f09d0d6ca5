/// Inline assets of the HTML report (internal to reports/): the stylesheet and the script,
/// as raw strings, and what the page knows about metrics (labels, units, direction).
#pragma once
#include <optional>
#include <string>

namespace aalab::html {

/// The page's stylesheet (inlined in <style>).
extern const char* const kStyle;

/// The page's script, in parts concatenated in this order into one inline <script>: shared
/// helpers and views, the charts and cost tables, the gallery and the self-test.
extern const char* const kScriptCore;
extern const char* const kScriptCharts;
extern const char* const kScriptGallery;

/// What the page says about a metric.
struct MetricInfo {
  std::string label;  ///< short column label ("Edge PSNR")
  std::string unit;   ///< "dB" or empty
  /// +1 higher is better, -1 lower is better, 0 unknown (then it is not offered as a chart
  /// axis: the page cannot say which way is better).
  int better = 0;
  std::string help;  ///< one sentence for the tooltip
};

/// Known metrics by name (metrics/METRICS.md); unknown names get a label equal to the name
/// and a direction guessed only from unambiguous suffixes (`_psnr_db`/`_db` higher,
/// `mse`/`rmse`/`_err` lower), else 0.
MetricInfo DescribeMetric(const std::string& name);

/// True for PSNR-type scores (`psnr_db` and `*_psnr_db`), which are checked against the
/// reference's noise floor.
bool IsPsnrMetric(const std::string& name);

}  // namespace aalab::html
