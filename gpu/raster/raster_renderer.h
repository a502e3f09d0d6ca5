/// The raster path's renderer (docs/gpu.md "The raster path"): draws a RasterScene
/// (core/raster_geometry.h) with OpenGL 4.5 into a target of a method's size and sample count
/// and turns it into the 8-bit frame aalab would write, in three timed stages:
///   draw    clear + one draw call: the forward pass (the tracer's unlit / lambert shading,
///           or its glTF metallic-roughness shading with the tracer's texture footprint and
///           filter, and the display transform per fragment) into an RGBA16F (or RGBA32F) target of
///           1, 2, 4, 8 or 16 samples, or k·W × k·H for SSAA, with a 32-bit float depth buffer
///   resolve MSAA: box average of the samples (a shader of texelFetch, or glBlitFramebuffer);
///           SSAA: box average of each k × k block; none for 1× and TAA's jittered frame
///   encode  sRGB encode and rounding to 8 bits (a fragment pass into an RGBA8 target)
/// Needs a current context (egl_context.h). Errors are std::runtime_error with the GL's words.
#pragma once
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/raster_geometry.h"

namespace aalab::raster {

/// What the GL cannot do for a method (too many samples, too large a target).
struct CapabilityError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A render-time method as the raster path draws it; `name` is aalab's method spec.
///   kOne    one sample at each pixel centre (`none`; also `aaa`, whose triangles aalab
///           renders as `none` does: methods/aaa.cpp)
///   kScale  the render of a render-scale method: one sample at each pixel centre of a
///           round(scale·W) × round(scale·H) target (`scale43`: aalab's render_scale size;
///           its rescale and any post filter are not drawn here)
struct RasterMethod {
  enum class Kind { kOne, kMsaa, kSsaa, kTaa, kScale };
  std::string name;
  Kind kind = Kind::kOne;
  bool analytic = false;  ///< `aaa`: drawn as kOne only where the scene has no analytic shape
  double scale = 1.0;     ///< kScale: the render scale (scale43: 4/3, methods/render_scale.cpp)
  int samples = 1;        ///< MSAA: samples per pixel
  int grid = 1;           ///< SSAA: k of the k × k ordered grid
  int taa_frame = 1;      ///< TAA: which frame's jitter (taa's Halton(2,3) over 16 points)
  float jx = 0, jy = 0;   ///< TAA: the sample's offset from the pixel centre, px, y down
};

/// none, aaa, msaa-2x/4x/8x/16x, ssaa-2x2/4x4, scale43, taa (frame 1's jitter) or taa@N
/// (frame N's); false with *why naming what is allowed.
bool ParseRasterMethod(const std::string& spec, RasterMethod* out, std::string* why);

/// Why `method` cannot be drawn on `scene` ("" when it can): `aaa` on a scene with analytic
/// disks, whose edge coverage aalab computes from the disk's distance (scenes/analytic.cpp),
/// which the raster path has no form of (it draws the disk's impostor with a hard edge).
std::string RasterMethodRefusal(const RasterMethod& method, const RasterScene& scene);

/// The size of the frame `method` draws for an output of w × h: w × h, except kScale's
/// max(1, lround(scale·w)) × max(1, lround(scale·h)) (harness/run's render size).
void RasterFrameSize(const RasterMethod& method, int w, int h, int* fw, int* fh);

/// The colour target's format: half floats (what a forward renderer typically uses) or floats.
enum class TargetFormat { kRgba16f, kRgba32f };
/// How MSAA's samples become a pixel: a box-average shader (defined) or glBlitFramebuffer
/// (the driver's resolve: a box average on the hardware we know, but not specified).
enum class ResolveKind { kShader, kBlit };

/// GPU time of each stage of one frame, from GL_TIME_ELAPSED queries, in milliseconds.
struct StageTimes {
  double draw = 0, resolve = 0, encode = 0;
  double Total() const { return draw + resolve + encode; }
};

/// A frame time that cannot be trusted, refused rather than reported: a query without a
/// result, no time (0 ns) for a stage that did work, an implausible time, or a GL error while
/// timing. `context_lost` when glGetGraphicsResetStatus reports a reset (nothing after it
/// can be timed on this context).
struct TimingError : std::runtime_error {
  TimingError(const std::string& why, bool lost) : std::runtime_error(why), context_lost(lost) {}
  bool context_lost = false;
};

/// How many frames to time per scene, size and method. With `budget_ms` > 0 the counts
/// adapt to the frame's cost, measured by one probe frame (timed and checked like the
/// others): repeat = clamp(⌊budget_ms / probe⌋, min(min_repeat, repeat), repeat) and
/// warmup = clamp(⌊budget_ms / 2 / probe⌋, min(1, warmup), warmup), so the timed frames take
/// about budget_ms of GPU time and the warm-up at most half of that, unless min_repeat
/// frames alone take longer. budget_ms = 0: exactly `warmup` and `repeat` frames.
struct TimingPlan {
  int warmup = 50, repeat = 100, min_repeat = 5;
  double budget_ms = 0;
  /// Tests of the refusal path only: the stage (0 draw, 1 resolve, 2 encode) whose results
  /// are taken as 0 ns, as a driver that returned none would give (−1: none).
  int zero_stage = -1;
};
/// The frame counts `plan` gives for a probe frame of `probe_ms` (the rule above; pure).
struct FrameCounts {
  int warmup = 0, repeat = 0;
};
FrameCounts PlanFrames(const TimingPlan& plan, double probe_ms);

/// One frame's three GL_TIME_ELAPSED results (ns) and whether each was available → its
/// StageTimes, or TimingError naming the stage: unavailable, 0 ns for draw or encode (or for
/// resolve when `has_resolve`), or over 100 s. Without a resolve its time is reported as 0.
StageTimes CheckedStageTimes(const uint64_t ns[3], const bool available[3], bool has_resolve);

/// What TimeFrames measured: the timed frames and how many untimed ones went before them.
struct TimedFrames {
  std::vector<StageTimes> frames;
  int warmup = 0;
  double probe_ms = 0;  ///< the probe frame's total (0 without a budget)
};

class RasterRenderer {
 public:
  /// Compiles the programs and uploads the scene's triangles.
  explicit RasterRenderer(const RasterScene& scene);
  ~RasterRenderer();
  RasterRenderer(const RasterRenderer&) = delete;
  RasterRenderer& operator=(const RasterRenderer&) = delete;

  /// Allocates the targets of `method` for an output of w × h (CapabilityError when the GL
  /// cannot: more samples than GL_MAX_SAMPLES, a target past GL_MAX_TEXTURE_SIZE).
  void Configure(const RasterMethod& method, int w, int h, TargetFormat format, ResolveKind resolve);
  /// Draws, resolves and encodes one frame (untimed).
  void RenderFrame();
  /// The plan's warm-up frames, then its timed ones; the stage times of each timed frame.
  /// Every frame (warm-up included) runs inside its own three queries, at most 3 frames in
  /// flight: a frame's results are read, checked (CheckedStageTimes, glGetGraphicsResetStatus,
  /// glGetError) and its queries reused only after that. Throws TimingError.
  TimedFrames TimeFrames(const TimingPlan& plan);
  /// The encoded frame, fw·fh·3 bytes (RasterFrameSize), top row first (after RenderFrame).
  std::vector<uint8_t> ReadRgb8() const;
  /// MSAA coverage, sample for sample: draws the scene's shape indices into an R32UI target
  /// of the method's sample count (same depth test) and returns w·h·samples values, pixel
  /// by pixel (top row first) and sample index within, of the shape seen (−1: background).
  std::vector<int32_t> SampleShapes();
  /// glGetMultisamplefv's sample positions of the configured MSAA target: 2 floats per
  /// sample in [0, 1], x then y, in window coordinates (which the raster path flips so that
  /// y grows downward with the image's rows).
  std::vector<float> SamplePositions() const;
  /// The colour target's samples per pixel as allocated (GL_TEXTURE_SAMPLES): a GL may give
  /// more than asked (Mesa 22's llvmpipe gives 4 for 2); 1 without MSAA.
  int Samples() const;
  /// GL_SUBPIXEL_BITS: how finely the rasteriser snaps vertices (a test's tolerance).
  int SubpixelBits() const;

  struct Gl;  ///< the GL objects (raster_renderer.cpp)

 private:
  std::unique_ptr<Gl> gl_;
};

}  // namespace aalab::raster
