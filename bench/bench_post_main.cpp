// aalab_bench_post [REPS] [METHOD,...] [SCENE,...]: make bench's post-filter figures alone,
// in process CPU time (what a shared machine cannot inflate much) and wall time, at 1 and 2
// threads, on 1920x1080 1x frames of library scenes (make bench's "real" frame is `mesh`, its
// "dense" frame `checker-plane`). Each figure is the minimum over REPS calls after one
// warm-up call; the floor is make bench's plain read+write pass (bench/bench_common.h).
// Per frame it also prints the share of pixels whose Rec. 709 luma (of the sRGB bytes, as
// SMAA's luma edge detection computes it) differs from the left or top neighbour's by at
// least 0.1 and 0.05: the pixels SMAA's passes 2 and 3 work on.
// Defaults: 7 repetitions; smaa-low, smaa-ultra, fxaa311-p39, fxaa-high, fxaa1-p0; mesh,checker-plane.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_memory.h"
#include "bench/bench_common.h"
#include "core/parallel.h"
#include "methods/registry.h"

namespace {

double CpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

double WallMs() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

struct Timing {
  double cpu_ms = 1e300, wall_ms = 1e300;
};

// Minimum process CPU ms and minimum wall ms of `reps` calls after one warm-up.
Timing MinTimes(int reps, const std::function<void()>& f) {
  f();
  Timing t;
  for (int r = 0; r < reps; ++r) {
    const double c0 = CpuMs(), w0 = WallMs();
    f();
    t.cpu_ms = std::min(t.cpu_ms, CpuMs() - c0);
    t.wall_ms = std::min(t.wall_ms, WallMs() - w0);
  }
  return t;
}

std::vector<std::string> Split(const std::string& s) {
  std::vector<std::string> v;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');) v.push_back(x);
  return v;
}

// Share of pixels whose luma differs from the left or top neighbour's by ≥ threshold.
double EdgeShare(const aalab::Image8& img, float threshold) {
  const auto luma = [&](int x, int y) {
    const uint8_t* p = img.Row(y) + 4 * x;
    return 0.2126f * p[0] / 255.0f + 0.7152f * p[1] / 255.0f + 0.0722f * p[2] / 255.0f;
  };
  long n = 0;
  for (int y = 0; y < img.Height(); ++y) {
    for (int x = 0; x < img.Width(); ++x) {
      const float c = luma(x, y);
      const bool e = (x > 0 && std::fabs(c - luma(x - 1, y)) >= threshold) ||
                     (y > 0 && std::fabs(c - luma(x, y - 1)) >= threshold);
      n += e;
    }
  }
  return static_cast<double>(n) / (static_cast<double>(img.Width()) * img.Height());
}

}  // namespace

int main(int argc, char** argv) {
  std::fprintf(stderr, "%s\n", aalab::bench::ApplyBenchMemoryPolicy());
  using namespace aalab;
  const int reps = argc > 1 ? std::atoi(argv[1]) : 7;
  const std::vector<std::string> methods =
      Split(argc > 2 ? argv[2] : "smaa-low,smaa-ultra,fxaa311-p39,fxaa-high,fxaa1-p0");
  const std::vector<std::string> scenes = Split(argc > 3 ? argv[3] : "mesh,checker-plane");
  std::printf(
      "| frame | filter | CPU ms, 1 thread | wall ms, 1 thread | CPU ms, 2 threads | wall ms, 2 threads | "
      "2 threads / 1 (wall) |\n|---|---|---|---|---|---|---|\n");
  for (const auto& scene : scenes) {
    SetThreadCount(0);
    const Image8 frame = bench::RenderFrame1x(scene, bench::kFrameW, bench::kFrameH);
    std::fprintf(stderr, "%s: edge pixels (luma step to left/top) %.2f %% at >= 0.1, %.2f %% at >= 0.05\n",
                 scene.c_str(), 100.0 * EdgeShare(frame, 0.1f), 100.0 * EdgeShare(frame, 0.05f));
    Image8 out(frame.Width(), frame.Height(), 4);
    std::vector<std::pair<std::string, std::function<void()>>> figs;
    figs.push_back({"floor (plain read+write)", [&] { bench::PlainPass(frame, out); }});
    for (const auto& m : methods) {
      const MethodPlan plan = MakeMethod(m);
      const PostFilter post = plan.post;
      figs.push_back({m, [&frame, post] { (void)post(frame, PostOptions{}, nullptr); }});
    }
    for (const auto& [name, f] : figs) {
      SetThreadCount(1);
      const Timing t1 = MinTimes(reps, f);
      SetThreadCount(2);
      const Timing t2 = MinTimes(reps, f);
      std::printf("| %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f× |\n", scene.c_str(), name.c_str(), t1.cpu_ms,
                  t1.wall_ms, t2.cpu_ms, t2.wall_ms, t1.wall_ms / t2.wall_ms);
      std::fflush(stdout);
    }
  }
  SetThreadCount(0);
  return 0;
}
