// What the `make bench` figures share; see bench/bench_common.h.
#include "bench/bench_common.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <sys/resource.h>

#include "core/format.h"
#include "core/parallel.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace aalab::bench {
namespace {

std::map<std::string, Stats>& Collected() {
  static std::map<std::string, Stats> m;
  return m;
}

// Cores the process actually got while a figure ran: CPU seconds / wall seconds, one value
// per repetition. On a machine shared with other work, 2 worker threads may get less than 2.
std::map<std::string, std::vector<double>>& CoresByFigure() {
  static std::map<std::string, std::vector<double>> m;
  return m;
}

class CollectingReporter : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration) continue;
      if (r.error_occurred) {
        std::fprintf(stderr, "benchmark %s failed: %s\n", r.run_name.function_name.c_str(), r.error_message.c_str());
        std::exit(3);
      }
      // Seconds per iteration, wall clock.
      const double secs = r.real_accumulated_time / static_cast<double>(r.iterations);
      Collected()[r.run_name.function_name].samples.push_back(secs);
      std::fprintf(stderr, "  %-60s %10.3f ms\n", r.run_name.function_name.c_str(), secs * 1e3);
    }
  }
};

}  // namespace

double ProcessCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + (u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
}

void Register(const std::string& name, int threads, int reps, double min_time, std::function<void()> body) {
  auto* b = benchmark::RegisterBenchmark(name.c_str(), [name, threads, body](benchmark::State& st) {
    SetThreadCount(threads);
    body();  // warm-up (also first touch of any buffer)
    const double cpu0 = ProcessCpuSeconds();
    const auto w0 = std::chrono::steady_clock::now();
    for (auto _ : st) body();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    if (wall > 0) CoresByFigure()[name].push_back((ProcessCpuSeconds() - cpu0) / wall);
  });
  b->UseRealTime()->Repetitions(reps)->MinTime(min_time);
}

namespace {

// Registers round r of figure f (Google Benchmark runs figures in registration order): on round
// 0 an untimed warm-up call first, which fixes *calls; then one repetition of *calls calls.
void RegisterRoundFigure(const RoundFigure& f, const std::shared_ptr<int>& calls, int r, double min_time) {
  const std::string name = f.name;
  const int threads = f.threads;
  const std::function<void()> body = f.body;
  auto* b = benchmark::RegisterBenchmark(name.c_str(), [name, threads, body, calls, r, min_time](benchmark::State& st) {
    SetThreadCount(threads);
    if (r == 0) {  // warm-up (also first touch of any buffer), which also sets the call count
      const auto t0 = std::chrono::steady_clock::now();
      body();
      const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      *calls = t > 0 ? std::max(1, static_cast<int>(std::ceil(min_time / t))) : 1;
    }
    const double cpu0 = ProcessCpuSeconds();
    const auto w0 = std::chrono::steady_clock::now();
    for (auto _ : st) {
      const auto i0 = std::chrono::steady_clock::now();
      for (int i = 0; i < *calls; ++i) body();
      st.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - i0).count() / *calls);
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    if (wall > 0) CoresByFigure()[name].push_back((ProcessCpuSeconds() - cpu0) / wall);
  });
  b->UseManualTime()->Iterations(1)->Repetitions(1);
}

}  // namespace

void RegisterRounds(const std::vector<std::vector<RoundFigure>>& groups, int reps, double min_time) {
  // Each figure's calls per repetition, fixed by its warm-up (before its first round) so that
  // every round runs the same count (≥ min_time s) with no calibration runs of its own.
  std::vector<std::vector<std::shared_ptr<int>>> counts(groups.size());
  for (size_t g = 0; g < groups.size(); ++g)
    for (size_t i = 0; i < groups[g].size(); ++i) counts[g].push_back(std::make_shared<int>(1));
  for (int r = 0; r < reps; ++r) {
    for (size_t g = 0; g < groups.size(); ++g) {
      for (size_t fi = 0; fi < groups[g].size(); ++fi) {
        RegisterRoundFigure(groups[g][fi], counts[g][fi], r, min_time);
      }
    }
  }
}

double PairedRatio(const std::string& a, const std::string& b) {
  const Stats& x = Figure(a);
  const Stats& y = Figure(b);
  if (x.samples.size() != y.samples.size()) {
    std::fprintf(stderr, "figures %s and %s have %zu and %zu samples: not one group of rounds\n", a.c_str(), b.c_str(),
                 x.samples.size(), y.samples.size());
    std::exit(3);
  }
  Stats r;
  for (size_t k = 0; k < x.samples.size(); ++k) r.samples.push_back(x.samples[k] / y.samples[k]);
  return r.Median();
}

double FastestRatio(const std::string& a, const std::string& b) { return Figure(a).Min() / Figure(b).Min(); }

void RunRegistered() {
  // Figures run in registration order. The figures a goal compares (a scene's reference and
  // bare loop at 1 and 2 threads, a frame's filters and floor at 1 and 2 threads, a metric at 1
  // and 2 threads) are one RegisterRounds group: one repetition of each per round, so each
  // ratio is taken per round from samples seconds apart (PairedRatio; docs/performance.md,
  // "What it measures").
  std::fprintf(stderr, "running %s figures (Google Benchmark %s)...\n", "registered", "repetitions");
  CollectingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  SetThreadCount(0);
}

const Stats& Figure(const std::string& name) {
  auto it = Collected().find(name);
  if (it == Collected().end()) {
    std::fprintf(stderr, "missing figure %s\n", name.c_str());
    std::exit(3);
  }
  return it->second;
}

double CoresUsed(const std::string& name) {
  auto it = CoresByFigure().find(name);
  return it == CoresByFigure().end() || it->second.empty() ? 0.0 : Stats{it->second}.Median();
}

Image8 RenderFrame1x(const std::string& scene_name, int w, int h) {
  const Scene scene = LoadScene(scene_name);
  const Tracer tracer(scene);
  return RenderFrame(tracer, w, h, RenderSpec{}, 1, nullptr);
}

void PlainPass(const Image8& in, Image8& out) {
  const int w = in.Width();
  ParallelForChunks(in.Height(), 8, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const uint8_t* s = in.Row(y);
      uint8_t* d = out.Row(y);
      for (int x = 0; x < w; ++x) {
        uint32_t v;
        std::memcpy(&v, s + 4 * x, 4);
        v |= 0xFF000000u;
        std::memcpy(d + 4 * x, &v, 4);
      }
    }
  });
}

void FailIdentity(const std::string& what) {
  std::fprintf(stderr, "\n*** BIT-IDENTITY FAILURE: %s: the optimised path differs from its reference ***\n",
               what.c_str());
  std::exit(2);
}

std::string Range(const Stats& s, double scale, const char* f) {
  return FormatDouble(f, s.Median() * scale) + " (" + FormatDouble(f, s.Min() * scale) + "–" +
         FormatDouble(f, s.Max() * scale) + ")";
}

Stats Mpix(const Stats& s, double mp) {  // median of rates = mp / median time
  Stats r;
  for (double v : s.samples) r.samples.push_back(mp / v);
  return r;
}

Json StatsJson(const std::vector<double>& v, double scale) {
  Stats s{v};
  Json j;
  j["median"] = s.Median() * scale;
  j["min"] = s.Min() * scale;
  j["max"] = s.Max() * scale;
  j["repeats"] = v.size();
  return j;
}

void BenchOutput::Goal(const std::string& goal, const std::string& measured, bool met) {
  Line("| " + goal + " | " + measured + " | " + (met ? "yes" : "**no**") + " |");
  goals.push_back({{"goal", goal}, {"measured", measured}, {"met", met}});
}

}  // namespace aalab::bench
