/// What an AA method is: how its frame is rendered, which post filter runs on the 8-bit
/// frame, and how the result is resampled to the output size. Pure data + pure functions:
/// methods do no I/O and read no clocks (the runner times the stages).
#pragma once
#include <any>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/params.h"
#include "core/render_spec.h"
#include "core/sampler.h"

namespace aalab {

/// Options that do not change a method's identity (debug views).
struct PostOptions {
  std::string debug_view;  ///< "" = normal output; otherwise a view the filter supports
  /// Arithmetic of every texel read and bilinear fetch (run-level `--sampler`): kGl (the
  /// default, llvmpipe's) or kGpuTexture (the H100 texture unit's, docs/gpu.md). Filters
  /// with a fast path run their reference implementation when it is not kGl.
  SamplerArithmetic sampler = SamplerArithmetic::kGl;
};

/// Counters a post filter reports.
struct PostStats {
  uint64_t taps = 0;  ///< texture fetches (bilinear or exact), summed over all pixels
};

/// A post filter: 8-bit RGBA frame in, 8-bit RGBA frame out, same size.
using PostFilter = std::function<Image8(const Image8& in, const PostOptions& options, PostStats* stats)>;

/// One frame's inputs to a method with memory (TAA), all data: the frame as rendered (with
/// the frame's jitter) and, from the second frame on, where each pixel's centre was in the
/// previous frame (exact motion vectors computed by the runner from the known motion).
struct TemporalInput {
  const Image8* frame = nullptr;
  /// Per pixel, row-major, x then y: the previous frame's continuous pixel position of this
  /// pixel's centre (centres at +0.5); NaN where there is no history. Empty on frame 0.
  const std::vector<float>* previous = nullptr;
  int frame_index = 0;
  /// Per pixel of `frame`, row-major: the view depth of the surface its sample hit (distance
  /// along the camera's forward axis; +Inf for the background). nullptr when unknown (captured
  /// sequences without depth). `taa` ignores it; the production TAA dilates and tests
  /// disocclusion with it (methods/taa_production.cpp).
  const std::vector<float>* depth = nullptr;
  /// This frame's sub-pixel jitter (render pixels), the offset of `frame`'s samples from the
  /// pixel centres.
  FrameJitter jitter;
  /// The camera's vertical field of view at this frame (radians; 0 when unknown: captured
  /// sequences, orthographic cameras). FSR 2's depth clip reads it (methods/fsr2_methods.cpp).
  float fov_y_radians = 0.0f;
  /// The size the step must return (temporal upscaling renders `frame` smaller); 0 = the
  /// frame's own size.
  int output_width = 0, output_height = 0;
};

/// Per-sequence state of a temporal method. The runner creates one per (scene, method)
/// sequence from MethodPlan::make_state, feeds it the frames in order and drops it after.
class TemporalState {
 public:
  virtual ~TemporalState() = default;
  /// Consumes one frame and returns the method's output for it (same size, RGBA8).
  virtual Image8 Step(const TemporalInput& in, PostStats* stats) = 0;
  /// A copy (the runner times Step on copies, so warm-up and repeats never advance the sequence twice).
  virtual std::unique_ptr<TemporalState> Clone() const = 0;
};

using TemporalFactory = std::function<std::unique_ptr<TemporalState>()>;

/// How the rendered/post-filtered frame is brought back to the output size.
/// kEasu: AMD FSR 1's EASU upscaler (methods/fsr1.h).
enum class Rescale { kNone, kBilinear, kBicubic, kEasu };

/// A fully resolved method: everything the runner needs.
struct MethodPlan {
  std::string name;    ///< registry name ("fxaa311-p39")
  std::string spec;    ///< canonical spec: name plus overrides in definition order
  ParamValues params;  ///< every parameter, resolved
  RenderSpec render;
  PostFilter post;                       ///< empty when the method has no post filter
  std::vector<std::string> debug_views;  ///< views `post` supports ("" excluded)
  Rescale rescale = Rescale::kNone;
  /// A filter run on the output-size frame after the rescale (FSR 1's RCAS after EASU);
  /// empty for most methods. The runner times it with the rescale.
  PostFilter sharpen;
  /// Methods with memory (TAA): makes the per-sequence state; empty for memoryless methods.
  /// The state's Step replaces the post filter stage.
  TemporalFactory make_state;

  /// The family's typed parameters, built by the family's factory from `params`: for a post
  /// filter the struct its `post` runs with (Fxaa1Params, Fxaa311Params, SmaaParams; for
  /// scale43-fxaa-high its FXAA's); empty for families whose `render`, `rescale` and
  /// `params` say everything (TAA: its state is private to methods/taa.cpp). Read with Config<T>(), not by parsing
  /// `name`.
  std::any config;
  /// For a post filter with a separate production path: the plain reference implementation
  /// that `post` equals bit for bit (same output, same taps); empty otherwise.
  PostFilter post_reference;

  // Properties of the registry row (MethodEntry), copied by MakeMethod.
  std::string family;            ///< the family's name ("fxaa311"), as `aalab list methods` groups it
  bool in_default_list = false;  ///< one of the methods `aalab run` compares when --methods is not given
  bool has_gpu_twin = false;     ///< the GPU tool (gpu/) has CUDA kernels for it

  /// The typed configuration when it is a T, else nullptr.
  template <class T>
  const T* Config() const {
    return std::any_cast<T>(&config);
  }
  /// True when the method works on a finished 1x frame alone (usable by `aalab apply`).
  bool IsPostOnly() const { return post && render.IsPlain1x() && rescale == Rescale::kNone; }
  /// True for methods with memory (TAA): they need a sequence, and a still run's default list leaves them out.
  bool NeedsHistory() const { return static_cast<bool>(make_state); }
  /// True when the method changes nothing: a plain 1x render, no post filter, no state, no rescale (`none`).
  bool IsIdentity() const {
    return !post && !sharpen && !make_state && render.IsPlain1x() && rescale == Rescale::kNone;
  }
};

/// One registry row: name, one-line help, parameter table and a factory.
struct MethodEntry {
  std::string name;
  std::string help;
  std::vector<ParamDef> params;
  std::function<MethodPlan(const ParamValues&)> make;
  /// Where the method comes from: BibTeX keys of reports/export_bibliography.cpp, comma
  /// separated ("" = defined here, nothing to cite). Set once per family in registry.cpp.
  std::string source = "";
  /// The family's name: set once per family in registry.cpp.
  std::string family = "";
  /// In the default list (`aalab run` without --methods, in registry order): set by the family file.
  bool in_default_list = false;
  /// Has a CUDA twin in the GPU tool: set once per family in registry.cpp.
  bool has_gpu_twin = false;
};

}  // namespace aalab
