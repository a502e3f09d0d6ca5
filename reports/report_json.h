/// JSON form of a report (schema in reports/SCHEMA.md). Never writes NaN or Infinity.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/result.h"

namespace aalab {

/// Current schema version written in every report.
constexpr int kSchemaVersion = 1;

/// Converts a report to ordered JSON. Non-finite numbers are an internal error (never null
/// silently): metrics already carry null + reason where a value is undefined.
nlohmann::ordered_json ReportToJson(const Report& report);

/// Parses a report written by ReportToJson. Throws UserError naming the file and field for
/// malformed input or an unsupported schema_version.
Report ReportFromJson(const nlohmann::ordered_json& doc, const std::string& origin);

/// Every image file the report links (scene and row images, frame images), relative to the
/// report's folder, in report order (a file linked twice is listed twice).
std::vector<std::string> ReportImages(const Report& report);

/// Reads and parses a report file (UserError on failure).
Report ReadReportFile(const std::string& path);

}  // namespace aalab
