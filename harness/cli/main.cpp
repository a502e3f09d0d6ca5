// aalab command line: list, render, run, apply (and more as issues land).
// Exit codes: 0 success, 1 bad input or failure (one clear message on stderr), 3 internal error.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

#include "build_info.h"
#include "harness/cli/commands.h"
#include "harness/core/error.h"

int main(int argc, char** argv) {
  using namespace aalab;
  CLI::App app{"aalab: measures anti-aliasing methods against a supersampled ground truth"};
  app.set_version_flag("--version", std::string("aalab ") + AALAB_VERSION + " (" + AALAB_GIT_COMMIT + ")");
  app.require_subcommand(1);
  Commands commands;
  RegisterCommands(app, commands);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return commands.Run();
  } catch (const UserError& e) {
    std::fprintf(stderr, "aalab: error: %s\n", e.what());
    return 1;
  } catch (const InternalError& e) {
    std::fprintf(stderr, "aalab: internal error (a bug, please report): %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aalab: error: %s\n", e.what());
    return 1;
  }
}
