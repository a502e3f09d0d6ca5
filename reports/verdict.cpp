// The per-scene verdict (reports/verdict.h): pure functions of the result rows.
#include "reports/verdict.h"
#include "core/format.h"

#include <cmath>
#include <cstdio>

namespace aalab {

namespace {

std::string FmtMs(double v) { return FormatDouble(v < 1 ? "%.3f" : v < 100 ? "%.2f" : "%.1f", v); }

const MetricResult* Find(const ResultRow& row, const std::string& name) {
  for (const auto& m : row.metrics) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

const ResultRow* NoneRow(const std::vector<ResultRow>& rows, const std::string& scene) {
  for (const auto& row : rows) {
    if (row.scene == scene && row.spec == "none" && row.not_applicable.empty()) return &row;
  }
  return nullptr;
}

/// The winner on `metric` (higher is better when `higher`), ties within `tie`.
std::optional<AxisVerdict> Axis(const std::vector<ResultRow>& rows, const std::string& scene, const std::string& metric,
                                bool higher, double tie) {
  // The best value first, then the first row in report order within `tie` of it.
  std::optional<double> top;
  for (const auto& row : rows) {
    if (row.scene != scene || !row.not_applicable.empty()) continue;
    const MetricResult* m = Find(row, metric);
    if (!m || !m->value || !std::isfinite(*m->value)) continue;
    if (!top || (higher ? *m->value > *top : *m->value < *top)) top = *m->value;
  }
  const ResultRow* best = nullptr;
  double best_v = 0;
  for (const auto& row : rows) {
    if (!top || row.scene != scene || !row.not_applicable.empty()) continue;
    const MetricResult* m = Find(row, metric);
    if (m && m->value && std::isfinite(*m->value) && std::fabs(*m->value - *top) <= tie) {
      best = &row;
      best_v = *m->value;
      break;
    }
  }
  if (!best) return std::nullopt;
  AxisVerdict a;
  a.metric = metric;
  a.winner = best->spec;
  a.value = best_v;
  a.time_ms = best->total.median_ms;
  for (const auto& row : rows) {
    if (row.scene != scene || !row.not_applicable.empty() || &row == best) continue;
    const MetricResult* m = Find(row, metric);
    if (m && m->value && std::isfinite(*m->value) && std::fabs(*m->value - *top) <= tie) a.tied.push_back(row.spec);
  }
  if (const ResultRow* none = NoneRow(rows, scene)) {
    a.none_time_ms = none->total.median_ms;
    const MetricResult* m = Find(*none, metric);
    if (m && m->value && std::isfinite(*m->value)) a.none_value = *m->value;
  }
  return a;
}

bool Wins(const AxisVerdict& a, const std::string& spec) {
  if (a.winner == spec) return true;
  for (const auto& t : a.tied) {
    if (t == spec) return true;
  }
  return false;
}

std::string Names(const AxisVerdict& a) {
  std::string s = a.winner;
  if (!a.tied.empty()) {
    s += " (tied with ";
    for (size_t i = 0; i < a.tied.size(); ++i) s += (i ? ", " : "") + a.tied[i];
    s += ")";
  }
  return s;
}

std::string AxisText(const char* label, const AxisVerdict& a, bool psnr) {
  std::string s = std::string(label) + " → " + Names(a) + " ";
  s += psnr ? FormatDouble("%.2f dB", a.value) : FormatDouble("%.4f", a.value);
  if (a.winner == "none") {
    s += " (no method beats none)";
    return s;
  }
  if (a.none_value) {
    const double d = a.value - *a.none_value;
    s += psnr ? FormatDouble(" (%+.2f dB over none", d) : FormatDouble(" (%+.4f vs none", d);
  } else {
    s += a.none_time_ms ? " (none has no value" : " (no none row";
  }
  s += ", " + FmtMs(a.time_ms) + " ms";
  if (a.none_time_ms)
    s += ", " + std::string(a.time_ms >= *a.none_time_ms ? "+" : "-") + FmtMs(std::fabs(a.time_ms - *a.none_time_ms)) +
         " ms over none";
  s += ")";
  return s;
}

}  // namespace

SceneVerdict VerdictForScene(const std::vector<ResultRow>& rows, const std::string& scene) {
  SceneVerdict v;
  v.scene = scene;
  size_t n = 0;
  bool only_none = true;
  for (const auto& row : rows) {
    if (row.scene != scene || !row.not_applicable.empty()) continue;
    ++n;
    if (row.spec != "none") only_none = false;
  }
  if (n == 0) {
    v.line = "no method ran on this scene";
    return v;
  }
  if (only_none) {
    v.line = "only none ran: nothing to compare";
    return v;
  }
  v.edge_psnr = Axis(rows, scene, "edge_psnr_db", true, kVerdictPsnrTieDb);
  v.flip = Axis(rows, scene, "flip_mean", false, kVerdictFlipTie);
  std::string line = v.edge_psnr ? AxisText("edge PSNR", *v.edge_psnr, true) : "edge PSNR: no values";
  line += "; " + (v.flip ? AxisText("FLIP", *v.flip, false) : std::string("FLIP: no values"));
  if (v.edge_psnr && v.flip) {
    bool common = Wins(*v.flip, v.edge_psnr->winner);
    for (const auto& t : v.edge_psnr->tied) common = common || Wins(*v.flip, t);
    v.disagree = !common;
    line += v.disagree ? "; the axes disagree: edge PSNR picks " + v.edge_psnr->winner + ", FLIP picks " +
                             v.flip->winner + " (look at both images)"
                       : "; both axes agree";
  }
  v.line = line;
  return v;
}

std::vector<SceneVerdict> Verdicts(const Report& report) {
  std::vector<SceneVerdict> out;
  for (const auto& s : report.scenes) out.push_back(VerdictForScene(report.rows, s.name));
  return out;
}

std::string FormatVerdicts(const std::vector<SceneVerdict>& verdicts) {
  if (verdicts.empty()) return "";
  std::string s = "verdict (edge PSNR higher is better, FLIP lower is better; times are median ms per frame):\n";
  for (const auto& v : verdicts) s += "  " + v.scene + ": " + v.line + "\n";
  return s;
}

}  // namespace aalab
