/// The exit codes of every aalab command (docs/cli.md, "Exit codes").
#pragma once

namespace aalab {

enum class ExitCode : int {
  kOk = 0,       ///< success (compare: no regression; same-results: same)
  kFailure = 1,  ///< bad input or a failure, one message on stderr (compare: a regression; same-results: different)
  kCouldNotCompare = 2,  ///< compare / same-results could not compare (a file missing, not a report, ...)
  kInternalError = 3,    ///< a bug in aalab (a broken internal invariant)
  kHangup = 129,         ///< SIGHUP (the terminal closed): 128 + 1, as shells report it
  kInterrupted = 130,    ///< SIGINT (Ctrl-C): 128 + 2, as shells report it
  kTerminated = 143,     ///< SIGTERM: 128 + 15
};

/// The process exit status of `code`.
constexpr int ToInt(ExitCode code) { return static_cast<int>(code); }

}  // namespace aalab
