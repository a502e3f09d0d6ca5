// The deterministic split of a run's work (harness/run/shard.h).
#include "harness/run/shard.h"

#include "core/error.h"

namespace aalab {

ShardSpec ParseShard(const std::string& text) {
  auto fail = [&](const std::string& why) {
    throw UserError("--shard '" + text + "': " + why +
                    " (allowed: K/N with 0 <= K < N <= " + std::to_string(kMaxShards) +
                    "; K counts from 0, as SLURM_ARRAY_TASK_ID with --array=0-(N-1) and JOB_COMPLETION_INDEX do)");
  };
  const auto slash = text.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 >= text.size()) fail("not of the form K/N");
  auto number = [&](const std::string& part) {
    if (part.size() > 6) fail("'" + part + "' is too large");
    for (char c : part) {
      if (c < '0' || c > '9') fail("'" + part + "' is not a non-negative whole number");
    }
    return std::stoi(part);
  };
  ShardSpec s;
  s.index = number(text.substr(0, slash));
  s.count = number(text.substr(slash + 1));
  if (s.count < 1 || s.count > kMaxShards) fail("N must be between 1 and " + std::to_string(kMaxShards));
  if (s.index >= s.count) fail("K must be below N");
  return s;
}

std::vector<size_t> ShardShare(size_t units, const ShardSpec& shard) {
  std::vector<size_t> share;
  for (size_t i = 0; i < units; ++i) {
    if (!shard.Active() || i % static_cast<size_t>(shard.count) == static_cast<size_t>(shard.index)) share.push_back(i);
  }
  return share;
}

}  // namespace aalab
