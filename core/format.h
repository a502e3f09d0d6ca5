/// Text of one number through a printf format: the one helper the reports, pages and
/// benchmarks share (they used to carry five copies of it).
#pragma once
#include <string>

namespace aalab {

/// snprintf(fmt, v) as a string; `fmt` holds exactly one double conversion ("%.2f", "%.4g",
/// "%.1f×"), whole at any length (before 2026-11-28 it was cut at 63 bytes).
std::string FormatDouble(const char* fmt, double v);

}  // namespace aalab
