/// The small helpers every offline HTML page of aalab shares (index.html and its GPU and
/// stability sections, compare, history, sweep): escaping text for HTML, JSON in a script tag
/// and relative URLs; number formatting; a colour ramp; and the frame of the plain pages
/// (compare, history, sweep: inline CSS, no scripts, no external files).
#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace aalab {

/// Escapes text for HTML element content and double- or single-quoted attribute values
/// (& < > " ' → entities). Bytes ≥ 0x80 pass through (the page is UTF-8).
std::string HtmlEscape(std::string_view text);

/// Makes serialized JSON safe inside `<script type="application/json">`: replaces every
/// `<`, `>` and `&` with its `\u00XX` escape (these only occur inside JSON strings, where the
/// escape is equivalent), so `</script>` or `<!--` in a name cannot end the block. U+2028 and
/// U+2029 are escaped too. The result parses to the same JSON value.
std::string JsonForScriptTag(std::string_view json);

/// Percent-encodes a relative path for use in `src`/`href`: every byte outside
/// [A-Za-z0-9-._~/] is written as %XX, so `#`, `?`, `%`, `:` and spaces in file names cannot
/// change the URL's meaning. `/` separates segments and is kept.
std::string UrlEncodePath(std::string_view path);

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
