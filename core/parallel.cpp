#include "core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <memory>
#include <mutex>
#include <string>

#include "core/error.h"

namespace aalab {
namespace {
std::unique_ptr<tbb::global_control> g_control;
int g_threads = 0;
std::mutex g_mutex;
}  // namespace

void SetThreadCount(int threads) {
  if (threads < 0 || threads > kMaxThreads) {
    throw UserError("--threads " + std::to_string(threads) + " is out of range (0 = all hardware threads, or 1.." +
                    std::to_string(kMaxThreads) + ")");
  }
  std::lock_guard<std::mutex> lock(g_mutex);
  g_control.reset();
  g_threads = threads > 0 ? threads : 0;
  if (g_threads > 0) {
    g_control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<size_t>(g_threads));
  }
}

int ThreadCount() {
  std::lock_guard<std::mutex> lock(g_mutex);
  return g_threads > 0 ? g_threads : tbb::info::default_concurrency();
}

void ParallelForChunks(int count, int grain, const std::function<void(int, int)>& body) {
  if (count <= 0) return;
  if (grain < 1) grain = 1;
  const int chunks = (count + grain - 1) / grain;
  tbb::parallel_for(
      tbb::blocked_range<int>(0, chunks, 1),
      [&](const tbb::blocked_range<int>& r) {
        for (int c = r.begin(); c != r.end(); ++c) {
          const int begin = c * grain;
          const int end = begin + grain < count ? begin + grain : count;
          body(begin, end);
        }
      },
      tbb::simple_partitioner());
}

void ParallelFor(int count, const std::function<void(int)>& body) {
  ParallelForChunks(count, 1, [&](int b, int e) {
    for (int i = b; i < e; ++i) body(i);
  });
}

}  // namespace aalab
