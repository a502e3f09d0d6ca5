/// `aalab merge`: the shards of a run or a sweep (`--shard K/N`, harness/run/shard.h) back into
/// the report one process would have written (docs/cluster.md).
#pragma once
#include <string>
#include <vector>

#include "reports/result.h"

namespace aalab {

/// What a merge produced.
struct MergeResult {
  std::string kind;  ///< "run" or "sweep"
  int shards = 0;
  size_t scenes = 0, rows = 0;
  std::string out_dir;
};

/// Merges shard folders into `out_dir` (written through `out_dir`.partial; a non-empty folder
/// without a report is never replaced). Before writing anything it checks, naming the folder
/// and what is wrong:
///   - every folder holds a shard's partial report (report.json or sweep.json with a "shard"
///     block), all of one kind;
///   - the shards agree: the same N and unit, the same settings (the worker thread count may
///     differ: results do not depend on it) and the same program (tool version, git commit,
///     build type, compiler, float flags, library versions);
///   - no missing or duplicate work: each K in 0..N-1 exactly once, each shard holds exactly
///     the units the round-robin split gives it, and its scenes and rows are those units'.
/// A run's merge writes report.json (scenes and rows in the single run's order), index.html
/// and the images (copied). The settings are the shards'; the context block is shard 0's
/// plus "shards" and "shard_hosts"; time_breakdown is each stage summed over the shards.
/// A sweep's merge re-summarises the points (best, Pareto front, suggested preset) over all
/// shards and writes sweep.json and index.html.
MergeResult MergeShards(const std::vector<std::string>& shard_dirs, const std::string& out_dir);

/// The merged report of run shards, without writing anything (the checks above, run kind).
/// `dirs[i]` names reports[i] in messages.
Report MergeRunReports(const std::vector<Report>& reports, const std::vector<std::string>& dirs);

}  // namespace aalab
