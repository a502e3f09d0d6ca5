/// Inline assets of the HTML report (internal to reports/): the stylesheet and the script,
/// as raw strings, and what the page says about metrics (labels, units, direction: read from
/// the metric registry, metrics/metric.h).
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace aalab::html {

/// One file of reports/html/ embedded into the binary at build time (reports/CMakeLists.txt
/// lists them; reports/html/embed_assets.cmake generates the table).
struct EmbeddedAsset {
  const char* name;  ///< file name under reports/html/ ("core.js")
  const char* data;  ///< its bytes, NUL-terminated
  std::size_t size;  ///< byte count without the NUL
};
extern const EmbeddedAsset kEmbeddedAssets[];
extern const std::size_t kEmbeddedAssetCount;

/// The bytes of the embedded file `name`; throws std::logic_error when no such file was
/// embedded (a build error, not user input).
std::string_view Asset(std::string_view name);

/// The run page's stylesheet (style.css, then abview.css; inlined in <style>).
std::string PageStyle();

/// What a plain page (compare, sweep) needs for its A/B views: abview.css in a <style> and
/// abview.js in a <script> that mounts every `.abview-host` element (its data-ab JSON:
/// {width, height, crops, choices: [{key, label, path?, crops?}], a, b}). Put it at the end of
/// the body.
std::string AbViewAssets();

/// The page's script: every embedded `.js` file in the order of reports/CMakeLists.txt, each
/// preceded by a newline, concatenated into one inline <script>.
std::string PageScript();

/// What the page says about a metric.
struct MetricInfo {
  std::string label;  ///< short column label ("Edge PSNR")
  std::string unit;   ///< "dB" or empty
  /// +1 higher is better, -1 lower is better, 0 unknown or a signed bias (closer to 0 is
  /// better; then it is not offered as a chart axis: neither end is better).
  int better = 0;
  std::string help;  ///< one sentence for the tooltip
  /// What a better score rewards and what it does not see (shown under the chart's axis
  /// choice; metrics/METRICS.md "What each metric rewards"); empty when unknown.
  std::string rewards;
};

/// What the metric registry says about `name` (metrics/metric.h MetricOutput, image and
/// sequence outputs); names no registered metric produces get a label equal to the name
/// and a direction guessed only from unambiguous suffixes (`_psnr_db`/`_db` higher,
/// `mse`/`rmse`/`_err` lower), else 0.
MetricInfo DescribeMetric(const std::string& name);

/// True for PSNR-type scores (`psnr_db` and `*_psnr_db`), which are checked against the
/// reference's noise floor.
bool IsPsnrMetric(const std::string& name);

}  // namespace aalab::html
