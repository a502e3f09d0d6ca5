#include "reports/html_page.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace aalab {

std::string HtmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string JsonForScriptTag(std::string_view json) {
  std::string out;
  out.reserve(json.size() + 64);
  for (size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '<') {
      out += "\\u003c";
    } else if (c == '>') {
      out += "\\u003e";
    } else if (c == '&') {
      out += "\\u0026";
    } else if (c == '\xE2' && i + 2 < json.size() && json[i + 1] == '\x80' &&
               (json[i + 2] == '\xA8' || json[i + 2] == '\xA9')) {
      out += json[i + 2] == '\xA8' ? "\\u2028" : "\\u2029";  // valid JSON, odd in a script
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

std::string UrlEncodePath(std::string_view path) {
  static const char* kHex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : path) {
    if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '.' ||
        c == '_' || c == '~' || c == '/') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

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
