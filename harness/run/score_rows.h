/// A frame's method rows, rendered and timed one after another, then scored together: the
/// metrics of different rows run concurrently once the frame's last timed render is done.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "harness/run/pipeline.h"
#include "harness/run/stage_clock.h"
#include "methods/method.h"

namespace aalab {

/// Runs plans[m] on the prepared frame for every m in order (RunMethod without scoring: each
/// timed render and filter has the machine to itself, as before), then hashes every output
/// (the rows in parallel) and scores the outputs:
/// each distinct output (by hash) not yet scored on this scene is scored once (ScoreFrame),
/// the distinct outputs concurrently, and the scores are stored in prepared.scored_by_hash.
/// Every row then equals RunMethod's scored row bit for bit, at any thread count (each score
/// is a pure function of its output; no score depends on another). `states[m]`: plan m's
/// sequence state (RunMethod); `keep_inputs` false drops each row's `input` (the frame the
/// post filter saw, needed only for debug views) before scoring. At most one score per thread
/// is in flight (each is isolated: its waits take no other row's score). With a `clock`, rendering
/// and filtering are charged to "method_renders_filters", hashing and scoring to "metrics".
/// `beside` (optional) is called once the rows are hashed, before the scores: the untimed
/// jobs it returns (the scene's image writes that need no score: harness/run/scene_pass.cpp)
/// run side by side with the scores in one parallel loop, each isolated as the scores are,
/// so that one job's serial parts overlap another's parallel loops; they are charged to
/// "metrics" with the scores. A job must not touch the rows' metrics or FLIP maps.
/// Returns one output per plan, in plan order (a row not applicable to the scene: its row,
/// no images).
using BesideJobs =
    std::function<std::vector<std::function<void()>>(const std::vector<std::shared_ptr<MethodOutput>>& rows)>;
std::vector<std::shared_ptr<MethodOutput>> RunAndScoreRows(const PreparedScene& prepared,
                                                           const std::vector<MethodPlan>& plans,
                                                           const MethodRunSettings& run,
                                                           std::vector<std::unique_ptr<TemporalState>>* states,
                                                           bool keep_inputs, const BesideJobs& beside = nullptr);

}  // namespace aalab
