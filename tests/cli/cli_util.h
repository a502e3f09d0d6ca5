// Helpers for tests that run the aalab executable (exit code, combined output, temp folders).
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "../temp_dir.h"

namespace aalab::clitest {

struct CmdResult {
  int code = -1;       ///< exit code; -1 when the process did not exit normally (a signal)
  int signal = 0;      ///< the signal that ended it, if any
  std::string output;  ///< stdout + stderr
};

/// Runs a shell command and captures its stdout (add "2>&1" to capture stderr too).
inline CmdResult RunCommand(const std::string& cmd) {
  CmdResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(p);
  if (WIFEXITED(status)) {
    r.code = WEXITSTATUS(status);
    // popen runs the command through sh, which reports a signal as exit code 128 + N.
    if (r.code > 128) r.signal = r.code - 128;
  } else if (WIFSIGNALED(status)) {
    r.signal = WTERMSIG(status);
  }
  return r;
}

/// Runs `aalab ARGS` from the build folder and captures everything it prints.
inline CmdResult Aalab(const std::string& args) {
  return RunCommand(std::string(AALAB_BINARY_DIR) + "/aalab " + args + " 2>&1");
}

/// A fresh, empty folder under the system temp folder, unique to this process, removed when
/// the process exits (tests/temp_dir.h).
inline std::filesystem::path TempDir(const std::string& name) { return testenv::ScratchDir(name); }

}  // namespace aalab::clitest
