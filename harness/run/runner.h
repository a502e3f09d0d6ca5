/// The run plan (scene × method matrix) and its execution: renders, post filters, timing,
/// metrics, images and the report.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/sampler.h"
#include "harness/run/shard.h"
#include "reports/result.h"

namespace aalab {

/// Everything `aalab run` needs. Validated by ValidateSettings before any work starts.
struct RunSettings {
  std::string suite = "default";
  std::vector<std::string> scenes;   ///< overrides the suite when non-empty (names or paths)
  std::vector<std::string> methods;  ///< empty: the default method list
  int width = 960, height = 540;
  int ref_spp = 64;                   ///< the default run's budget (README "How long"); 256+ for publication
  std::string reference = "sampled";  ///< "sampled" (ref_spp stratified samples) or "exact"
  uint64_t seed = 1;
  int threads = 0;  ///< 0: all hardware threads
  int repeat = 2;   ///< timed repeats after one warm-up
  std::string out_dir = "out";
  bool debug_views = false;
  bool quiet = false;            ///< no progress on stderr
  int frames = 1;                ///< sequence length (1..kMaxFrames; 1 = a still run, as before)
  ShardSpec shard;               ///< --shard K/N: this process's share of the scenes (docs/cluster.md)
  std::string ref_cache;         ///< --ref-cache DIR: read/write references there ("" = none)
  bool references_only = false;  ///< --references-only: fill the cache, write no report
  /// --viewing PRESET[:key=value,...]: the display and observer of the perceptual metrics
  /// (metrics/viewing.h); "" = the default preset (67 px/deg, every result as before).
  std::string viewing;
  /// --frame-exr: in a motion run, also write every frame's reference as display-linear
  /// float EXR (images/<scene>/reference.f<t>.exr), for outside video metrics.
  bool frame_exr = false;
  /// --sampler: the post filters' texel and bilinear arithmetic (PostOptions::sampler);
  /// kGpuTexture is recorded in the report's settings as "sampler".
  SamplerArithmetic sampler = SamplerArithmetic::kGl;
};

/// The methods `aalab run` uses when --methods is not given: one or two of each family
/// (`--methods all`: every registered method).
std::vector<std::string> DefaultMethods();

/// Parses "WxH" (1..16384 each, at most 64 Mpx); UserError otherwise.
void ParseSize(const std::string& text, int* width, int* height);

/// Runs the matrix and writes DIR/report.json, DIR/images/... Output goes to a temporary
/// folder that replaces DIR only when everything succeeded: a failed run leaves no partial
/// report. Returns the report.
Report RunSuite(const RunSettings& settings);

/// `run --references-only`: renders this shard's share of the references into the cache
/// (settings.ref_cache, required) and writes no report. The units are every reference the
/// run needs, in run order: one per rendered scene, one per frame of a moving scene in a
/// motion run (image-scene views need none). Entries already cached are skipped. Returns the
/// number rendered; `*cached` gets the number found in the cache.
int RenderReferencesOnly(const RunSettings& settings, int* cached = nullptr);

/// Facts for the report's context block (tool version, git commit, build type, library
/// versions, machine, threads).
std::vector<std::pair<std::string, std::string>> ContextFacts();

}  // namespace aalab
