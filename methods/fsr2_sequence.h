/// FSR 2.2.1's sequence driver: the context `api/ffx_fsr2.cpp` keeps between frames (the
/// ping-pong resources, the reset on the first frame, the luminance pyramid's state) and one
/// Dispatch that runs the six ported passes in the API's order (pyramid, reconstruct & dilate,
/// depth clip, lock, accumulate, RCAS when sharpening is on) with each frame's cbFSR2 from
/// Fsr2NextFrameConstants. The passes are pluggable (Fsr2Passes) so that the oracle runs the
/// original shaders through the very same driver (tests/oracle/fsr2_chain_oracle_test.cpp).
/// methods/fsr2_sequence.cpp documents every choice; docs/fsr2.md has the proof.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "methods/fsr2.h"
#include "methods/fsr2_pyramid.h"
#include "methods/fsr2_tables.h"
#include "methods/method.h"

namespace aalab {

/// The six passes the driver calls, one function each (the ported ones by default,
/// Fsr2PortedPasses; the oracle substitutes the original shaders run on lavapipe).
struct Fsr2Passes {
  std::function<void(const Fsr2Constants&, const Fsr2Options&, const Fsr2SpdDispatch&, const Fsr2Plane& color,
                     Fsr2PyramidState*)>
      pyramid;
  std::function<void(const Fsr2Constants&, const Fsr2Options&, const Fsr2Plane& color, const Fsr2Plane& depth,
                     const Fsr2Plane& motion, float exposure, Fsr2ReconstructOut*)>
      reconstruct;
  std::function<void(const Fsr2Constants&, const Fsr2Options&, const Fsr2DepthClipIn&, Fsr2DepthClipOut*)> depth_clip;
  std::function<void(const Fsr2Constants&, const Fsr2Options&, const Fsr2Plane& lock_luma, Fsr2Plane* new_locks,
                     std::vector<uint32_t>* prev_depth)>
      lock;
  std::function<void(const Fsr2Constants&, const Fsr2Options&, const Fsr2AccumulateIn&, Fsr2AccumulateOut*)> accumulate;
  std::function<std::vector<float>(const Fsr2Constants&, const Fsr2Plane& upscaled, float exposure, uint32_t con_x)>
      rcas;
};
/// The ported passes (methods/fsr2.h, methods/fsr2_pyramid.h).
Fsr2Passes Fsr2PortedPasses();

/// What the app hands one dispatch (FfxFsr2DispatchDescription): the jittered colour (rgba,
/// render size), the device depth (1 channel) and the motion vectors (2 channels, render size:
/// where the pixel's surface was in the previous frame minus where it is, in units that
/// `dispatch.motion_vector_scale` turns into render pixels), and the dispatch parameters.
struct Fsr2DispatchInput {
  const Fsr2Plane* color = nullptr;
  const Fsr2Plane* depth = nullptr;
  const Fsr2Plane* motion = nullptr;
  Fsr2DispatchParams dispatch;
  bool sharpen = false;    ///< enableSharpening: RCAS after accumulate
  float sharpness = 0.0f;  ///< [0, 1]
};

/// The context's resources that outlive a dispatch (the API's names in comments). Index [0] is
/// the API's `_1` resource, [1] its `_2`.
struct Fsr2Resources {
  Fsr2Plane lock_status[2];          ///< LOCK_STATUS_1/2 (display size, rg16f)
  Fsr2Plane internal_upscaled[2];    ///< INTERNAL_UPSCALED_COLOR_1/2 (display size, rgba16f)
  Fsr2Plane luma_history[2];         ///< LUMA_HISTORY_1/2 (display size, rgba8)
  Fsr2Plane dilated_motion[2];       ///< INTERNAL_DILATED_MOTION_VECTORS_1/2 (render size, rg16f)
  Fsr2Plane new_locks;               ///< NEW_LOCKS (display size, r8)
  std::vector<uint32_t> prev_depth;  ///< RECONSTRUCTED_PREVIOUS_NEAREST_DEPTH (render size, r32ui)
  Fsr2PyramidState pyramid;          ///< the luma mips, AUTO_EXPOSURE, SPD's atomic counter
};

/// What one dispatch returns: the display-size output (rgb floats, 3 per pixel: RCAS's when
/// sharpening, else accumulate's), and what the frame decided (for tests).
struct Fsr2DispatchResult {
  std::vector<float> output;
  Fsr2FrameSetup setup;
  Fsr2Constants constants;
  float exposure = 0.0f;  ///< the exposure texel the passes read (0: the API's default, read as 1)
};

/// An FSR 2 context (ffxFsr2ContextCreate + ffxFsr2ContextDispatch) over whole planes.
class Fsr2Context {
 public:
  /// `ctx`: sizes and flags (max render size = the render size of every dispatch: aalab does
  /// not change resolution within a sequence); `auto_exposure`: FFX_FSR2_ENABLE_AUTO_EXPOSURE
  /// (off: the API's default exposure texture, 0, which the passes read as 1). `options`'
  /// inverted_depth must agree with ctx.inverted_depth. Throws std::invalid_argument for sizes ≤ 0.
  Fsr2Context(const Fsr2ContextParams& ctx, const Fsr2Options& options, bool auto_exposure,
              Fsr2Passes passes = Fsr2PortedPasses());
  /// One frame. Throws std::invalid_argument when the planes are not render size with 4, 1 and
  /// 2 channels.
  Fsr2DispatchResult Dispatch(const Fsr2DispatchInput& in);
  const Fsr2Resources& Resources() const { return res_; }
  const Fsr2ContextState& State() const { return state_; }

 private:
  Fsr2ContextParams ctx_;
  Fsr2Options options_;
  bool auto_exposure_;
  Fsr2Passes passes_;
  Fsr2ContextState state_;
  Fsr2Resources res_;
  Fsr2Plane lanczos_lut_;
};

// ---- aalab's frames as FSR 2's inputs (methods/fsr2_methods.cpp; the doc block there says why)

/// The RGBA8 sRGB frame as FSR 2's colour input: each channel sRGB-decoded to linear [0, 1]
/// (SrgbDecode8), alpha 1.
Fsr2Plane Fsr2ColorFromSrgb8(const Image8& frame);
/// aalab's view depth (+Inf: background) as inverted infinite device depth near / z (0 for the
/// background); all 0 (the far plane) when `depth` is null.
Fsr2Plane Fsr2DeviceDepth(const std::vector<float>* depth, int w, int h, float near_plane);
/// The near plane the sequence uses: half the nearest finite depth of the reset frame (1 when
/// it has none), so that every device depth of the sequence stays a normal half float.
float Fsr2NearPlane(const std::vector<float>* depth);
/// aalab's previous positions as FSR 2 motion vectors in render pixels: previous − pixel
/// centre (x + 0.5, y + 0.5); 0 on frame 0 (`previous` null); a vector twice the render size
/// off screen where `previous` is NaN (no history: FSR 2 then treats the pixel as new).
Fsr2Plane Fsr2MotionFromPrevious(const std::vector<float>* previous, int w, int h);
/// FSR 2's jitter (the image's shift, ffx_fsr2_upsample.h: a sample of pixel i lies at
/// unjittered i + 0.5 − jitter) of aalab's FrameJitter (the sample's offset from the pixel
/// centre): its negative, on both axes.
Fsr2Jitter Fsr2JitterFromFrame(const FrameJitter& j);

/// The per-sequence parameters of an `fsr2-*` row.
struct Fsr2MethodParams {
  double ratio = 1.5;  ///< display / render size
  bool sharpen = true;
  float sharpness = 0.8f;
  bool auto_exposure = true;
};
/// The temporal state of an `fsr2-*` row (an Fsr2Context created on its first frame).
std::unique_ptr<TemporalState> MakeFsr2State(const Fsr2MethodParams& p);
/// The Halton phase count of a mode: Fsr2JitterPhaseCount at the mode's nominal sizes
/// (display 3840, render int(3840 / ratio), as ffxFsr2GetRenderResolutionFromQualityMode):
/// 18, 23, 32, 72, 8 for 1.5, 1.7, 2, 3, 1.
int Fsr2ModePhaseCount(double ratio);

}  // namespace aalab
