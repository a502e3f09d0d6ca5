#include "reports/compare_html.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace aalab {

std::string FormatFixed(double v, int decimals) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);  // no "-0.000"
  return s;
}

std::string FormatOptional(const std::optional<double>& v, int decimals, const std::string& null_text) {
  return v ? FormatFixed(*v, decimals) : null_text;
}

std::string RampColor(double t) {
  // viridis at 0, 0.25, 0.5, 0.75, 1 (matplotlib table entries 0, 64, 128, 191, 255).
  static constexpr std::array<std::array<double, 3>, 5> kAnchors = {{{0.267004, 0.004874, 0.329415},
                                                                     {0.229739, 0.322361, 0.545706},
                                                                     {0.127568, 0.566949, 0.550556},
                                                                     {0.369214, 0.788888, 0.382914},
                                                                     {0.993248, 0.906157, 0.143936}}};
  if (!(t >= 0.0)) t = 0.0;
  if (t > 1.0) t = 1.0;
  const double f = t * 4.0;
  const int i = std::min(3, static_cast<int>(f));
  const double u = f - i;
  char buf[8];
  int c[3];
  for (int k = 0; k < 3; ++k) {
    const double v = kAnchors[i][k] + (kAnchors[i + 1][k] - kAnchors[i][k]) * u;
    c[k] = static_cast<int>(std::lround(v * 255.0));
  }
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c[0], c[1], c[2]);
  return buf;
}

std::string HtmlPageStart(const std::string& title) {
  return "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + HtmlEscape(title) +
         "</title>\n<style>\n"
         "body{font-family:system-ui,sans-serif;margin:1.5em;color:#222;background:#fff}\n"
         "table{border-collapse:collapse;margin:0.5em 0}\n"
         "th,td{border:1px solid #ccc;padding:2px 6px;text-align:right;font-variant-numeric:tabular-nums}\n"
         "th{background:#f0f0f0}td.l,th.l{text-align:left}\n"
         ".regression{color:#b00020;font-weight:bold}.improved{color:#1b7f2a}.within{color:#666}\n"
         ".not-judged{color:#a06000}.unchanged{color:#999}\n"
         ".imgs{display:flex;gap:12px;flex-wrap:wrap}.imgs figure{margin:0}\n"
         ".imgs img{image-rendering:pixelated;border:1px solid #999;min-width:192px}\n"
         ".missing{border:1px dashed #999;padding:1em;color:#a06000;max-width:24em}\n"
         "section{margin-bottom:2em}svg{background:#fafafa;border:1px solid #ddd;margin:2px}\n"
         "svg text{font-family:system-ui,sans-serif}\n"
         "</style></head><body>\n";
}

std::string HtmlPageEnd() { return "</body></html>\n"; }

}  // namespace aalab
