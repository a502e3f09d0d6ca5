// MSAA bench: what one shading per primitive saves. msaa-4x against ssaa-rgss — the same
// four standard positions, so the same coverage — on every library scene: shading
// evaluations, rays and texture lookups per pixel (hardware-independent) and the render time
// (this implementation on this machine). The time saved follows the shading's share of the
// cost: largest where every shade traces a shadow ray (shadow-stipple); where shading is free
// (unlit scenes) the emulation's centre rays and sample grouping make MSAA the slower one.
// Measured ratios: docs/msaa.md.
//
// Timing: one untimed warm-up render, then `reps` timed renders (steady clock, all worker
// threads; and process CPU time, less exposed to other load); median, min and max.
// Standalone: aalab_bench_msaa [WxH] [reps] [scene,...] (bench_msaa_main.cpp).
#include "bench/bench_stats.h"
#include "bench/bench_msaa.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <vector>

#include "core/format.h"
#include "methods/registry.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace aalab {

namespace {

/// Process CPU time (all threads), ms: less exposed than wall time to other load on a shared
/// machine.
double CpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) / 1e6;
}

struct Figure {
  TraceCounters counters;
  SampleStats wall, cpu;  // ms, one per repetition
  double Median() const { return wall.Median(); }
  double CpuMedian() const { return cpu.Median(); }
};

Figure Measure(const Tracer& tracer, int w, int h, const RenderSpec& spec, int reps) {
  Figure f;
  RenderFrame(tracer, w, h, spec, 1, &f.counters);  // warm-up; counters are the same every time
  for (int r = 0; r < reps; ++r) {
    const double c0 = CpuMs();
    const auto t0 = std::chrono::steady_clock::now();
    const Image8 img = RenderFrame(tracer, w, h, spec, 1, nullptr);
    f.wall.samples.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    f.cpu.samples.push_back(CpuMs() - c0);
    if (img.Width() != w) std::abort();  // keeps the render observable
  }
  return f;
}

}  // namespace

MsaaBenchResult RunMsaaBench(int width, int height, int reps, const std::vector<std::string>& scenes) {
  MsaaBenchResult out;
  const RenderSpec msaa = MakeMethod("msaa-4x").render;
  const RenderSpec ssaa = MakeMethod("ssaa-rgss").render;
  const double px = static_cast<double>(width) * height;
  std::string& md = out.markdown;
  md += "## MSAA — msaa-4x vs ssaa-rgss (same 4 positions), " + std::to_string(width) + "x" + std::to_string(height) +
        ", render time median (min–max) of " + std::to_string(reps) + " runs\n\n";
  md +=
      "| scene | shading evals/px MSAA | SSAA | ratio | rays/px MSAA (coverage + centre + shadow) | SSAA | "
      "texture lookups/px MSAA | SSAA | wall ms MSAA | wall ms SSAA | wall ratio | CPU ratio |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  out.json = nlohmann::ordered_json::array();
  for (const auto& name : scenes) {
    const Scene scene = LoadScene(name);
    const Tracer tracer(scene);
    const Figure m = Measure(tracer, width, height, msaa, reps);
    const Figure s = Measure(tracer, width, height, ssaa, reps);
    auto per = [px](uint64_t v) { return static_cast<double>(v) / px; };
    auto range = [](const Figure& f) {
      return FormatDouble("%.1f", f.Median()) + " (" + FormatDouble("%.1f", f.wall.Min()) + "–" +
             FormatDouble("%.1f", f.wall.Max()) + ")";
    };
    const double eval_ratio =
        per(s.counters.shading_evals) > 0 ? per(m.counters.shading_evals) / per(s.counters.shading_evals) : 0.0;
    const double time_ratio = m.Median() / s.Median();
    const double cpu_ratio = m.CpuMedian() / s.CpuMedian();
    auto rays = [&](const Figure& f) {
      return FormatDouble("%.2f", per(f.counters.coverage_rays)) + " + " +
             FormatDouble("%.2f", per(f.counters.primary_rays - f.counters.coverage_rays)) + " + " +
             FormatDouble("%.2f", per(f.counters.shadow_rays));
    };
    md += "| " + name + " | " + FormatDouble("%.3f", per(m.counters.shading_evals)) + " | " +
          FormatDouble("%.3f", per(s.counters.shading_evals)) + " | " + FormatDouble("%.2f", eval_ratio) + " | " +
          rays(m) + " | " + rays(s) + " | " + FormatDouble("%.3f", per(m.counters.texture_lookups)) + " | " +
          FormatDouble("%.3f", per(s.counters.texture_lookups)) + " | " + range(m) + " | " + range(s) + " | " +
          FormatDouble("%.2f", time_ratio) + " | " + FormatDouble("%.2f", cpu_ratio) + " |\n";
    auto fig = [&](const Figure& f) {
      return nlohmann::ordered_json{{"shading_evals_per_px", per(f.counters.shading_evals)},
                                    {"coverage_rays_per_px", per(f.counters.coverage_rays)},
                                    {"primary_rays_per_px", per(f.counters.primary_rays)},
                                    {"shadow_rays_per_px", per(f.counters.shadow_rays)},
                                    {"texture_lookups_per_px", per(f.counters.texture_lookups)},
                                    {"render_ms", f.wall.samples},
                                    {"render_ms_median", f.Median()},
                                    {"render_cpu_ms", f.cpu.samples},
                                    {"render_cpu_ms_median", f.CpuMedian()}};
    };
    out.json.push_back({{"scene", name},
                        {"width", width},
                        {"height", height},
                        {"msaa-4x", fig(m)},
                        {"ssaa-rgss", fig(s)},
                        {"shading_evals_ratio", eval_ratio},
                        {"time_ratio", time_ratio},
                        {"cpu_time_ratio", cpu_ratio}});
    std::fprintf(stderr, "  msaa/%-20s evals %.2f×  time %.2f×  cpu %.2f×\n", name.c_str(), eval_ratio, time_ratio,
                 cpu_ratio);
  }
  return out;
}

void AppendMsaaBench(bool quick, std::ostringstream& table, nlohmann::ordered_json& report) {
  std::fprintf(stderr, "MSAA vs SSAA...\n");
  const MsaaBenchResult r =
      quick ? RunMsaaBench(160, 90, 2, LibrarySceneNames()) : RunMsaaBench(480, 270, 5, LibrarySceneNames());
  table << "\n" << r.markdown;
  report["msaa"] = r.json;
}

}  // namespace aalab
