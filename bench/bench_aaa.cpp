// Analytical-AA bench figures (bench/bench_aaa.h): aaa render time vs none on sdf-circles
// (the goal: within 1.5x) and the exact reference of a 1080p flat scene vs a 256-spp
// sampled reference (goal: no slower). Both at the bench's default thread count.
#include "bench/bench_stats.h"
#include "bench/bench_aaa.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>

#include "core/format.h"
#include "core/render_spec.h"
#include "scenes/analytic.h"
#include "scenes/exact_reference.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace aalab {

namespace {

using Json = nlohmann::ordered_json;

struct Times : SampleStats {  // samples in ms
  Json ToJson() const { return {{"median", Median()}, {"min", Min()}, {"max", Max()}, {"samples", samples}}; }
};

Times Time(int reps, const std::function<void()>& body) {
  body();  // warm-up
  Times t;
  for (int i = 0; i < reps; ++i) {
    const auto a = std::chrono::steady_clock::now();
    body();
    t.samples.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
  }
  return t;
}

}  // namespace

std::vector<Json> BenchAnalyticAa(int reps, std::string* table) {
  std::vector<Json> figures;
  const Scene scene = LoadScene("sdf-circles");
  const Tracer tracer(scene);
  AnalyticSpec aaa;
  aaa.enabled = true;
  const Times none = Time(reps, [&] { RenderFrame(tracer, 960, 540, RenderSpec{}, 1, nullptr); });
  const Times analytic = Time(reps, [&] { RenderAnalyticFrame(tracer, 960, 540, aaa, nullptr, nullptr); });
  const Times exact = Time(reps, [&] { RenderExactReference(scene, 1920, 1080); });
  const Times sampled = Time(std::max(1, reps / 2), [&] { RenderReference(tracer, 1920, 1080, 16, 1, nullptr); });
  const double ratio = analytic.Median() / none.Median();
  const double ref_ratio = exact.Median() / sampled.Median();
  figures.push_back({{"group", "analytic-aa"},
                     {"name", "aaa-render"},
                     {"frame", "sdf-circles 960x540"},
                     {"unit", "ms"},
                     {"value", analytic.ToJson()},
                     {"limit", "none render"},
                     {"limit_ms", none.ToJson()},
                     {"ratio_to_limit", ratio},
                     {"goal", "<= 1.5"}});
  figures.push_back({{"group", "analytic-aa"},
                     {"name", "exact-reference"},
                     {"frame", "sdf-circles 1920x1080"},
                     {"unit", "ms"},
                     {"value", exact.ToJson()},
                     {"limit", "256-spp sampled reference"},
                     {"limit_ms", sampled.ToJson()},
                     {"ratio_to_limit", ref_ratio},
                     {"goal", "<= 1"}});
  *table +=
      "\n## Analytical AA\n\n| figure | ms median | limit | limit ms median | ratio | goal "
      "|\n|---|---|---|---|---|---|\n";
  *table += "| aaa render, sdf-circles 960x540 | " + FormatDouble("%.1f", analytic.Median()) + " | none render | " +
            FormatDouble("%.1f", none.Median()) + " | " + FormatDouble("%.2f", ratio) + " | <= 1.5 |\n";
  *table += "| exact reference, sdf-circles 1920x1080 | " + FormatDouble("%.1f", exact.Median()) +
            " | 256-spp reference | " + FormatDouble("%.1f", sampled.Median()) + " | " +
            FormatDouble("%.2f", ref_ratio) + " | <= 1 |\n";
  return figures;
}

}  // namespace aalab
