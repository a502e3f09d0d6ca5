/// Small helpers for the offline HTML pages of compare, history and sweep: escaping, number
/// formatting, a colour ramp and the page frame (inline CSS, no scripts, no external files).
#pragma once
#include <optional>
#include <string>

#include "reports/html_report.h"  // HtmlEscape

namespace aalab {


/// Fixed-point with `decimals` digits; "inf" / "-inf" for infinities, "nan" for NaN.
std::string FormatFixed(double v, int decimals);

/// Optional value: FormatFixed, or `null_text` when empty.
std::string FormatOptional(const std::optional<double>& v, int decimals, const std::string& null_text);

/// A perceptually ordered colour ramp (dark blue → green → yellow, viridis anchors linearly
/// interpolated) for t in [0, 1] (clamped), as "#rrggbb".
std::string RampColor(double t);

/// "<!doctype html>..." up to and including "<body>", with the shared inline style sheet.
std::string HtmlPageStart(const std::string& title);

/// "</body></html>\n".
std::string HtmlPageEnd();

}  // namespace aalab
