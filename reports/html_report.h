/// The HTML report (`DIR/index.html`): what accuracy costs in time, where each method fails,
/// side by side. One self-contained page that works offline from disk (file://): no network,
/// no fetch(); the report's JSON is embedded, the CSS and script are inline, images are linked
/// relative to the report folder. Tables are rendered here (readable without JavaScript); the
/// charts, the cost-of-accuracy tables and the gallery are drawn by the inline script from the
/// embedded JSON.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "reports/result.h"

namespace aalab {

/// Renders the whole page for `report`. Pure: reads nothing, writes nothing, same report →
/// same bytes. Shows whichever metrics and images the rows hold. Image paths in the report
/// must be relative to the report folder (they are linked as they are, percent-encoded).
std::string RenderHtmlReport(const Report& report);

/// The same page, with `report_json` = ReportToJson(report) built by the caller (who also
/// writes it as report.json): the same bytes as RenderHtmlReport(report), one build fewer.
std::string RenderHtmlReport(const Report& report, const nlohmann::ordered_json& report_json);

}  // namespace aalab
