// Regression comparison of two reports: the rules (compare.h, docs/regression.md); exit
// codes as OpenImageIO's idiff (0 pass, 1 fail, 2 could not compare). The text:
// compare_text.cpp; the page: compare_page.cpp.
#include "reports/compare.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/exit_code.h"
#include "reports/compare_text.h"
#include "reports/html_page.h"

namespace aalab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct DirectionRule {
  const char* text;  // exact name, or pattern with one '*' at the start or end
  Better better;
};

// The explicit table (METRICS.md "better" column). Exact names first, then patterns.
constexpr DirectionRule kDirections[] = {
    {"psnr_db", Better::kHigher},          {"edge_psnr_db", Better::kHigher},
    {"interior_psnr_db", Better::kHigher}, {"ssim", Better::kHigher},
    {"edge_error_removed", Better::kHigher}, {"mse", Better::kLower},
    {"edge_rmse", Better::kLower},         {"temporal_rmse", Better::kLower},
    {"temporal_edge_rmse", Better::kLower}, {"temporal_perceptual", Better::kLower},
    {"temporal_csf_rmse", Better::kLower},  {"*_psnr_db", Better::kHigher},
    {"flip_*", Better::kLower},            {"abs_err_*", Better::kLower},
    {"area_bias_abs_rel", Better::kLower},
};

bool Matches(const std::string& pattern, const std::string& name) {
  if (pattern.front() == '*') {
    const std::string suffix = pattern.substr(1);
    return name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  }
  if (pattern.back() == '*') {
    const std::string prefix = pattern.substr(0, pattern.size() - 1);
    return name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0;
  }
  return pattern == name;
}

bool ParseNumber(const std::string& text, double* out) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return false;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

std::string RowName(const std::string& scene, const std::string& spec) { return scene + " / " + spec; }

struct MetricLookup {
  bool present = false;
  std::optional<double> value;
  std::string null_reason;
};

MetricLookup Lookup(const ResultRow& row, const std::string& name) {
  for (const auto& m : row.metrics) {
    if (m.name == name) return {true, m.value, m.value ? std::string() : (m.null_reason.empty() ? "no reason given" : m.null_reason)};
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

}  // namespace

std::optional<Better> MetricDirection(const std::string& name) {
  for (const auto& rule : kDirections) {
    if (Matches(rule.text, name)) return rule.better;
  }
  return std::nullopt;
}

std::string KnownMetricsText() {
  std::string higher, lower;
  for (const auto& rule : kDirections) {
    std::string& s = rule.better == Better::kHigher ? higher : lower;
    s += (s.empty() ? "" : ", ") + std::string(rule.text);
  }
  return higher + " (higher is better); " + lower + " (lower is better)";
}

bool IsDbMetric(const std::string& name) {
  return name.size() > 3 && name.compare(name.size() - 3, 3, "_db") == 0;
}

double Threshold::Allowed(double base) const { return relative ? value * std::fabs(base) : value; }

std::string Threshold::Text(const std::string& unit) const {
  char buf[64];
  if (relative) {
    std::snprintf(buf, sizeof buf, "%g%%", value * 100.0);
  } else {
    std::snprintf(buf, sizeof buf, "%g%s", value, unit.c_str());
  }
  return buf;
}

Threshold ParseMetricThreshold(const std::string& text, const std::string& what) {
  Threshold t;
  std::string num = text;
  if (!num.empty() && num.back() == '%') {
    t.relative = true;
    num.pop_back();
  }
  double v = 0;
  if (!ParseNumber(num, &v) || v < 0) {
    throw UserError(what + " '" + text + "' is not a non-negative number (absolute, e.g. 0.005) or percentage (relative to the baseline value, e.g. 2%)");
  }
  t.value = t.relative ? v / 100.0 : v;
  return t;
}

Threshold ParseTimeThreshold(const std::string& text, const std::string& what) {
  Threshold t;
  std::string num = text;
  if (!num.empty() && num.back() == '%') {
    t.relative = true;
    num.pop_back();
  } else if (num.size() > 2 && num.compare(num.size() - 2, 2, "ms") == 0) {
    num.resize(num.size() - 2);
  } else {
    throw UserError(what + " '" + text + "' needs a unit: a percentage of the baseline median (e.g. 10%) or milliseconds (e.g. 0.5ms), or 'off'");
  }
  double v = 0;
  if (!ParseNumber(num, &v) || v < 0) {
    throw UserError(what + " '" + text + "' is not a non-negative percentage (e.g. 10%) or duration (e.g. 0.5ms)");
  }
  t.value = t.relative ? v / 100.0 : v;
  return t;
}

std::map<std::string, Threshold> ParseMetricChangeOption(const std::string& text) {
  std::map<std::string, Threshold> out;
  if (text.find('=') == std::string::npos) {
    out["*"] = ParseMetricThreshold(text, "--max-metric-change");
    return out;
  }
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw UserError("--max-metric-change item '" + item + "' is not NAME=THRESHOLD (e.g. ssim=0.002,mse=5%)");
    }
    const std::string name = item.substr(0, eq);
    if (!MetricDirection(name)) {
      throw UserError("--max-metric-change: unknown metric '" + name + "' (known: " + KnownMetricsText() + ")");
    }
    if (IsDbMetric(name)) {
      throw UserError("--max-metric-change: '" + name + "' is in dB; its tolerance is --max-drop-db");
    }
    if (out.count(name)) throw UserError("--max-metric-change: metric '" + name + "' is given twice");
    out[name] = ParseMetricThreshold(item.substr(eq + 1), "--max-metric-change " + name);
  }
  if (!text.empty() && text.back() == ',') throw UserError("--max-metric-change '" + text + "' ends with a comma");
  return out;
}

bool HasDefaultTolerance(const std::string& metric) {
  return metric == "temporal_rmse" || metric == "temporal_perceptual" || metric == "temporal_csf_rmse" ||
         metric == "flip_mean";
}

void ValidateCompareOptions(const CompareOptions& o) {
  if (!std::isfinite(o.max_drop_db) || o.max_drop_db < 0) {
    throw UserError("--max-drop-db " + FormatFixed(o.max_drop_db, 3) + " must be a non-negative number of dB");
  }
  std::set<std::string> seen;
  for (const auto& m : o.metrics) {
    if (!MetricDirection(m)) {
      throw UserError("--metrics: unknown metric '" + m + "' (known: " + KnownMetricsText() + ")");
    }
    if (!seen.insert(m).second) throw UserError("--metrics: metric '" + m + "' is listed twice");
    if (!IsDbMetric(m) && !o.metric_change.count(m) && !o.metric_change.count("*") && !HasDefaultTolerance(m)) {
      throw UserError("--metrics: '" + m + "' is not in dB, so --max-drop-db does not apply; give its tolerance with "
                      "--max-metric-change (absolute, e.g. 0.005, or relative, e.g. 2%; per metric: " + m +
                      "=0.005) or leave it out of --metrics");
    }
  }
  for (const auto& [name, t] : o.metric_change) {
    if (o.metrics.empty()) {
      throw UserError("--max-metric-change applies to non-dB metrics, but no --metrics are given and the default "
                      "metrics (edge_psnr_db, psnr_db) are in dB");
    }
    if (name != "*" && !seen.count(name)) {
      throw UserError("--max-metric-change names '" + name + "', which --metrics does not compare");
    }
  }
  if (o.time_increase.value < 0 || !std::isfinite(o.time_increase.value)) {
    throw UserError("--max-time-increase must be non-negative");
  }
  if (!std::isfinite(o.warn_drop_db) || o.warn_drop_db < 0 || o.warn_drop_db > o.max_drop_db) {
    throw UserError("--warn-drop-db " + FormatFixed(o.warn_drop_db, 3) + " must be a number of dB from 0 to --max-drop-db (" +
                    FormatFixed(o.max_drop_db, 3) + ")");
  }
  if (!std::isfinite(o.time_floor_ms) || o.time_floor_ms < 0) {
    throw UserError("--time-floor must be a non-negative duration");
  }
  if (!o.check_time && o.fail_on != CompareOptions::FailOn::kQuality) {
    throw UserError(std::string("--fail-on ") + FailOnName(o.fail_on) +
                    " gates time, but --max-time-increase is off: give a time threshold or use --fail-on quality");
  }
}

CompareOptions::FailOn ParseFailOn(const std::string& text) {
  if (text == "quality") return CompareOptions::FailOn::kQuality;
  if (text == "time") return CompareOptions::FailOn::kTime;
  if (text == "any") return CompareOptions::FailOn::kAny;
  throw UserError("--fail-on '" + text + "' is not one of: quality (default), time, any");
}

const char* FailOnName(CompareOptions::FailOn f) {
  switch (f) {
    case CompareOptions::FailOn::kQuality: return "quality";
    case CompareOptions::FailOn::kTime: return "time";
    case CompareOptions::FailOn::kAny: return "any";
  }
  return "?";
}

// "name" or "name:k=v,k=v" (each override with exactly one '=').
static bool LooksLikeSpec(const std::string& s) {
  const auto colon = s.find(':');
  const std::string name = s.substr(0, colon);
  if (name.empty() || name.find('=') != std::string::npos || name.find(',') != std::string::npos) return false;
  if (colon == std::string::npos) return true;
  std::stringstream ss(s.substr(colon + 1));
  std::string item;
  int n = 0;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size() || item.find('=', eq + 1) != std::string::npos ||
        item.find(':') != std::string::npos) {
      return false;
    }
    ++n;
  }
  return n > 0 && s.back() != ',';
}

void AddSpecMapping(const std::string& text, std::map<std::string, std::string>* map) {
  // A spec may hold '=' itself (fxaa311-p39:subpix=0): the split is the one '=' that leaves
  // a well-formed spec on both sides.
  std::vector<size_t> splits;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '=' && LooksLikeSpec(text.substr(0, i)) && LooksLikeSpec(text.substr(i + 1))) splits.push_back(i);
  }
  if (splits.size() != 1) {
    throw UserError("--map '" + text + "' is not OLD=NEW (the baseline row's method spec, '=', the current row's; "
                    "e.g. fxaa311-p39=fxaa311-p39:subpix=0)");
  }
  const std::string from = text.substr(0, splits[0]), to = text.substr(splits[0] + 1);
  if (!map->emplace(from, to).second) throw UserError("--map: '" + from + "' is mapped twice");
}

const char* VerdictName(Verdict v) {
  switch (v) {
    case Verdict::kUnchanged: return "unchanged";
    case Verdict::kWithin: return "within";
    case Verdict::kImproved: return "improved";
    case Verdict::kRegression: return "REGRESSION";
    case Verdict::kNotJudged: return "not judged";
    case Verdict::kWarning: return "warning";
  }
  return "?";
}

bool IsQualityLine(const CompareLine& l) { return l.quantity != "time_ms"; }

int CompareResult::ExitCode() const {
  // The member's name hides the enum here: aalab::ExitCode is the type.
  if (!cannot_compare.empty() || !missing_rows.empty() || !extra_rows.empty()) {
    return ToInt(aalab::ExitCode::kCouldNotCompare);
  }
  const bool fail = regressions > 0 || (strict && !capture_warnings.empty());
  return ToInt(fail ? aalab::ExitCode::kFailure : aalab::ExitCode::kOk);
}

std::string SettingValue(const Report& report, const std::string& key) {
  for (const auto& [k, v] : report.settings) {
    if (k == key) return v;
  }
  return "";
}

Timing MethodTime(const ResultRow& row) {
  Timing t;
  const size_t n = std::max({row.render.samples_ms.size(), row.post.samples_ms.size(), row.resample.samples_ms.size()});
  auto at = [](const Timing& s, size_t i) { return i < s.samples_ms.size() ? s.samples_ms[i] : 0.0; };
  for (size_t i = 0; i < n; ++i) {
    t.samples_ms.push_back(at(row.post, i) + at(row.resample, i) + (row.render_shared ? 0.0 : at(row.render, i)));
  }
  t.Summarize();
  return t;
}

CompareResult CompareReports(const Report& base, const Report& cur, const CompareOptions& o) {
  CompareResult res;
  if (base.schema_version != cur.schema_version) {
    res.cannot_compare.push_back("schema_version differs: baseline " + std::to_string(base.schema_version) +
                                 ", current " + std::to_string(cur.schema_version));
  }
  for (const char* key : {"size", "ref_spp", "seed"}) {
    const std::string a = SettingValue(base, key), b = SettingValue(cur, key);
    if (a.empty() || b.empty()) {
      res.cannot_compare.push_back(std::string("setting '") + key + "' is missing from the " +
                                   (a.empty() ? "baseline" : "current") + " report");
    } else if (a != b) {
      res.cannot_compare.push_back(std::string("setting '") + key + "' differs: baseline " + a + ", current " + b +
                                   " (reports are comparable only when size, ref_spp and seed agree)");
    }
  }
  // Motion runs: the frame count (absent = 1, a still run) must agree too.
  {
    const std::string fa = SettingValue(base, "frames"), fb = SettingValue(cur, "frames");
    if ((fa.empty() ? "1" : fa) != (fb.empty() ? "1" : fb)) {
      res.cannot_compare.push_back("setting 'frames' differs: baseline " + (fa.empty() ? std::string("1") : fa) +
                                   ", current " + (fb.empty() ? std::string("1") : fb) +
                                   " (pooled and temporal metrics depend on the sequence length)");
    }
  }

  // The viewing condition (absent = the default, 67 px/deg at 60 fps, as before it existed):
  // FLIP and the perceptual temporal error depend on it.
  // The sampler (absent = gl) likewise: the post filters' texel arithmetic changes their outputs.
  for (const auto& [key, def] :
       {std::pair<const char*, const char*>{"ppd", "67"}, {"fps", "60"}, {"sampler", "gl"}}) {
    std::string a = SettingValue(base, key), b = SettingValue(cur, key);
    if (a.empty()) a = def;
    if (b.empty()) b = def;
    if (a != b) {
      res.cannot_compare.push_back(
          std::string("setting '") + key + "' differs: baseline " + a + ", current " + b +
          (std::string(key) == "sampler"
               ? " (the post filters' texel and bilinear arithmetic: gl and gpu-texture outputs differ by design, "
                 "not by regression; compare runs of one --sampler)"
               : " (FLIP and the perceptual temporal error depend on the viewing condition)"));
    }
  }

  if (base.rows.empty()) res.cannot_compare.push_back("the baseline report has no rows");
  if (cur.rows.empty()) res.cannot_compare.push_back("the current report has no rows");
  if (!res.cannot_compare.empty()) return res;

  // Metrics.
  if (o.metrics.empty()) {
    const bool edge_base = HasMetricEverywhere(base, "edge_psnr_db"), edge_cur = HasMetricEverywhere(cur, "edge_psnr_db");
    if (edge_base && edge_cur) {
      res.metrics = {"edge_psnr_db", "psnr_db"};
    } else {
      res.metrics = {"psnr_db"};
      if (edge_base || edge_cur) {
        res.notes.push_back(std::string("edge_psnr_db not compared: the ") + (edge_base ? "current" : "baseline") +
                            " report does not have it in every row (default metrics: edge_psnr_db and psnr_db when "
                            "both reports have them, else psnr_db)");
      }
    }
    // Motion runs (--frames > 1): the temporal error too, when both reports have it.
    if (HasMetricEverywhere(base, "temporal_rmse") && HasMetricEverywhere(cur, "temporal_rmse")) {
      res.metrics.push_back("temporal_rmse");
    }
    if (HasMetricEverywhere(base, "temporal_perceptual") && HasMetricEverywhere(cur, "temporal_perceptual")) {
      res.metrics.push_back("temporal_perceptual");
    }
  } else {
    res.metrics = o.metrics;
  }

  // Index rows; duplicates are ambiguous.
  auto index = [&res](const Report& r, const char* which) {
    std::map<std::pair<std::string, std::string>, int> idx;
    for (size_t i = 0; i < r.rows.size(); ++i) {
      const auto key = std::make_pair(r.rows[i].scene, r.rows[i].spec);
      if (!idx.emplace(key, static_cast<int>(i)).second) {
        res.cannot_compare.push_back(std::string("the ") + which + " report holds row " + RowName(key.first, key.second) +
                                     " twice");
      }
    }
    return idx;
  };
  const auto base_idx = index(base, "baseline");
  const auto cur_idx = index(cur, "current");
  // --map OLD=NEW: the baseline's OLD rows are matched with the current NEW rows.
  auto mapped = [&o](const std::string& spec) {
    auto it = o.map.find(spec);
    return it == o.map.end() ? spec : it->second;
  };
  for (const auto& [from, to] : o.map) {
    bool in_base = false, in_cur = false;
    for (const auto& row : base.rows) in_base = in_base || row.spec == from;
    for (const auto& row : cur.rows) in_cur = in_cur || row.spec == to;
    if (!in_base || !in_cur) {
      std::set<std::string> specs;
      for (const auto& row : (in_base ? cur : base).rows) specs.insert(row.spec);
      std::string list;
      for (const auto& x : specs) list += (list.empty() ? "" : ", ") + x;
      res.cannot_compare.push_back("--map " + from + "=" + to + ": the " + (in_base ? "current" : "baseline") +
                                   " report has no row of spec '" + (in_base ? to : from) + "' (its specs: " + list + ")");
    }
  }
  std::set<std::pair<std::string, std::string>> matched_cur;
  for (const auto& row : base.rows) {
    const auto key = std::make_pair(row.scene, mapped(row.spec));
    if (!cur_idx.count(key)) {
      res.missing_rows.push_back(RowName(row.scene, row.spec));
    } else {
      matched_cur.insert(key);
    }
  }
  for (const auto& row : cur.rows) {
    if (!matched_cur.count({row.scene, row.spec})) res.extra_rows.push_back(RowName(row.scene, row.spec));
  }
  for (const auto& sc : cur.scenes) {
    for (const auto& w : sc.warnings) res.capture_warnings.push_back(sc.name + ": " + w);
  }
  res.strict = o.strict;
  res.fail_on = o.fail_on;

  // Timing judged only on the same machine configuration.
  bool judge_time = o.check_time;
  if (o.check_time) {
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
    if (a != b) {
      if (o.time_across_machines) {
        res.notes.push_back("time judged across different machine configurations (--time-across-machines): baseline " + a +
                            "; current " + b);
      } else {
        judge_time = false;
        res.notes.push_back("time not judged: the reports come from different machine configurations (baseline " + a +
                            "; current " + b + "); pass --time-across-machines to judge it anyway");
      }
    }
  } else {
    res.notes.push_back("time not compared (--max-time-increase off)");
  }

  // Missing metrics: per (metric, side) the count and the first row.
  std::map<std::pair<std::string, std::string>, std::pair<int, std::string>> missing_metric;
  int bit_identical_value_changes = 0;
  std::string bit_identical_example;
  bool few_samples = false;

  const bool gate_quality = o.fail_on != CompareOptions::FailOn::kTime;
  const bool gate_time = o.fail_on != CompareOptions::FailOn::kQuality;
  std::set<std::string> mapped_notes;
  for (const auto& brow : base.rows) {
    const std::string cur_spec = mapped(brow.spec);
    auto it = cur_idx.find({brow.scene, cur_spec});
    if (it == cur_idx.end()) continue;
    const ResultRow& crow = cur.rows[static_cast<size_t>(it->second)];
    const std::string name = RowName(brow.scene, brow.spec) + (cur_spec == brow.spec ? "" : " -> " + cur_spec);
    const std::string pdiff = ParamsDiff(brow, crow);
    if (!pdiff.empty() && cur_spec == brow.spec) {
      res.cannot_compare.push_back("row " + name + ": resolved parameters differ (" + pdiff +
                                   "); the method's defaults changed, so the rows measure different settings (a "
                                   "deliberate change: compare them anyway with --map, or accept a new baseline)");
      continue;
    }
    if (cur_spec != brow.spec && mapped_notes.insert(brow.spec).second) {
      res.notes.push_back("mapped " + brow.spec + " (baseline) -> " + cur_spec + " (current)" +
                          (pdiff.empty() ? std::string(": same parameters") : ": parameters " + pdiff));
    }
    RowMatch match;
    match.scene = brow.scene;
    match.spec = cur_spec;
    match.base_spec = brow.spec;
    match.base_index = base_idx.at({brow.scene, brow.spec});
    match.current_index = it->second;
    match.bit_identical = !brow.output_hash.empty() && brow.output_hash == crow.output_hash;

    for (const auto& metric : res.metrics) {
      const MetricLookup a = Lookup(brow, metric), b = Lookup(crow, metric);
      bool skip = false;
      for (const auto& [side, look] : {std::make_pair("baseline", a), std::make_pair("current", b)}) {
        if (look.present) continue;
        auto& entry = missing_metric[{metric, side}];
        if (entry.first++ == 0) entry.second = name;
        skip = true;
      }
      if (skip) {
        continue;
      }
      const Better better = *MetricDirection(metric);
      CompareLine l;
      l.scene = brow.scene;
      l.spec = cur_spec;
      l.base_spec = brow.spec;
      l.gated = gate_quality;
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
          if (bit_identical_value_changes++ == 0) {
            bit_identical_example = name + " " + metric + " " + LineValueText(l, true) + " -> " + LineValueText(l, false);
          }
        }
      } else if (same_value) {
        l.verdict = Verdict::kUnchanged;
      } else if (l.base && l.current) {
        const double gain = better == Better::kHigher ? *l.current - *l.base : *l.base - *l.current;
        if (std::isinf(*l.base) && !std::isinf(*l.current)) {
          l.verdict = Verdict::kRegression;
          l.note = "baseline was identical to the reference (infinite PSNR)";
        } else if (std::isinf(*l.current) && !std::isinf(*l.base)) {
          l.verdict = Verdict::kImproved;
          l.note = "now identical to the reference (infinite PSNR)";
        } else {
          const double allowed = tol.Allowed(*l.base);
          l.verdict = gain == 0.0 ? Verdict::kUnchanged
                      : gain < -allowed ? Verdict::kRegression
                      : gain > allowed  ? Verdict::kImproved
                                        : Verdict::kWithin;
          if (l.verdict == Verdict::kWithin && gain < -warn.Allowed(*l.base)) {
            l.verdict = Verdict::kWarning;
            l.note = "worse beyond the warn level " + (IsDbMetric(metric) ? FormatFixed(o.warn_drop_db, 3) + " dB"
                                                                           : warn.Text());
          }
        }
      } else if (l.base && !l.current) {
        l.verdict = Verdict::kRegression;
        l.note = "became null: " + l.current_null;
      } else if (!l.base && l.current) {
        l.verdict = Verdict::kNotJudged;
        l.note = "was null (" + l.base_null + "), now a number";
      } else {
        l.verdict = Verdict::kRegression;
        l.note = "null reason changed: '" + l.base_null + "' -> '" + l.current_null + "'";
      }
      res.lines.push_back(l);
    }

    if (o.check_time) {
      const Timing ta = MethodTime(brow), tb = MethodTime(crow);
      if (ta.samples_ms.size() < 2 || tb.samples_ms.size() < 2) few_samples = true;
      CompareLine l;
      l.scene = brow.scene;
      l.spec = cur_spec;
      l.base_spec = brow.spec;
      l.gated = gate_time;
      l.quantity = "time_ms";
      l.base = ta.median_ms;
      l.current = tb.median_ms;
      l.delta = tb.median_ms - ta.median_ms;
      const double allowed = o.time_increase.Allowed(ta.median_ms);
      const double noise = (ta.max_ms - ta.min_ms) + (tb.max_ms - tb.min_ms);
      const double need = std::max({allowed, noise, o.time_floor_ms});
      l.threshold = "+" + o.time_increase.Text("ms") + (o.time_increase.relative ? " (" + FormatFixed(allowed, 3) + "ms)" : "") +
                    ", >spreads " + FormatFixed(noise, 3) + "ms, >floor " + FormatFixed(o.time_floor_ms, 3) +
                    "ms, ranges apart";
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
          l.note = d <= o.time_floor_ms ? "increase below the floor" : "increase within the runs' noise (spreads or overlapping ranges)";
        }
      }
      res.lines.push_back(l);
    }
    res.rows.push_back(match);
  }

  for (const auto& [key, entry] : missing_metric) {
    res.cannot_compare.push_back("metric '" + key.first + "' is missing from " + std::to_string(entry.first) + " " +
                                 key.second + " row(s), e.g. " + entry.second +
                                 " (a report written before the metric existed cannot be compared on it; choose "
                                 "--metrics present in both)");
  }
  if (bit_identical_value_changes > 0) {
    res.notes.push_back(std::to_string(bit_identical_value_changes) +
                        " value(s) of rows with bit-identical output differ (so the reference or a metric changed, "
                        "not the method); counted as unchanged. E.g. " + bit_identical_example);
  }
  if (o.check_time && !gate_time) {
    res.notes.push_back("time is shown, not gated (--fail-on quality, the default): a time change beyond the noise "
                        "test is a warning; gate it with --fail-on time or any");
  }
  if (few_samples && judge_time && gate_time) {
    res.notes.push_back("some rows have fewer than 2 timed repeats: their timing spread is 0, so any increase beyond "
                        "the threshold counts (run with --repeat 3 or more)");
  }

  // A regression on a line that is not gated is a warning.
  for (auto& l : res.lines) {
    if (l.verdict == Verdict::kRegression && !l.gated) {
      l.verdict = Verdict::kWarning;
      l.note = std::string("worse beyond the threshold, not gated (--fail-on ") + FailOnName(o.fail_on) + ")" +
               (l.note.empty() ? "" : "; " + l.note);
    }
  }
  // Per-row flags and totals.
  for (auto& m : res.rows) {
    for (const auto& l : res.lines) {
      if (l.scene != m.scene || l.spec != m.spec || l.base_spec != m.base_spec) continue;
      if (l.verdict == Verdict::kRegression) m.regression = true;
      if (l.verdict == Verdict::kRegression || l.verdict == Verdict::kImproved || l.verdict == Verdict::kWarning ||
          (IsQualityLine(l) && l.verdict != Verdict::kUnchanged)) {
        m.changed = true;
      }
    }
    // A row not applicable in both reports (a renderer-side method on an image scene) has no
    // output to differ.
    const bool both_na = !base.rows[m.base_index].not_applicable.empty() &&
                         !cur.rows[m.current_index].not_applicable.empty();
    if (!m.bit_identical && !both_na) m.changed = true;
  }
  for (const auto& l : res.lines) {
    if (l.verdict == Verdict::kRegression) ++res.regressions;
    if (l.verdict == Verdict::kImproved) ++res.improvements;
    if (l.verdict == Verdict::kWarning) ++res.warnings;
  }
  return res;
}

}  // namespace aalab
