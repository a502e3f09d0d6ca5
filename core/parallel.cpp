#include "core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/error.h"

namespace aalab {
namespace {
std::unique_ptr<tbb::global_control> g_control;
int g_threads = 0;
std::mutex g_mutex;

// LoopStats: counters of top-level loops, and one busy-time counter per thread (on its own
// cache line, written by its thread alone) so that timing a chunk shares no line between threads.
std::atomic<bool> g_stats_on{false};
std::atomic<int64_t> g_loops{0}, g_in_loops_ns{0};
struct alignas(64) ThreadBusy {
  std::atomic<int64_t> ns{0};
};
std::mutex g_busy_mutex;
std::vector<std::unique_ptr<ThreadBusy>>& BusyCounters() {  // never destroyed: threads may outlive main
  static auto* counters = new std::vector<std::unique_ptr<ThreadBusy>>();
  return *counters;
}
thread_local ThreadBusy* t_busy = nullptr;
thread_local int t_in_chunk = 0;  // chunks this thread is inside (a nested loop's chunk adds one)

int64_t NowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

ThreadBusy& MyBusy() {
  if (!t_busy) {
    std::lock_guard<std::mutex> lock(g_busy_mutex);
    BusyCounters().push_back(std::make_unique<ThreadBusy>());
    t_busy = BusyCounters().back().get();
  }
  return *t_busy;
}

// Inside one chunk while counting: the outermost chunk of the thread times itself (an
// exception thrown by the body still leaves the thread's depth as it was).
class ChunkTimer {
 public:
  ChunkTimer() : start_(t_in_chunk++ == 0 ? NowNs() : -1) {}
  ~ChunkTimer() {
    --t_in_chunk;
    if (start_ >= 0) MyBusy().ns.fetch_add(NowNs() - start_, std::memory_order_relaxed);
  }
  ChunkTimer(const ChunkTimer&) = delete;
  ChunkTimer& operator=(const ChunkTimer&) = delete;

 private:
  int64_t start_;
};
}  // namespace

void EnableLoopStats(bool on) { g_stats_on.store(on, std::memory_order_relaxed); }

LoopStats LoopStatsNow() {
  LoopStats s;
  s.loops = g_loops.load(std::memory_order_relaxed);
  s.in_loops_s = 1e-9 * static_cast<double>(g_in_loops_ns.load(std::memory_order_relaxed));
  std::lock_guard<std::mutex> lock(g_busy_mutex);
  int64_t busy = 0;
  for (const auto& c : BusyCounters()) busy += c->ns.load(std::memory_order_relaxed);
  s.busy_s = 1e-9 * static_cast<double>(busy);
  return s;
}

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
  const bool stats = g_stats_on.load(std::memory_order_relaxed);
  const bool top = stats && t_in_chunk == 0;
  const int64_t start = top ? NowNs() : 0;
  tbb::parallel_for(
      tbb::blocked_range<int>(0, chunks, 1),
      [&](const tbb::blocked_range<int>& r) {
        for (int c = r.begin(); c != r.end(); ++c) {
          const int begin = c * grain;
          const int end = begin + grain < count ? begin + grain : count;
          if (stats) {
            const ChunkTimer timer;
            body(begin, end);
          } else {
            body(begin, end);
          }
        }
      },
      tbb::simple_partitioner());
  if (top) {
    g_in_loops_ns.fetch_add(NowNs() - start, std::memory_order_relaxed);
    g_loops.fetch_add(1, std::memory_order_relaxed);
  }
}

void ParallelFor(int count, const std::function<void(int)>& body) {
  ParallelForChunks(count, 1, [&](int b, int e) {
    for (int i = b; i < e; ++i) body(i);
  });
}

}  // namespace aalab
