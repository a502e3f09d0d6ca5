// core/parallel.h on std::thread, for the stand-alone GPU tool build (gpu/
// CMakeLists.txt without the main project): the device machine has no TBB. Same contract
// as core/parallel.cpp: chunks are fixed by count and grain alone, each chunk
// writes its own outputs, so results do not depend on the thread count.
#include <algorithm>
#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"

namespace aalab {
namespace {
int g_threads = 0;
}  // namespace

void SetThreadCount(int threads) {
  if (threads < 0 || threads > kMaxThreads) {
    throw UserError("--threads " + std::to_string(threads) + " is out of range (0 = all hardware threads, or 1.." +
                    std::to_string(kMaxThreads) + ")");
  }
  g_threads = threads;
}

int ThreadCount() {
  if (g_threads > 0) return g_threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

void ParallelForChunks(int count, int grain, const std::function<void(int, int)>& body) {
  if (count <= 0) return;
  if (grain < 1) grain = 1;
  const int chunks = (count + grain - 1) / grain;
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int c = next++; c < chunks; c = next++) {
      const int begin = c * grain;
      body(begin, std::min(begin + grain, count));
    }
  };
  const int n = std::min(ThreadCount(), chunks);
  std::vector<std::thread> pool;
  for (int i = 1; i < n; ++i) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

void ParallelFor(int count, const std::function<void(int)>& body) {
  ParallelForChunks(count, 1, [&](int b, int e) {
    for (int i = b; i < e; ++i) body(i);
  });
}

}  // namespace aalab
