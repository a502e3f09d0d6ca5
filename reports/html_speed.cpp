// The speed-sweep chart: scenes named motion-speed-<kind>-<speed> (scenes/library, written by
// scripts/gen_motion_speed_scenes.py), plotted as quality against speed per method. Static
// SVG: x = log2(speed) over the family's speeds, y = the measure from 0 to the largest value.
#include "reports/html_speed.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "core/format.h"
#include "reports/html_method_style.h"
#include "reports/html_page.h"

namespace aalab {

namespace {

constexpr const char* kPrefix = "motion-speed-";

// "translate-0p25" → ("translate", 0.25); false for names outside the family.
bool ParseSweepScene(const std::string& scene, std::string* kind, double* speed) {
  if (scene.rfind(kPrefix, 0) != 0) return false;
  const std::string rest = scene.substr(std::char_traits<char>::length(kPrefix));
  const size_t dash = rest.rfind('-');
  if (dash == std::string::npos || dash == 0) return false;
  std::string num = rest.substr(dash + 1);
  std::replace(num.begin(), num.end(), 'p', '.');
  char* end = nullptr;
  const double v = std::strtod(num.c_str(), &end);
  if (num.empty() || end != num.c_str() + num.size() || !(v > 0.0)) return false;
  *kind = rest.substr(0, dash);
  *speed = v;
  return true;
}

std::optional<double> MetricOf(const ResultRow& row, const std::string& name) {
  for (const auto& m : row.metrics) {
    if (m.name == name) return m.value;
  }
  return std::nullopt;
}

std::string Num(double v, const char* fmt = "%.1f") { return FormatDouble(fmt, v); }

void Chart(std::string& h, const std::vector<const SpeedPoint*>& pts, bool temporal,
           const std::vector<std::string>& methods) {
  const double W = 340, H = 200, L = 52, R = 10, T = 22, B = 30;
  double smin = 1e30, smax = -1e30, ymax = 0.0;
  for (const SpeedPoint* p : pts) {
    smin = std::min(smin, p->speed);
    smax = std::max(smax, p->speed);
    ymax = std::max(ymax, temporal ? p->temporal_perceptual : p->flip_mean);
  }
  if (ymax <= 0.0) ymax = 1.0;
  const double lx0 = std::log2(smin), lx1 = std::max(std::log2(smax), lx0 + 1e-9);
  auto X = [&](double s) { return L + (std::log2(s) - lx0) / (lx1 - lx0) * (W - L - R); };
  auto Y = [&](double v) { return H - B - v / ymax * (H - T - B); };
  h += "<svg class=\"speed-chart\" width=\"" + Num(W, "%.0f") + "\" height=\"" + Num(H, "%.0f") +
       "\" role=\"img\"><text x=\"" + Num(L) + "\" y=\"14\" font-size=\"12\">" +
       (temporal ? "temporal_perceptual (pooled)" : "flip_mean (pooled)") + " vs px/frame</text>";
  h += "<line x1=\"" + Num(L) + "\" y1=\"" + Num(H - B) + "\" x2=\"" + Num(W - R) + "\" y2=\"" + Num(H - B) +
       "\" stroke=\"#888\"/><line x1=\"" + Num(L) + "\" y1=\"" + Num(T) + "\" x2=\"" + Num(L) + "\" y2=\"" +
       Num(H - B) + "\" stroke=\"#888\"/>";
  h += "<text x=\"2\" y=\"" + Num(T + 8) + "\" font-size=\"10\">" + Num(ymax, "%.4g") + "</text><text x=\"2\" y=\"" +
       Num(H - B) + "\" font-size=\"10\">0</text>";
  std::map<double, bool> ticks;
  for (const SpeedPoint* p : pts) ticks[p->speed] = true;
  for (const auto& [s, _] : ticks) {
    h += "<text x=\"" + Num(X(s) - 8) + "\" y=\"" + Num(H - B + 14) + "\" font-size=\"10\">" + Num(s, "%g") + "</text>";
  }
  for (size_t m = 0; m < methods.size(); ++m) {
    std::string line;
    for (const SpeedPoint* p : pts) {
      if (p->method != methods[m]) continue;
      line += Num(X(p->speed)) + "," + Num(Y(temporal ? p->temporal_perceptual : p->flip_mean)) + " ";
    }
    std::string marks;
    for (const SpeedPoint* p : pts) {
      if (p->method == methods[m])
        marks += html::MarkerSvg(methods[m], X(p->speed), Y(temporal ? p->temporal_perceptual : p->flip_mean), 3.5);
    }
    h += "<g><title>" + HtmlEscape(methods[m]) + "</title><polyline fill=\"none\" stroke-width=\"1.5\" stroke=\"" +
         html::StyleOfMethod(methods[m]).colour + "\" points=\"" + line + "\"/>" + marks + "</g>";
  }
  h += "</svg>\n";
}

}  // namespace

std::vector<SpeedPoint> SpeedSweepPoints(const Report& report) {
  std::vector<SpeedPoint> out;
  for (const auto& row : report.rows) {
    SpeedPoint p;
    if (!ParseSweepScene(row.scene, &p.kind, &p.speed)) continue;
    const auto tp = MetricOf(row, "temporal_perceptual"), flip = MetricOf(row, "flip_mean");
    if (!tp || !flip) continue;
    p.method = row.spec;
    p.temporal_perceptual = *tp;
    p.flip_mean = *flip;
    out.push_back(std::move(p));
  }
  // By kind (first appearance), then speed, then report order.
  std::vector<std::string> kinds;
  for (const auto& p : out) {
    if (std::find(kinds.begin(), kinds.end(), p.kind) == kinds.end()) kinds.push_back(p.kind);
  }
  std::stable_sort(out.begin(), out.end(), [&](const SpeedPoint& a, const SpeedPoint& b) {
    const auto ka = std::find(kinds.begin(), kinds.end(), a.kind), kb = std::find(kinds.begin(), kinds.end(), b.kind);
    return ka != kb ? ka < kb : a.speed < b.speed;
  });
  return out;
}

void AppendSpeedSection(std::string& h, const Report& report) {
  const std::vector<SpeedPoint> pts = SpeedSweepPoints(report);
  if (pts.empty()) return;
  std::vector<std::string> methods, kinds;
  for (const auto& p : pts) {
    if (std::find(methods.begin(), methods.end(), p.method) == methods.end()) methods.push_back(p.method);
    if (std::find(kinds.begin(), kinds.end(), p.kind) == kinds.end()) kinds.push_back(p.kind);
  }
  h += "<section id=\"speed-sweep\"><h2>Speed sweep</h2>\n<p>Pooled temporal_perceptual and pooled FLIP (lower is "
       "better) against the speed in px per frame at 320x180 (log scale), per kind of motion "
       "(scenes motion-speed-&lt;kind&gt;-&lt;speed&gt;; docs/motion.md). Methods: ";
  for (size_t m = 0; m < methods.size(); ++m) {
    h += std::string(m ? ", " : "") + "<span style=\"color:" + html::StyleOfMethod(methods[m]).colour +
         "\"><svg width=\"12\" height=\"12\" viewBox=\"-6 -6 12 12\" aria-hidden=\"true\">" +
         html::MarkerSvg(methods[m], 0, 0, 4.5) + "</svg> " + HtmlEscape(methods[m]) + "</span>";
  }
  h += "</p>\n";
  for (const auto& k : kinds) {
    std::vector<const SpeedPoint*> sel;
    for (const auto& p : pts) {
      if (p.kind == k) sel.push_back(&p);
    }
    h += "<h3>" + HtmlEscape(k) + "</h3>\n";
    Chart(h, sel, true, methods);
    Chart(h, sel, false, methods);
  }
  h += "</section>\n";
}

std::string SpeedSweepCsv(const Report& report) {
  std::string s = "kind,speed,method,temporal_perceptual,flip_mean\n";
  for (const auto& p : SpeedSweepPoints(report)) {
    s += p.kind + "," + Num(p.speed, "%.17g") + "," + p.method + "," + Num(p.temporal_perceptual, "%.17g") + "," +
         Num(p.flip_mean, "%.17g") + "\n";
  }
  return s;
}

}  // namespace aalab
