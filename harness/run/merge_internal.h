/// Shared by the run and sweep merges (harness/run/merge.cpp, harness/run/sweep_shard.cpp).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "harness/run/merge.h"
#include "reports/result.h"

namespace aalab {

/// The checks of MergeShards common to runs and sweeps (shard blocks, one split, each K once,
/// same settings and program, exact round-robin shares, no unit twice). Returns the whole
/// run's unit order: for unit u, (index into `reports`, index into that shard's units). There
/// is at least one unit, so order.front().first is shard 0.
std::vector<std::pair<size_t, size_t>> CheckShardSet(const std::vector<const Report*>& reports,
                                                     const std::vector<std::string>& dirs);

/// The sweep half of MergeShards (harness/run/sweep_shard.cpp).
MergeResult MergeSweepFolders(const std::vector<std::string>& dirs, const std::string& out_dir);

}  // namespace aalab
