/// Text of one number through a printf format: the one helper the reports, pages and
/// benchmarks share (they used to carry five copies of it).
#pragma once
#include <string>

namespace aalab {

/// snprintf(fmt, v) as a string; `fmt` holds exactly one double conversion ("%.2f", "%.4g",
/// "%.1f×"). Output longer than 63 bytes is cut there.
std::string FormatDouble(const char* fmt, double v);

}  // namespace aalab
