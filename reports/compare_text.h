/// The text of a comparison (reports/compare.h): how compared values are written, shared by
/// the rules' notes and the page, and the table `aalab compare` prints.
#pragma once
#include <string>

#include "reports/compare.h"
#include "reports/result.h"

namespace aalab {

/// A compared value as text: 3 decimals for dB metrics and time_ms, else %.6g; "inf" / "-inf".
std::string CompareValueText(const std::string& quantity, double v);

/// A delta as text: CompareValueText with a sign ("+0.000", "-1.5"); "+inf" / "-inf".
std::string CompareDeltaText(const std::string& quantity, double d);

/// The baseline (`base`) or current value of a line: the number, "inf (reason)" for a null
/// read as +infinity, or "null (reason)".
std::string LineValueText(const CompareLine& line, bool base);

/// The human-readable result: a header, the table of changed values (every value with
/// `all`), missing/extra rows, notes and a summary line ending in the exit code.
std::string FormatCompareText(const CompareResult& result, const Report& baseline, const Report& current,
                              const std::string& baseline_name, const std::string& current_name, bool all);

}  // namespace aalab
