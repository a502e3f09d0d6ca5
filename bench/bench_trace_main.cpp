// aalab_bench_trace [WxH] [reps] [scene,...]: the tracing figures alone, in process CPU time
// (load-independent on a shared machine) and wall time, 1 thread: the reference render
// (RenderReference, 64 spp) beside the bare Embree loop (Tracer::BareTrace) on the same scene,
// size and samples per pixel, and the method renders of the default run (ssaa-2x2, ssaa-4x4,
// msaa-4x, 1x). The Mrays/s ratio counts primary + shadow rays of the reference against the
// bare loop's primary rays, as make bench does. Default: 320x180, 5 repetitions, the default suite. Minimum over
// repetitions.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_memory.h"
#include "core/parallel.h"
#include "methods/registry.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace {

double CpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

/// Minimum process CPU ms of `reps` calls after one warm-up.
double MinCpuMs(int reps, const std::function<void()>& f) {
  f();
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const double t0 = CpuMs();
    f();
    best = std::min(best, CpuMs() - t0);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  std::fprintf(stderr, "%s\n", aalab::bench::ApplyBenchMemoryPolicy());
  using namespace aalab;
  int w = 320, h = 180;
  if (argc > 1) std::sscanf(argv[1], "%dx%d", &w, &h);
  const int reps = argc > 2 ? std::atoi(argv[2]) : 5;
  std::vector<std::string> scenes = SuiteScenes("default");
  if (argc > 3) {
    scenes.clear();
    std::stringstream ss(argv[3]);
    for (std::string s; std::getline(ss, s, ',');) scenes.push_back(s);
  }
  SetThreadCount(1);
  const int grid = 8;
  std::printf(
      "| scene | reference ms | bare Embree ms | bare / reference time | reference / bare Mrays/s (make bench's ratio) "
      "| ssaa-2x2 ms | ssaa-4x4 ms | msaa-4x ms | 1x ms |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  double sum_ref = 0, sum_bare = 0, sum_methods = 0;
  for (const auto& name : scenes) {
    const Scene scene = LoadScene(name);
    const Tracer tracer(scene);
    TraceCounters c;
    (void)RenderReference(tracer, w, h, grid, 1, &c);
    const double ref_rays = static_cast<double>(c.primary_rays + c.shadow_rays);
    const double bare_rays = static_cast<double>(w) * h * grid * grid;
    const double ref = MinCpuMs(reps, [&] { (void)RenderReference(tracer, w, h, grid, 1, nullptr); });
    const double bare = MinCpuMs(reps, [&] { (void)tracer.BareTrace(w, h, grid); });
    double m[4];
    const char* specs[4] = {"ssaa-2x2", "ssaa-4x4", "msaa-4x", "none"};
    for (int k = 0; k < 4; ++k) {
      const MethodPlan plan = MakeMethod(specs[k]);
      m[k] = MinCpuMs(reps, [&] { (void)RenderFrame(tracer, w, h, plan.render, 1, nullptr); });
      sum_methods += m[k];
    }
    sum_ref += ref;
    sum_bare += bare;
    std::printf("| %s | %.1f | %.1f | %.0f%% | %.0f%% | %.1f | %.1f | %.1f | %.1f |\n", name.c_str(), ref, bare,
                100.0 * bare / ref, 100.0 * (ref_rays / ref) / (bare_rays / bare), m[0], m[1], m[2], m[3]);
    std::fflush(stdout);
  }
  std::printf("| all | %.1f | %.1f | %.0f%% | | methods sum %.1f | | | |\n", sum_ref, sum_bare,
              100.0 * sum_bare / sum_ref, sum_methods);
  return 0;
}
