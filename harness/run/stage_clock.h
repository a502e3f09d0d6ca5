/// Where a run's time goes: wall-clock and process CPU time (all threads) per named stage,
/// for the breakdown `aalab run` prints at its end and stores in report.json.
#pragma once
#include <string>
#include <vector>

#include "core/timer.h"
#include "reports/result.h"

namespace aalab {

/// Splits one stretch of time into stages: each Enter() closes the stage before it, so the
/// stages add up to the total with no gap. Not thread-safe: the runner calls it between
/// parallel sections, never inside one.
class StageClock {
 public:
  /// `order`: stages listed here are reported first, in this order (with zero time when
  /// never entered), so the report's layout does not depend on which stage a run enters
  /// first; any other stage follows in the order first entered.
  explicit StageClock(std::vector<std::string> order = {});
  /// Charges the time since the last Enter() (or construction) to the current stage, then
  /// makes `stage` current.
  void Enter(const std::string& stage);
  /// Closes the current stage; returns every stage (the constructor's order, then the order
  /// first entered), then "total"
  /// (their sum: time before the first Enter() belongs to no stage).
  std::vector<StageTime> Finish();

 private:
  void Charge();
  std::vector<StageTime> stages_;
  std::string current_;
  Stopwatch wall_;
  double last_wall_ms_ = 0, last_cpu_ms_ = 0;
};

/// CPU time of this process so far (user + system, every thread), in milliseconds.
double ProcessCpuMs();

/// The breakdown as a small table for the terminal ("stage  wall s  cpu s  share").
std::string FormatTimeBreakdown(const std::vector<StageTime>& stages);

}  // namespace aalab
