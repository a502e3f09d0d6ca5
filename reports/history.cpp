// The history database (JSON lines) and its trend page. Format and rules in history.h.
#include "reports/history.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/core/error.h"
#include "reports/html_page.h"

namespace aalab {

namespace {

using Json = nlohmann::ordered_json;

Json Num(double v) {
  AALAB_CHECK(std::isfinite(v), "non-finite number headed for the history");
  return v;
}

Json Samples(const Timing& t) {
  Json a = Json::array();
  for (double v : t.samples_ms) a.push_back(Num(v));
  return a;
}

Timing SamplesFrom(const Json& j) {
  Timing t;
  for (const auto& v : j) t.samples_ms.push_back(v.get<double>());
  t.Summarize();
  return t;
}

std::string Setting(const Report& r, const std::string& k) {
  const std::string v = SettingValue(r, k);
  return v.empty() ? "(absent)" : v;
}

HistoryEntry EntryFromJson(const Json& j, const std::string& where) {
  HistoryEntry e;
  try {
    if (!j.is_object()) throw UserError(where + ": not a JSON object");
    const int version = j.at("history_version").get<int>();
    if (version != kHistoryVersion) {
      throw UserError(where + ": history_version " + std::to_string(version) + " is not supported (this aalab reads " +
                      std::to_string(kHistoryVersion) + ")");
    }
    e.series = j.at("series").get<std::string>();
    e.commit = j.at("commit").get<std::string>();
    e.date = j.at("date").get<std::string>();
    e.source = j.at("source").get<std::string>();
    for (auto it = j.at("settings").begin(); it != j.at("settings").end(); ++it) {
      e.report.settings.emplace_back(it.key(), it.value().get<std::string>());
    }
    for (auto it = j.at("context").begin(); it != j.at("context").end(); ++it) {
      e.report.context[it.key()] = it.value().get<std::string>();
    }
    for (const auto& jr : j.at("rows")) {
      ResultRow row;
      row.scene = jr.at("scene").get<std::string>();
      row.method = jr.at("method").get<std::string>();
      row.spec = jr.at("spec").get<std::string>();
      for (auto it = jr.at("params").begin(); it != jr.at("params").end(); ++it) {
        row.params.emplace_back(it.key(), it.value().get<std::string>());
      }
      const auto& reasons = jr.at("null_reasons");
      for (auto it = jr.at("metrics").begin(); it != jr.at("metrics").end(); ++it) {
        MetricResult m;
        m.name = it.key();
        if (!it.value().is_null()) m.value = it.value().get<double>();
        if (!m.value && reasons.contains(m.name)) m.null_reason = reasons.at(m.name).get<std::string>();
        row.metrics.push_back(m);
      }
      row.output_hash = jr.at("output_hash").get<std::string>();
      row.render_shared = jr.at("render_shared_with_none").get<bool>();
      const auto& t = jr.at("timing");
      row.render = SamplesFrom(t.at("render"));
      row.post = SamplesFrom(t.at("post"));
      row.resample = SamplesFrom(t.at("resample"));
      row.total = SamplesFrom(t.at("total"));
      e.report.rows.push_back(row);
    }
  } catch (const nlohmann::json::exception& ex) {
    throw UserError(where + ": not a history entry (" + std::string(ex.what()) + ")");
  }
  ValidateSeriesName(e.series);
  return e;
}

}  // namespace

const std::vector<std::string>& HistorySeriesKeys() {
  static const std::vector<std::string> keys = {"size", "ref_spp", "seed", "scenes", "methods", "frames"};
  return keys;
}

void ValidateSeriesName(const std::string& name) {
  bool ok = !name.empty() && name.size() <= 64;
  for (char c : name) {
    ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-');
  }
  if (!ok) throw UserError("series name '" + name + "' must be 1-64 characters from A-Z a-z 0-9 . _ -");
}

void ValidateHistoryDate(const std::string& d) {
  auto digits = [&d](size_t from, size_t n) {
    for (size_t i = from; i < from + n; ++i) {
      if (i >= d.size() || !std::isdigit(static_cast<unsigned char>(d[i]))) return false;
    }
    return true;
  };
  const bool day = d.size() >= 10 && digits(0, 4) && d[4] == '-' && digits(5, 2) && d[7] == '-' && digits(8, 2);
  const bool ok = day && (d.size() == 10 || (d.size() == 20 && d[10] == 'T' && digits(11, 2) && d[13] == ':' &&
                                             digits(14, 2) && d[16] == ':' && digits(17, 2) && d[19] == 'Z'));
  if (!ok) throw UserError("date '" + d + "' is not YYYY-MM-DD or YYYY-MM-DDTHH:MM:SSZ (UTC)");
}

HistoryEntry HistoryEntryFromReport(const Report& report, const std::string& series, const std::string& commit,
                                    const std::string& date, const std::string& source) {
  ValidateSeriesName(series);
  ValidateHistoryDate(date);
  if (commit.empty() || commit == "unknown") {
    throw UserError("report '" + source + "' has no git commit (git_commit '" + commit +
                    "': built outside git); give it with --commit");
  }
  if (report.rows.empty()) throw UserError("report '" + source + "' has no rows");
  HistoryEntry e;
  e.series = series;
  e.commit = commit;
  e.date = date;
  e.source = source;
  e.report.schema_version = report.schema_version;
  e.report.settings = report.settings;
  e.report.context = report.context;
  for (const auto& r : report.rows) {
    ResultRow row;
    row.scene = r.scene;
    row.method = r.method;
    row.spec = r.spec;
    row.params = r.params;
    row.metrics = r.metrics;
    row.output_hash = r.output_hash;
    row.render_shared = r.render_shared;
    row.render = r.render;
    row.post = r.post;
    row.resample = r.resample;
    row.total = r.total;
    e.report.rows.push_back(row);
  }
  return e;
}

std::string HistoryLine(const HistoryEntry& e) {
  Json j;
  j["history_version"] = kHistoryVersion;
  j["series"] = e.series;
  j["commit"] = e.commit;
  j["date"] = e.date;
  j["source"] = e.source;
  Json settings = Json::object();
  for (const auto& [k, v] : e.report.settings) settings[k] = v;
  j["settings"] = settings;
  Json ctx = Json::object();
  for (const auto& [k, v] : e.report.context) ctx[k] = v;
  j["context"] = ctx;
  Json rows = Json::array();
  for (const auto& r : e.report.rows) {
    Json jr;
    jr["scene"] = r.scene;
    jr["method"] = r.method;
    jr["spec"] = r.spec;
    Json params = Json::object();
    for (const auto& [k, v] : r.params) params[k] = v;
    jr["params"] = params;
    Json metrics = Json::object(), reasons = Json::object();
    for (const auto& m : r.metrics) {
      metrics[m.name] = m.value ? Num(*m.value) : Json(nullptr);
      if (!m.value) reasons[m.name] = m.null_reason;
    }
    jr["metrics"] = metrics;
    jr["null_reasons"] = reasons;
    jr["output_hash"] = r.output_hash;
    jr["render_shared_with_none"] = r.render_shared;
    jr["timing"] = {{"render", Samples(r.render)},
                    {"post", Samples(r.post)},
                    {"resample", Samples(r.resample)},
                    {"total", Samples(r.total)}};
    rows.push_back(jr);
  }
  j["rows"] = rows;
  return j.dump();
}

std::vector<HistoryEntry> ParseHistory(const std::string& text, const std::string& origin) {
  std::vector<HistoryEntry> out;
  size_t pos = 0;
  int line_no = 0;
  while (pos < text.size()) {
    ++line_no;
    const size_t nl = text.find('\n', pos);
    const std::string line = text.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos);
    pos = nl == std::string::npos ? text.size() : nl + 1;
    const std::string where = origin + " line " + std::to_string(line_no);
    if (line.find_first_not_of(" \t\r") == std::string::npos) {
      throw UserError(where + ": empty line (every line must be one history entry)");
    }
    Json j;
    try {
      j = Json::parse(line);
    } catch (const nlohmann::json::parse_error& ex) {
      throw UserError(where + ": malformed JSON (" + std::string(ex.what()) + ")");
    }
    HistoryEntry e = EntryFromJson(j, where);
    e.line = line_no;
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<HistoryEntry> ReadHistoryFile(const std::string& path, bool missing_ok) {
  std::error_code ec;
  if (missing_ok && !std::filesystem::exists(path, ec)) return {};
  std::ifstream f(path, std::ios::binary);
  if (!f) throw UserError("history database '" + path + "' cannot be read");
  std::stringstream ss;
  ss << f.rdbuf();
  return ParseHistory(ss.str(), "history database '" + path + "'");
}

void CheckSeriesCompatible(const std::vector<HistoryEntry>& entries, const HistoryEntry& e) {
  const HistoryEntry* last = nullptr;
  for (const auto& x : entries) {
    if (x.series != e.series) continue;
    last = &x;
    if (x.commit == e.commit && x.date == e.date) {
      throw UserError("series '" + e.series + "' already holds commit " + e.commit + " dated " + e.date + " (line " +
                      std::to_string(x.line) + ", from '" + x.source + "'); pass --date to add another run of it");
    }
  }
  if (!last) return;
  std::vector<std::string> diffs;
  for (const auto& k : HistorySeriesKeys()) {
    const std::string a = Setting(last->report, k), b = Setting(e.report, k);
    if (a != b) diffs.push_back(k + ": series " + a + ", report " + b);
  }
  if (!diffs.empty()) {
    std::string s;
    for (size_t i = 0; i < diffs.size(); ++i) s += (i ? "; " : "") + diffs[i];
    throw UserError("report '" + e.source + "' does not match series '" + e.series + "' (line " +
                    std::to_string(last->line) + "): " + s +
                    ". Entries of a series must agree on size, ref_spp, seed, scenes and methods; start another series "
                    "with --series NAME");
  }
}

std::vector<std::string> HistorySeriesNames(const std::vector<HistoryEntry>& entries) {
  std::vector<std::string> names;
  for (const auto& e : entries) {
    if (std::find(names.begin(), names.end(), e.series) == names.end()) names.push_back(e.series);
  }
  return names;
}

namespace {

/// One point of a trend chart.
struct TrendPoint {
  std::optional<double> value;  ///< +inf: identical to the reference
  std::optional<double> lo, hi; ///< min–max bar (time)
  std::string null_text;        ///< when value is empty
  std::string mark;             ///< "", "regression", "improved", "cannot"
  std::string tooltip;
};

std::string SvgTrend(const std::string& title, const std::string& unit, const std::vector<TrendPoint>& pts,
                     const std::vector<std::string>& labels) {
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
  if (hi - lo < 1e-9 * std::max(1.0, std::fabs(hi))) {
    const double pad = std::max(1e-3, std::fabs(hi) * 0.01);
    lo -= pad;
    hi += pad;
  } else {
    const double pad = (hi - lo) * 0.08;
    lo -= pad;
    hi += pad;
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
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W << " "
    << H << "\" role=\"img\"><title>" << HtmlEscape(title) << "</title>\n";
  s << "<text x=\"" << L << "\" y=\"13\" font-size=\"12\">" << HtmlEscape(title) << " (" << HtmlEscape(unit) << ")</text>\n";
  s << "<line x1=\"" << L << "\" y1=\"" << T << "\" x2=\"" << L << "\" y2=\"" << H - B << "\" stroke=\"#888\"/>"
    << "<line x1=\"" << L << "\" y1=\"" << H - B << "\" x2=\"" << W - R << "\" y2=\"" << H - B << "\" stroke=\"#888\"/>\n";
  const int digits = unit == "dB" ? 2 : 3;
  s << "<text x=\"" << L - 4 << "\" y=\"" << T + 4 << "\" font-size=\"10\" text-anchor=\"end\">" << FormatFixed(hi, digits)
    << "</text><text x=\"" << L - 4 << "\" y=\"" << H - B << "\" font-size=\"10\" text-anchor=\"end\">"
    << FormatFixed(lo, digits) << "</text>\n";
  if (!labels.empty()) {
    s << "<text x=\"" << X(0) << "\" y=\"" << H - 8 << "\" font-size=\"10\" text-anchor=\"start\">"
      << HtmlEscape(labels.front()) << "</text>";
    if (labels.size() > 1) {
      s << "<text x=\"" << X(n - 1) << "\" y=\"" << H - 8 << "\" font-size=\"10\" text-anchor=\"end\">"
        << HtmlEscape(labels.back()) << "</text>";
    }
    s << "\n";
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
  if (!path.empty()) s << "<path d=\"" << path << "\" fill=\"none\" stroke=\"#2060c0\" stroke-width=\"1.5\"/>\n";
  for (size_t i = 0; i < n; ++i) {
    const auto& p = pts[i];
    const std::string color = p.mark == "regression" ? "#d00020"
                              : p.mark == "improved" ? "#1b9e3a"
                              : p.mark == "cannot"   ? "#e08000"
                                                     : "#2060c0";
    const double r = p.mark.empty() ? 3 : 5.5;
    s << "<g><title>" << HtmlEscape(p.tooltip) << "</title>";
    if (p.value) {
      s << "<circle cx=\"" << X(i) << "\" cy=\"" << Y(*p.value) << "\" r=\"" << r << "\" fill=\"" << color << "\"/>";
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

std::string Short(const std::string& commit) { return commit.substr(0, std::min<size_t>(commit.size(), 10)); }

}  // namespace

HistoryPage HistoryHtml(const std::vector<HistoryEntry>& entries, const std::string& only_series,
                        const CompareOptions& options) {
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
    << (options.check_time ? options.time_increase.Text("ms") : std::string("(off)"))
    << " and more than the repeats' spread, on the same machine configuration): "
       "<span class=\"regression\">red = regression</span>, <span class=\"improved\">green = improvement</span>, "
       "<span class=\"not-judged\">orange = could not compare</span>. Hover a point for its values. "
       "&#8734; = identical to the reference (infinite PSNR); &#215; = null.</p>\n";
  for (const auto& series : names) {
    std::vector<const HistoryEntry*> es;
    for (const auto& e : entries) {
      if (e.series == series) es.push_back(&e);
    }
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
    std::vector<std::string> metrics = has_edge ? std::vector<std::string>{"edge_psnr_db", "psnr_db"}
                                                : std::vector<std::string>{"psnr_db"};
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
    // Consecutive comparisons.
    std::vector<CompareResult> cmp(es.size());
    for (size_t i = 1; i < es.size(); ++i) {
      cmp[i] = CompareReports(es[i - 1]->report, es[i]->report, opt);
      page.regressions += cmp[i].regressions;
      page.improvements += cmp[i].improvements;
      page.cannot_compare += static_cast<int>(cmp[i].cannot_compare.size() + cmp[i].missing_rows.size() +
                                              cmp[i].extra_rows.size());
    }
    h << "<section><h2>series " << HtmlEscape(series) << "</h2>\n<p>settings:";
    for (const auto& k : HistorySeriesKeys()) {
      h << " " << HtmlEscape(k) << " <code>" << HtmlEscape(Setting(es.front()->report, k)) << "</code>";
    }
    h << "</p>\n<table><tr><th>#</th><th class=\"l\">commit</th><th class=\"l\">date</th><th>regressions</th>"
         "<th>improvements</th><th class=\"l\">could not compare / notes</th></tr>\n";
    for (size_t i = 0; i < es.size(); ++i) {
      h << "<tr><td>" << i + 1 << "</td><td class=\"l\"><code>" << HtmlEscape(es[i]->commit) << "</code></td><td class=\"l\">"
        << HtmlEscape(es[i]->date) << "</td>";
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
    std::vector<std::pair<std::string, std::string>> keys;
    for (auto it = es.rbegin(); it != es.rend(); ++it) {
      for (const auto& r : (*it)->report.rows) {
        const auto key = std::make_pair(r.scene, r.spec);
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
      }
    }
    std::vector<std::string> labels;
    for (const auto* e : es) labels.push_back(Short(e->commit));
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
                p.tooltip += FormatFixed(*m.value, 3) + (q.size() > 3 && q.compare(q.size() - 3, 3, "_db") == 0 ? " dB" : "");
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
        h << SvgTrend(title, q == "time_ms" ? "ms" : "dB", pts, labels);
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
