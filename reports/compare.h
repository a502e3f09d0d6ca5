/// Regression comparison of two reports (`aalab compare`), shared by `aalab history`: the
/// rules. The text of a result: compare_text.h; its HTML page: compare_page.h.
///
/// Pure functions: no I/O except what the caller does with the results. The rules (also in
/// `aalab compare --help` and docs/regression.md):
///
/// - Reports are comparable when schema_version and the settings `size`, `ref_spp` and `seed`
///   agree. Otherwise nothing is compared (exit 2).
/// - Rows match by (scene, canonical spec). A matched pair whose resolved `params` differ
///   (e.g. a preset's defaults changed) is not compared: "could not compare" (exit 2). Rows
///   present in only one report are listed by name as missing / extra (exit 2). Duplicate
///   (scene, spec) rows in one report are an error (exit 2).
/// - Quality: each compared metric's "gain" is current − baseline for higher-is-better
///   metrics and baseline − current for lower-is-better ones. The tolerance is
///   `max_drop_db` for dB metrics (names ending in `_db`) and the metric's
///   `--max-metric-change` (absolute, or relative to |baseline|) otherwise. gain < −tol:
///   regression; gain > tol: improved; gain = 0: unchanged; otherwise changed within
///   tolerance. A null with reason `identical` on a higher-is-better metric is +infinity
///   (better than any number); a value that became null for another reason is a regression
///   with that reason. Rows with equal `output_hash` are unchanged for quality at once.
///   Warn level: a drop beyond `warn_drop_db` (dB metrics) or half the tolerance (others)
///   but within the tolerance is a warning (exit 0), as idiff's -warn below its -fail.
/// - Time: the method's own time per repeat (post + resample, plus render unless the render
///   is the 1x frame shared with `none`), median over repeats. increase = median_cur −
///   median_base; it is a regression only when it exceeds all of: the allowed increase (a
///   percentage of the baseline median, or milliseconds), the absolute floor `time_floor_ms`,
///   and the sum of both runs' spreads (max − min of their samples); AND the runs' ranges do
///   not overlap (the current run's fastest repeat is slower than the baseline's slowest).
///   Improvement symmetric. Time is judged only when both reports come from the same CPU
///   model, thread count and build type (else: not judged, with a note).
/// - Gating (`fail_on`): quality lines count towards exit 1 under kQuality and kAny, time
///   lines under kTime and kAny. A regression on a line that is not gated is reported as a
///   warning ("not gated"). Default: quality only, since quality is deterministic and
///   time on a shared machine is not.
/// - Renamed rows (`map`): a baseline row of spec OLD is matched with the current row of
///   spec NEW on the same scene; their parameters may differ (said in a note).
/// - Exit code: 2 when anything could not be compared (settings, missing/extra rows,
///   parameters, missing metrics), else 1 when a gated regression was found (or, with
///   `strict`, the current report has capture warnings), else 0.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reports/result.h"

namespace aalab {

/// Which way a metric improves.
enum class Better { kHigher, kLower };

/// Which way a metric improves, from the metric registry (metrics/metric.h MetricOutput):
/// image and sequence outputs. Empty for names no registered metric produces and for signed
/// biases (closer to 0 is better: area_bias_px2, area_bias_rel_r*), which compare cannot judge.
std::optional<Better> MetricDirection(const std::string& name);

/// The known names and patterns, for "allowed: ..." messages.
std::string KnownMetricsText();

/// True for metrics in decibels (the registry's unit "dB"; for names it does not know, a name
/// ending in `_db`): judged with --max-drop-db.
bool IsDbMetric(const std::string& name);

/// A tolerance: absolute (metric units or ms) or relative (fraction of the baseline).
struct Threshold {
  double value = 0.0;
  bool relative = false;
  /// The allowed change for a baseline value `base`.
  double Allowed(double base) const;
  /// "0.005", "2%", "1.5ms" (`unit` appended to absolute values).
  std::string Text(const std::string& unit = "") const;
};

/// Parses "0.005" (absolute) or "2%" (relative); negative or non-numeric values are a
/// UserError naming `what`.
Threshold ParseMetricThreshold(const std::string& text, const std::string& what);

/// Parses "10%" (relative) or "2ms" (absolute milliseconds); a bare number is a UserError
/// (the unit must be explicit). "off" is handled by the caller.
Threshold ParseTimeThreshold(const std::string& text, const std::string& what);

struct CompareOptions {
  double max_drop_db = 0.1;
  /// Metrics to compare; empty: edge_psnr_db and psnr_db when every row of both reports has
  /// edge_psnr_db, else psnr_db.
  std::vector<std::string> metrics;
  /// Tolerances for non-dB metrics, by name; the key "*" applies to every non-dB metric
  /// without its own entry.
  std::map<std::string, Threshold> metric_change;
  bool check_time = true;
  Threshold time_increase{0.10, true};
  /// Judge time even when the reports come from different machines / thread counts.
  bool time_across_machines = false;
  /// The absolute floor below which no time change counts, in milliseconds.
  double time_floor_ms = 0.5;
  /// Which lines make exit 1.
  enum class FailOn { kQuality, kTime, kAny } fail_on = FailOn::kQuality;
  /// The warn level for dB metrics (a drop beyond it but within max_drop_db is a warning);
  /// must not exceed max_drop_db. Non-dB metrics warn at half their tolerance.
  double warn_drop_db = 0.02;
  /// Fail (exit 1) when the current report's scenes carry capture warnings.
  bool strict = false;
  /// Renamed rows: baseline spec → current spec (`--map OLD=NEW`).
  std::map<std::string, std::string> map;
};

/// Parses --fail-on: quality, time or any. UserError otherwise.
CompareOptions::FailOn ParseFailOn(const std::string& text);
const char* FailOnName(CompareOptions::FailOn f);

/// Parses one --map value "OLD=NEW" into `map` (both non-empty; OLD given once). UserError
/// otherwise.
void AddSpecMapping(const std::string& text, std::map<std::string, std::string>* map);

/// Parses --max-metric-change: "0.005", "2%" (every non-dB metric) or
/// "ssim=0.002,mse=5%" (per metric; names must be known). UserError otherwise.
std::map<std::string, Threshold> ParseMetricChangeOption(const std::string& text);

/// True for the metrics compared with a default tolerance of 5 % of the baseline when
/// --max-metric-change does not name them: temporal_rmse, temporal_perceptual,
/// temporal_csf_rmse and flip_mean (so `--metrics edge_psnr_db,flip_mean` needs no more).
bool HasDefaultTolerance(const std::string& metric);

/// Checks the options: every metric is known (else the message lists the known ones),
/// listed once, and has a threshold (dB metrics: max_drop_db >= 0; others: an entry in
/// metric_change). Throws UserError.
void ValidateCompareOptions(const CompareOptions& options);

enum class Verdict {
  kUnchanged,   ///< equal (or bit-identical output)
  kWithin,      ///< changed, within the tolerance
  kImproved,    ///< better by more than the tolerance
  kRegression,  ///< worse by more than the tolerance
  kNotJudged,   ///< changed but no rule applies (timing across machines; null → number)
  kWarning,     ///< worse beyond the warn level but within the tolerance, or a regression not gated
};
const char* VerdictName(Verdict v);

/// One compared value of one matched row.
struct CompareLine {
  std::string scene, spec;
  std::string quantity;                 ///< metric name, or "time_ms"
  std::optional<double> base, current;  ///< +inf for a null `identical` on higher-is-better
  std::string base_null, current_null;  ///< null reasons ("" when a number)
  std::optional<double> delta;          ///< current − base (may be ±inf)
  std::string threshold;                ///< the rule applied, as text
  Verdict verdict = Verdict::kUnchanged;
  std::string note;       ///< why, when the numbers alone do not say
  std::string base_spec;  ///< the baseline row's spec (differs from spec under --map)
  bool gated = true;      ///< counts towards the exit code (CompareOptions::fail_on)
};

/// True for a metric's line, false for the time line ("time_ms").
bool IsQualityLine(const CompareLine& line);

/// A matched row pair.
struct RowMatch {
  std::string scene, spec;
  std::string base_spec;                     ///< the baseline row's spec (differs from spec under --map)
  int base_index = -1, current_index = -1;   ///< into the reports' rows
  bool bit_identical = false;                ///< equal output_hash
  bool regression = false, changed = false;  ///< any line regressed / any line not unchanged
};

struct CompareResult {
  std::vector<std::string> metrics;           ///< the metrics compared
  std::vector<std::string> cannot_compare;    ///< reasons for exit 2 (settings, params, metrics)
  std::vector<std::string> missing_rows;      ///< "scene / spec" only in the baseline
  std::vector<std::string> extra_rows;        ///< "scene / spec" only in the current report
  std::vector<std::string> notes;             ///< said once (timing not judged, noise unknown)
  std::vector<std::string> capture_warnings;  ///< "scene: warning" of the current report's scenes
  bool strict = false;                        ///< capture warnings fail (exit 1)
  CompareOptions::FailOn fail_on = CompareOptions::FailOn::kQuality;
  std::vector<RowMatch> rows;
  std::vector<CompareLine> lines;                       ///< every compared value, unchanged ones included
  int regressions = 0, improvements = 0, warnings = 0;  ///< regressions: gated ones only

  /// 2 could not compare (anything in cannot_compare / missing_rows / extra_rows), 1 at
  /// least one gated regression (or, strict, a capture warning), 0 otherwise (ExitCode,
  /// core/exit_code.h, as an int).
  int ExitCode() const;
};

/// Compares `current` against `baseline` with the rules above. Options must have passed
/// ValidateCompareOptions.
CompareResult CompareReports(const Report& baseline, const Report& current, const CompareOptions& options);

/// The method's own time per repeat: post + resample (+ render unless shared with `none`).
Timing MethodTime(const ResultRow& row);

/// Value of a report setting, or empty when absent.
std::string SettingValue(const Report& report, const std::string& key);

}  // namespace aalab
