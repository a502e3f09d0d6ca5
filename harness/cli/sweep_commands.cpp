// `aalab sweep`: thin CLI over harness/run/sweep.h.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "harness/cli/commands.h"
#include "core/error.h"
#include "core/exit_code.h"
#include "core/params.h"
#include "harness/run/runner.h"
#include "harness/run/sweep.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

constexpr const char* kSweepNotes =
    R"(Each scene's reference and 1x frame are rendered once and reused for every grid point.
Grid values go through the method's parameter table (unknown parameter or out-of-range value:
the method's own error); a parameter given twice is an error; at most 1024 points.
Objectives (default flip_mean, then edge_psnr_db: squared-error objectives reward blur):
mean over scenes (a null 'identical' PSNR counts as +infinity; any other null makes the
point's mean null). Time: the method's own time (post + resample, plus render unless shared
with 'none'), median over repeats, mean over scenes; its spread (max - min over repeats)
is the noise. Best per objective: the best mean, ties to the point closest to the defaults,
then grid order. Pareto front (first objective vs time): times within both points' spreads
count as equal. Suggested preset: the first objective's best; among ties, one that another
is faster than beyond the spreads is dropped, then the closest to the defaults. Printed:
every objective's pick, a NOTE when they disagree, the suggestion against the default point
per scene. Writes DIR/sweep.json, DIR/index.html and DIR/crops/ (via DIR.partial).)";

}  // namespace

void RegisterSweepCommands(CLI::App& app, Commands& commands) {
  auto* sw =
      app.add_subcommand("sweep", "tune one method over a parameter grid; prints the best setting and a preset line");
  struct Args {
    SweepSettings s;
    std::string scenes, size = "960x540", objectives, shard;
    bool references_only = false;
  };
  auto a = std::make_shared<Args>();
  sw->add_option("--scenes", a->scenes, "comma-separated library scene names or scene file paths")->required();
  sw->add_option("--method", a->s.method, "method to tune, optionally with fixed overrides (fxaa1-p3:search_steps=8)")
      ->required();
  sw->add_option("--grid", a->s.grid, "NAME=V1,V2,... (repeat for more parameters; see aalab list methods)")
      ->required();
  sw->add_option("--objective", a->objectives,
                 "comma-separated metrics to optimise, the first drives the Pareto front, heatmaps and suggested "
                 "preset (default: flip_mean,edge_psnr_db; psnr_db when edge PSNR is not computed)");
  sw->add_option("--out", a->s.out_dir, "output folder")->capture_default_str();
  sw->add_option("--size", a->size, "output size WxH")->capture_default_str();
  sw->add_option("--ref-spp", a->s.ref_spp,
                 "reference samples per pixel: n*n, n even (4, 16, 64, 256, 1024); default as aalab run")
      ->capture_default_str();
  sw->add_option(
        "--reference", a->s.reference,
        "sampled (--ref-spp stratified samples) or exact (closed-form coverage; flat unlit orthographic scenes)")
      ->capture_default_str();
  sw->add_option("--seed", a->s.seed, "jitter seed")->capture_default_str();
  sw->add_option("--repeat", a->s.repeat,
                 "timed repeats after one warm-up (default as aalab run; 3+ gives the time spread the suggestion uses)")
      ->capture_default_str();
  sw->add_option("--threads", a->s.threads, "worker threads (0 = all hardware threads)")->capture_default_str();
  sw->add_option(
      "--viewing", a->s.viewing,
      "viewing condition PRESET[:key=value,...] for FLIP (default: 'default', 67 px/deg; aalab list viewing)");
  sw->add_flag("--quiet", a->s.quiet, "no progress on stderr");
  sw->add_option("--shard", a->shard,
                 "K/N: run shard K (0..N-1) of N, its share of the grid points on every scene, for 'aalab merge' "
                 "(docs/cluster.md)");
  sw->add_option("--ref-cache", a->s.ref_cache,
                 "folder of cached references shared by shards and runs: read when present, written when rendered");
  sw->add_flag("--references-only", a->references_only,
               "only render this shard's share of the scenes' references into --ref-cache; write no sweep");
  sw->footer(kSweepNotes);
  sw->callback([&commands, a] {
    commands.action = [a] {
      ParseSize(a->size, &a->s.width, &a->s.height);
      a->s.scenes = SplitCommaList(a->scenes, "--scenes");
      if (!a->objectives.empty()) a->s.objectives = SplitCommaList(a->objectives, "--objective");
      if (!a->shard.empty()) a->s.shard = ParseShard(a->shard);
      if (a->references_only) {
        int cached = 0;
        const int rendered = RenderSweepReferences(a->s, &cached);
        std::printf("references: %d rendered, %d already cached, in %s\n", rendered, cached,
                    fs::absolute(a->s.ref_cache).string().c_str());
        return ToInt(ExitCode::kOk);
      }
      const SweepResult r = RunSweep(a->s);
      if (r.report.shard) {
        std::printf(
            "sweep shard %d/%d: %zu of %d grid points on %zu scenes\npartial sweep: %s (merge the shards with "
            "aalab merge)\n",
            r.report.shard->index, r.report.shard->count, r.report.shard->units.size(), r.report.shard->total_units,
            r.report.scenes.size(), (fs::absolute(r.out_dir) / "sweep.json").string().c_str());
        return ToInt(ExitCode::kOk);
      }
      std::fputs(SweepSummaryText(r).c_str(), stdout);
      std::printf("wrote %s and %s\n", (fs::absolute(r.out_dir) / "sweep.json").string().c_str(),
                  (fs::absolute(r.out_dir) / "index.html").string().c_str());
      return ToInt(ExitCode::kOk);
    };
  });
}

}  // namespace aalab
