#include "reports/sweep_result.h"

#include <cmath>
#include <cstdio>

#include "reports/html_page.h"

namespace aalab {

std::string JoinOverrides(const std::vector<std::pair<std::string, std::string>>& kv) {
  std::string s;
  for (const auto& [k, v] : kv) s += (s.empty() ? "" : ",") + k + "=" + v;
  return s;
}

std::string SweepValueText(const std::string& metric, double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (IsDbMetric(metric)) return FormatFixed(v, 3);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string SweepMeanText(const std::string& metric, const ObjectiveMean& m) {
  if (!m.mean) return "null (" + m.null_reason + ")";
  return SweepValueText(metric, *m.mean) + (IsDbMetric(metric) && std::isfinite(*m.mean) ? " dB" : "");
}

bool StrictlyBetter(const std::optional<double>& a, const std::optional<double>& b, Better better) {
  if (!a) return false;
  if (!b) return true;
  return better == Better::kHigher ? *a > *b : *a < *b;
}

}  // namespace aalab
