/// The offline HTML page of `aalab compare --html` (reports/compare.h): the summary, missing
/// and extra rows, and per changed row its lines, its images and (given the current report)
/// the shared A/B view (reports/html/abview.js): any two of the row's baseline and current
/// outputs, the reference and the other changed rows of its scene, with flip, crop zoom,
/// pixel readout and |A − B|.
#pragma once
#include <string>
#include <vector>

#include "reports/compare.h"
#include "reports/result.h"

namespace aalab {

/// One image shown on the HTML page.
struct HtmlImage {
  std::string label;    ///< "baseline output", "current output", "reference"
  std::string source;   ///< path of the image as the report names it, joined to its folder
  std::string href;     ///< path relative to the HTML file; empty when not available
  std::string missing;  ///< why it is not shown (when href is empty)
};

/// The images to show per changed row, in the order of result.rows filtered to changed or
/// regressed rows: baseline output, current output, reference (current report's
/// `reference_png`). `href` is left for the caller, who copies the files.
std::vector<std::vector<HtmlImage>> CompareHtmlImages(const CompareResult& result, const Report& baseline,
                                                      const Report& current, const std::string& baseline_dir,
                                                      const std::string& current_dir);

/// The offline HTML page: summary, missing/extra rows, and per changed row its lines and
/// images side by side (`images` as returned by CompareHtmlImages with hrefs filled); with
/// `current` (the current report: scene sizes and crop windows) an A/B view per changed row.
std::string CompareHtml(const CompareResult& result, const std::vector<std::vector<HtmlImage>>& images,
                        const std::string& baseline_name, const std::string& current_name,
                        const Report* current = nullptr);

/// Indices (into result.rows) of the rows shown on the HTML page: rows with a regression
/// first, then other changed rows, in report order.
std::vector<size_t> ChangedRowOrder(const CompareResult& result);

}  // namespace aalab
