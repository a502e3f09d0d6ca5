/// Deterministic parallel loops over rows or tiles (TBB underneath).
#pragma once
#include <functional>

namespace aalab {

/// Largest thread count SetThreadCount accepts.
inline constexpr int kMaxThreads = 4096;

/// Sets the number of worker threads for all later parallel loops (0 = hardware default).
/// Results never depend on it: every loop writes disjoint outputs, and reductions merge
/// per-chunk partials in chunk order. Throws UserError outside 0..kMaxThreads (a negative
/// count is never silently taken as "all").
void SetThreadCount(int threads);
/// The thread count in force (resolved: never 0).
int ThreadCount();

/// Calls body(begin, end) on disjoint chunks covering [0, count). Chunks have `grain` items
/// (the last may be shorter) and are fixed by count and grain alone, never by threads.
void ParallelForChunks(int count, int grain, const std::function<void(int, int)>& body);

/// Calls body(i) for every i in [0, count), in parallel.
void ParallelFor(int count, const std::function<void(int)>& body);

/// Where the parallel loops' time went, counted since EnableLoopStats(true) (diagnostics for
/// thread scaling: `AALAB_LOOP_STATS`, docs/cli.md). A top-level loop is one called from
/// outside every loop's chunk; loops nested in a chunk count as that chunk's work. Loops
/// started at once from several threads outside any loop would each add their wall time (aalab
/// starts none). Counted by the TBB build (core/parallel.cpp) only: the stand-alone GPU
/// tool's std::thread build (gpu/parallel_threads.cpp) neither defines nor calls these.
struct LoopStats {
  long long loops = 0;    ///< top-level loops run
  double in_loops_s = 0;  ///< wall seconds inside top-level loops (outside them: serial work)
  /// Thread-seconds inside chunk bodies, summed over threads; a chunk a thread runs while
  /// inside another chunk (a nested loop's) is not counted twice. threads × in_loops_s −
  /// busy_s is the time threads spent in loops without a chunk to run (waits, imbalance,
  /// the scheduler's own work).
  double busy_s = 0;
};

/// Starts (true) or stops counting LoopStats. Off by default; off, a loop pays one flag read.
/// Call from the main thread while no loop runs (as SetThreadCount).
void EnableLoopStats(bool on);
/// The counts so far (zero until EnableLoopStats(true); kept when counting stops).
LoopStats LoopStatsNow();

}  // namespace aalab
