#include "reports/history_page.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "core/error.h"
#include "reports/html_method_style.h"
#include "reports/html_page.h"

namespace aalab {

namespace {

/// One point of a trend chart.
struct TrendPoint {
  std::optional<double> value;   ///< +inf: identical to the reference
  std::optional<double> lo, hi;  ///< min–max bar (time)
  std::string null_text;         ///< when value is empty
  std::string mark;              ///< "", "regression", "improved", "cannot"
  std::string tooltip;
};

// `tol`: the comparison's tolerance in the chart's unit (0: none); the axis spans at least
// 4 tolerances (a change far below the threshold does not look like a cliff), and a band of
// ± tol around the latest value shows where the next entry would pass.
std::string SvgTrend(const std::string& title, const std::string& unit, const std::vector<TrendPoint>& pts,
                     const std::vector<std::string>& labels, double tol, const std::string& spec) {
  const double W = 420, H = 160, L = 58, R = 12, T = 20, B = 26;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& p : pts) {
    for (const auto& v : {p.value, p.lo, p.hi}) {
      if (v && std::isfinite(*v)) {
        lo = std::min(lo, *v);
        hi = std::max(hi, *v);
      }
    }
  }
  if (!(lo <= hi)) lo = 0, hi = 1;
  const bool non_negative = lo >= 0;
  std::optional<double> latest;
  for (const auto& p : pts) {
    if (p.value && std::isfinite(*p.value)) latest = *p.value;
  }
  if (tol > 0 && hi - lo < 4 * tol) {
    const double mid = (hi + lo) / 2;
    lo = mid - 2 * tol;
    hi = mid + 2 * tol;
  } else if (hi - lo < 1e-9 * std::max(1.0, std::fabs(hi))) {
    const double pad = std::max(1e-3, std::fabs(hi) * 0.01);
    lo -= pad;
    hi += pad;
  } else {
    const double pad = (hi - lo) * 0.08;
    lo -= pad;
    hi += pad;
  }
  if (non_negative && lo < 0) {  // times and errors: no negative axis
    hi -= lo;
    lo = 0;
  }
  const size_t n = pts.size();
  const double inset = 10;  // keep the first point off the axis
  auto X = [&](size_t i) {
    return n <= 1 ? L + (W - L - R) / 2 : L + inset + (W - L - R - inset) * static_cast<double>(i) / (n - 1);
  };
  auto Y = [&](double v) {
    if (std::isinf(v)) return T - 6.0;
    return T + (H - T - B) * (1.0 - (v - lo) / (hi - lo));
  };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W
    << " " << H << "\" role=\"img\"><title>" << HtmlEscape(title) << "</title>\n";
  s << "<text x=\"" << L << "\" y=\"13\" font-size=\"12\">" << HtmlEscape(title) << " (" << HtmlEscape(unit)
    << ")</text>\n";
  s << "<line x1=\"" << L << "\" y1=\"" << T << "\" x2=\"" << L << "\" y2=\"" << H - B << "\" stroke=\"#888\"/>"
    << "<line x1=\"" << L << "\" y1=\"" << H - B << "\" x2=\"" << W - R << "\" y2=\"" << H - B
    << "\" stroke=\"#888\"/>\n";
  const int digits = unit == "dB" ? 2 : 3;
  s << "<text x=\"" << L - 4 << "\" y=\"" << T + 4 << "\" font-size=\"10\" text-anchor=\"end\">"
    << FormatFixed(hi, digits) << "</text><text x=\"" << L - 4 << "\" y=\"" << H - B
    << "\" font-size=\"10\" text-anchor=\"end\">" << FormatFixed(lo, digits) << "</text>\n";
  if (!labels.empty()) {
    s << "<text x=\"" << X(0) << "\" y=\"" << H - 8 << "\" font-size=\"10\" text-anchor=\"start\">"
      << HtmlEscape(labels.front()) << "</text>";
    if (labels.size() > 1) {
      s << "<text x=\"" << X(n - 1) << "\" y=\"" << H - 8 << "\" font-size=\"10\" text-anchor=\"end\">"
        << HtmlEscape(labels.back()) << "</text>";
    }
    s << "\n";
  }
  if (tol > 0 && latest) {
    const double b0 = std::max(lo, *latest - tol), b1 = std::min(hi, *latest + tol);
    s << "<rect class=\"band\" x=\"" << L << "\" y=\"" << Y(b1) << "\" width=\"" << W - L - R << "\" height=\""
      << std::max(0.0, Y(b0) - Y(b1)) << "\" fill=\"#2060c0\" fill-opacity=\"0.08\"><title>threshold band: the latest "
      << "value &#177; " << FormatFixed(tol, 3) << " " << HtmlEscape(unit) << "</title></rect>\n";
  }
  // Min–max bars.
  for (size_t i = 0; i < n; ++i) {
    if (pts[i].lo && pts[i].hi) {
      s << "<line x1=\"" << X(i) << "\" y1=\"" << Y(*pts[i].lo) << "\" x2=\"" << X(i) << "\" y2=\"" << Y(*pts[i].hi)
        << "\" stroke=\"#9ab\" stroke-width=\"3\"/>";
    }
  }
  // The line through finite values (broken at nulls / infinities).
  std::string path;
  bool pen = false;
  for (size_t i = 0; i < n; ++i) {
    const auto& v = pts[i].value;
    if (v && std::isfinite(*v)) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%s%.1f,%.1f ", pen ? "L" : "M", X(i), Y(*v));
      path += buf;
      pen = true;
    } else {
      pen = false;
    }
  }
  // The method's colour and marker (html_method_style.h), as in every other chart; a point
  // marked against the previous entry is filled with its verdict's colour.
  const std::string colour = html::StyleOfMethod(spec).colour;
  if (!path.empty())
    s << "<path d=\"" << path << "\" fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\"/>\n";
  for (size_t i = 0; i < n; ++i) {
    const auto& p = pts[i];
    const std::string color = p.mark == "regression" ? "#d00020"
                              : p.mark == "improved" ? "#1b9e3a"
                              : p.mark == "cannot"   ? "#e08000"
                                                     : colour;
    const double r = p.mark.empty() ? 3 : 5.5;
    s << "<g><title>" << HtmlEscape(p.tooltip) << "</title>";
    if (p.value) {
      s << html::MarkerSvg(spec, X(i), Y(*p.value), r, color);
      if (std::isinf(*p.value)) {
        s << "<text x=\"" << X(i) + 7 << "\" y=\"" << Y(*p.value) + 4 << "\" font-size=\"10\">&#8734;</text>";
      }
    } else {
      const double y = H - B - 6;
      s << "<text x=\"" << X(i) << "\" y=\"" << y << "\" font-size=\"12\" text-anchor=\"middle\" fill=\"" << color
        << "\">&#215;</text>";
    }
    s << "</g>\n";
  }
  s << "</svg>";
  return s.str();
}

// A commit as people write it: 7 hex digits, then the subject when the report has one.
std::string Short(const HistoryEntry& e) {
  std::string s = e.commit.substr(0, std::min<size_t>(e.commit.size(), 7));
  auto it = e.report.context.find("git_subject");
  if (it != e.report.context.end() && !it->second.empty()) s += " " + it->second.substr(0, 40);
  return s;
}

// The maps that apply between two entries: OLD in the earlier one, NEW (and not OLD) in the
// later one.
std::map<std::string, std::string> MapsBetween(const Report& a, const Report& b,
                                               const std::map<std::string, std::string>& maps) {
  std::map<std::string, std::string> out;
  auto has = [](const Report& r, const std::string& spec) {
    for (const auto& row : r.rows) {
      if (row.spec == spec) return true;
    }
    return false;
  };
  for (const auto& [from, to] : maps) {
    if (has(a, from) && has(b, to) && !has(b, from)) out[from] = to;
  }
  return out;
}

}  // namespace

HistoryPage HistoryHtml(const std::vector<HistoryEntry>& entries, const std::string& only_series,
                        const CompareOptions& options, const std::string& out_dir) {
  HistoryPage page;
  std::vector<std::string> names = HistorySeriesNames(entries);
  if (entries.empty()) throw UserError("the history database holds no entries");
  if (!only_series.empty()) {
    if (std::find(names.begin(), names.end(), only_series) == names.end()) {
      std::string all;
      for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
      throw UserError("no series '" + only_series + "' in the history (series: " + all + ")");
    }
    names = {only_series};
  }
  std::ostringstream h;
  h << HtmlPageStart("aalab history");
  h << "<h1>aalab history</h1>\n<p>Trend per scene &times; method. Marked points crossed a threshold against the "
       "previous entry of the series (the rule of <code>aalab compare</code>: dB metrics more than "
    << FormatFixed(options.max_drop_db, 3) << " dB; time more than "
    << (options.check_time ? options.time_increase.Text("ms") : std::string("(off)")) << ", the "
    << FormatFixed(options.time_floor_ms, 3)
    << " ms floor and both repeats' spreads, on the same machine configuration; time crossings are marked whatever "
       "compare's --fail-on): "
       "<span class=\"regression\">red = regression</span>, <span class=\"improved\">green = improvement</span>, "
       "<span class=\"not-judged\">orange = could not compare</span>. Hover a point for its values. "
       "&#8734; = identical to the reference (infinite PSNR); &#215; = null.</p>\n";
  for (const auto& series : names) {
    std::vector<const HistoryEntry*> es;
    for (const auto& e : entries) {
      if (e.series == series) es.push_back(&e);
    }
    // Date order (ISO 8601 text sorts by date); entries of one date keep the file's order.
    std::stable_sort(es.begin(), es.end(),
                     [](const HistoryEntry* a, const HistoryEntry* b) { return a->date < b->date; });
    ++page.series;
    page.entries += static_cast<int>(es.size());
    bool has_edge = true;
    for (const auto* e : es) {
      for (const auto& r : e->report.rows) {
        bool found = false;
        for (const auto& m : r.metrics) found = found || m.name == "edge_psnr_db";
        has_edge = has_edge && found;
      }
    }
    std::vector<std::string> metrics =
        has_edge ? std::vector<std::string>{"edge_psnr_db", "psnr_db"} : std::vector<std::string>{"psnr_db"};
    bool has_temporal = true;  // motion runs (--frames > 1): the temporal error too
    for (const auto* e : es) {
      for (const auto& r : e->report.rows) {
        bool found = false;
        for (const auto& m : r.metrics) found = found || (m.name == "temporal_rmse" && m.value);
        has_temporal = has_temporal && found;
      }
    }
    if (has_temporal) metrics.push_back("temporal_rmse");
    CompareOptions opt = options;
    opt.metrics = metrics;
    opt.metric_change.clear();
    opt.fail_on = options.check_time ? CompareOptions::FailOn::kAny : CompareOptions::FailOn::kQuality;  // mark both
    // Consecutive comparisons.
    std::vector<CompareResult> cmp(es.size());
    for (size_t i = 1; i < es.size(); ++i) {
      opt.map = MapsBetween(es[i - 1]->report, es[i]->report, options.map);
      cmp[i] = CompareReports(es[i - 1]->report, es[i]->report, opt);
      page.regressions += cmp[i].regressions;
      page.improvements += cmp[i].improvements;
      page.cannot_compare +=
          static_cast<int>(cmp[i].cannot_compare.size() + cmp[i].missing_rows.size() + cmp[i].extra_rows.size());
    }
    h << "<section><h2>series " << HtmlEscape(series) << "</h2>\n<p>settings:";
    for (const auto& k : HistorySeriesKeys()) {
      h << " " << HtmlEscape(k) << " <code>" << HtmlEscape(HistorySettingText(es.front()->report, k)) << "</code>";
    }
    h << "</p>\n<table><tr><th>#</th><th class=\"l\">commit</th><th class=\"l\">date</th><th class=\"l\">report</th>"
         "<th>regressions</th><th>improvements</th><th class=\"l\">could not compare / notes</th></tr>\n";
    for (size_t i = 0; i < es.size(); ++i) {
      h << "<tr><td>" << i + 1 << "</td><td class=\"l\"><code title=\"" << HtmlEscape(es[i]->commit) << "\">"
        << HtmlEscape(Short(*es[i])) << "</code></td><td class=\"l\">" << HtmlEscape(es[i]->date)
        << "</td><td class=\"l\">";
      {
        // The run's own page, when it is still next to its report.
        std::error_code ec;
        const std::filesystem::path page = std::filesystem::absolute(es[i]->source, ec).parent_path() / "index.html";
        if (!out_dir.empty() && std::filesystem::is_regular_file(page, ec)) {
          const auto rel = std::filesystem::relative(page, std::filesystem::absolute(out_dir), ec);
          h << "<a href=\"" << HtmlEscape(ec ? page.string() : rel.string()) << "\">report</a>";
        } else {
          h << "<span title=\"" << HtmlEscape(es[i]->source) << "\">-</span>";
        }
        if (es[i]->accepted) {
          const auto& a = *es[i]->accepted;
          h << " <b>accepted as baseline</b> " << HtmlEscape(a.baseline) << " by " << HtmlEscape(a.by) << " at "
            << HtmlEscape(a.at) << ": " << HtmlEscape(a.why);
        }
      }
      h << "</td>";
      if (i == 0) {
        h << "<td>-</td><td>-</td><td class=\"l\">first entry</td></tr>\n";
        continue;
      }
      const CompareResult& c = cmp[i];
      std::string problems;
      for (const auto& v : {c.cannot_compare, c.missing_rows, c.extra_rows, c.notes}) {
        for (const auto& s : v) problems += (problems.empty() ? "" : "; ") + s;
      }
      h << "<td class=\"" << (c.regressions ? "regression" : "") << "\">" << c.regressions << "</td><td>"
        << c.improvements << "</td><td class=\"l\">" << HtmlEscape(problems) << "</td></tr>\n";
    }
    h << "</table>\n";
    // Rows in the order of the latest entry, then any only in earlier ones.
    // A mapped OLD spec is charted on its NEW spec's line.
    auto canonical = [&options](const std::string& spec) {
      auto it = options.map.find(spec);
      return it == options.map.end() ? spec : it->second;
    };
    std::vector<std::pair<std::string, std::string>> keys;
    for (auto it = es.rbegin(); it != es.rend(); ++it) {
      for (const auto& r : (*it)->report.rows) {
        const auto key = std::make_pair(r.scene, canonical(r.spec));
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
      }
    }
    std::vector<std::string> labels;
    for (const auto* e : es) labels.push_back(Short(*e).substr(0, 7));
    for (const auto& [scene, spec] : keys) {
      h << "<h3>" << HtmlEscape(scene) << " / " << HtmlEscape(spec) << "</h3>\n<div>";
      std::vector<std::string> quantities = metrics;
      if (options.check_time) quantities.push_back("time_ms");
      for (const auto& q : quantities) {
        std::vector<TrendPoint> pts;
        for (size_t i = 0; i < es.size(); ++i) {
          TrendPoint p;
          const ResultRow* row = nullptr;
          for (const auto& r : es[i]->report.rows) {
            if (r.scene == scene && r.spec == spec) row = &r;
          }
          for (const auto& r : es[i]->report.rows) {
            if (!row && r.scene == scene && canonical(r.spec) == spec) row = &r;
          }
          p.tooltip = es[i]->commit + " " + es[i]->date + ": ";
          if (!row) {
            p.null_text = "no such row";
            p.tooltip += "no such row";
          } else if (q == "time_ms") {
            const Timing t = MethodTime(*row);
            p.value = t.median_ms;
            p.lo = t.min_ms;
            p.hi = t.max_ms;
            p.tooltip += "median " + FormatFixed(t.median_ms, 3) + " ms (min " + FormatFixed(t.min_ms, 3) + ", max " +
                         FormatFixed(t.max_ms, 3) + ")";
          } else {
            bool found = false;
            for (const auto& m : row->metrics) {
              if (m.name != q) continue;
              found = true;
              if (m.value) {
                p.value = *m.value;
                p.tooltip +=
                    FormatFixed(*m.value, 3) + (q.size() > 3 && q.compare(q.size() - 3, 3, "_db") == 0 ? " dB" : "");
              } else if (m.null_reason == "identical") {
                p.value = std::numeric_limits<double>::infinity();
                p.tooltip += "infinite (identical)";
              } else {
                p.null_text = m.null_reason;
                p.tooltip += "null (" + m.null_reason + ")";
              }
            }
            if (!found) p.tooltip += "metric absent";
          }
          if (i > 0) {
            const CompareResult& c = cmp[i];
            const std::string name = scene + " / " + spec;
            for (const auto& l : c.lines) {
              if (l.scene != scene || l.spec != spec || l.quantity != q) continue;
              if (l.verdict == Verdict::kRegression || l.verdict == Verdict::kImproved) {
                p.mark = l.verdict == Verdict::kRegression ? "regression" : "improved";
                p.tooltip += std::string("; ") + VerdictName(l.verdict) + " vs previous (delta " +
                             (l.delta ? FormatFixed(*l.delta, 3) : std::string("-")) + ", threshold " + l.threshold +
                             (l.note.empty() ? "" : ", " + l.note) + ")";
              }
            }
            auto cannot = [&p](const std::string& why) {
              p.mark = "cannot";
              p.tooltip += "; could not compare: " + why;
            };
            for (const auto& s : c.cannot_compare) {
              // Row-level reasons start with "row <name>: "; anything else concerns the whole report.
              if (s.rfind("row ", 0) != 0 || s.rfind("row " + name + ": ", 0) == 0) cannot(s);
            }
            for (const auto& s : c.missing_rows) {
              if (s == name) cannot("row missing from this entry");
            }
            for (const auto& s : c.extra_rows) {
              if (s == name) cannot("row not in the previous entry");
            }
          }
          pts.push_back(p);
        }
        const std::string title = q == "time_ms" ? "method time" : q;
        const double tol = q == "time_ms" ? 0.0 : IsDbMetric(q) ? options.max_drop_db : 0.0;
        h << SvgTrend(title, q == "time_ms" ? "ms" : IsDbMetric(q) ? "dB" : "", pts, labels, tol, spec);
        ++page.charts;
      }
      h << "</div>\n";
    }
    h << "</section>\n";
  }
  h << HtmlPageEnd();
  page.html = h.str();
  return page;
}

}  // namespace aalab
