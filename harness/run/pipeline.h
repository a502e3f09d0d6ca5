/// The per-scene pipeline shared by `run` and `sweep`: a scene is prepared once (BVH,
/// reference, the shared 1x frame) and any number of methods then run against it.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "harness/run/reference_cache.h"
#include "harness/run/stage_clock.h"
#include "methods/method.h"
#include "metrics/flip.h"
#include "metrics/metric.h"
#include "metrics/ssim.h"
#include "reports/result.h"
#include "scenes/render.h"
#include "scenes/scene.h"
#include "scenes/tracer.h"

namespace aalab {

/// A frame anti-aliased by the user's own pipeline (an engine's TAA, DLSS, FSR...), given
/// under the user's name: a row of the report beside aalab's methods, supplied, not run.
struct SuppliedFrame {
  std::string name;          ///< lowercase-kebab, never one of aalab's method names
  std::string file;          ///< as the manifest names it (this frame's file)
  Image8 frame;              ///< RGBA8, alpha 255
  std::optional<double> ms;  ///< the user's measured time per frame, when given
};

/// A scene ready for methods. Everything here is computed once per scene.
struct PreparedScene {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<Tracer> tracer;
  Reference ref;
  Image8 frame1x;            ///< the 1x centre-sample frame (the `none` output)
  ImageF none_f;             ///< frame1x as float RGB
  TraceCounters counters1x;  ///< cost of frame1x
  Timing render1x;           ///< timing of frame1x over the repeats
  SceneResult info;          ///< what the report says about the scene (images filled by the caller)
  /// The reference's half of LDR-FLIP, computed once and shared by every method's score.
  std::shared_ptr<const flip::ReferenceSide> flip_reference;
  double flip_ppd = kFlipDefaultPpd;  ///< the viewing condition's pixels per degree FLIP uses
  /// The reference's half of SSIM (its window means), computed once per scene.
  std::shared_ptr<const SsimReferenceSide> ssim_reference;
  /// Isolated flat disks for the area-bias metrics (empty for scenes that are not flat).
  std::vector<CoverageProbe> coverage_probes;
  /// The sequence this frame belongs to: the scene with its animation (for motion vectors)
  /// and the frame's index. A still run: the scene itself, frame 0.
  std::shared_ptr<const Scene> sequence_scene;
  int frame = 0;
  /// Scores already computed on this scene, by output hash: a method whose output is
  /// bit-identical to an earlier method's (e.g. SSAA on a texel-aligned texture) gets the same
  /// metrics and FLIP map without computing them again. Filled by RunMethod (not thread-safe:
  /// methods of one scene run one after another).
  struct Scored {
    std::vector<MetricResult> metrics;
    std::vector<uint8_t> flip_grey;
  };
  mutable std::map<std::string, Scored> scored_by_hash;
  /// Image-scene views only: the user's own AA outputs of this frame; whether motion vectors
  /// and jitter were given (the 1x frame is then the jittered TAA input) and, from frame 1
  /// on, TAA's previous positions derived from them (TemporalInput::previous).
  std::vector<SuppliedFrame> supplied;
  bool captured_motion = false;
  std::vector<float> captured_previous;
  FrameJitter captured_jitter;  ///< the captured frame's jitter (TemporalInput::jitter)
};

/// Loads and validates scenes by name or path; duplicates are an error.
std::vector<std::unique_ptr<Scene>> LoadScenes(const std::vector<std::string>& names);

/// Resolves method specs; duplicates (same canonical spec) are an error.
std::vector<MethodPlan> ResolveMethods(const std::vector<std::string>& specs);

/// Builds the BVH, renders the reference (grid × grid spp, or the closed-form exact reference
/// when `exact_reference`: scenes/exact_reference.h) and the timed 1x frame, computes the
/// noise floor (null for the exact reference) and the crop windows. With a `clock`, charges
/// the BVH and the reference to "references" and the 1x frame (warm-up and timed repeats) to
/// "method_renders_filters". With a `cache`, the reference is read from it when present and
/// stored in it when rendered (harness/run/reference_cache.h); `info.reference_ms` is then the
/// time the render took when the entry was made, and `ref.half_a`/`half_b` are empty (the
/// noise floor comes from the halves' stored MSE). `flip_ppd`: the viewing condition's pixels
/// per degree for FLIP (metrics/viewing.h).
std::unique_ptr<PreparedScene> PrepareScene(std::unique_ptr<Scene> scene, int width, int height, int grid,
                                            uint64_t seed, int repeat, bool exact_reference = false,
                                            StageClock* clock = nullptr, const ReferenceCache* cache = nullptr,
                                            double flip_ppd = kFlipDefaultPpd);

/// Checks the --reference choice ("sampled" or "exact") and, for "exact", that every scene
/// qualifies; throws UserError naming the scene and the disqualifying field. Returns true for
/// "exact".
bool CheckReferenceKind(const std::string& kind, const std::vector<const Scene*>& scenes);

/// What one method produced on a prepared scene.
struct MethodOutput {
  ResultRow row;  ///< metrics, timing, cost and hash filled; `images` left to the caller
  Image8 input;   ///< the frame the post filter saw (for debug views); empty without a post filter
  Image8 output;  ///< the final frame at the output size
  /// The LDR-FLIP map quantised to 8 bits, round(255 · value), width × height bytes: the page
  /// colours it (magma, 0 → 1). The absolute-error heatmap is drawn by the page from the
  /// output and reference PNGs (|output − reference|, mean over RGB, full scale
  /// kErrorHeatmapMax), so it is not stored.
  std::vector<uint8_t> flip_grey;
};

/// Renders (or reuses the 1x frame), post-filters and rescales as the plan says, timing each
/// stage (one warm-up + `repeat` runs), and scores the output against the reference.
/// A method with memory (plan.make_state) carries `*state` from frame to frame: RunMethod
/// creates it when empty and advances it by one frame; state == nullptr runs a fresh
/// sequence of one frame. Jittered renders (plan.render.jitter) use the prepared frame's
/// index for the jitter and, from frame 1 on, pass exact motion vectors to the state. With
/// `run.clock`, charges rendering and filtering to "method_renders_filters" and scoring to
/// "metrics". `run.sampler` goes to the post filter (PostOptions::sampler) and the rescale.
/// Scores `frame` (the output size) against the prepared scene: every metric and the 8-bit
/// FLIP map, reusing the scores of a bit-identical earlier output; fills out->row.metrics,
/// output_hash, out->flip_grey and moves the frame into out->output.
void ScoreOutput(const PreparedScene& prepared, Image8 frame, MethodOutput* out, StageClock* clock = nullptr);
/// The scores of `frame` (the output size) against the prepared scene: every metric and the
/// 8-bit FLIP map, computed anew (no reuse, nothing stored): safe to call concurrently.
PreparedScene::Scored ScoreFrame(const PreparedScene& prepared, const Image8& frame);

/// What every method of a run shares: how it is rendered, timed, filtered and charged.
struct MethodRunSettings {
  uint64_t seed = 1;  ///< the renderer's sample seed (RenderFrame)
  int repeat = 1;     ///< timed runs after one warm-up (TimeRepeats)
  /// The post filter's texel and bilinear arithmetic (PostOptions::sampler) and the rescale's.
  SamplerArithmetic sampler = SamplerArithmetic::kGl;
  StageClock* clock = nullptr;  ///< charges the stages when set
};

/// `score` false: the row is rendered, filtered and timed but neither hashed nor scored:
/// out.output holds the frame; row.output_hash, row.metrics and flip_grey stay empty (for
/// harness/run/score_rows.h, which hashes and scores a frame's rows together after its timed
/// renders).
MethodOutput RunMethod(const PreparedScene& prepared, const MethodPlan& plan, const MethodRunSettings& run,
                       std::unique_ptr<TemporalState>* state = nullptr, bool score = true);

/// True when the plan needs nothing but the 1x frame: `none` and the post-only methods
/// (MethodPlan::IsPostOnly), and on a view with motion vectors and jitter (`has_motion`) the
/// jittered 1x methods (TAA). Everything else needs the renderer.
bool RunsOnImageScenes(const MethodPlan& plan, bool has_motion = false);

/// The row of a method that cannot run on an image-scene view: every metric null with the
/// reason, no timings (empty), no images, `not_applicable` set.
ResultRow NotApplicableRow(const PreparedScene& prepared, const MethodPlan& plan);

/// Runs `body` once untimed, then `repeat` times timed (wall clock).
Timing TimeRepeats(int repeat, const std::function<void()>& body);

}  // namespace aalab
