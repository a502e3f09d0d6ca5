#include "core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace aalab {
namespace {

TEST(Parallel, ChunksCoverRangeOnceAndDoNotDependOnThreads) {
  for (int threads : {1, 2, 8}) {
    SetThreadCount(threads);
    std::vector<int> hits(1000, 0);
    std::vector<std::pair<int, int>> chunks(1000 / 64 + 1);
    ParallelForChunks(1000, 64, [&](int b, int e) {
      chunks[b / 64] = {b, e};
      for (int i = b; i < e; ++i) hits[i]++;
    });
    for (int h : hits) EXPECT_EQ(h, 1);
    EXPECT_EQ(chunks.back(), std::make_pair(960, 1000));
  }
  SetThreadCount(0);
}

TEST(Parallel, ZeroCountDoesNothing) {
  std::atomic<int> calls{0};
  ParallelFor(0, [&](int) { calls++; });
  EXPECT_EQ(calls.load(), 0);
}

// LoopStats. Sleeps set lower bounds that hold on any machine (a sleep lasts at least as long
// as asked); upper bounds are the ones the definitions imply, never a machine's speed.
void SleepMs(int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }

LoopStats Since(const LoopStats& a) {
  const LoopStats b = LoopStatsNow();
  return {b.loops - a.loops, b.in_loops_s - a.in_loops_s, b.busy_s - a.busy_s};
}

TEST(LoopStats, CountNothingWhileOff) {
  EnableLoopStats(false);
  const LoopStats before = LoopStatsNow();
  ParallelFor(4, [](int) { SleepMs(2); });
  const LoopStats d = Since(before);
  EXPECT_EQ(d.loops, 0);
  EXPECT_EQ(d.in_loops_s, 0.0);
  EXPECT_EQ(d.busy_s, 0.0);
}

TEST(LoopStats, OneThreadIsBusyForTheWholeLoop) {
  SetThreadCount(1);
  EnableLoopStats(true);
  const LoopStats before = LoopStatsNow();
  ParallelForChunks(40, 10, [](int, int) { SleepMs(5); });  // 4 chunks of 5 ms
  const LoopStats d = Since(before);
  EnableLoopStats(false);
  SetThreadCount(0);
  EXPECT_EQ(d.loops, 1);
  EXPECT_GE(d.busy_s, 0.020);
  EXPECT_LE(d.busy_s, d.in_loops_s);  // one thread: its chunks lie inside the loop
}

TEST(LoopStats, NestedLoopsCountOnceAsTheirChunksWork) {
  // 2 outer chunks, each running an inner loop of 2 chunks of 5 ms: one top-level loop, and
  // with one thread the busy time is the loop's time, not twice it.
  SetThreadCount(1);
  EnableLoopStats(true);
  const LoopStats before = LoopStatsNow();
  ParallelFor(2, [](int) { ParallelFor(2, [](int) { SleepMs(5); }); });
  const LoopStats d = Since(before);
  EnableLoopStats(false);
  SetThreadCount(0);
  EXPECT_EQ(d.loops, 1);
  EXPECT_GE(d.busy_s, 0.020);
  EXPECT_LE(d.busy_s, d.in_loops_s);
}

TEST(LoopStats, TwoThreadsWaitingOnOneLongChunkShowIdleTime) {
  // Chunk 0 sleeps 60 ms, the other three nothing: at most one thread is busy for those 60 ms,
  // so with two threads, 2 × in-loop time − busy time (the idle time) is at least ~60 ms when the
  // second thread exists, and busy time never exceeds 2 × the loop's time.
  SetThreadCount(2);
  EnableLoopStats(true);
  const LoopStats before = LoopStatsNow();
  ParallelFor(4, [](int i) {
    if (i == 0) SleepMs(60);
  });
  const LoopStats d = Since(before);
  EnableLoopStats(false);
  SetThreadCount(0);
  EXPECT_EQ(d.loops, 1);
  EXPECT_GE(d.in_loops_s, 0.060);
  EXPECT_GE(d.busy_s, 0.060);
  EXPECT_LE(d.busy_s, 2 * d.in_loops_s);
  EXPECT_LT(d.busy_s, d.in_loops_s + 0.030);  // the other chunks are empty: ~no second-thread work
  EXPECT_GE(2 * d.in_loops_s - d.busy_s, 0.030);
}

TEST(LoopStats, AThrowingChunkLeavesLaterLoopsTopLevel) {
  SetThreadCount(1);
  EnableLoopStats(true);
  EXPECT_THROW(ParallelFor(3,
                           [](int i) {
                             if (i == 1) throw std::runtime_error("chunk 1");
                           }),
               std::runtime_error);
  const LoopStats before = LoopStatsNow();
  ParallelFor(2, [](int) { SleepMs(2); });
  const LoopStats d = Since(before);
  EnableLoopStats(false);
  SetThreadCount(0);
  EXPECT_EQ(d.loops, 1);  // with the thread's depth left at 1, this loop would count as nested
  EXPECT_GE(d.busy_s, 0.004);
}

}  // namespace
}  // namespace aalab
