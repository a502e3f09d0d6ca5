// Regression comparison of two reports: the rules (compare.h, docs/regression.md); exit
// codes as OpenImageIO's idiff (0 pass, 1 fail, 2 could not compare). The text:
// compare_text.cpp; the page: compare_page.cpp; CompareReports itself, stage by stage:
// compare_judge.cpp.
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
#include "metrics/metric.h"
#include "reports/compare_text.h"
#include "reports/html_page.h"

namespace aalab {

namespace {

bool ParseNumber(const std::string& text, double* out) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return false;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

}  // namespace

std::optional<Better> MetricDirection(const std::string& name) {
  const MetricOutput* o = FindMetricOutput(name);  // the registry (metrics/metric.h)
  if (!o || o->better == Improves::kTowardZero) return std::nullopt;
  return o->better == Improves::kHigher ? Better::kHigher : Better::kLower;
}

std::string KnownMetricsText() {
  std::string higher, lower;
  for (const MetricEntry& e : MetricRegistry()) {
    for (const MetricOutput& o : e.outputs) {
      const std::optional<Better> b = MetricDirection(o.key);
      if (!b) continue;
      std::string& s = *b == Better::kHigher ? higher : lower;
      s += (s.empty() ? "" : ", ") + o.key;
    }
  }
  return higher + " (higher is better); " + lower + " (lower is better)";
}

bool IsDbMetric(const std::string& name) {
  if (const MetricOutput* o = FindMetricOutput(name)) return o->unit == "dB";
  return name.size() > 3 && name.compare(name.size() - 3, 3, "_db") == 0;  // another version's name
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
    throw UserError(what + " '" + text +
                    "' is not a non-negative number (absolute, e.g. 0.005) or percentage (relative to the baseline "
                    "value, e.g. 2%)");
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
    throw UserError(
        what + " '" + text +
        "' needs a unit: a percentage of the baseline median (e.g. 10%) or milliseconds (e.g. 0.5ms), or 'off'");
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
      throw UserError("--metrics: '" + m +
                      "' is not in dB, so --max-drop-db does not apply; give its tolerance with "
                      "--max-metric-change (absolute, e.g. 0.005, or relative, e.g. 2%; per metric: " +
                      m + "=0.005) or leave it out of --metrics");
    }
  }
  for (const auto& [name, t] : o.metric_change) {
    if (o.metrics.empty()) {
      throw UserError(
          "--max-metric-change applies to non-dB metrics, but no --metrics are given and the default "
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
    throw UserError("--warn-drop-db " + FormatFixed(o.warn_drop_db, 3) +
                    " must be a number of dB from 0 to --max-drop-db (" + FormatFixed(o.max_drop_db, 3) + ")");
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
    throw UserError("--map '" + text +
                    "' is not OLD=NEW (the baseline row's method spec, '=', the current row's; "
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

}  // namespace aalab
