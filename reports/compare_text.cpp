#include "reports/compare_text.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "reports/html_page.h"

namespace aalab {

std::string CompareValueText(const std::string& quantity, double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (IsDbMetric(quantity)) return FormatFixed(v, 3);
  if (quantity == "time_ms") return FormatFixed(v, 3);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string CompareDeltaText(const std::string& quantity, double d) {
  if (std::isinf(d)) return d > 0 ? "+inf" : "-inf";
  std::string s = CompareValueText(quantity, d);
  if (d >= 0 && s.front() != '-') s = "+" + s;
  return s;
}

std::string LineValueText(const CompareLine& l, bool base) {
  const auto& v = base ? l.base : l.current;
  const std::string& reason = base ? l.base_null : l.current_null;
  if (v) {
    if (std::isinf(*v) && !reason.empty()) return "inf (" + reason + ")";
    return CompareValueText(l.quantity, *v);
  }
  return "null (" + reason + ")";
}

std::string FormatCompareText(const CompareResult& r, const Report& base, const Report& cur,
                              const std::string& base_name, const std::string& cur_name, bool all) {
  std::ostringstream out;
  auto describe = [](const Report& rep) {
    auto it = rep.context.find("git_commit");
    return "commit " + (it == rep.context.end() ? std::string("unknown") : it->second) + ", size " +
           SettingValue(rep, "size") + ", ref_spp " + SettingValue(rep, "ref_spp") + ", seed " +
           SettingValue(rep, "seed");
  };
  out << "baseline: " << base_name << " (" << describe(base) << ")\n";
  out << "current:  " << cur_name << " (" << describe(cur) << ")\n";

  // Table of changed values.
  std::vector<std::array<std::string, 8>> table;
  table.push_back({"scene", "method", "metric", "baseline", "current", "delta", "threshold", "verdict"});
  for (const auto& l : r.lines) {
    const bool show = all || l.verdict == Verdict::kRegression || l.verdict == Verdict::kImproved ||
                      l.verdict == Verdict::kWarning || (IsQualityLine(l) && l.verdict != Verdict::kUnchanged);
    if (!show) continue;
    std::string verdict = VerdictName(l.verdict);
    if (!l.note.empty()) verdict += ": " + l.note;
    const std::string spec = l.base_spec.empty() || l.base_spec == l.spec ? l.spec : l.base_spec + " -> " + l.spec;
    table.push_back({l.scene, spec, l.quantity, LineValueText(l, true), LineValueText(l, false),
                     l.delta ? CompareDeltaText(l.quantity, *l.delta) : "-", l.threshold, verdict});
  }
  if (table.size() > 1) {
    std::array<size_t, 8> w{};
    for (const auto& row : table) {
      for (size_t c = 0; c < 8; ++c) w[c] = std::max(w[c], row[c].size());
    }
    for (const auto& row : table) {
      std::string line;
      for (size_t c = 0; c < 8; ++c) {
        std::string cell = row[c];
        if (c + 1 < 8) cell.resize(w[c], ' ');
        line += cell + (c + 1 < 8 ? "  " : "");
      }
      out << line << "\n";
    }
  } else if (r.cannot_compare.empty() || !r.rows.empty()) {
    out << (all ? "no values compared\n" : "no changed values\n");
  }
  if (!r.cannot_compare.empty()) {
    out << "could not compare (" << r.cannot_compare.size() << "):\n";
    for (const auto& s : r.cannot_compare) out << "  " << s << "\n";
  }
  if (!r.missing_rows.empty()) {
    out << "missing from the current report (" << r.missing_rows.size() << " rows):\n";
    for (const auto& s : r.missing_rows) out << "  " << s << "\n";
  }
  if (!r.extra_rows.empty()) {
    out << "extra in the current report, not in the baseline (" << r.extra_rows.size() << " rows):\n";
    for (const auto& s : r.extra_rows) out << "  " << s << "\n";
  }
  for (const auto& n : r.notes) out << "note: " << n << "\n";
  if (!r.capture_warnings.empty()) {
    out << "capture warnings in the current report (" << r.capture_warnings.size() << ")"
        << (r.strict ? ", failing (--strict)" : ", not failing (pass --strict to fail on them)") << ":\n";
    for (const auto& w : r.capture_warnings) out << "  " << w << "\n";
  }
  int identical = 0;
  for (const auto& m : r.rows) identical += m.bit_identical ? 1 : 0;
  std::string metrics;
  for (const auto& m : r.metrics) metrics += (metrics.empty() ? "" : ", ") + m;
  const int code = r.ExitCode();
  out << "summary: " << r.rows.size() << " rows compared on " << (metrics.empty() ? "(none)" : metrics)
      << (r.lines.empty() || r.lines.back().quantity != "time_ms" ? "" : " and time") << " (" << identical
      << " bit-identical outputs); gating " << FailOnName(r.fail_on) << "; " << r.regressions << " regression(s), "
      << r.warnings << " warning(s), " << r.improvements << " improvement(s); exit " << code
      << (code == 0   ? " (no regression)"
          : code == 1 ? " (regression)"
                      : " (could not compare)")
      << "\n";
  return out.str();
}

}  // namespace aalab
