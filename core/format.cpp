#include "core/format.h"

#include <cstdio>

namespace aalab {

std::string FormatDouble(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

}  // namespace aalab
