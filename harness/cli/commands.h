/// The aalab subcommands: CLI11 wiring and their implementations.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/exit_code.h"

namespace aalab {

/// Holds the chosen subcommand's action after parsing.
struct Commands {
  std::function<int()> action;
  int Run() const { return action ? action() : ToInt(ExitCode::kOk); }
};

/// Splits a comma-separated list of names or method specs: a comma followed by "key=" inside
/// a spec's parameter list ("a:x=1,y=2,b") continues that spec. UserError on an empty item.
std::vector<std::string> SplitList(const std::string& text);

/// Adds every subcommand to `app`; the parsed one sets `commands.action`.
void RegisterCommands(CLI::App& app, Commands& commands);

/// `aalab metrics` (harness/cli/metrics_command.cpp).
void RegisterMetricsCommand(CLI::App& app, Commands& commands);
/// Adds `compare` and `history` (compare_commands.cpp). `compare` returns its own exit codes:
/// 0 no regression, 1 regression, 2 could not compare (errors included).
void RegisterCompareCommands(CLI::App& app, Commands& commands);

/// Adds `sweep` (sweep_commands.cpp).
void RegisterSweepCommands(CLI::App& app, Commands& commands);

/// Adds `export-frames`, `export-geometry` and `merge-gpu` (gpu_commands.cpp; docs/gpu.md).
void RegisterGpuCommands(CLI::App& app, Commands& commands);
/// Checks a GPU timings file (aalab_gpu's or aalab_raster's JSON) before any work; throws
/// UserError naming what is wrong.
void CheckGpuTimingsFile(const std::string& path);
/// Merges GPU timings files, in order, into the report in `dir` (report.json and index.html
/// rewritten once): aalab_gpu's and aalab_vk's into the rows' `gpu` blocks, aalab_raster's
/// into `gpu_raster`. Returns one line per file to print; UserError (report unchanged) when a
/// file matches no row.
std::string AttachGpuTimings(const std::string& dir, const std::vector<std::string>& gpu_jsons);

/// Adds `merge` and `same-results` (cluster_commands.cpp; docs/cluster.md). `same-results`
/// exits 0 same, 1 different, 2 could not compare.
void RegisterClusterCommands(CLI::App& app, Commands& commands);

/// Adds `export` (export_command.cpp; docs/publishing.md).
void RegisterExportCommand(CLI::App& app, Commands& commands);

/// Adds `scene` (scene_command.cpp; docs/real-content.md "A model as a scene").
void RegisterSceneCommand(CLI::App& app, Commands& commands);

}  // namespace aalab
