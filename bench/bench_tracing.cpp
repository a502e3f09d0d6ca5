// The tracing figures of `make bench`; see bench/bench_tracing.h.
#include "bench/bench_tracing.h"

#include <benchmark/benchmark.h>

#include <cstdio>

#include "bench/bench_bigmesh.h"
#include "core/format.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace aalab::bench {

TracingBench RegisterTracingFigures(const Settings& cfg) {
  TracingBench tb;
  for (const auto& n : LibrarySceneNames()) {
    if (n.rfind("real-", 0) != 0) tb.scenes.push_back(n);
  }
  if (cfg.quick) tb.scenes = {"wedges", "shadow-stipple"};
  struct Traced {
    std::unique_ptr<Scene> scene;
    std::unique_ptr<Tracer> tracer;
  };
  auto traced = std::make_shared<std::map<std::string, Traced>>();
  for (const auto& name : tb.scenes) {
    Traced t;
    t.scene = std::make_unique<Scene>(LoadScene(name));
    t.tracer = std::make_unique<Tracer>(*t.scene);
    TraceCounters c;
    RenderReference(*t.tracer, cfg.trace_w, cfg.trace_h, cfg.trace_grid, 1, &c);
    tb.rays[name] = c.primary_rays + c.shadow_rays;
    (*traced)[name] = std::move(t);
  }
  std::vector<std::vector<RoundFigure>> groups;
  // A scene's four figures: one group, measured in rounds; the scenes' rounds interleaved (round
  // r of every scene, then r + 1), so each scene's rounds lie minutes apart.
  for (const auto& name : tb.scenes) {
    std::vector<RoundFigure> group;
    for (int threads : {1, 2}) {
      const Tracer* tr = (*traced)[name].tracer.get();
      const std::string t = "/t" + std::to_string(threads);
      const int w = cfg.trace_w, h = cfg.trace_h, g = cfg.trace_grid;
      group.push_back({"reference/" + name + t, threads, [traced, tr, w, h, g] {
                         Reference r = RenderReference(*tr, w, h, g, 1, nullptr);
                         benchmark::DoNotOptimize(r.image.Data().data());
                       }});
      group.push_back({"bare-embree/" + name + t, threads,
                       [traced, tr, w, h, g] { benchmark::DoNotOptimize(tr->BareTrace(w, h, g)); }});
    }
    groups.push_back(std::move(group));
  }
  RegisterRounds(groups, cfg.trace_reps, cfg.min_time);
  return tb;
}

void TracingTable(const Settings& cfg, TracingBench& tb, BenchOutput& out) {
  out.Line("");
  out.Line("## Tracing — reference render, " + std::to_string(cfg.trace_w) + "x" + std::to_string(cfg.trace_h) + ", " +
           std::to_string(cfg.trace_grid * cfg.trace_grid) +
           " spp; ratio = reference Mrays/s / bare Embree loop Mrays/s");
  out.Line("");
  out.Line("| scene | threads | reference Mrays/s | bare Embree Mrays/s | reference / bare | cores used (ref) |");
  out.Line("|---|---|---|---|---|---|");
  for (int threads : {1, 2}) {
    for (const auto& name : tb.scenes) {
      const std::string t = "/t" + std::to_string(threads);
      const Stats& rs = Figure("reference/" + name + t);
      const Stats& bs = Figure("bare-embree/" + name + t);
      const double ref_mr = static_cast<double>(tb.rays[name]) / 1e6;
      const double bare_mr = static_cast<double>(cfg.trace_w) * cfg.trace_h * cfg.trace_grid * cfg.trace_grid / 1e6;
      const Stats rr = Mpix(rs, ref_mr), br = Mpix(bs, bare_mr);
      // Rays per second, reference over bare: per round (bare s / reference s) × rays ratio.
      const double ratio = PairedRatio("bare-embree/" + name + t, "reference/" + name + t) * ref_mr / bare_mr;
      if (threads == 1)
        tb.ratio_t1[name] = ratio;
      else {
        tb.scaling[name] = PairedRatio("reference/" + name + "/t1", "reference/" + name + t);
        tb.scaling_fastest[name] = FastestRatio("reference/" + name + "/t1", "reference/" + name + t);
      }
      out.Line("| " + name + " | " + std::to_string(threads) + " | " + Range(rr, 1, "%.1f") + " | " +
               Range(br, 1, "%.1f") + " | " + FormatDouble("%.0f%%", 100 * ratio) + " | " +
               FormatDouble("%.2f", CoresUsed("reference/" + name + t)) + " |");
      out.figures.push_back({{"group", "tracing"},
                             {"name", name},
                             {"threads", threads},
                             {"unit", "Mrays/s"},
                             {"reference", StatsJson(rr.samples, 1)},
                             {"bare_embree", StatsJson(br.samples, 1)},
                             {"reference_rays", tb.rays[name]},
                             {"limit", "bare Embree loop"},
                             {"ratio_to_limit", ratio}});
    }
  }
}

void BigMeshTable(BenchOutput& out) {
  std::fprintf(stderr, "building and tracing the 1M-triangle torus...\n");
  const BigMeshFigures bm = MeasureBigMesh(1024, 512, 960, 540, 3);
  out.Line("");
  out.Line("## Big mesh — a procedural torus of " + std::to_string(bm.triangles) +
           " triangles, 960x540 1x frame (best of 3)");
  out.Line("");
  out.Line(
      "| BVH build ms | scene arrays MB | RSS added by the tracer MB | 1x Mrays/s t1 | t2 | bare Embree Mrays/s t1 | "
      "t2 |");
  out.Line("|---|---|---|---|---|---|---|");
  out.Line("| " + FormatDouble("%.0f", bm.bvh_build_ms) + " | " + FormatDouble("%.1f", bm.scene_mb) + " | " +
           FormatDouble("%.1f", bm.rss_bvh_mb) + " | " + FormatDouble("%.2f", bm.render_mrays_t1) + " | " +
           FormatDouble("%.2f", bm.render_mrays_t2) + " | " + FormatDouble("%.2f", bm.bare_mrays_t1) + " | " +
           FormatDouble("%.2f", bm.bare_mrays_t2) + " |");
  out.figures.push_back({{"group", "bigmesh"},
                         {"name", "torus"},
                         {"triangles", bm.triangles},
                         {"bvh_build_ms", bm.bvh_build_ms},
                         {"scene_mb", bm.scene_mb},
                         {"rss_tracer_mb", bm.rss_bvh_mb},
                         {"render_mrays_t1", bm.render_mrays_t1},
                         {"render_mrays_t2", bm.render_mrays_t2},
                         {"bare_mrays_t1", bm.bare_mrays_t1},
                         {"bare_mrays_t2", bm.bare_mrays_t2}});
}

void TracingRatioGoal(const TracingBench& tb, BenchOutput& out) {
  double worst = 1e9;
  std::string worst_name;
  for (const auto& [n, r] : tb.ratio_t1) {
    if (r < worst) worst = r, worst_name = n;
  }
  int below = 0;
  for (const auto& [n, r] : tb.ratio_t1) below += r < 0.7;
  out.Goal("reference tracing ≥ 70% of the bare Embree loop (every scene, 1 thread)",
           "worst " + worst_name + " " + FormatDouble("%.0f%%", 100 * worst) + "; " + std::to_string(below) + " of " +
               std::to_string(tb.ratio_t1.size()) + " scenes below 70%",
           below == 0);
}

void TracingScalingGoal(const TracingBench& tb, BenchOutput& out) {
  double worst = 1e9, fworst = 1e9;
  std::string worst_name, fworst_name;
  for (const auto& [n, s] : tb.scaling) {
    if (s < worst) worst = s, worst_name = n;
  }
  for (const auto& [n, s] : tb.scaling_fastest) {
    if (s < fworst) fworst = s, fworst_name = n;
  }
  const auto it = tb.scaling_fastest.find(worst_name);
  const double worst_fastest = it == tb.scaling_fastest.end() ? 0.0 : it->second;
  std::vector<double> tc;
  for (const auto& name : tb.scenes) tc.push_back(CoresUsed("reference/" + name + "/t2"));
  out.Goal("2 threads ≥ 1.8× one thread, tracing (reference, every scene)",
           "worst " + worst_name + " " + FormatDouble("%.2f×", worst) + "; the 2-thread runs got " +
               FormatDouble("%.2f", Stats{tc}.Median()) +
               " cores (median CPU s / wall s); fastest 1-thread / fastest " + "2-thread sample: " + worst_name +
               FormatDouble(" %.2f×", worst_fastest) + ", worst " + fworst_name + FormatDouble(" %.2f×", fworst),
           worst >= 1.8);
}

}  // namespace aalab::bench
