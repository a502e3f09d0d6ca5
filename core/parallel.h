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

}  // namespace aalab
