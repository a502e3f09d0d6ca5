// aalab export's tables (reports/export_tables.h): the numbers, their precision and the best
// of each column. The writers (LaTeX, Markdown, CSV) are in export_table_writers.cpp.
#include "reports/export_tables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "core/error.h"
#include "metrics/metric.h"
#include "reports/html_assets.h"

namespace aalab {

namespace {

/// PSNRs at least this close to the reference's noise floor are marked (the page's ⚠ rule).
constexpr double kNearFloorDb = 3.0;

/// How a column's numbers are printed: dB with 2 decimals, milliseconds with 3/2/1 decimals by
/// magnitude, other values with enough decimals for 3 significant digits of the largest.
enum class Kind { kDb, kMs, kValue, kFlag };

int Decimals(Kind kind, const std::vector<TableCell>& column, int fixed) {
  double largest = 0;
  for (const auto& c : column) {
    if (c.value) largest = std::max(largest, std::fabs(*c.value));
  }
  switch (kind) {
    case Kind::kDb: return fixed;
    case Kind::kMs: return largest < 1 ? 3 : largest < 100 ? 2 : 1;
    case Kind::kFlag: return 0;
    case Kind::kValue:
      if (largest == 0) return 2;
      return std::clamp(2 - static_cast<int>(std::floor(std::log10(largest))), 2, 6);
  }
  return 2;
}

/// A metric's column: fixed decimals where the registry gives them (every dB value: 2), else
/// significant digits; a name the registry does not know: fixed 2 for dB, else significant.
Kind MetricKind(const std::string& metric) {
  if (const MetricOutput* o = FindMetricOutput(metric)) return o->decimals >= 0 ? Kind::kDb : Kind::kValue;
  return html::DescribeMetric(metric).unit == "dB" ? Kind::kDb : Kind::kValue;
}

/// The fixed decimals of a Kind::kDb metric column (the registry's; 2 for unknown dB names).
int MetricDecimals(const std::string& metric) {
  const MetricOutput* o = FindMetricOutput(metric);
  return o && o->decimals >= 0 ? o->decimals : 2;
}

/// Fills every cell's text of column `col` at the column's precision.
void FormatColumn(ExportTable& t, size_t col, Kind kind, int fixed = 2) {
  std::vector<TableCell> column;
  for (const auto& row : t.cells) column.push_back(row[col]);
  const int dec = Decimals(kind, column, fixed);
  for (auto& row : t.cells) {
    TableCell& c = row[col];
    if (!c.value) continue;
    if (kind == Kind::kFlag) {
      c.text = *c.value != 0 ? "yes" : "";
      continue;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", dec, *c.value);
    c.text = buf;
    if (c.text == "-0" || c.text.find_first_not_of("-0.") == std::string::npos) {
      if (c.text[0] == '-') c.text.erase(0, 1);  // "-0.00" reads as a sign that is not there
    }
  }
}

/// Marks the best cell(s) of column `col` among rows [begin, end): largest for better = +1,
/// smallest for -1. Exact values decide; ties are all marked.
void MarkBest(ExportTable& t, size_t col, int better, size_t begin, size_t end) {
  if (better == 0) return;
  std::optional<double> best;
  for (size_t r = begin; r < end; ++r) {
    const auto& v = t.cells[r][col].value;
    if (v && (!best || better * *v > better * *best)) best = v;
  }
  if (!best) return;
  for (size_t r = begin; r < end; ++r) {
    const auto& v = t.cells[r][col].value;
    if (v && *v == *best) t.cells[r][col].best = true;
  }
}

std::string Join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

std::string Direction(int better) {
  return better > 0 ? "higher is better" : better < 0 ? "lower is better" : "direction unknown";
}

std::string MetricWithUnit(const std::string& metric) {
  const html::MetricInfo info = html::DescribeMetric(metric);
  return info.label + (info.unit.empty() ? "" : " (" + info.unit + ")");
}

/// Methods not applicable on every chosen scene (left out of suite means, as in the page).
std::set<std::string> NotApplicableEverywhere(const Report& r, const ExportSelection& sel) {
  std::set<std::string> out;
  for (const auto& spec : sel.methods) {
    bool all = !sel.scenes.empty();
    for (const auto& scene : sel.scenes) {
      const ResultRow* row = FindRow(r, scene, spec);
      all = all && row && !row->not_applicable.empty();
    }
    if (all) out.insert(spec);
  }
  return out;
}

/// The scenes the suite mean uses (every method that is applicable somewhere has a value
/// there), and why each other scene was left out.
struct MeanScope {
  std::vector<std::string> used;
  std::vector<std::string> left;  ///< "scene: why"
};

std::string NullReason(const ResultRow& row, const std::string& metric) {
  if (!row.not_applicable.empty()) return "not applicable: " + row.not_applicable;
  for (const auto& m : row.metrics) {
    if (m.name == metric) return m.null_reason.empty() ? "no value" : m.null_reason;
  }
  return "not measured";
}

MeanScope ScopeOf(const Report& r, const ExportSelection& sel) {
  MeanScope scope;
  const std::set<std::string> na = NotApplicableEverywhere(r, sel);
  for (const auto& scene : sel.scenes) {
    std::set<std::string> reasons;
    for (const auto& spec : sel.methods) {
      if (na.count(spec)) continue;
      const ResultRow* row = FindRow(r, scene, spec);
      if (!row) {
        reasons.insert("not run with " + spec);
      } else if (!MetricOf(*row, sel.metric)) {
        reasons.insert(NullReason(*row, sel.metric));
      }
    }
    if (reasons.empty()) {
      scope.used.push_back(scene);
    } else {
      scope.left.push_back(scene + ": " + Join({reasons.begin(), reasons.end()}, "; "));
    }
  }
  return scope;
}

std::string ScopeSentence(const MeanScope& s, size_t total) {
  std::string out = "Means over " +
                    (s.left.empty() ? "all " + std::to_string(total)
                                    : std::to_string(s.used.size()) + " of " + std::to_string(total)) +
                    " scenes";
  if (!s.left.empty()) out += " (left out, not every method has a value there: " + Join(s.left, "; ") + ")";
  return out + ".";
}

std::string RunsSentence(const std::vector<ExportSource>& sources) {
  if (sources.size() < 2) return "";
  std::vector<std::string> parts;
  for (const auto& s : sources) parts.push_back(s.label + " = " + s.dir);
  return " Runs: " + Join(parts, ", ") + ".";
}

std::string Conditions(const std::vector<ExportSource>& sources) {
  std::string out = " " + ConditionsSentence(sources.front().report);
  for (size_t i = 1; i < sources.size(); ++i) {
    const std::string c = ConditionsSentence(sources[i].report);
    if (c != ConditionsSentence(sources.front().report)) out += " Run " + sources[i].label + ": " + c;
  }
  return out;
}

}  // namespace

std::vector<MeanPoint> MeanPoints(const ExportSource& src, const ExportSelection& sel) {
  const MeanScope scope = ScopeOf(src.report, sel);
  const std::set<std::string> na = NotApplicableEverywhere(src.report, sel);
  std::vector<MeanPoint> pts;
  for (const auto& spec : sel.methods) {
    MeanPoint p{spec, std::nullopt, std::nullopt};
    if (!na.count(spec) && !scope.used.empty()) {
      double q = 0, ms = 0;
      for (const auto& scene : scope.used) {
        const ResultRow* row = FindRow(src.report, scene, spec);
        q += *MetricOf(*row, sel.metric);
        ms += row->total.median_ms;
      }
      p.q = q / static_cast<double>(scope.used.size());
      p.t = ms / static_cast<double>(scope.used.size());
    }
    pts.push_back(p);
  }
  std::stable_sort(pts.begin(), pts.end(), [](const MeanPoint& a, const MeanPoint& b) {
    if (a.t.has_value() != b.t.has_value()) return a.t.has_value();
    return a.t && *a.t < *b.t;
  });
  return pts;
}

std::set<std::string> ParetoFront(const std::vector<MeanPoint>& pts, int better) {
  std::vector<const MeanPoint*> order;
  for (const auto& p : pts) {
    if (p.q && p.t && *p.t > 0) order.push_back(&p);
  }
  std::stable_sort(order.begin(), order.end(), [&](const MeanPoint* a, const MeanPoint* b) {
    if (*a->t != *b->t) return *a->t < *b->t;
    return better * *a->q > better * *b->q;
  });
  std::set<std::string> front;
  double best = -INFINITY;
  for (const MeanPoint* p : order) {
    if (better != 0 && better * *p->q > best) {
      front.insert(p->spec);
      best = better * *p->q;
    }
  }
  return front;
}

ExportTable MetricTable(const std::vector<ExportSource>& sources, const ExportSelection& sel) {
  const html::MetricInfo info = html::DescribeMetric(sel.metric);
  ExportTable t;
  t.row_header = "Method";
  const bool grouped = sources.size() > 1;
  const bool mean = sel.scenes.size() > 1;
  t.row_labels = sel.methods;
  t.row_groups.assign(sel.methods.size(), "");
  t.cells.assign(sel.methods.size(), {});
  std::map<std::string, std::set<std::string>> empty_why;  // reason → scenes
  std::vector<std::string> scope_notes, floor_notes;
  // A scene where no chosen method of any report has a value (no edge pixels for an edge
  // metric) gets no column of dashes, only a note.
  std::vector<std::string> shown;
  for (const auto& scene : sel.scenes) {
    bool any = false;
    std::set<std::string> reasons;
    for (const auto& src : sources) {
      for (const auto& spec : sel.methods) {
        const ResultRow* row = FindRow(src.report, scene, spec);
        if (row && MetricOf(*row, sel.metric)) any = true;
        if (row && !MetricOf(*row, sel.metric)) reasons.insert(NullReason(*row, sel.metric));
      }
    }
    if (any) {
      shown.push_back(scene);
    } else {
      t.notes.push_back("No column for " + scene + ": " + info.label + " is undefined there for every method (" +
                        Join({reasons.begin(), reasons.end()}, "; ") + ").");
    }
  }
  for (const auto& src : sources) {
    const MeanScope scope = ScopeOf(src.report, sel);
    const std::set<std::string> na = NotApplicableEverywhere(src.report, sel);
    for (const auto& scene : shown) {
      t.columns.push_back(scene);
      t.column_groups.push_back(grouped ? src.label : "");
      for (size_t m = 0; m < sel.methods.size(); ++m) {
        const ResultRow* row = FindRow(src.report, scene, sel.methods[m]);
        TableCell c;
        if (row) c.value = MetricOf(*row, sel.metric);
        if (!c.value) empty_why[row ? NullReason(*row, sel.metric) : "not run"].insert(scene);
        const SceneResult* sc = FindScene(src.report, scene);
        if (c.value && html::IsPsnrMetric(sel.metric) && sc && sc->ref_floor_psnr_db &&
            *c.value >= *sc->ref_floor_psnr_db - kNearFloorDb) {
          c.near_floor = true;
          char note[160];
          std::snprintf(note, sizeof note, "%s (noise floor %.2f dB)", scene.c_str(), *sc->ref_floor_psnr_db);
          if (std::find(floor_notes.begin(), floor_notes.end(), note) == floor_notes.end()) floor_notes.push_back(note);
        }
        t.cells[m].push_back(c);
      }
    }
    if (mean) {
      t.columns.push_back("Mean");
      t.column_groups.push_back(grouped ? src.label : "");
      for (size_t m = 0; m < sel.methods.size(); ++m) {
        TableCell c;
        if (!na.count(sel.methods[m]) && !scope.used.empty()) {
          double sum = 0;
          for (const auto& scene : scope.used)
            sum += *MetricOf(*FindRow(src.report, scene, sel.methods[m]), sel.metric);
          c.value = sum / static_cast<double>(scope.used.size());
        }
        t.cells[m].push_back(c);
      }
      scope_notes.push_back((grouped ? src.label + ": " : "") + ScopeSentence(scope, sel.scenes.size()));
    }
  }
  for (size_t col = 0; col < t.columns.size(); ++col) {
    FormatColumn(t, col, MetricKind(sel.metric), MetricDecimals(sel.metric));
    MarkBest(t, col, info.better, 0, t.cells.size());
  }
  t.caption = MetricWithUnit(sel.metric) + ", " + Direction(info.better) + ", of each method per scene" +
              (mean ? " and the mean over scenes" : "") + "; best per column in bold." + RunsSentence(sources) +
              Conditions(sources);
  for (const auto& n : scope_notes) t.notes.push_back(n);
  if (!floor_notes.empty()) {
    t.notes.push_back(
        "†: within 3 dB of the reference's noise floor or above it, so not distinguishable from "
        "the reference at its sample count: " +
        Join(floor_notes, ", ") + ".");
  }
  for (const auto& [why, scenes] : empty_why) {
    t.notes.push_back("Empty cells (" + Join({scenes.begin(), scenes.end()}, ", ") + "): " + why + ".");
  }
  return t;
}

ExportTable CostTable(const std::vector<ExportSource>& sources, const ExportSelection& sel) {
  const html::MetricInfo info = html::DescribeMetric(sel.metric);
  const std::string unit = info.unit.empty() ? "" : " (" + info.unit + ")";
  ExportTable t;
  t.row_header = "Method";
  t.columns = {MetricWithUnit(sel.metric),
               "Gain" + unit,
               "Time (ms)",
               "Added (ms)",
               "Gain/ms" + (info.unit.empty() ? "" : " (" + info.unit + "/ms)"),
               "Pareto"};
  t.column_groups.assign(t.columns.size(), "");
  std::vector<std::pair<size_t, size_t>> group_rows;
  bool any_baseless = false, any_nonpositive = false;
  for (const auto& src : sources) {
    const MeanScope scope = ScopeOf(src.report, sel);
    const std::vector<MeanPoint> pts = MeanPoints(src, sel);
    const MeanPoint* base = nullptr;
    for (const auto& p : pts) {
      if (p.spec == "none" && p.q) base = &p;
    }
    any_baseless = any_baseless || !base;
    const std::set<std::string> front = ParetoFront(pts, info.better);
    const size_t begin = t.cells.size();
    for (const auto& p : pts) {
      std::vector<TableCell> row(t.columns.size());
      row[0].value = p.q;
      row[2].value = p.t;
      if (base && p.q) row[1].value = info.better * (*p.q - *base->q);
      if (base && p.t) row[3].value = *p.t - *base->t;
      if (base && &p != base && p.q && p.t) {
        const double dt = *p.t - *base->t;
        if (dt > 0) {
          row[4].value = info.better * (*p.q - *base->q) / dt;
        } else {
          any_nonpositive = true;
        }
      }
      row[5].value = front.count(p.spec) ? 1.0 : 0.0;
      t.row_labels.push_back(p.spec);
      t.row_groups.push_back(sources.size() > 1 ? src.label : "");
      t.cells.push_back(row);
    }
    group_rows.push_back({begin, t.cells.size()});
    if (sel.scenes.size() > 1) {
      t.notes.push_back((sources.size() > 1 ? src.label + ": " : "") + ScopeSentence(scope, sel.scenes.size()));
    }
  }
  const Kind q = MetricKind(sel.metric);
  const Kind kinds[] = {q, q, Kind::kMs, Kind::kMs, Kind::kValue, Kind::kFlag};
  const int betters[] = {info.better, +1, -1, 0, +1, 0};
  for (size_t col = 0; col < t.columns.size(); ++col) {
    FormatColumn(t, col, kinds[col], col < 2 ? MetricDecimals(sel.metric) : 2);
    for (const auto& [b, e] : group_rows) MarkBest(t, col, betters[col], b, e);
  }
  const std::string scope_text = sel.scenes.size() > 1 ? "means over the scenes" : "on " + sel.scenes.front();
  t.caption =
      "Cost of accuracy (" + scope_text + "): " + info.label + ", its gain over no AA (none; " +
      (info.better < 0 ? "none's value minus the method's, positive = less error" : "the method's value minus none's") +
      "), time per frame (mean of the per-scene medians), time added over none, gain per ms added, and "
      "whether the method is on the Pareto front of quality against time. Fastest first; best per "
      "column in bold." +
      RunsSentence(sources) + Conditions(sources);
  if (any_baseless) t.notes.push_back("No gain or time added without a none row with a value.");
  if (any_nonpositive) {
    t.notes.push_back(
        "Gain/ms is empty where the time added is 0 ms or less: not measurably slower than none in "
        "this run, so no gain per ms.");
  }
  return t;
}

}  // namespace aalab
