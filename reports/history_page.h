/// The offline trend page of `aalab history report` (DIR/index.html), drawn from the history
/// database (reports/history.h): inline SVG charts, no scripts, no external files.
#pragma once
#include <string>
#include <vector>

#include "reports/compare.h"
#include "reports/history.h"

namespace aalab {

/// What `history report` produced.
struct HistoryPage {
  std::string html;
  int series = 0, entries = 0, charts = 0;
  int regressions = 0, improvements = 0, cannot_compare = 0;  ///< over consecutive pairs
};

/// The offline trend page: per series and scene × method an inline-SVG chart each for
/// edge_psnr_db (when every entry has it), psnr_db and the method time (median, min–max
/// bar), with every point where CompareReports(previous, this, options) crossed a threshold
/// marked (red regression, green improvement, orange could not compare; the reason in the
/// point's tooltip and in a table). `only_series` empty: every series, else that one
/// (UserError when unknown). `options.metrics` is ignored (the charted metrics are used).
/// Entries are charted in date order; each chart of a dB metric spans at least 4× the
/// tolerance and shades ± tolerance around the latest value; time and other non-negative
/// quantities never get a negative axis. `options.map` (OLD → NEW) charts a renamed row as
/// one line and compares it across the rename. `out_dir` (the page's folder) is used to link
/// each entry's run page (index.html beside its report, when it exists).
HistoryPage HistoryHtml(const std::vector<HistoryEntry>& entries, const std::string& only_series,
                        const CompareOptions& options, const std::string& out_dir = "");

}  // namespace aalab
