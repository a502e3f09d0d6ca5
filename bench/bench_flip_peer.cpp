// FLIP against NVIDIA's FLIP tool (see bench_flip_peer.h). The tool reads 8-bit PNGs and
// prints "Mean: m" (6 decimals) and "Evaluation time: t seconds" (FLIP::evaluate alone, no
// file I/O or pooling) per test image; OMP_NUM_THREADS sets its threads.
#include "bench/bench_memory.h"
#include "bench/bench_flip_peer.h"
#include "bench/run_capture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "core/format.h"
#include "io/image_io.h"
#include "metrics/flip.h"

namespace aalab::bench {
namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

NvidiaFlipRun RunNvidiaFlip(const Image8& reference, const Image8& test, int reps, const std::string& tmp_dir) {
  NvidiaFlipRun r;
  const char* env = std::getenv("AALAB_NVIDIA_FLIP");
  r.path = env && *env ? env : kNvidiaFlipDefaultPath;
  if (!std::filesystem::is_regular_file(r.path)) {
    r.error = "NVIDIA FLIP tool not found at " + r.path +
              " (set AALAB_NVIDIA_FLIP; docs/performance.md says how to build it)";
    return r;
  }
  const std::string ref_png = tmp_dir + "/flip_ref.png", test_png = tmp_dir + "/flip_test.png";
  WriteImage8(ref_png, reference);
  WriteImage8(test_png, test);
  const ImageF ref_f = ToFloat(reference, 3), test_f = ToFloat(test, 3);
  const FlipValues v = flip::ErrorValues(ref_f, test_f, kFlipDefaultPpd);
  r.aalab_mean = PoolFlip(v).mean;
  for (int threads : {1, 2}) {
    std::string cmd = "cd " + tmp_dir + " && " + PeerEnvPrefix() + "OMP_NUM_THREADS=" + std::to_string(threads) + " " +
                      r.path + " -nerm -v 2 -ppd 67 -r " + ref_png + " -t";
    for (int i = 0; i < reps + 1; ++i) cmd += " " + test_png;
    const std::string out = RunCapture(cmd + " 2>&1");
    std::istringstream in(out);
    std::string l;
    std::vector<double> times;
    while (std::getline(in, l)) {
      double x = 0;
      if (std::sscanf(l.c_str(), " Evaluation time: %lf", &x) == 1) times.push_back(x);
      if (std::sscanf(l.c_str(), " Mean: %lf", &x) == 1) r.tool_mean = x;
    }
    if (times.size() != static_cast<size_t>(reps + 1)) {
      r.error = "NVIDIA FLIP tool at " + r.path + " gave no timings: " + out.substr(0, 300);
      return r;
    }
    times.erase(times.begin());  // warm-up
    r.eval_s[threads] = times;
  }
  return r;
}

std::vector<BenchGoal> ReportNvidiaFlip(const NvidiaFlipRun& run, const std::function<double(int)>& aalab_ms,
                                        const std::function<void(const std::string&)>& line,
                                        nlohmann::ordered_json* figures) {
  std::vector<BenchGoal> goals;
  auto goal = [&](const std::string& g, const std::string& m, bool met) { goals.push_back({g, m, met}); };
  line("");
  line("## FLIP vs NVIDIA's FLIP tool — the same 1920x1080 pair, 8-bit PNGs, 67 pixels per degree");
  line("");
  if (!run.error.empty()) {
    line("not measured: " + run.error);
    goal("FLIP as in a run ≥ 5× faster than NVIDIA's FLIP tool (1 and 2 threads)", "not measured: " + run.error, false);
    goal("FLIP mean within 1e-5 of NVIDIA's FLIP tool", "not measured", false);
    return goals;
  }
  line("NVIDIA's tool (" + run.path +
       "): its printed evaluation time (FLIP::evaluate only, no I/O, no pooling), OpenMP threads; "
       "aalab: flip::ErrorValues against the prepared reference + PoolFlip, as a run scores a method.");
  line("");
  line("| threads | NVIDIA tool ms median (min–max) | aalab ms median | aalab speed-up |");
  line("|---|---|---|---|");
  double worst = 1e30;
  std::string measured;
  for (const auto& [threads, s] : run.eval_s) {
    const double nv = Median(s) * 1e3, aa = aalab_ms(threads);
    const double sp = nv / aa;
    worst = std::min(worst, sp);
    line("| " + std::to_string(threads) + " | " + FormatDouble("%.0f", nv) + " (" +
         FormatDouble("%.0f", *std::min_element(s.begin(), s.end()) * 1e3) + "–" +
         FormatDouble("%.0f", *std::max_element(s.begin(), s.end()) * 1e3) + ") | " + FormatDouble("%.1f", aa) + " | " +
         FormatDouble("%.1f×", sp) + " |");
    measured += (measured.empty() ? "" : ", ") + FormatDouble("%.1f×", sp) + " at " + std::to_string(threads) +
                " thread" + (threads > 1 ? "s" : "");
    std::vector<double> ms;
    for (double x : s) ms.push_back(x * 1e3);
    figures->push_back({{"group", "metrics"},
                        {"name", "flip-nvidia-tool"},
                        {"threads", threads},
                        {"unit", "ms"},
                        {"samples", ms},
                        {"median", nv},
                        {"aalab_ms", aa},
                        {"speedup", sp}});
  }
  const double d = std::abs(run.aalab_mean - run.tool_mean);
  line("");
  line("Mean FLIP: NVIDIA tool " + FormatDouble("%.6f", run.tool_mean) +
       " (it prints 6 decimals: up to 5e-7 of |Δ| is that rounding), aalab " + FormatDouble("%.9f", run.aalab_mean) +
       ", |Δ| " + FormatDouble("%.2g", d) + ".");
  goal("FLIP as in a run ≥ 5× faster than NVIDIA's FLIP tool (1 and 2 threads)", measured, worst >= 5.0);
  goal("FLIP mean within 1e-5 of NVIDIA's FLIP tool (its 6-decimal print)", FormatDouble("%.2g", d), d <= 1e-5);
  return goals;
}

}  // namespace aalab::bench
