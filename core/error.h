/// Errors: bad user input versus broken internal invariants.
#pragma once
#include <stdexcept>
#include <string>

namespace aalab {

/// Bad user input (scene file, image, CLI argument, parameter). The message names what was
/// wrong and what is allowed; the CLI prints it and exits non-zero.
class UserError : public std::runtime_error {
 public:
  explicit UserError(const std::string& message) : std::runtime_error(message) {}
};

/// A broken internal invariant: a bug in aalab, never the user's fault.
class InternalError : public std::logic_error {
 public:
  explicit InternalError(const std::string& message) : std::logic_error(message) {}
};

/// Throws InternalError with file:line when `condition` is false. Always on (also in Release).
[[noreturn]] void FailCheck(const char* expr, const char* file, int line, const std::string& msg);

}  // namespace aalab

#define AALAB_CHECK(cond, msg)                                         \
  do {                                                                 \
    if (!(cond)) ::aalab::FailCheck(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)
