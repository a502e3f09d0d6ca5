/// `aalab same-results A B`: do two output folders (runs, or sweeps) hold the same results,
/// timings and the context block aside? How a sharded-and-merged run is checked against a
/// single process (docs/cluster.md), and what `make test-slurm` runs.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace aalab {

/// A report.json or sweep.json document without what may differ between two runs of the same
/// work: the context block, the time breakdown, the shard block, the worker thread count
/// setting, every timing (rows' timing and gpu blocks; scenes' reference and BVH times and
/// sequence totals; a sweep's mean_time_ms, and the Pareto flags and front, which rank time).
nlohmann::ordered_json WithoutTimings(nlohmann::ordered_json doc);

struct SameResults {
  bool same = true;
  std::vector<std::string> differences;  ///< the first differences, one line each
};

/// Compares folders `a` and `b`: report.json (or sweep.json) through WithoutTimings, then the
/// bytes of every image the report links. UserError when a folder holds neither file or the
/// two are of different kinds; a linked image missing in either folder is a difference.
SameResults CompareResultFolders(const std::string& a, const std::string& b, size_t max_listed = 20);

}  // namespace aalab
