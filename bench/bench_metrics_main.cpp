// aalab_bench_metrics: the metric figures of `make bench` against their outside peers, alone
// (bench/bench_flip_peer.cpp): FLIP as in a run vs NVIDIA's FLIP tool, SSIM as in a run vs
// scikit-image, on the bench's 1920x1080 pair (mesh reference at 2x2 spp vs fxaa311-p39 on
// the 1x frame). Prints markdown.
//   aalab_bench_metrics [REPS]   default 7
#include <chrono>
#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <map>
#include <vector>
#include <string>
#include <unistd.h>

#include "bench/bench_memory.h"
#include "bench/bench_flip_peer.h"
#include "core/parallel.h"
#include "methods/fxaa311.h"
#include "metrics/flip.h"
#include "metrics/ssim.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace {

template <typename F>
double MedianMs(int reps, const F& body) {
  body();  // warm-up
  std::vector<double> ms;
  for (int i = 0; i < reps; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    body();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::fprintf(stderr, "%s\n", aalab::bench::ApplyBenchMemoryPolicy());
  using namespace aalab;
  const int reps = argc > 1 ? std::stoi(argv[1]) : 7;
  constexpr int W = 1920, H = 1080;
  const Scene scene = LoadScene("mesh");
  const Tracer tracer(scene);
  const Reference ref = RenderReference(tracer, W, H, 2, 1, nullptr);
  Fxaa311Params p;
  p.steps = Fxaa311PresetSteps(39);
  const ImageF img = ToFloat(Fxaa311(RenderFrame(tracer, W, H, RenderSpec{}, 1, nullptr), p, nullptr), 3);
  const auto flip_side = flip::PrepareReference(ref.image, kFlipDefaultPpd);
  const auto ssim_side = PrepareSsimReference(ref.image);
  std::printf("| figure | threads | aalab ms (median of %d) |\n|---|---|---|\n", reps);
  std::map<int, double> flip_ms;
  for (int threads : {1, 2}) {
    SetThreadCount(threads);
    flip_ms[threads] = MedianMs(reps, [&] { PoolFlip(flip::ErrorValues(*flip_side, img)); });
    const double direct = MedianMs(reps, [&] { PoolFlip(flip::ErrorValues(ref.image, img, kFlipDefaultPpd)); });
    const double ssim = MedianMs(reps, [&] { ComputeSsim(img, *ssim_side); });
    std::printf("| flip (reference half reused, as in a run) | %d | %.1f |\n", threads, flip_ms[threads]);
    std::printf("| flip (from scratch) | %d | %.1f |\n", threads, direct);
    std::printf("| ssim (reference half reused, as in a run) | %d | %.1f |\n", threads, ssim);
  }
  SetThreadCount(0);
  const std::filesystem::path tmp =
      std::filesystem::temp_directory_path() / ("aalab_bench_metrics_" + std::to_string(getpid()));
  std::filesystem::create_directories(tmp);
  const bench::NvidiaFlipRun nv = bench::RunNvidiaFlip(ToUnorm8(ref.image), ToUnorm8(img), reps, tmp.string());
  nlohmann::ordered_json figures = nlohmann::ordered_json::array();
  const auto goals = bench::ReportNvidiaFlip(
      nv, [&](int t) { return flip_ms[t]; }, [](const std::string& l) { std::printf("%s\n", l.c_str()); }, &figures);
  std::printf("\n| goal | measured | met |\n|---|---|---|\n");
  for (const auto& g : goals)
    std::printf("| %s | %s | %s |\n", g.goal.c_str(), g.measured.c_str(), g.met ? "yes" : "no");
  std::filesystem::remove_all(tmp);
  return 0;
}
