/// Sharding: one run or sweep split over N independent processes (Slurm array tasks,
/// Kubernetes Indexed Job pods, or plain shell loops) and merged back by `aalab merge`
/// (harness/run/merge.h) into the report one process would have written. docs/cluster.md.
///
/// The split is deterministic and depends only on the work list and N: the work units are
/// numbered in the run's own order (the suite's scenes, image-scene views expanded; a sweep's
/// grid points; for `--references-only`, every reference frame) and shard K takes the units
/// i with i mod N = K. Round robin rather than blocks: neighbouring units (the frames of one
/// sequence, the points along one axis) cost about the same, so round robin balances better.
#pragma once
#include <string>
#include <vector>

namespace aalab {

/// The largest N accepted by --shard.
constexpr int kMaxShards = 100000;

/// Shard `index` of `count` (0 <= index < count). count == 0: not sharded.
struct ShardSpec {
  int index = 0;
  int count = 0;
  bool Active() const { return count > 0; }
  std::string Text() const { return std::to_string(index) + "/" + std::to_string(count); }
};

/// Parses "K/N" (decimal, 0 <= K < N <= kMaxShards). UserError naming the text and the rule
/// otherwise (e.g. "--shard '4/4': K must be below N (K counts from 0, as SLURM_ARRAY_TASK_ID
/// does with --array=0-3)").
ShardSpec ParseShard(const std::string& text);

/// The unit indices of `shard` among `units` work units, ascending (i mod N = K). An inactive
/// shard takes every unit. A shard may get none (N larger than the work).
std::vector<size_t> ShardShare(size_t units, const ShardSpec& shard);

}  // namespace aalab
