/// `aalab export`'s tables: methods × scenes for one metric, and the cost of accuracy, every
/// number taken from report.json; rendered as LaTeX (booktabs), Markdown and CSV
/// (docs/publishing.md).
#pragma once
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "reports/export_source.h"

namespace aalab {

/// One cell: the value as in report.json (or a mean/difference of such values), its text at
/// the column's precision, and whether it is the best of its column.
struct TableCell {
  std::optional<double> value;  ///< empty: "—" (the table's notes say why)
  std::string text;             ///< formatted, without markup; "" when empty
  bool best = false;
  /// A PSNR within 3 dB of the scene's reference noise floor (or above it): the method is
  /// indistinguishable from the reference at its sample count. Marked † (as ⚠ in the page).
  bool near_floor = false;
};

/// A table in a form every writer shares.
struct ExportTable {
  std::string caption;                     ///< plain text (writers escape it)
  std::string row_header;                  ///< header of the label column ("Method")
  std::vector<std::string> columns;        ///< data column headers, units included
  std::vector<std::string> column_groups;  ///< per data column: its group ("" = none), e.g. the run's label
  std::vector<std::string> row_labels;
  std::vector<std::string> row_groups;        ///< per row: its group ("" = none)
  std::vector<std::vector<TableCell>> cells;  ///< rows × columns
  std::vector<std::string> notes;             ///< sentences under the table (why a cell is empty, ...)
};

/// One method's point over the chosen scenes: the mean of the metric and of the median
/// time per frame over the scenes where every chosen method has a value (the HTML report's
/// suite means); empty when it has none (not applicable everywhere, or no such scene).
struct MeanPoint {
  std::string spec;
  std::optional<double> q, t;
};
/// The points of every chosen method of `src`, fastest first (points without a time last).
std::vector<MeanPoint> MeanPoints(const ExportSource& src, const ExportSelection& sel);
/// Specs on the Pareto front (as the page draws it): among points with a value and a time
/// > 0, sorted by time then quality, each point better than every faster one.
std::set<std::string> ParetoFront(const std::vector<MeanPoint>& pts, int better);

/// Methods × scenes of `sel.metric` (one column per scene and report; a "Mean" column per
/// report when more than one scene: the mean over the scenes where every chosen method has a
/// value, the HTML report's suite mean). Best per column by the metric's direction.
ExportTable MetricTable(const std::vector<ExportSource>& sources, const ExportSelection& sel);

/// The cost of accuracy over the chosen scenes' means (the HTML report's table): metric,
/// gain over `none`, time per frame, time added, gain per ms added (only when time added
/// > 0), Pareto front. Rows fastest first; one group of rows per report.
ExportTable CostTable(const std::vector<ExportSource>& sources, const ExportSelection& sel);

/// LaTeX: a table(*) float with a booktabs tabular, best in bold, caption, label
/// `tab:aalab-<id>`; `provenance` lines become % comments at the top; the tabular is scaled
/// down to \linewidth only when it is wider. Needs \usepackage{booktabs} and graphicx.
std::string TableToLatex(const ExportTable& t, const std::string& id, const std::vector<std::string>& provenance);
/// Markdown (GitHub pipe table), best in bold, caption above, notes below, provenance in an
/// HTML comment.
std::string TableToMarkdown(const ExportTable& t, const std::vector<std::string>& provenance);
/// CSV (RFC 4180 quoting): provenance and caption as leading `#` lines, a header row, one
/// row per table row with full-precision values (shortest round-trip form), empty for "—";
/// a last `best` row names the best row of each column.
std::string TableToCsv(const ExportTable& t, const std::vector<std::string>& provenance);

/// Escapes text for LaTeX (\ { } $ & # ^ _ % ~ and the dashes/Unicode the captions use).
std::string LatexEscape(const std::string& text);

}  // namespace aalab
