/// The first stage of `aalab run`: the run's scenes and methods resolved and every setting
/// checked before any work (harness/run/runner.cpp runs the stages in order). Also the small
/// pieces every stage shares: the progress line on stderr.
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/timer.h"
#include "harness/run/image_scene.h"
#include "harness/run/runner.h"
#include "methods/method.h"
#include "metrics/viewing.h"
#include "reports/result.h"

namespace aalab {

/// A run's scenes, loaded and checked against its settings before any work: the reference
/// samples, the frame count, the reference kind and each sequence's length.
struct RunScenes {
  std::vector<std::string> names;  ///< as given (a suite's, or --scenes)
  std::vector<SceneSource> sources;
  int grid = 0;
  bool exact = false;
};

/// Loads the scenes of `s` (its suite or --scenes) and checks --frames, --reference and the
/// sequence views' lengths; UserError naming the setting otherwise.
RunScenes LoadRunScenes(const RunSettings& s);

/// Everything a run does, resolved: this shard's scenes, the methods (the default list
/// without the methods with memory on a still run), the user's supplied outputs, the viewing
/// condition.
struct RunPlan {
  RunScenes scenes;                ///< sources: this shard's share, in run order
  std::optional<ShardInfo> shard;  ///< set for --shard K/N
  ViewingCondition viewing;
  std::vector<std::string> method_specs;  ///< as the report's settings list them
  std::vector<MethodPlan> methods;
  std::vector<std::string> supplied;  ///< image scenes' outputs: rows after the methods
  int frames = 1;                     ///< --frames

  /// A sequence view runs its own frames (all of them, or the first --frames); everything
  /// else runs --frames.
  int FramesOf(const SceneSource& src) const { return src.Frames() > 1 && frames == 1 ? src.Frames() : frames; }
  /// The rows of one frame: the methods, then the supplied outputs.
  size_t RowsPerFrame() const { return methods.size() + supplied.size(); }
  /// Progress steps of the whole run: per frame, the reference and each row.
  int TotalSteps() const;
};

/// The resolve stage: checks every setting of `s` (UserError naming the first wrong one,
/// in the order the run has always checked them) and resolves what the run will do.
RunPlan ResolveRun(const RunSettings& s);

/// The files the run reads (scene files, manifests, every file the scenes were built from,
/// the reference cache): the output folder may neither be nor contain one of them. Call after
/// ResolveRun (which reads them).
std::vector<std::string> RunInputs(const RunSettings& s);

/// The report's settings block: what applied (--size, --ref-spp and --seed apply to rendered
/// scenes only; an image-scene view has its images' size and the user's reference).
std::vector<std::pair<std::string, std::string>> RunReportSettings(const RunSettings& s, const RunPlan& plan);

/// Progress with ETA on stderr.
class Progress {
 public:
  Progress(int total, bool quiet) : total_(total), quiet_(quiet) {}
  void Step(const std::string& what);

 private:
  int total_;
  int done_ = 0;
  bool quiet_;
  Stopwatch clock_;
};

}  // namespace aalab
