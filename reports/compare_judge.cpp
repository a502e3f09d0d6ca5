// CompareReports (compare.h): two reports judged line by line, as a short sequence of named
// stages — can they be compared, which metrics, which rows match, is time judged, each row's
// lines, the closing notes, the totals. The rules themselves: docs/regression.md; thresholds,
// options and metric directions: compare.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "core/error.h"
#include "reports/compare.h"
#include "reports/compare_text.h"
#include "reports/html_page.h"

namespace aalab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string RowName(const std::string& scene, const std::string& spec) { return scene + " / " + spec; }

struct MetricLookup {
  bool present = false;
  std::optional<double> value;
  std::string null_reason;
};

MetricLookup Lookup(const ResultRow& row, const std::string& name) {
  for (const auto& m : row.metrics) {
    if (m.name == name)
      return {true, m.value, m.value ? std::string() : (m.null_reason.empty() ? "no reason given" : m.null_reason)};
  }
  return {};
}

bool HasMetricEverywhere(const Report& r, const std::string& name) {
  for (const auto& row : r.rows) {
    if (!Lookup(row, name).present) return false;
  }
  return !r.rows.empty();
}

std::string ParamsDiff(const ResultRow& a, const ResultRow& b) {
  std::map<std::string, std::string> ma(a.params.begin(), a.params.end()), mb(b.params.begin(), b.params.end());
  std::vector<std::string> parts;
  for (const auto& [k, v] : ma) {
    auto it = mb.find(k);
    if (it == mb.end()) {
      parts.push_back(k + " " + v + " -> (absent)");
    } else if (it->second != v) {
      parts.push_back(k + " " + v + " -> " + it->second);
    }
  }
  for (const auto& [k, v] : mb) {
    if (!ma.count(k)) parts.push_back(k + " (absent) -> " + v);
  }
  std::string s;
  for (size_t i = 0; i < parts.size(); ++i) s += (i ? ", " : "") + parts[i];
  return s;
}

/// The spec a baseline row is matched with in the current report (--map OLD=NEW, else itself).
std::string Mapped(const CompareOptions& o, const std::string& spec) {
  auto it = o.map.find(spec);
  return it == o.map.end() ? spec : it->second;
}

/// Stage 1: the settings that make two reports comparable (schema, size, ref_spp, seed, frames,
/// viewing condition, sampler) and that both have rows. Adds to `cannot_compare`.
void CheckComparable(const Report& base, const Report& cur, CompareResult* res) {
  if (base.schema_version != cur.schema_version) {
    res->cannot_compare.push_back("schema_version differs: baseline " + std::to_string(base.schema_version) +
                                  ", current " + std::to_string(cur.schema_version));
  }
  for (const char* key : {"size", "ref_spp", "seed"}) {
    const std::string a = SettingValue(base, key), b = SettingValue(cur, key);
    if (a.empty() || b.empty()) {
      res->cannot_compare.push_back(std::string("setting '") + key + "' is missing from the " +
                                    (a.empty() ? "baseline" : "current") + " report");
    } else if (a != b) {
      res->cannot_compare.push_back(std::string("setting '") + key + "' differs: baseline " + a + ", current " + b +
                                    " (reports are comparable only when size, ref_spp and seed agree)");
    }
  }
  // Motion runs: the frame count (absent = 1, a still run) must agree too.
  {
    const std::string fa = SettingValue(base, "frames"), fb = SettingValue(cur, "frames");
    if ((fa.empty() ? "1" : fa) != (fb.empty() ? "1" : fb)) {
      res->cannot_compare.push_back("setting 'frames' differs: baseline " + (fa.empty() ? std::string("1") : fa) +
                                    ", current " + (fb.empty() ? std::string("1") : fb) +
                                    " (pooled and temporal metrics depend on the sequence length)");
    }
  }
  // The viewing condition (absent = the default, 67 px/deg at 60 fps, as before it existed):
  // FLIP and the perceptual temporal error depend on it.
  // The sampler (absent = gl) likewise: the post filters' texel arithmetic changes their outputs.
  for (const auto& [key, def] : {std::pair<const char*, const char*>{"ppd", "67"}, {"fps", "60"}, {"sampler", "gl"}}) {
    std::string a = SettingValue(base, key), b = SettingValue(cur, key);
    if (a.empty()) a = def;
    if (b.empty()) b = def;
    if (a != b) {
      res->cannot_compare.push_back(
          std::string("setting '") + key + "' differs: baseline " + a + ", current " + b +
          (std::string(key) == "sampler"
               ? " (the post filters' texel and bilinear arithmetic: gl and gpu-texture outputs differ by design, "
                 "not by regression; compare runs of one --sampler)"
               : " (FLIP and the perceptual temporal error depend on the viewing condition)"));
    }
  }
  if (base.rows.empty()) res->cannot_compare.push_back("the baseline report has no rows");
  if (cur.rows.empty()) res->cannot_compare.push_back("the current report has no rows");
}

/// Stage 2: the metrics compared — the options' list, else edge_psnr_db and psnr_db when both
/// reports have them in every row (else psnr_db), plus the temporal errors of motion runs.
void ChooseMetrics(const Report& base, const Report& cur, const CompareOptions& o, CompareResult* res) {
  if (!o.metrics.empty()) {
    res->metrics = o.metrics;
    return;
  }
  const bool edge_base = HasMetricEverywhere(base, "edge_psnr_db"), edge_cur = HasMetricEverywhere(cur, "edge_psnr_db");
  if (edge_base && edge_cur) {
    res->metrics = {"edge_psnr_db", "psnr_db"};
  } else {
    res->metrics = {"psnr_db"};
    if (edge_base || edge_cur) {
      res->notes.push_back(std::string("edge_psnr_db not compared: the ") + (edge_base ? "current" : "baseline") +
                           " report does not have it in every row (default metrics: edge_psnr_db and psnr_db when "
                           "both reports have them, else psnr_db)");
    }
  }
  // Motion runs (--frames > 1): the temporal error too, when both reports have it.
  for (const char* temporal : {"temporal_rmse", "temporal_perceptual"}) {
    if (HasMetricEverywhere(base, temporal) && HasMetricEverywhere(cur, temporal)) res->metrics.push_back(temporal);
  }
}

using RowIndex = std::map<std::pair<std::string, std::string>, int>;  // (scene, spec) -> row

/// The rows of `r` by (scene, spec); a row held twice is ambiguous (cannot compare).
RowIndex IndexRows(const Report& r, const char* which, CompareResult* res) {
  RowIndex idx;
  for (size_t i = 0; i < r.rows.size(); ++i) {
    const auto key = std::make_pair(r.rows[i].scene, r.rows[i].spec);
    if (!idx.emplace(key, static_cast<int>(i)).second) {
      res->cannot_compare.push_back(std::string("the ") + which + " report holds row " +
                                    RowName(key.first, key.second) + " twice");
    }
  }
  return idx;
}

/// Stage 3: rows matched (through --map), each --map pair checked, rows found on one side only,
/// and the current report's capture warnings.
void MatchRows(const Report& base, const Report& cur, const RowIndex& cur_idx, const CompareOptions& o,
               CompareResult* res) {
  for (const auto& [from, to] : o.map) {
    bool in_base = false, in_cur = false;
    for (const auto& row : base.rows) in_base = in_base || row.spec == from;
    for (const auto& row : cur.rows) in_cur = in_cur || row.spec == to;
    if (!in_base || !in_cur) {
      std::set<std::string> specs;
      for (const auto& row : (in_base ? cur : base).rows) specs.insert(row.spec);
      std::string list;
      for (const auto& x : specs) list += (list.empty() ? "" : ", ") + x;
      res->cannot_compare.push_back("--map " + from + "=" + to + ": the " + (in_base ? "current" : "baseline") +
                                    " report has no row of spec '" + (in_base ? to : from) + "' (its specs: " + list +
                                    ")");
    }
  }
  std::set<std::pair<std::string, std::string>> matched_cur;
  for (const auto& row : base.rows) {
    const auto key = std::make_pair(row.scene, Mapped(o, row.spec));
    if (!cur_idx.count(key)) {
      res->missing_rows.push_back(RowName(row.scene, row.spec));
    } else {
      matched_cur.insert(key);
    }
  }
  for (const auto& row : cur.rows) {
    if (!matched_cur.count({row.scene, row.spec})) res->extra_rows.push_back(RowName(row.scene, row.spec));
  }
  for (const auto& sc : cur.scenes) {
    for (const auto& w : sc.warnings) res->capture_warnings.push_back(sc.name + ": " + w);
  }
}

/// Stage 4: whether time is judged — asked for, and on the same machine configuration (or
/// --time-across-machines). Says why in `notes` when it is not.
bool TimeIsJudged(const Report& base, const Report& cur, const CompareOptions& o, CompareResult* res) {
  if (!o.check_time) {
    res->notes.push_back("time not compared (--max-time-increase off)");
    return false;
  }
  auto ctx = [](const Report& r, const std::string& k) {
    auto it = r.context.find(k);
    return it == r.context.end() ? std::string("unknown") : it->second;
  };
  auto threads = [&](const Report& r) {
    const std::string s = SettingValue(r, "threads");
    return s.empty() ? ctx(r, "threads") : s;
  };
  const std::string a = "cpu '" + ctx(base, "cpu") + "', " + threads(base) + " threads, " + ctx(base, "build_type");
  const std::string b = "cpu '" + ctx(cur, "cpu") + "', " + threads(cur) + " threads, " + ctx(cur, "build_type");
  if (a == b) return true;
  if (o.time_across_machines) {
    res->notes.push_back("time judged across different machine configurations (--time-across-machines): baseline " + a +
                         "; current " + b);
    return true;
  }
  res->notes.push_back("time not judged: the reports come from different machine configurations (baseline " + a +
                       "; current " + b + "); pass --time-across-machines to judge it anyway");
  return false;
}

/// What the row loop gathers for the closing notes.
struct Tally {
  std::map<std::pair<std::string, std::string>, std::pair<int, std::string>> missing_metric;  ///< (metric, side)
  int bit_identical_value_changes = 0;
  std::string bit_identical_example;
  bool few_samples = false;
};

/// The verdict of a metric line whose values differ and whose output is not bit-identical.
void JudgeMetricValues(const CompareOptions& o, const std::string& metric, Better better, const Threshold& tol,
                       const Threshold& warn, CompareLine* l) {
  if (l->base && l->current) {
    const double gain = better == Better::kHigher ? *l->current - *l->base : *l->base - *l->current;
    if (std::isinf(*l->base) && !std::isinf(*l->current)) {
      l->verdict = Verdict::kRegression;
      l->note = "baseline was identical to the reference (infinite PSNR)";
    } else if (std::isinf(*l->current) && !std::isinf(*l->base)) {
      l->verdict = Verdict::kImproved;
      l->note = "now identical to the reference (infinite PSNR)";
    } else {
      const double allowed = tol.Allowed(*l->base);
      l->verdict = gain == 0.0       ? Verdict::kUnchanged
                   : gain < -allowed ? Verdict::kRegression
                   : gain > allowed  ? Verdict::kImproved
                                     : Verdict::kWithin;
      if (l->verdict == Verdict::kWithin && gain < -warn.Allowed(*l->base)) {
        l->verdict = Verdict::kWarning;
        l->note = "worse beyond the warn level " +
                  (IsDbMetric(metric) ? FormatFixed(o.warn_drop_db, 3) + " dB" : warn.Text());
      }
    }
  } else if (l->base && !l->current) {
    l->verdict = Verdict::kRegression;
    l->note = "became null: " + l->current_null;
  } else if (!l->base && l->current) {
    l->verdict = Verdict::kNotJudged;
    l->note = "was null (" + l->base_null + "), now a number";
  } else {
    l->verdict = Verdict::kRegression;
    l->note = "null reason changed: '" + l->base_null + "' -> '" + l->current_null + "'";
  }
}

/// One metric's line of a matched row; nothing when either side lacks the metric (tallied).
std::optional<CompareLine> MetricLine(const ResultRow& brow, const ResultRow& crow, const RowMatch& match,
                                      const std::string& name, const std::string& metric, const CompareOptions& o,
                                      Tally* tally) {
  const MetricLookup a = Lookup(brow, metric), b = Lookup(crow, metric);
  bool skip = false;
  for (const auto& [side, look] : {std::make_pair("baseline", a), std::make_pair("current", b)}) {
    if (look.present) continue;
    auto& entry = tally->missing_metric[{metric, side}];
    if (entry.first++ == 0) entry.second = name;
    skip = true;
  }
  if (skip) return std::nullopt;
  const Better better = *MetricDirection(metric);
  CompareLine l;
  l.scene = match.scene;
  l.spec = match.spec;
  l.base_spec = match.base_spec;
  l.gated = o.fail_on != CompareOptions::FailOn::kTime;
  l.quantity = metric;
  l.base = a.value;
  l.current = b.value;
  l.base_null = a.null_reason;
  l.current_null = b.null_reason;
  // Identical images: infinite PSNR, better than any number.
  if (better == Better::kHigher) {
    if (!l.base && a.null_reason == "identical") l.base = kInf;
    if (!l.current && b.null_reason == "identical") l.current = kInf;
  }
  Threshold tol, warn;
  if (IsDbMetric(metric)) {
    tol = Threshold{o.max_drop_db, false};
    warn = Threshold{o.warn_drop_db, false};
    l.threshold = (better == Better::kHigher ? "-" : "+") + FormatFixed(o.max_drop_db, 3) + " dB";
  } else {
    auto t = o.metric_change.find(metric);
    if (t == o.metric_change.end()) t = o.metric_change.find("*");
    if (t == o.metric_change.end() && HasDefaultTolerance(metric)) {
      tol = Threshold{0.05, true};  // the perceptual and temporal measures: 5% of the baseline
    } else {
      AALAB_CHECK(t != o.metric_change.end(), "validated options must give every non-dB metric a tolerance");
      tol = t->second;
    }
    warn = Threshold{tol.value / 2, tol.relative};
    l.threshold = (better == Better::kHigher ? "-" : "+") + tol.Text();
  }
  const bool same_value = (l.base == l.current) && (l.base_null == l.current_null);
  if (l.base && l.current) {
    const double d = *l.current - *l.base;
    l.delta = std::isnan(d) ? 0.0 : d;  // inf − inf: both identical
  }
  if (match.bit_identical) {
    l.verdict = Verdict::kUnchanged;
    if (!same_value) {
      l.note = "output bit-identical; value differs (the reference or the metric changed, not the method)";
      if (tally->bit_identical_value_changes++ == 0) {
        tally->bit_identical_example =
            name + " " + metric + " " + LineValueText(l, true) + " -> " + LineValueText(l, false);
      }
    }
  } else if (same_value) {
    l.verdict = Verdict::kUnchanged;
  } else {
    JudgeMetricValues(o, metric, better, tol, warn, &l);
  }
  return l;
}

/// The time line of a matched row: a regression only beyond the threshold, both runs' spreads
/// and the floor, with the two ranges apart.
CompareLine TimeLine(const ResultRow& brow, const ResultRow& crow, const RowMatch& match, const CompareOptions& o,
                     bool judge_time, Tally* tally) {
  const Timing ta = MethodTime(brow), tb = MethodTime(crow);
  if (ta.samples_ms.size() < 2 || tb.samples_ms.size() < 2) tally->few_samples = true;
  CompareLine l;
  l.scene = match.scene;
  l.spec = match.spec;
  l.base_spec = match.base_spec;
  l.gated = o.fail_on != CompareOptions::FailOn::kQuality;
  l.quantity = "time_ms";
  l.base = ta.median_ms;
  l.current = tb.median_ms;
  l.delta = tb.median_ms - ta.median_ms;
  const double allowed = o.time_increase.Allowed(ta.median_ms);
  const double noise = (ta.max_ms - ta.min_ms) + (tb.max_ms - tb.min_ms);
  const double need = std::max({allowed, noise, o.time_floor_ms});
  l.threshold = "+" + o.time_increase.Text("ms") +
                (o.time_increase.relative ? " (" + FormatFixed(allowed, 3) + "ms)" : "") + ", >spreads " +
                FormatFixed(noise, 3) + "ms, >floor " + FormatFixed(o.time_floor_ms, 3) + "ms, ranges apart";
  const double d = *l.delta;
  const bool slower_apart = tb.min_ms > ta.max_ms, faster_apart = tb.max_ms < ta.min_ms;
  if (d == 0.0) {
    l.verdict = Verdict::kUnchanged;
  } else if (!judge_time) {
    l.verdict = Verdict::kNotJudged;
  } else if (d > need && slower_apart) {
    l.verdict = Verdict::kRegression;
  } else if (-d > need && faster_apart) {
    l.verdict = Verdict::kImproved;
  } else {
    l.verdict = Verdict::kWithin;
    if (d > allowed) {
      l.note = d <= o.time_floor_ms ? "increase below the floor"
                                    : "increase within the runs' noise (spreads or overlapping ranges)";
    }
  }
  return l;
}

/// Stage 5: every baseline row with a match in the current report — its parameters checked,
/// its metric lines and time line judged.
void CompareRows(const Report& base, const Report& cur, const RowIndex& base_idx, const RowIndex& cur_idx,
                 const CompareOptions& o, bool judge_time, Tally* tally, CompareResult* res) {
  std::set<std::string> mapped_notes;
  for (const auto& brow : base.rows) {
    const std::string cur_spec = Mapped(o, brow.spec);
    auto it = cur_idx.find({brow.scene, cur_spec});
    if (it == cur_idx.end()) continue;
    const ResultRow& crow = cur.rows[static_cast<size_t>(it->second)];
    const std::string name = RowName(brow.scene, brow.spec) + (cur_spec == brow.spec ? "" : " -> " + cur_spec);
    const std::string pdiff = ParamsDiff(brow, crow);
    if (!pdiff.empty() && cur_spec == brow.spec) {
      res->cannot_compare.push_back("row " + name + ": resolved parameters differ (" + pdiff +
                                    "); the method's defaults changed, so the rows measure different settings (a "
                                    "deliberate change: compare them anyway with --map, or accept a new baseline)");
      continue;
    }
    if (cur_spec != brow.spec && mapped_notes.insert(brow.spec).second) {
      res->notes.push_back("mapped " + brow.spec + " (baseline) -> " + cur_spec + " (current)" +
                           (pdiff.empty() ? std::string(": same parameters") : ": parameters " + pdiff));
    }
    RowMatch match;
    match.scene = brow.scene;
    match.spec = cur_spec;
    match.base_spec = brow.spec;
    match.base_index = base_idx.at({brow.scene, brow.spec});
    match.current_index = it->second;
    match.bit_identical = !brow.output_hash.empty() && brow.output_hash == crow.output_hash;
    for (const auto& metric : res->metrics) {
      if (auto line = MetricLine(brow, crow, match, name, metric, o, tally)) res->lines.push_back(*line);
    }
    if (o.check_time) res->lines.push_back(TimeLine(brow, crow, match, o, judge_time, tally));
    res->rows.push_back(match);
  }
}

/// Stage 6: what the row loop found, said once.
void AddClosingNotes(const CompareOptions& o, bool judge_time, const Tally& tally, CompareResult* res) {
  for (const auto& [key, entry] : tally.missing_metric) {
    res->cannot_compare.push_back("metric '" + key.first + "' is missing from " + std::to_string(entry.first) + " " +
                                  key.second + " row(s), e.g. " + entry.second +
                                  " (a report written before the metric existed cannot be compared on it; choose "
                                  "--metrics present in both)");
  }
  if (tally.bit_identical_value_changes > 0) {
    res->notes.push_back(std::to_string(tally.bit_identical_value_changes) +
                         " value(s) of rows with bit-identical output differ (so the reference or a metric changed, "
                         "not the method); counted as unchanged. E.g. " +
                         tally.bit_identical_example);
  }
  const bool gate_time = o.fail_on != CompareOptions::FailOn::kQuality;
  if (o.check_time && !gate_time) {
    res->notes.push_back(
        "time is shown, not gated (--fail-on quality, the default): a time change beyond the noise "
        "test is a warning; gate it with --fail-on time or any");
  }
  if (tally.few_samples && judge_time && gate_time) {
    res->notes.push_back(
        "some rows have fewer than 2 timed repeats: their timing spread is 0, so any increase beyond "
        "the threshold counts (run with --repeat 3 or more)");
  }
}

/// Stage 7: ungated regressions become warnings; each row's flags; the totals.
void Totals(const Report& base, const Report& cur, const CompareOptions& o, CompareResult* res) {
  for (auto& l : res->lines) {
    if (l.verdict == Verdict::kRegression && !l.gated) {
      l.verdict = Verdict::kWarning;
      l.note = std::string("worse beyond the threshold, not gated (--fail-on ") + FailOnName(o.fail_on) + ")" +
               (l.note.empty() ? "" : "; " + l.note);
    }
  }
  for (auto& m : res->rows) {
    for (const auto& l : res->lines) {
      if (l.scene != m.scene || l.spec != m.spec || l.base_spec != m.base_spec) continue;
      if (l.verdict == Verdict::kRegression) m.regression = true;
      if (l.verdict == Verdict::kRegression || l.verdict == Verdict::kImproved || l.verdict == Verdict::kWarning ||
          (IsQualityLine(l) && l.verdict != Verdict::kUnchanged)) {
        m.changed = true;
      }
    }
    // A row not applicable in both reports (a renderer-side method on an image scene) has no
    // output to differ.
    const bool both_na =
        !base.rows[m.base_index].not_applicable.empty() && !cur.rows[m.current_index].not_applicable.empty();
    if (!m.bit_identical && !both_na) m.changed = true;
  }
  for (const auto& l : res->lines) {
    if (l.verdict == Verdict::kRegression) ++res->regressions;
    if (l.verdict == Verdict::kImproved) ++res->improvements;
    if (l.verdict == Verdict::kWarning) ++res->warnings;
  }
}

}  // namespace

CompareResult CompareReports(const Report& base, const Report& cur, const CompareOptions& o) {
  CompareResult res;
  CheckComparable(base, cur, &res);
  if (!res.cannot_compare.empty()) return res;
  ChooseMetrics(base, cur, o, &res);
  const RowIndex base_idx = IndexRows(base, "baseline", &res);
  const RowIndex cur_idx = IndexRows(cur, "current", &res);
  MatchRows(base, cur, cur_idx, o, &res);
  res.strict = o.strict;
  res.fail_on = o.fail_on;
  const bool judge_time = TimeIsJudged(base, cur, o, &res);
  Tally tally;
  CompareRows(base, cur, base_idx, cur_idx, o, judge_time, &tally, &res);
  AddClosingNotes(o, judge_time, tally, &res);
  Totals(base, cur, o, &res);
  return res;
}

}  // namespace aalab
