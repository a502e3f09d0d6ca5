#include "reports/sweep_page.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/compare.h"
#include "reports/html_assets.h"
#include "reports/html_page.h"

namespace aalab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string ParetoSvg(const SweepResult& r) {
  const std::string& obj = r.objectives.front();
  const double W = 620, H = 380, L = 70, R = 20, T = 20, B = 44;
  double tmin = kInf, tmax = -kInf, qmin = kInf, qmax = -kInf;
  for (const auto& p : r.points) {
    tmin = std::min(tmin, p.mean_time_ms);
    tmax = std::max(tmax, p.mean_time_ms);
    const auto& m = p.objectives.at(obj).mean;
    if (m && std::isfinite(*m)) {
      qmin = std::min(qmin, *m);
      qmax = std::max(qmax, *m);
    }
  }
  if (!(tmin <= tmax)) tmin = 0, tmax = 1;
  if (!(qmin <= qmax)) qmin = 0, qmax = 1;
  auto pad = [](double& lo, double& hi) {
    const double span = hi - lo;
    const double d = span > 1e-12 ? span * 0.06 : std::max(1e-3, std::fabs(hi) * 0.01);
    lo -= d;
    hi += d;
  };
  const bool nonneg = tmin >= 0;
  pad(tmin, tmax);
  if (nonneg) tmin = std::max(0.0, tmin);  // no negative times on the axis
  pad(qmin, qmax);
  auto X = [&](double t) { return L + (W - L - R) * (t - tmin) / (tmax - tmin); };
  auto Y = [&](double q) { return std::isinf(q) ? T - 8 : T + (H - T - B) * (1.0 - (q - qmin) / (qmax - qmin)); };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W
    << " " << H << "\" role=\"img\"><title>Pareto front: " << HtmlEscape(obj) << " vs method time</title>\n";
  s << "<line x1=\"" << L << "\" y1=\"" << T << "\" x2=\"" << L << "\" y2=\"" << H - B << "\" stroke=\"#888\"/>"
    << "<line x1=\"" << L << "\" y1=\"" << H - B << "\" x2=\"" << W - R << "\" y2=\"" << H - B
    << "\" stroke=\"#888\"/>\n";
  const int dq = IsDbMetric(obj) ? 2 : 4;
  s << "<text x=\"" << L - 4 << "\" y=\"" << T + 4 << "\" font-size=\"11\" text-anchor=\"end\">"
    << FormatFixed(qmax, dq) << "</text><text x=\"" << L - 4 << "\" y=\"" << H - B
    << "\" font-size=\"11\" text-anchor=\"end\">" << FormatFixed(qmin, dq) << "</text>\n";
  s << "<text x=\"" << L << "\" y=\"" << H - B + 14 << "\" font-size=\"11\">" << FormatFixed(tmin, 3) << "</text>"
    << "<text x=\"" << W - R << "\" y=\"" << H - B + 14 << "\" font-size=\"11\" text-anchor=\"end\">"
    << FormatFixed(tmax, 3) << "</text>\n";
  s << "<text x=\"" << (L + W - R) / 2 << "\" y=\"" << H - 8
    << "\" font-size=\"12\" text-anchor=\"middle\">method time, "
       "mean over scenes of the median (ms) &#8594; cheaper to the left</text>\n";
  s << "<text x=\"14\" y=\"" << (T + H - B) / 2
    << "\" font-size=\"12\" text-anchor=\"middle\" transform=\"rotate(-90 14 " << (T + H - B) / 2 << ")\">"
    << HtmlEscape(obj) << " (mean over scenes)</text>\n";
  std::string path;
  for (size_t i : r.pareto_front) {
    const auto& m = r.points[i].objectives.at(obj).mean;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%.1f,%.1f ", path.empty() ? "M" : "L", X(r.points[i].mean_time_ms), Y(*m));
    path += buf;
  }
  if (!path.empty()) s << "<path d=\"" << path << "\" fill=\"none\" stroke=\"#d00020\" stroke-width=\"1.5\"/>\n";
  for (size_t i = 0; i < r.points.size(); ++i) {
    const auto& p = r.points[i];
    const auto& m = p.objectives.at(obj);
    if (!m.mean) continue;
    s << "<g><title>"
      << HtmlEscape(p.spec + ": " + SweepMeanText(obj, m) + ", " + FormatFixed(p.mean_time_ms, 3) + " ms" +
                    (p.pareto ? " (Pareto front)" : ""))
      << "</title><circle cx=\"" << X(p.mean_time_ms) << "\" cy=\"" << Y(*m.mean) << "\" r=\"" << (p.pareto ? 5 : 3)
      << "\" fill=\"" << (p.pareto ? "#d00020" : "#8899aa") << "\"/></g>\n";
  }
  s << "</svg>";
  return s.str();
}

/// Heatmap of the first objective over axes a (rows) × b (columns; b == a: one row), each
/// cell the best value over the other axes.
std::string HeatmapSvg(const SweepResult& r, size_t a, size_t b) {
  const std::string& obj = r.objectives.front();
  const Better dir = *MetricDirection(obj);
  const GridAxis& A = r.axes[a];
  const GridAxis& Bx = r.axes[b];
  const bool one = a == b;
  const size_t rows = one ? 1 : A.values.size(), cols = Bx.values.size();
  std::vector<std::optional<double>> cell(rows * cols);
  std::vector<bool> defined(rows * cols, false);
  for (const auto& p : r.points) {
    size_t i = 0, j = 0;
    for (size_t k = 0; k < A.values.size(); ++k) {
      if (p.overrides[a].second == A.values[k]) i = k;
    }
    for (size_t k = 0; k < Bx.values.size(); ++k) {
      if (p.overrides[b].second == Bx.values[k]) j = k;
    }
    if (one) i = 0;
    const auto& m = p.objectives.at(obj).mean;
    auto& c = cell[i * cols + j];
    if (m && (!c || StrictlyBetter(m, c, dir))) c = m;
    defined[i * cols + j] = true;
  }
  double lo = kInf, hi = -kInf;
  for (const auto& c : cell) {
    if (c && std::isfinite(*c)) {
      lo = std::min(lo, *c);
      hi = std::max(hi, *c);
    }
  }
  std::optional<double> best_value;
  for (const auto& c : cell) {
    if (c && (!best_value || StrictlyBetter(c, best_value, dir))) best_value = c;
  }
  const double cw = 76, ch = 30, L = 120, T = 52;
  const double W = L + cw * cols + 10, H = T + ch * rows + 10;
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W
    << " " << H << "\" role=\"img\"><title>" << HtmlEscape(obj) << " over "
    << HtmlEscape(one ? A.name : A.name + " x " + Bx.name) << "</title>\n";
  s << "<text x=\"" << L << "\" y=\"14\" font-size=\"12\">" << HtmlEscape(Bx.name) << " &#8594;"
    << (one ? "" : "  (rows: " + HtmlEscape(A.name) + ")") << "</text>\n";
  for (size_t j = 0; j < cols; ++j) {
    s << "<text x=\"" << L + cw * j + cw / 2 << "\" y=\"" << T - 8 << "\" font-size=\"11\" text-anchor=\"middle\">"
      << HtmlEscape(Bx.values[j]) << "</text>";
  }
  s << "\n";
  for (size_t i = 0; i < rows; ++i) {
    s << "<text x=\"" << L - 6 << "\" y=\"" << T + ch * i + ch / 2 + 4 << "\" font-size=\"11\" text-anchor=\"end\">"
      << HtmlEscape(one ? obj : A.name + "=" + A.values[i]) << "</text>";
    for (size_t j = 0; j < cols; ++j) {
      const auto& c = cell[i * cols + j];
      double t = 0.5;
      std::string fill = "#dddddd", label = "null";
      if (c) {
        if (std::isinf(*c)) {
          t = dir == Better::kHigher ? (*c > 0 ? 1.0 : 0.0) : (*c < 0 ? 1.0 : 0.0);
        } else if (hi > lo) {
          t = (*c - lo) / (hi - lo);
          if (dir == Better::kLower) t = 1.0 - t;
        } else {
          t = 1.0;
        }
        fill = RampColor(t);
        label = SweepValueText(obj, *c);
      }
      const std::string text_color = c && t < 0.55 ? "#ffffff" : "#000000";
      s << "<g><title>"
        << HtmlEscape((one ? "" : A.name + "=" + A.values[i] + ", ") + Bx.name + "=" + Bx.values[j] + ": " + label +
                      (r.axes.size() > 2 ? " (best over the other parameters)" : ""))
        << "</title><rect x=\"" << L + cw * j << "\" y=\"" << T + ch * i << "\" width=\"" << cw - 1 << "\" height=\""
        << ch - 1 << "\" fill=\"" << fill << "\""
        << (c && c == best_value ? " stroke=\"#d00020\" stroke-width=\"3\"" : "") << "/><text x=\""
        << L + cw * j + cw / 2 << "\" y=\"" << T + ch * i + ch / 2 + 4
        << "\" font-size=\"11\" text-anchor=\"middle\" fill=\"" << text_color << "\">" << HtmlEscape(label)
        << "</text></g>";
    }
    s << "\n";
  }
  s << "</svg>";
  return s.str();
}

/// The A/B view of one scene's crops (abview.js): every column of the crop table (reference,
/// default, suggested, each objective's pick, extremes) as a choice whose images are its crop
/// files, one per window; A = default, B = suggested (or the first two columns). Empty when
/// the scene's windows are unknown or fewer than two columns exist.
std::string SweepAbViewHost(const SweepResult& r, const std::string& scene,
                            const std::vector<std::pair<std::string, std::string>>& cols, int windows) {
  const SceneResult* sc = nullptr;
  for (const auto& s : r.report.scenes) {
    if (s.name == scene) sc = &s;
  }
  if (!sc || cols.size() < 2 || static_cast<int>(sc->crops.size()) < windows) return "";
  nlohmann::json choices = nlohmann::json::array();
  std::string a, b;
  for (const auto& [role, spec] : cols) {
    nlohmann::json paths = nlohmann::json::array();
    for (int w = 0; w < windows; ++w) {
      std::string path;
      for (const auto& c : r.crops) {
        if (c.scene == scene && c.role == role && c.spec == spec && c.window == w) path = c.path;
      }
      paths.push_back(path.empty() ? nlohmann::json(nullptr) : nlohmann::json(path));
    }
    const std::string label = spec.empty() ? role : role + ": " + spec;
    choices.push_back({{"key", role}, {"label", label}, {"crops", paths}});
    if (a.empty() && role.find("default") != std::string::npos) a = role;
    if (b.empty() && role.find("suggested") != std::string::npos && role != a) b = role;
  }
  if (a.empty()) a = choices[1]["key"];
  if (b.empty()) b = choices[0]["key"] == a ? choices[1]["key"] : choices[0]["key"];
  nlohmann::json crops = nlohmann::json::array();
  for (int w = 0; w < windows; ++w) {
    const auto& c = sc->crops[static_cast<size_t>(w)];
    crops.push_back({c[0], c[1], c[2], c[3]});
  }
  const nlohmann::json d = {
      {"width", sc->width}, {"height", sc->height}, {"crops", crops}, {"choices", choices}, {"a", a}, {"b", b}};
  return "<div class=\"abview abview-host\" data-ab=\"" + HtmlEscape(d.dump()) + "\"></div>\n";
}

}  // namespace

std::string SweepHtml(const SweepResult& r) {
  std::ostringstream h;
  const std::string& primary = r.objectives.front();
  h << HtmlPageStart("aalab sweep: " + r.method);
  h << "<h1>aalab sweep: " << HtmlEscape(r.method) << "</h1>\n<p>";
  for (const auto& [k, v] : r.report.settings) h << HtmlEscape(k) << " <code>" << HtmlEscape(v) << "</code> ";
  h << "<br>" << r.points.size() << " grid points on " << r.report.scenes.size() << " scenes; each scene's reference "
    << "and 1x frame rendered once (" << r.reference_renders << " reference renders). Objective values are means over "
    << "scenes; time is the method's own time (post + resample, plus render unless it is the 1x frame shared with "
    << "<code>none</code>), median over repeats, mean over scenes.</p>\n";
  h << "<h2>Best setting per objective</h2>\n<table><tr><th class=\"l\">objective</th><th>mean</th><th>time (ms)</th>"
       "<th class=\"l\">setting</th><th class=\"l\">spec</th></tr>\n";
  for (const auto& o : r.objectives) {
    auto it = r.best.find(o);
    if (it == r.best.end()) {
      h << "<tr><td class=\"l\">" << HtmlEscape(o)
        << "</td><td colspan=\"4\" class=\"l\">every point is null</td></tr>\n";
      continue;
    }
    const auto& p = r.points[it->second];
    h << "<tr><td class=\"l\">" << HtmlEscape(o) << "</td><td>" << HtmlEscape(SweepMeanText(o, p.objectives.at(o)))
      << "</td><td>" << FormatFixed(p.mean_time_ms, 3) << "</td><td class=\"l\">"
      << HtmlEscape(JoinOverrides(p.overrides)) << "</td><td class=\"l\"><code>" << HtmlEscape(p.spec)
      << "</code></td></tr>\n";
  }
  h << "</table>\n";
  for (const auto& d : r.disagreements) {
    h << "<p class=\"disagree\" style=\"border:2px solid #d00020;padding:4px 8px;font-weight:bold\">&#9888; "
      << HtmlEscape(d) << "</p>\n";
  }
  if (!r.suggested_preset.empty()) {
    h << "<p>Suggested preset: <code>" << HtmlEscape(r.suggested_preset) << "</code> (" << HtmlEscape(r.suggestion_rule)
      << ")</p>\n";
  }
  // The suggestion against the shipped default, per scene.
  h << "<h2>Suggestion against the default</h2>\n";
  if (!r.default_point) {
    h << "<p>" << HtmlEscape(r.default_note) << "</p>\n";
  } else if (r.suggested && *r.suggested == *r.default_point) {
    h << "<p>The suggestion is the default (<code>" << HtmlEscape(r.points[*r.default_point].spec) << "</code>).</p>\n";
  } else if (!r.scene_changes.empty()) {
    h << "<table class=\"scene-change\"><tr><th class=\"l\">scene</th>";
    for (const auto& o : r.objectives) h << "<th>" << HtmlEscape(o) << " default</th><th>suggested</th><th>change</th>";
    h << "<th>time default (ms)</th><th>suggested</th><th>spreads</th></tr>\n";
    for (const auto& c : r.scene_changes) {
      h << "<tr><td class=\"l\">" << HtmlEscape(c.scene) << "</td>";
      for (const auto& v : c.values) {
        auto txt = [&v](const std::optional<double>& x) {
          return x ? SweepValueText(v.objective, *x) : std::string("null");
        };
        std::string delta = "-";
        if (v.at_default && v.suggested && std::isfinite(*v.at_default) && std::isfinite(*v.suggested)) {
          const double d = *v.suggested - *v.at_default;
          delta = (d >= 0 ? "+" : "") + SweepValueText(v.objective, d);
        }
        h << "<td>" << txt(v.at_default) << "</td><td>" << txt(v.suggested) << "</td><td>" << delta << "</td>";
      }
      h << "<td>" << FormatFixed(c.default_ms, 3) << "</td><td>" << FormatFixed(c.suggested_ms, 3) << "</td><td>"
        << FormatFixed(c.default_spread_ms, 3) << ", " << FormatFixed(c.suggested_spread_ms, 3) << "</td></tr>\n";
    }
    h << "</table>\n";
  }
  // Crops: the reference, the default, the suggestion, each objective's pick and the extremes.
  h << "<h2>Crops</h2>\n";
  if (r.crops.empty()) {
    h << "<p>No crops (a merged sweep: crops are written by an unsharded sweep only).</p>\n";
  } else {
    h << "<p>Each scene's crop windows (where <code>none</code> is furthest from the reference on edges), "
         "enlarged nearest-neighbour to 192 px; hover for the spec.</p>\n";
    std::vector<std::string> scenes;
    for (const auto& c : r.crops) {
      if (std::find(scenes.begin(), scenes.end(), c.scene) == scenes.end()) scenes.push_back(c.scene);
    }
    for (const auto& sc : scenes) {
      std::vector<std::pair<std::string, std::string>> cols;  // role, spec
      int windows = 0;
      for (const auto& c : r.crops) {
        if (c.scene != sc) continue;
        windows = std::max(windows, c.window + 1);
        if (std::find(cols.begin(), cols.end(), std::make_pair(c.role, c.spec)) == cols.end())
          cols.emplace_back(c.role, c.spec);
      }
      h << "<h3>" << HtmlEscape(sc) << "</h3>\n<table class=\"sweep-crops\"><tr>";
      for (const auto& [role, spec] : cols) {
        h << "<th title=\"" << HtmlEscape(spec) << "\">" << HtmlEscape(role)
          << "<br><code style=\"font-weight:normal\">" << HtmlEscape(spec.empty() ? std::string("reference") : spec)
          << "</code></th>";
      }
      h << "</tr>\n";
      for (int w = 0; w < windows; ++w) {
        h << "<tr>";
        for (const auto& [role, spec] : cols) {
          h << "<td>";
          for (const auto& c : r.crops) {
            if (c.scene == sc && c.role == role && c.spec == spec && c.window == w) {
              h << "<img src=\"" << HtmlEscape(c.path) << "\" alt=\"" << HtmlEscape(role) << "\" title=\""
                << HtmlEscape(spec) << "\" style=\"width:192px;image-rendering:pixelated\">";
            }
          }
          h << "</td>";
        }
        h << "</tr>\n";
      }
      h << "</table>\n";
      const std::string ab = SweepAbViewHost(r, sc, cols, windows);
      if (!ab.empty()) {
        h << "<p>Any two side by side (the crop windows of " << HtmlEscape(sc)
          << "; keys 1&#8211;9 pick the window, f flips A and B):</p>\n"
          << ab;
      }
    }
  }
  h << "<h2>Pareto front: " << HtmlEscape(primary) << " vs time</h2>\n" << ParetoSvg(r) << "\n";
  h << "<h2>Heatmaps of " << HtmlEscape(primary) << "</h2>\n";
  h << "<p>Colour from worse (dark) to better (yellow), scaled to the cells shown; red outline: the best cell"
    << (r.axes.size() > 2 ? "; each cell is the best value over the parameters not shown" : "") << ".</p>\n";
  if (r.axes.size() == 1) {
    h << HeatmapSvg(r, 0, 0) << "\n";
  } else {
    for (size_t a = 0; a < r.axes.size(); ++a) {
      for (size_t b = a + 1; b < r.axes.size(); ++b) h << "<div>" << HeatmapSvg(r, a, b) << "</div>\n";
    }
  }
  // Every point, best first.
  std::vector<size_t> order(r.points.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  const Better dir = *MetricDirection(primary);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return StrictlyBetter(r.points[a].objectives.at(primary).mean, r.points[b].objectives.at(primary).mean, dir);
  });
  h << "<h2>All points</h2>\n<table><tr>";
  for (const auto& a : r.axes) h << "<th>" << HtmlEscape(a.name) << "</th>";
  for (const auto& o : r.objectives) h << "<th>" << HtmlEscape(o) << "</th>";
  h << "<th>time (ms)</th><th>Pareto</th></tr>\n";
  for (size_t i : order) {
    const auto& p = r.points[i];
    h << "<tr>";
    for (const auto& [k, v] : p.overrides) h << "<td>" << HtmlEscape(v) << "</td>";
    for (const auto& o : r.objectives) h << "<td>" << HtmlEscape(SweepMeanText(o, p.objectives.at(o))) << "</td>";
    h << "<td>" << FormatFixed(p.mean_time_ms, 3) << "</td><td>" << (p.pareto ? "&#9679;" : "") << "</td></tr>\n";
  }
  h << "</table>\n";
  if (!r.crops.empty()) h << html::AbViewAssets();
  h << HtmlPageEnd();
  return h.str();
}

}  // namespace aalab
