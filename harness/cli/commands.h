/// The aalab subcommands: CLI11 wiring and their implementations.
#pragma once
#include <functional>

#include <CLI/CLI.hpp>

namespace aalab {

/// Holds the chosen subcommand's action after parsing.
struct Commands {
  std::function<int()> action;
  int Run() const { return action ? action() : 0; }
};

/// Adds every subcommand to `app`; the parsed one sets `commands.action`.
void RegisterCommands(CLI::App& app, Commands& commands);

/// `aalab metrics` (harness/cli/metrics_command.cpp).
void RegisterMetricsCommand(CLI::App& app, Commands& commands);

}  // namespace aalab
