// aalab command line: the CLI11 app and its subcommands (list, render, apply, metrics, run,
// scene, compare, baseline, history, sweep, merge, same-results, export, export-sequences,
// export-frames, export-geometry, merge-gpu; each is set up in harness/cli/*_command(s).cpp, docs/cli.md).
// Exit codes: core/exit_code.h (docs/cli.md). Signals: SIGINT, SIGTERM and SIGHUP are
// taken by one thread, which removes the command's unfinished output (core/cleanup.h)
// and exits 130 / 143 / 129 with one line. SIGPIPE is ignored: a closed stdout (`aalab run |
// head`) makes the writes to stdout fail, never the command; its work is finished and kept,
// and one line on stderr says what was not printed.
#include <CLI/CLI.hpp>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <thread>

#include "build_info.h"
#include "harness/cli/commands.h"
#include "core/exit_code.h"
#include "core/cleanup.h"
#include "core/error.h"
#include "core/memory_policy.h"
#include "core/parallel.h"

namespace aalab {
namespace {

/// Blocks SIGINT, SIGTERM and SIGHUP in every thread (threads started later inherit the mask) and
/// waits for them in one thread of their own, where cleaning up is safe.
void HandleSignals() {
  sigset_t set;
  sigemptyset(&set);
  // A reader that goes away (`aalab run ... | head`) must not kill the run: writes to the
  // closed pipe fail with EPIPE instead, and main() says so once at the end.
  ::signal(SIGPIPE, SIG_IGN);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    // A signal the caller ignores (nohup, a shell's background job) stays ignored.
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaddset(&set, sig);
  }
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread([set] {
    int sig = 0;
    while (sigwait(&set, &sig) != 0) {
    }
    const int removed = RemoveUnfinishedForExit();
    const char* what = sig == SIGINT   ? "interrupted (SIGINT)"
                       : sig == SIGHUP ? "hung up (SIGHUP)"
                                       : "terminated (SIGTERM)";
    const ExitCode code = sig == SIGINT   ? ExitCode::kInterrupted
                          : sig == SIGHUP ? ExitCode::kHangup
                                          : ExitCode::kTerminated;
    const std::string line = std::string("aalab: ") + what + ": stopped; removed " + std::to_string(removed) +
                             " unfinished output path(s), left everything that was there before as it was\n";
    if (::write(STDERR_FILENO, line.data(), line.size()) < 0) {
      // Nothing more to do: the exit status says it.
    }
    ::_exit(ToInt(code));
  }).detach();
}

/// How a value of `opt` is written, for parse error messages.
std::string Allowed(const CLI::Option* opt) {
  const std::string type = opt->get_type_name();
  // (A range check adds to CLI11's type name: "INT:INT in [1 - 32]".)
  std::string what = type.rfind("INT", 0) == 0     ? "a whole number"
                     : type.rfind("UINT", 0) == 0  ? "a whole number >= 0"
                     : type.rfind("FLOAT", 0) == 0 ? "a number"
                     : opt->get_type_size() == 0   ? "no value (a flag)"
                                                   : "a value (" + (type.empty() ? std::string("text") : type) + ")";
  const std::string def = opt->get_default_str();
  if (!def.empty()) what += ", default " + def;
  return opt->get_name() + " takes " + what + ": " + opt->get_description();
}

/// CLI11's message, with what the option allows where the message names an option.
std::string DescribeParseError(CLI::App& app, const CLI::ParseError& e) {
  std::string msg = e.what();
  std::vector<CLI::App*> apps = app.get_subcommands();  // the subcommand(s) parsed so far
  if (apps.empty()) apps = app.get_subcommands({});
  for (CLI::App* sub : apps) {
    for (const CLI::Option* opt : sub->get_options()) {
      const std::string name = opt->get_name();
      if (name.rfind("--", 0) != 0) continue;
      const size_t at = msg.find(name);
      if (at == std::string::npos) continue;
      const size_t end = at + name.size();
      if (end < msg.size() && (std::isalnum(static_cast<unsigned char>(msg[end])) || msg[end] == '-')) continue;
      return msg + " (" + Allowed(opt) + ")";
    }
  }
  bool negative = false;  // "-3": CLI11 reads a negative number as an unknown option
  for (size_t i = 0; i + 1 < msg.size(); ++i) {
    negative = negative ||
               (msg[i] == '-' && (i == 0 || msg[i - 1] == ' ') && std::isdigit(static_cast<unsigned char>(msg[i + 1])));
  }
  if (msg.find("not expected") != std::string::npos && negative) {
    msg += " (a value that starts with '-' is read as an option: write --option=-value; see --help for the options)";
  } else if (msg.find("not expected") != std::string::npos) {
    msg +=
        " (see 'aalab " + (apps.size() == 1 ? apps[0]->get_name() + " " : std::string()) + "--help' for the options)";
  } else if (msg.find("subcommand is required") != std::string::npos && apps.size() == 1 &&
             !apps[0]->get_subcommands({}).empty()) {
    // `aalab history` alone: that command's own usage, not the top-level list.
    std::string names;
    for (CLI::App* sub : apps[0]->get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
    msg = "'aalab " + apps[0]->get_name() + "' needs a sub-command (" + names + ")\n" + apps[0]->help();
  } else if (msg.find("subcommand is required") != std::string::npos) {
    std::string names;
    for (CLI::App* sub : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
    msg += " (commands: " + names + ")";
  }
  return msg;
}

/// The exit code of an option error: the command's own "could not compare" for the commands
/// whose 1 means a verdict (compare: regression, same-results: different), else 1.
ExitCode OptionErrorCode(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands()) {
    if (sub->get_name() == "compare" || sub->get_name() == "same-results") return ExitCode::kCouldNotCompare;
  }
  return ExitCode::kFailure;
}

/// Unsigned options (--seed): CLI11 reads "-1" as 2^64-1; refused instead, naming the option.
void RefuseNegativeUnsigned(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands({})) {
    RefuseNegativeUnsigned(*sub);
    for (CLI::Option* opt : sub->get_options()) {
      if (opt->get_type_name() != "UINT") continue;
      opt->check(CLI::Validator(
          [](std::string& v) {
            if (v.empty() || v.find_first_not_of("0123456789") != std::string::npos) {
              return "'" + v + "' is not a whole number >= 0";
            }
            errno = 0;
            std::strtoull(v.c_str(), nullptr, 10);  // 2^64 and beyond: ERANGE, not a wrap
            return errno == ERANGE ? "'" + v + "' is larger than 18446744073709551615 (2^64-1)" : std::string();
          },
          "", "non-negative"));
    }
  }
}

/// When stdout was a pipe whose reader left (`aalab run | head`), what was printed after that
/// is lost but the work is not: one line on stderr says so. The exit code stays the command's.
void ReportClosedStdout() {
  const bool flush_failed = std::fflush(stdout) != 0 && errno == EPIPE;
  if (!flush_failed && !std::ferror(stdout)) return;
  static const char line[] =
      "aalab: standard output was closed before aalab finished writing to it (broken pipe); the command's work "
      "finished and was kept, only the lines after the break were not printed\n";
  if (::write(STDERR_FILENO, line, sizeof line - 1) < 0) {
    // stderr closed too: the exit code says how the command ended.
  }
}

/// `AALAB_LOOP_STATS=PATH` (docs/cli.md): where the command's parallel loops spent
/// their time, written to PATH as one JSON object once the command ended with status 0,
/// through a temporary file beside it, renamed, so PATH is never half-written. With `probe`,
/// only that temporary file is made and removed again: the check before the command, so that
/// a path that cannot be written is refused before any work. Returns false, with one line on
/// stderr, when it cannot be written.
bool WriteLoopStats(const std::string& path, bool probe) {
  const LoopStats s = LoopStatsNow();
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "w");
  bool ok = f != nullptr;
  if (f && probe) {
    ok = std::fclose(f) == 0 && std::remove(tmp.c_str()) == 0;
  } else if (f) {
    ok = std::fprintf(f, "{\"threads\": %d, \"loops\": %lld, \"in_loops_s\": %.6f, \"busy_s\": %.6f}\n", ThreadCount(),
                      s.loops, s.in_loops_s, s.busy_s) > 0;
    ok = std::fclose(f) == 0 && ok;
  }
  if (ok && !probe) ok = std::rename(tmp.c_str(), path.c_str()) == 0;
  if (!ok) {
    const int err = errno;
    std::remove(tmp.c_str());
    std::fprintf(stderr, "aalab: error: AALAB_LOOP_STATS=%s: cannot write the loop statistics there (%s)\n",
                 path.c_str(), std::strerror(err));
  }
  return ok;
}

}  // namespace
}  // namespace aalab

int main(int argc, char** argv) {
  using namespace aalab;
  KeepFreedMemory();  // core/memory_policy.h: freed buffers reused, not faulted in again
  HandleSignals();
  CLI::App app{"aalab: measures anti-aliasing methods against a supersampled ground truth"};
  app.set_version_flag("--version", std::string("aalab ") + AALAB_VERSION + " (" + AALAB_GIT_COMMIT + ")");
  app.require_subcommand(1);
  Commands commands;
  RegisterCommands(app, commands);
  RefuseNegativeUnsigned(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end parsing with CLI11's "success" code: printed as CLI11 does.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::fprintf(stderr, "aalab: error: %s\n", DescribeParseError(app, e).c_str());
    return ToInt(OptionErrorCode(app));
  }
  const char* loop_stats = std::getenv("AALAB_LOOP_STATS");
  if (loop_stats && *loop_stats) {
    // Refused before the command runs when its file cannot be written (its folder missing, say).
    if (!WriteLoopStats(loop_stats, /*probe=*/true)) return ToInt(ExitCode::kFailure);
    EnableLoopStats(true);
  }
  int code = ToInt(ExitCode::kFailure);
  try {
    code = commands.Run();
  } catch (const UserError& e) {
    std::fprintf(stderr, "aalab: error: %s\n", e.what());
    code = ToInt(ExitCode::kFailure);
  } catch (const InternalError& e) {
    std::fprintf(stderr, "aalab: internal error (a bug, please report): %s\n", e.what());
    code = ToInt(ExitCode::kInternalError);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aalab: error: %s\n", e.what());
    code = ToInt(ExitCode::kFailure);
  }
  if (loop_stats && *loop_stats && code == 0 && !WriteLoopStats(loop_stats, /*probe=*/false))
    code = ToInt(ExitCode::kFailure);
  ReportClosedStdout();
  return code;
}
