// Tests that need something outside the repository (../shared/seeds, Chromium) skip visibly on
// a developer machine without it, and FAIL under CI, so that a CI run cannot go green without
// them (as the missing-GL case of the FXAA oracle already fails: tests/CMakeLists.txt).
#pragma once
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>

namespace aalab::testenv {

/// True when the environment variable CI is set to anything but "", "0" or "false" (GitHub
/// Actions, GitLab CI and most others set CI=true; .ci/run sets it too).
inline bool UnderCi() {
  const char* ci = std::getenv("CI");
  return ci && *ci && std::strcmp(ci, "0") != 0 && std::strcmp(ci, "false") != 0;
}

}  // namespace aalab::testenv

/// Skips the current test with `message` (a std::string); under CI (UnderCi()) fails it with
/// the same message instead. Use only at the top level of a TEST body or a fixture's SetUp:
/// like GTEST_SKIP and GTEST_FAIL it returns from the enclosing function.
#define AALAB_SKIP_OR_FAIL_UNDER_CI(message)                                                                       \
  do {                                                                                                             \
    const std::string aalab_skip_message_ = (message);                                                             \
    if (::aalab::testenv::UnderCi()) {                                                                             \
      GTEST_FAIL() << "CI is set, so a missing test dependency is a failure, not a skip: " << aalab_skip_message_; \
    }                                                                                                              \
    GTEST_SKIP() << aalab_skip_message_ << " (skipped: not under CI)";                                             \
  } while (0)
