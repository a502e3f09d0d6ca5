#include "core/error.h"

namespace aalab {

void FailCheck(const char* expr, const char* file, int line, const std::string& msg) {
  throw InternalError(std::string("internal check failed: ") + expr + " (" + msg + ") at " + file + ":" +
                      std::to_string(line));
}

}  // namespace aalab
