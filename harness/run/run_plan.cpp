#include "harness/run/run_plan.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/input_files.h"
#include "core/params.h"
#include "core/parallel.h"
#include "harness/run/pipeline.h"
#include "harness/run/sequence.h"
#include "methods/registry.h"
#include "scenes/library.h"
#include "scenes/motion.h"

namespace aalab {
namespace fs = std::filesystem;

RunScenes LoadRunScenes(const RunSettings& s) {
  RunScenes r;
  r.grid = ReferenceGridForSpp(s.ref_spp);
  r.names = s.scenes.empty() ? SuiteScenes(s.suite) : s.scenes;
  if (s.frames < 1 || s.frames > kMaxFrames) {
    throw UserError("--frames " + std::to_string(s.frames) + " is out of range (1.." + std::to_string(kMaxFrames) +
                    ")");
  }
  r.sources = LoadSceneSources(r.names);
  r.exact = CheckReferenceKind(s.reference, r.sources);
  for (const auto& src : r.sources) {
    if (src.scene) CheckSequenceLength(*src.scene, s.frames);
    if (src.view && src.view->frames > 1 && s.frames > src.view->frames) {
      throw UserError("--frames " + std::to_string(s.frames) + " runs past the sequence of view '" + src.Name() +
                      "' of image scene '" + src.view->manifest + "', which has " + std::to_string(src.view->frames) +
                      " frames (allowed: 1.." + std::to_string(src.view->frames) +
                      "; without --frames a sequence view runs all its frames)");
    }
  }
  return r;
}

namespace {

/// A shard keeps its share of the scenes (whole sequences: a method's memory and the
/// temporal metrics chain a sequence's frames); the settings still describe the whole run.
std::optional<ShardInfo> KeepShardShare(const ShardSpec& shard, std::vector<SceneSource>* scenes) {
  if (!shard.Active()) return std::nullopt;
  ShardInfo info{shard.index, shard.count, "scene", static_cast<int>(scenes->size()), {}};
  std::vector<SceneSource> mine;
  for (size_t i : ShardShare(scenes->size(), shard)) {
    info.units.push_back((*scenes)[i].Name());
    mine.push_back(std::move((*scenes)[i]));
  }
  *scenes = std::move(mine);
  return info;
}

/// The run's methods: --methods, `all`, or the default list. Methods with memory need a
/// sequence: a still run's default list leaves them out (a still run is unchanged by their
/// existence); name them with --methods to see frame 0.
void ResolveRunMethods(const RunSettings& s, bool any_sequence, RunPlan* plan) {
  const bool all = s.methods.size() == 1 && s.methods[0] == "all";
  plan->method_specs = s.methods.empty() ? DefaultMethods() : all ? MethodNames() : s.methods;
  plan->methods = ResolveMethods(plan->method_specs);
  if ((!s.methods.empty() && !all) || any_sequence) return;
  for (size_t i = plan->methods.size(); i-- > 0;) {
    if (!plan->methods[i].NeedsHistory()) continue;
    plan->methods.erase(plan->methods.begin() + static_cast<std::ptrdiff_t>(i));
    plan->method_specs.erase(plan->method_specs.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

}  // namespace

int RunPlan::TotalSteps() const {
  int total = 0;
  for (const auto& src : scenes.sources) total += static_cast<int>(RowsPerFrame() + 1) * FramesOf(src);
  return total;
}

RunPlan ResolveRun(const RunSettings& s) {
  if (s.repeat < 1 || s.repeat > 1000)
    throw UserError("--repeat " + std::to_string(s.repeat) + " is out of range (1..1000)");
  RunPlan plan;
  plan.frames = s.frames;
  plan.scenes = LoadRunScenes(s);
  if (s.frame_exr && s.frames < 2)
    throw UserError("--frame-exr writes each frame's reference of a motion run: it needs --frames N > 1");
  plan.viewing = ResolveViewing(s.viewing);
  plan.shard = KeepShardShare(s.shard, &plan.scenes.sources);
  bool any_sequence = false;
  for (const auto& src : plan.scenes.sources) any_sequence = any_sequence || plan.FramesOf(src) > 1;
  ResolveRunMethods(s, any_sequence, &plan);
  // The user's own AA outputs (image scenes' `outputs`): rows after aalab's methods.
  plan.supplied = SuppliedOutputNames(plan.scenes.sources);
  for (const auto& name : plan.supplied) {
    for (const auto& p : plan.methods) {
      if (p.spec == name)
        throw UserError("output '" + name + "' of an image scene has the name of a method of this run");
    }
  }
  return plan;
}

std::vector<std::string> RunInputs(const RunSettings& s) {
  std::vector<std::string> inputs = {s.ref_cache};
  for (const auto& name : s.scenes) {
    if (fs::exists(name)) inputs.push_back(name);  // a scene file or manifest (not a library name)
  }
  // Every file the scenes were built from: meshes, glTF buffers and textures, image-scene
  // frames and captures (core/input_files.h).
  for (const auto& file : InputFilesRead()) inputs.push_back(file);
  return inputs;
}

std::vector<std::pair<std::string, std::string>> RunReportSettings(const RunSettings& s, const RunPlan& plan) {
  bool any_rendered = false;
  std::vector<std::string> view_sizes;
  for (const auto& src : plan.scenes.sources) {
    if (src.scene) any_rendered = true;
    if (!src.view) continue;
    const std::string sz = std::to_string(src.view->width) + "x" + std::to_string(src.view->height);
    if (std::find(view_sizes.begin(), view_sizes.end(), sz) == view_sizes.end()) view_sizes.push_back(sz);
  }
  std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
  std::string ref_spp = plan.scenes.exact ? std::string("exact") : std::to_string(s.ref_spp);
  std::string seed = std::to_string(s.seed);
  if (!view_sizes.empty()) {
    const std::string views = JoinNames(view_sizes);
    size =
        any_rendered ? size + " (rendered scenes; image-scene views: " + views + ")" : views + " (the views' own size)";
    ref_spp = any_rendered ? ref_spp + " (rendered scenes; image-scene views: the user's own)" : "the user's own";
    if (!any_rendered) seed = "(not used: image scenes only)";
  }
  std::vector<std::pair<std::string, std::string>> out = {{"suite", s.scenes.empty() ? s.suite : "(custom)"},
                                                          {"scenes", JoinNames(plan.scenes.names)},
                                                          {"methods", JoinNames(plan.method_specs)},
                                                          {"size", size},
                                                          {"ref_spp", ref_spp},
                                                          {"seed", seed},
                                                          {"threads", std::to_string(ThreadCount())},
                                                          {"repeat", std::to_string(s.repeat)},
                                                          {"warmup", "1"},
                                                          {"debug_views", s.debug_views ? "true" : "false"}};
  if (s.frames > 1) out.emplace_back("frames", std::to_string(s.frames));
  if (s.frame_exr) out.emplace_back("frame_exr", "true");
  if (s.sampler != SamplerArithmetic::kGl) out.emplace_back("sampler", SamplerArithmeticName(s.sampler));
  for (auto& kv : plan.viewing.Settings()) out.push_back(std::move(kv));
  if (!plan.supplied.empty()) out.emplace_back("supplied", JoinNames(plan.supplied));
  return out;
}

void Progress::Step(const std::string& what) {
  ++done_;
  if (quiet_) return;
  const double elapsed = clock_.ElapsedMs() / 1000.0;
  const double eta = done_ > 0 ? elapsed / done_ * (total_ - done_) : 0.0;
  std::fprintf(stderr, "[%3d/%d] %-40s elapsed %6.1fs  eta %6.1fs\n", done_, total_, what.c_str(), elapsed, eta);
  std::fflush(stderr);
}

}  // namespace aalab
