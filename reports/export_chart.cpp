// aalab export's quality-vs-time chart (reports/export_chart.h).
#include "reports/export_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/format.h"
#include "reports/export_crops.h"
#include "reports/export_tables.h"
#include "reports/html_assets.h"

namespace aalab {

namespace {

constexpr double kW = 660, kH = 420, kL = 70, kR = 20, kT = 16, kB = 52;
const char* kFont = "DejaVu Sans, Helvetica, Arial, sans-serif";
const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2"};

std::string F(double v) { return FormatDouble("%.1f", v); }

/// Tick text: whole numbers in full ("1000", not "1e+03"), others to 3 significant digits.
std::string Tick(double v) {
  char buf[32];
  if (std::fabs(v) >= 1 && std::fabs(v) < 1e7 && std::fabs(v - std::round(v)) < 1e-9 * std::fabs(v)) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
  } else {
    std::snprintf(buf, sizeof buf, "%.3g", v);
  }
  return buf;
}

/// 1-2-5 ticks between lo and hi (1..9 when fewer than 3), as the page's log axis.
std::vector<double> LogTicks(double lo, double hi) {
  std::vector<double> out;
  const int e0 = static_cast<int>(std::floor(std::log10(lo))), e1 = static_cast<int>(std::ceil(std::log10(hi)));
  for (const std::vector<int>& mants : {std::vector<int>{1, 2, 5}, std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}}) {
    out.clear();
    for (int e = e0; e <= e1; ++e) {
      for (int m : mants) {
        const double v = m * std::pow(10.0, e);
        if (v >= lo && v <= hi) out.push_back(v);
      }
    }
    if (out.size() >= 3) break;
  }
  return out;
}

/// About six round linear ticks between lo and hi.
std::vector<double> LinTicks(double lo, double hi) {
  const double raw = (hi - lo) / 6, mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * mag;
  for (double k : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (k * mag >= raw) {
      step = k * mag;
      break;
    }
  }
  std::vector<double> out;
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step)
    out.push_back(std::fabs(v) < step * 1e-9 ? 0 : v);
  return out;
}

struct Box {
  double x0, x1, y0, y1;
  bool Overlaps(const Box& o) const { return !(x1 < o.x0 || x0 > o.x1 || y1 < o.y0 || y0 > o.y1); }
};

}  // namespace

std::string QualityTimeChartSvg(const std::vector<ExportSource>& sources, const ExportSelection& sel,
                                const std::vector<std::string>& provenance) {
  const html::MetricInfo info = html::DescribeMetric(sel.metric);
  std::vector<std::vector<MeanPoint>> series;
  std::vector<std::string> unplotted;
  double lx0 = INFINITY, lx1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto& src : sources) {
    std::vector<MeanPoint> pts;
    for (const auto& p : MeanPoints(src, sel)) {
      if (p.q && p.t && *p.t > 0) {
        pts.push_back(p);
        lx0 = std::min(lx0, std::log10(*p.t));
        lx1 = std::max(lx1, std::log10(*p.t));
        y0 = std::min(y0, *p.q);
        y1 = std::max(y1, *p.q);
      } else {
        unplotted.push_back((sources.size() > 1 ? src.label + ": " : "") + p.spec +
                            (p.q ? " (time 0 ms, not on a log axis)" : " (no value over the chosen scenes)"));
      }
    }
    series.push_back(pts);
  }
  std::string o = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!--\n";
  for (const auto& line : provenance) o += "  " + XmlEscape(line) + "\n";
  o += "-->\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + F(kW) + "\" height=\"" + F(kH) +
       "\" viewBox=\"0 0 " + F(kW) + " " + F(kH) + "\" font-family=\"" + kFont + "\" font-size=\"11\">\n<metadata>";
  for (const auto& line : provenance) o += XmlEscape(line) + "\n";
  o += "</metadata>\n<desc>" +
       XmlEscape("Mean " + info.label + " against mean time per frame over the chosen scenes (" +
                 std::to_string(sel.scenes.size()) + " asked; the tables' notes name any left out). " +
                 ConditionsSentence(sources.front().report) +
                 (unplotted.empty() ? ""
                                    : " Not plotted: " +
                                          [&] {
                                            std::string s;
                                            for (const auto& u : unplotted) s += (s.empty() ? "" : "; ") + u;
                                            return s;
                                          }())) +
       "</desc>\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  if (!std::isfinite(lx0)) {
    o += "<text x=\"" + F(kW / 2) + "\" y=\"" + F(kH / 2) + "\" text-anchor=\"middle\">No method has a value of " +
         XmlEscape(info.label) + " and a time to plot.</text>\n</svg>\n";
    return o;
  }
  if (lx1 - lx0 < 0.5) {
    const double c = (lx0 + lx1) / 2;
    lx0 = c - 0.25;
    lx1 = c + 0.25;
  }
  const double padx = (lx1 - lx0) * 0.07;
  lx0 -= padx;
  lx1 += padx;
  if (y1 - y0 < 1e-12) {
    const double d = std::fabs(y0) * 0.05 > 0 ? std::fabs(y0) * 0.05 : 0.5;
    y0 -= d;
    y1 += d;
  }
  const double pady = (y1 - y0) * 0.08;
  y0 -= pady;
  y1 += pady;
  auto X = [&](double t) { return kL + (std::log10(t) - lx0) / (lx1 - lx0) * (kW - kL - kR); };
  auto Y = [&](double q) { return kH - kB - (q - y0) / (y1 - y0) * (kH - kT - kB); };
  o += "<g stroke=\"#ddd\" stroke-width=\"1\">\n";
  std::string ticks;
  for (double v : LogTicks(std::pow(10.0, lx0), std::pow(10.0, lx1))) {
    o += "<line x1=\"" + F(X(v)) + "\" x2=\"" + F(X(v)) + "\" y1=\"" + F(kT) + "\" y2=\"" + F(kH - kB) + "\"/>\n";
    ticks +=
        "<text x=\"" + F(X(v)) + "\" y=\"" + F(kH - kB + 15) + "\" text-anchor=\"middle\">" + Tick(v) + "</text>\n";
  }
  for (double v : LinTicks(y0, y1)) {
    o += "<line x1=\"" + F(kL) + "\" x2=\"" + F(kW - kR) + "\" y1=\"" + F(Y(v)) + "\" y2=\"" + F(Y(v)) + "\"/>\n";
    ticks += "<text x=\"" + F(kL - 6) + "\" y=\"" + F(Y(v) + 4) + "\" text-anchor=\"end\">" + Tick(v) + "</text>\n";
  }
  o += "</g>\n<g fill=\"#333\">\n" + ticks + "</g>\n";
  o += "<g stroke=\"#333\" stroke-width=\"1\"><line x1=\"" + F(kL) + "\" x2=\"" + F(kW - kR) + "\" y1=\"" + F(kH - kB) +
       "\" y2=\"" + F(kH - kB) + "\"/><line x1=\"" + F(kL) + "\" x2=\"" + F(kL) + "\" y1=\"" + F(kT) + "\" y2=\"" +
       F(kH - kB) + "\"/></g>\n";
  o += "<text x=\"" + F(kL + (kW - kL - kR) / 2) + "\" y=\"" + F(kH - 14) +
       "\" text-anchor=\"middle\" font-size=\"12\">time per frame (ms, mean of per-scene medians, log scale)</text>\n";
  o += "<text transform=\"translate(16 " + F(kT + (kH - kT - kB) / 2) +
       ") rotate(-90)\" text-anchor=\"middle\" font-size=\"12\">" +
       XmlEscape("mean " + info.label + (info.unit.empty() ? "" : " (" + info.unit + ")") + ", " +
                 (info.better > 0   ? "higher is better"
                  : info.better < 0 ? "lower is better"
                                    : "direction unknown")) +
       "</text>\n";
  std::vector<Box> placed;
  for (const auto& pts : series) {
    for (const auto& p : pts) placed.push_back({X(*p.t) - 5, X(*p.t) + 5, Y(*p.q) - 5, Y(*p.q) + 5});
  }
  for (size_t s = 0; s < series.size(); ++s) {
    const char* c = kColours[s % 6];
    const std::set<std::string> front = ParetoFront(series[s], info.better);
    std::vector<const MeanPoint*> fpts;
    for (const auto& p : series[s]) {
      if (front.count(p.spec)) fpts.push_back(&p);
    }
    if (fpts.size() > 1) {
      std::string d = "M" + F(X(*fpts[0]->t)) + " " + F(Y(*fpts[0]->q));
      for (size_t i = 1; i < fpts.size(); ++i) d += " H" + F(X(*fpts[i]->t)) + " V" + F(Y(*fpts[i]->q));
      o += "<path d=\"" + d + "\" fill=\"none\" stroke=\"" + c + "\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\"/>\n";
    }
    for (const auto& p : series[s]) {
      const double cx = X(*p.t), cy = Y(*p.q);
      const bool on = front.count(p.spec) > 0;
      o += "<circle cx=\"" + F(cx) + "\" cy=\"" + F(cy) + "\" r=\"" + (on ? "4.5" : "4") + "\" fill=\"" +
           (on ? c : "#fff") + "\" stroke=\"" + c + "\" stroke-width=\"1.5\" data-spec=\"" + XmlEscape(p.spec) +
           "\"><title>" + XmlEscape(p.spec) + "</title></circle>\n";
      const double w = p.spec.size() * 6.2 + 2;
      struct Try {
        double dx, dy;
        bool end;
      };
      // Beside the point first, then further up or down with a leader line.
      std::vector<Try> tries = {{7, 4, false},  {7, -6, false}, {7, 14, false},      {-7, 4, true},
                                {-7, -6, true}, {-7, 14, true}, {-w / 2, -9, false}, {-w / 2, 17, false}};
      for (double dy = 26; dy <= 86; dy += 12) {
        for (const double sign : {-1.0, 1.0}) {
          tries.push_back({12, sign * dy + 4, false});
          tries.push_back({-12, sign * dy + 4, true});
        }
      }
      const Try* pick = nullptr;
      Box box{};
      for (const Try& t : tries) {
        const double x0 = t.end ? cx + t.dx - w : cx + t.dx;
        box = {x0, x0 + w, cy + t.dy - 9, cy + t.dy + 2};
        if (box.x0 < kL || box.x1 > kW - kR || box.y0 < kT || box.y1 > kH - kB) continue;
        if (std::any_of(placed.begin(), placed.end(), [&](const Box& b) { return b.Overlaps(box); })) continue;
        pick = &t;
        break;
      }
      if (!pick) {  // nowhere free: overlap rather than lose the name
        pick = &tries[0];
        box = {cx + 7, cx + 7 + w, cy - 5, cy + 6};
      }
      placed.push_back(box);
      if (std::fabs(pick->dy) > 20) {
        o += "<line x1=\"" + F(cx) + "\" y1=\"" + F(cy) + "\" x2=\"" + F(cx + pick->dx) + "\" y2=\"" +
             F(cy + pick->dy - 4) + "\" stroke=\"" + c + "\" stroke-width=\"0.6\"/>\n";
      }
      o += "<text x=\"" + F(cx + pick->dx) + "\" y=\"" + F(cy + pick->dy) + "\"" +
           (pick->end ? " text-anchor=\"end\"" : "") + " fill=\"" + c + "\">" + XmlEscape(p.spec) + "</text>\n";
    }
  }
  // Legend: the series (several reports) and what filled / hollow mean.
  double ly = kT + 12;
  for (size_t s = 0; s < series.size() && sources.size() > 1; ++s) {
    o += "<circle cx=\"" + F(kW - kR - 150) + "\" cy=\"" + F(ly - 4) + "\" r=\"4\" fill=\"" + kColours[s % 6] +
         "\"/><text x=\"" + F(kW - kR - 142) + "\" y=\"" + F(ly) + "\">" + XmlEscape(sources[s].label) + "</text>\n";
    ly += 14;
  }
  o += "<text x=\"" + F(kW - kR - 4) + "\" y=\"" + F(kH - kB - 6) +
       "\" text-anchor=\"end\" fill=\"#555\">filled: on the Pareto front (dashed); hollow: dominated</text>\n";
  return o + "</svg>\n";
}

}  // namespace aalab
