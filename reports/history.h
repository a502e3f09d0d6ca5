/// Quality and time over commits (`aalab history`): a JSON-lines database, one line per
/// report (per-row metrics, timing samples, output hashes and parameters; no images), grouped
/// into named series whose run settings agree. Its offline HTML trend page: history_page.h.
///
/// Line format (history_version 1), keys in this order:
///   {"history_version":1, "series":S, "commit":C, "date":D, "source":PATH,
///    "settings":{...report settings...}, "context":{...report context...},
///    "rows":[{"scene","method","spec","params":{},"metrics":{},"null_reasons":{},
///             "output_hash","render_shared_with_none":bool,
///             "timing":{"render":[ms...],"post":[...],"resample":[...],"total":[...]}}]}
///   optionally followed by "accepted":{"by":WHO,"at":WHEN,"why":TEXT,"baseline":DIR}: the
///   report was accepted as the new baseline DIR (`aalab baseline accept`).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "reports/compare.h"
#include "reports/result.h"

namespace aalab {

constexpr int kHistoryVersion = 1;

/// One report in the database.
struct HistoryEntry {
  int line = 0;        ///< 1-based line in the file (0 before it is written)
  std::string series;  ///< series name
  std::string commit;  ///< git commit of the build that ran the report
  std::string date;    ///< when the report was made (ISO 8601, UTC)
  std::string source;  ///< path of the report file as given to `history add`
  Report report;       ///< settings, context and rows (no scenes, no images)
  /// Set when the report was accepted as a baseline (`aalab baseline accept`): who, when
  /// (UTC), why, and the baseline folder.
  struct Acceptance {
    std::string by, at, why, baseline;
  };
  std::optional<Acceptance> accepted;
};

/// The settings that must agree within a series.
const std::vector<std::string>& HistorySeriesKeys();

/// A report setting's value as the history shows it: the value, or "(absent)".
std::string HistorySettingText(const Report& report, const std::string& key);

/// Checks a series name: 1–64 characters from [A-Za-z0-9._-]. UserError otherwise.
void ValidateSeriesName(const std::string& name);

/// Checks a date: "YYYY-MM-DD" or "YYYY-MM-DDTHH:MM:SSZ". UserError otherwise.
void ValidateHistoryDate(const std::string& date);

/// Builds an entry from a report (images and scene details dropped). UserError when the
/// commit is empty or "unknown" (give one with --commit).
HistoryEntry HistoryEntryFromReport(const Report& report, const std::string& series, const std::string& commit,
                                    const std::string& date, const std::string& source);

/// The entry as one JSON line (no trailing newline). Non-finite numbers are an internal error.
std::string HistoryLine(const HistoryEntry& entry);

/// Parses a whole database. Every line (a final newline excepted) must be a valid entry:
/// a malformed or empty line is a UserError naming `origin` and the 1-based line number.
std::vector<HistoryEntry> ParseHistory(const std::string& text, const std::string& origin);

/// Reads and parses a database file; a missing file is a UserError unless `missing_ok`
/// (then: empty).
/// With `raw`, the file's text is stored there too (empty when the file is missing).
std::vector<HistoryEntry> ReadHistoryFile(const std::string& path, bool missing_ok, std::string* raw = nullptr);

/// Checks that `entry` may be appended: its settings (HistorySeriesKeys) equal those of the
/// series' last entry, no entry of the series has the same commit and date, and no entry of
/// any series holds the same report (equal context, rows, hashes and timing samples: the
/// same report.json added twice). UserError listing the differing settings and suggesting
/// --series NAME, or naming the line that holds the report, otherwise.
void CheckSeriesCompatible(const std::vector<HistoryEntry>& entries, const HistoryEntry& entry);

/// Series names in order of first appearance.
std::vector<std::string> HistorySeriesNames(const std::vector<HistoryEntry>& entries);

}  // namespace aalab
