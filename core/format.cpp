#include "core/format.h"

#include <cstdio>

namespace aalab {

std::string FormatDouble(const char* fmt, double v) {
  char buf[64];
  const int n = std::snprintf(buf, sizeof buf, fmt, v);
  if (n < 0) return {};
  if (static_cast<size_t>(n) < sizeof buf) return std::string(buf, static_cast<size_t>(n));
  std::string s(static_cast<size_t>(n) + 1, '\0');  // longer text: printed again at its length
  std::snprintf(s.data(), s.size(), fmt, v);
  s.resize(static_cast<size_t>(n));
  return s;
}

}  // namespace aalab
