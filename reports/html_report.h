/// The HTML report (`DIR/index.html`): what accuracy costs in time, where each method fails,
/// side by side. One self-contained page that works offline from disk (file://): no network,
/// no fetch(); the report's JSON is embedded, the CSS and script are inline, images are linked
/// relative to the report folder. Tables are rendered here (readable without JavaScript); the
/// charts, the cost-of-accuracy tables and the gallery are drawn by the inline script from the
/// embedded JSON.
#pragma once
#include <string>
#include <string_view>

#include "reports/result.h"

namespace aalab {

/// Renders the whole page for `report`. Pure: reads nothing, writes nothing, same report →
/// same bytes. Shows whichever metrics and images the rows hold. Image paths in the report
/// must be relative to the report folder (they are linked as they are, percent-encoded).
std::string RenderHtmlReport(const Report& report);

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

}  // namespace aalab
