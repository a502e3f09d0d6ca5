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
/// Adds `compare` and `history` (compare_commands.cpp). `compare` returns its own exit codes:
/// 0 no regression, 1 regression, 2 could not compare (errors included).
void RegisterCompareCommands(CLI::App& app, Commands& commands);

/// Adds `sweep` (sweep_commands.cpp).
void RegisterSweepCommands(CLI::App& app, Commands& commands);

/// Adds `export-frames` and `merge-gpu` (gpu_commands.cpp; docs/gpu.md).
void RegisterGpuCommands(CLI::App& app, Commands& commands);

/// Adds `merge` and `same-results` (cluster_commands.cpp; docs/cluster.md). `same-results`
/// exits 0 same, 1 different, 2 could not compare.
void RegisterClusterCommands(CLI::App& app, Commands& commands);

}  // namespace aalab
