#include "core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
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

}  // namespace
}  // namespace aalab
