// The metric figures of `make bench`; see bench/bench_metrics.h.
#include "bench/bench_memory.h"
#include "bench/bench_metrics.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

#include <unistd.h>

#include "core/format.h"
#include "core/color.h"
#include "core/parallel.h"
#include "io/image_io.h"
#include "methods/registry.h"
#include "metrics/metrics.h"
#include "scenes/library.h"
#include "scenes/tracer.h"

namespace aalab::bench {

namespace fs = std::filesystem;

MetricsBench RegisterMetricFigures(const Settings& cfg, const Image8& real_frame) {
  std::fprintf(stderr, "rendering the 1080p metric pair...\n");
  SetThreadCount(0);
  MetricsBench mb;
  auto pair_ref = std::make_shared<Reference>();
  auto pair_img = std::make_shared<ImageF>();
  auto pair_none = std::make_shared<ImageF>();
  {
    const Scene scene = LoadScene("mesh");
    const Tracer tracer(scene);
    *pair_ref = RenderReference(tracer, kFrameW, kFrameH, 2, 1, nullptr);
    *pair_img = ToFloat(MakeMethod("fxaa311-p39").post(real_frame, PostOptions{}, nullptr), 3);
    *pair_none = ToFloat(real_frame, 3);
  }
  mb.ref = pair_ref, mb.img = pair_img, mb.none = pair_none;
  // Each metric at 1 and 2 threads: one group, measured in rounds; the metrics' rounds
  // interleaved (RegisterRounds, below).
  std::vector<std::vector<RoundFigure>> groups;
  const auto both = [&groups](const std::string& name, const std::function<void()>& body) {
    groups.push_back({{name + "/t1", 1, body}, {name + "/t2", 2, body}});
  };
  both("metric-psnr",
       [pair_ref, pair_img] { benchmark::DoNotOptimize(MeanSquaredError(*pair_img, pair_ref->image).mse); });
  both("metric-ssim", [pair_ref, pair_img] { benchmark::DoNotOptimize(ComputeSsim(*pair_img, pair_ref->image).ssim); });
  // SSIM as a run computes it per method: the reference's half prepared once per scene.
  both("metric-ssim-run", [pair_ref, pair_img] {
    static const std::shared_ptr<const SsimReferenceSide> side = PrepareSsimReference(pair_ref->image);
    benchmark::DoNotOptimize(ComputeSsim(*pair_img, *side).ssim);
  });
  // FLIP as a run computes it per method (the reference's half reused after the first
  // method of a scene), and from scratch (the first method of a scene, or `aalab metrics`).
  both("metric-flip", [pair_ref, pair_img] {
    static const std::shared_ptr<const flip::ReferenceSide> side =
        flip::PrepareReference(pair_ref->image, kFlipDefaultPpd);
    benchmark::DoNotOptimize(PoolFlip(flip::ErrorValues(*side, *pair_img)).mean);
  });
  both("metric-flip-uncached", [pair_ref, pair_img] {
    benchmark::DoNotOptimize(PoolFlip(flip::ErrorValues(pair_ref->image, *pair_img, kFlipDefaultPpd)).mean);
  });
  both("metric-edge", [pair_ref, pair_img, pair_none] {
    for (const auto& e : MetricRegistry()) {
      if (e.name != "edge") continue;
      MetricInput in;
      in.image = pair_img.get();
      in.reference = &pair_ref->image;
      in.edge_mask = &pair_ref->edge_mask;
      in.none_image = pair_none.get();
      benchmark::DoNotOptimize(e.compute(in).size());
    }
  });
  both("metric-all", [pair_ref, pair_img, pair_none] {
    MetricInput in;
    in.image = pair_img.get();
    in.reference = &pair_ref->image;
    in.edge_mask = &pair_ref->edge_mask;
    in.none_image = pair_none.get();
    benchmark::DoNotOptimize(ComputeAllMetrics(in).size());
  });
  RegisterRounds(groups, cfg.reps, cfg.min_time);
  return mb;
}

void RunExternalTools(const Settings& cfg, MetricsBench& mb) {
  std::fprintf(stderr, "external tools on the same pair...\n");
  const fs::path tmp = fs::temp_directory_path() / ("aalab_bench_" + std::to_string(getpid()));
  fs::create_directories(tmp);
  auto write_raw = [&](const ImageF& img, const fs::path& p) {
    std::ofstream f(p, std::ios::binary);
    for (int y = 0; y < img.Height(); ++y) {
      for (int x = 0; x < img.Width(); ++x) {
        for (int c = 0; c < 3; ++c) {
          const float v = img.At(x, y, c);
          f.write(reinterpret_cast<const char*>(&v), 4);
        }
      }
    }
  };
  write_raw(*mb.img, tmp / "a.f32");
  write_raw(mb.ref->image, tmp / "b.f32");
  Json& external = mb.external;
  mb.nvidia_flip =
      RunNvidiaFlip(ToUnorm8(mb.ref->image), ToUnorm8(*mb.img), std::max(3, cfg.reps / 2 + 1), tmp.string());
  {
    const std::string cmd = PeerEnvPrefix() + cfg.python + " " + cfg.script_dir + "/external_metrics.py " +
                            (tmp / "a.f32").string() + " " + (tmp / "b.f32").string() + " " + std::to_string(kFrameW) +
                            " " + std::to_string(kFrameH) + " " + std::to_string(std::max(3, cfg.reps / 2 + 1)) +
                            " 2>/dev/null";
    const std::string out = RunCapture(cmd);
    try {
      external["skimage"] = Json::parse(out);
    } catch (...) {
      external["skimage"] = Json{{"error", "scikit-image run failed: " + out}};
    }
  }
  {
    WriteImageF((tmp / "a.exr").string(), *mb.img);
    WriteImageF((tmp / "b.exr").string(), mb.ref->image);
    const bool have_idiff = std::system("command -v idiff >/dev/null 2>&1") == 0;
    if (have_idiff) {
      std::vector<double> ms;
      const std::string cmd =
          "idiff -fail 1 -warn 1 " + (tmp / "a.exr").string() + " " + (tmp / "b.exr").string() + " >/dev/null 2>&1";
      std::system(cmd.c_str());  // warm-up (page cache)
      for (int i = 0; i < std::max(3, cfg.reps / 2 + 1); ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        std::system(cmd.c_str());
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      }
      external["idiff"] = Json{{"samples_ms", ms},
                               {"what", "idiff process: load two 1080p float EXRs, compare (mean/RMS error, PSNR)"}};
    } else {
      external["idiff"] = Json{{"error", "idiff not installed"}};
    }
  }
  fs::remove_all(tmp);
}

void MetricsTable(MetricsBench& mb, BenchOutput& out) {
  out.Line("");
  out.Line("## Metrics — ms per 1920x1080 pair (fxaa311-p39 output vs the mesh reference)");
  out.Line("");
  out.Line("| metric | threads | aalab ms median (min–max) | external tool, same pair | aalab speed-up |");
  out.Line("|---|---|---|---|---|");
  auto ext_stats = [&](const Json& j) -> std::optional<Stats> {
    if (!j.contains("samples_ms")) return std::nullopt;
    Stats s;
    for (double v : j["samples_ms"]) s.samples.push_back(v / 1e3);
    return s;
  };
  Json& external = mb.external;
  std::optional<Stats> sk_ssim, sk_psnr, idiff_s;
  if (external["skimage"].contains("ssim")) sk_ssim = ext_stats(external["skimage"]["ssim"]);
  if (external["skimage"].contains("psnr")) sk_psnr = ext_stats(external["skimage"]["psnr"]);
  idiff_s = ext_stats(external["idiff"]);
  for (int threads : {1, 2}) {
    const std::string t = "/t" + std::to_string(threads);
    for (const char* m : {"psnr", "ssim", "ssim-run", "flip", "flip-uncached", "edge", "all"}) {
      const Stats& s = Figure(std::string("metric-") + m + t);
      std::string ext = "—", speed = "—";
      Json fj = {{"group", "metrics"},
                 {"name", m},
                 {"threads", threads},
                 {"unit", "ms"},
                 {"value", StatsJson(s.samples, 1e3)}};
      const std::optional<Stats>* e = nullptr;
      std::string tool;
      if ((std::string(m) == "ssim" || std::string(m) == "ssim-run") && sk_ssim) {
        e = &sk_ssim, tool = "scikit-image structural_similarity (float64)";
      }
      if (std::string(m) == "psnr" && sk_psnr) e = &sk_psnr, tool = "scikit-image peak_signal_noise_ratio (float64)";
      if (e) {
        ext = tool + " " + Range(**e, 1e3, "%.1f") + " ms";
        const double sp = (*e)->Median() / s.Median();
        speed = FormatDouble("%.1f×", sp);
        fj["external"] = {{"tool", tool}, {"ms", StatsJson((*e)->samples, 1e3)}, {"speedup", sp}};
        if (std::string(m) == "ssim-run" && threads == 1) mb.ssim_speedup = sp;
      }
      if (std::string(m) == "psnr" && idiff_s && threads == 1) {
        ext += "; idiff process " + Range(*idiff_s, 1e3, "%.0f") + " ms";
        fj["external_idiff"] = {{"tool", "idiff (whole process: load two float EXRs + compare)"},
                                {"ms", StatsJson(idiff_s->samples, 1e3)}};
      }
      const std::string label = std::string(m) == "all"             ? "all metrics (ComputeAllMetrics, as a run)"
                                : std::string(m) == "edge"          ? "edge/interior error (edge mask)"
                                : std::string(m) == "flip"          ? "flip (reference half reused, as in a run)"
                                : std::string(m) == "ssim"          ? "ssim (from scratch)"
                                : std::string(m) == "ssim-run"      ? "ssim (reference half reused, as in a run)"
                                : std::string(m) == "flip-uncached" ? "flip (from scratch)"
                                                                    : m;
      out.Line("| " + label + " | " + std::to_string(threads) + " | " + Range(s, 1e3, "%.1f") + " | " + ext + " | " +
               speed + " |");
      out.figures.push_back(fj);
    }
  }
  // FLIP against NVIDIA's tool on the same pair (bench/bench_flip_peer.cpp).
  mb.nvidia_flip_goals = ReportNvidiaFlip(
      mb.nvidia_flip, [](int th) { return Figure("metric-flip/t" + std::to_string(th)).Median() * 1e3; },
      [&out](const std::string& l) { out.Line(l); }, &out.figures);
}

void MetricsGoals(const MetricsBench& mb, BenchOutput& out) {
  for (const auto& g : mb.nvidia_flip_goals) out.Goal(g.goal, g.measured, g.met);
  out.Goal("SSIM as in a run ≥ 15× faster than scikit-image's Gaussian SSIM (1 thread)",
           mb.ssim_speedup > 0 ? FormatDouble("%.1f×", mb.ssim_speedup) : "skimage missing", mb.ssim_speedup >= 15.0);
  const double sp = PairedRatio("metric-ssim-run/t1", "metric-ssim-run/t2");
  out.Goal("SSIM as in a run: 2 threads ≥ 1.8× one thread",
           FormatDouble("%.2f×", sp) + "; the 2-thread runs got " +
               FormatDouble("%.2f", CoresUsed("metric-ssim-run/t2")) + " cores",
           sp >= 1.8);
}

}  // namespace aalab::bench
