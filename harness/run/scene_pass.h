/// The per-scene stage of `aalab run`: one scene's frames prepared (reference, BVH, 1x frame),
/// every method and supplied output run and scored on each frame, the frames' rows folded
/// into the report and the scene's images written. The run's modes are small strategies
/// chosen once per scene, not branches in the frame loop:
///  - where frames come from (FrameSource): a still scene (prepared once), a moving scene
///    (built and referenced anew at every frame), a captured sequence (an image-scene view
///    with N frames, read anew at every frame);
///  - what a row is (RowSource): one of aalab's methods (run) or the user's supplied output
///    (scored, not run);
///  - which files a frame writes (SceneImages): the sequence's per-frame PNGs, the
///    display-linear EXR references of --frame-exr, the last frame's images written in
///    parallel at the scene's end (a bit-identical output stored once).
#pragma once
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "harness/run/pipeline.h"
#include "harness/run/reference_cache.h"
#include "harness/run/run_plan.h"
#include "harness/run/score_rows.h"
#include "harness/run/stage_clock.h"
#include "reports/result.h"

namespace aalab {

/// What every scene of a run shares: the settings, the resolved plan, the temporary output
/// folder, the clock, the reference cache (null: none) and the progress line.
struct ScenePass {
  const RunSettings& settings;
  const RunPlan& plan;
  std::filesystem::path tmp;
  StageClock* clock;
  const ReferenceCache* cache;
  Progress* progress;
};

/// One frame's rows, in the run's row order (the methods, then the supplied outputs), each
/// run and scored against the prepared frame: the methods rendered and timed one after
/// another, then their outputs scored concurrently (harness/run/score_rows.h). `states`: the
/// methods' sequence states (one per method, carried from frame to frame); `last_frame`: the
/// rows keep the post filter's input for --debug-views only there. `beside`: untimed jobs
/// run side by side with the scores (RunAndScoreRows; the scene's image writes).
std::vector<std::shared_ptr<MethodOutput>> ScoreFrameRows(const ScenePass& pass, const PreparedScene& prepared,
                                                          std::vector<std::unique_ptr<TemporalState>>* states,
                                                          const std::string& step_prefix, bool last_frame,
                                                          const BesideJobs& beside = nullptr);

/// Runs one scene (all its frames) and returns what the report says about it; its rows are
/// appended to `rows`. Consumes source.scene.
SceneResult RunScene(const ScenePass& pass, SceneSource& source, std::vector<ResultRow>* rows);

}  // namespace aalab
