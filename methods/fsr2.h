/// AMD FidelityFX Super Resolution 2 (FSR 2.2.1, the GLSL shaders of its Vulkan backend) ported
/// pass by pass in the shaders' 32-bit float path (FFX_HALF=0): each function computes what one
/// compute pass writes, texel for texel, with the pass's stores rounded to the formats the
/// shaders declare for them (r16f, rg16f, ...). docs/fsr2.md says which passes are ported and
/// how each is proven against the original shader (tests/oracle/fsr2_oracle_test.cpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace aalab {

/// FSR2's constant buffer cbFSR2 (ffx_fsr2_callbacks_glsl.h), field for field, in its std140
/// layout (so the oracle can upload it as is: 31 4-byte words, 124 bytes).
struct Fsr2Constants {
  int32_t render_size[2] = {0, 0};
  int32_t max_render_size[2] = {0, 0};
  int32_t display_size[2] = {0, 0};
  int32_t input_color_size[2] = {0, 0};
  int32_t luma_mip_size[2] = {0, 0};
  int32_t luma_mip_level = 0;
  int32_t frame_index = 0;
  float device_to_view_depth[4] = {0, 0, 0, 0};
  float jitter[2] = {0, 0};
  float motion_vector_scale[2] = {0, 0};
  float downscale_factor[2] = {0, 0};
  float motion_vector_jitter_cancellation[2] = {0, 0};
  float pre_exposure = 1.0f;
  float previous_pre_exposure = 1.0f;
  float tan_half_fov = 0.0f;
  float jitter_sequence_length = 0.0f;
  float delta_time = 0.0f;
  float dynamic_res_change_factor = 0.0f;
  float view_space_to_meters = 1.0f;
};

/// The transcendental builtins a GPU evaluates its own way (exp2, log2, sin: each driver has
/// its own approximation, a few float ulps from the correctly rounded value).
struct Fsr2Math {
  virtual ~Fsr2Math() = default;
  virtual float Exp2(float x) const = 0;
  virtual float Log2(float x) const = 0;
  virtual float Sin(float x) const = 0;
};

/// The shaders' compile-time options (FFX_FSR2_OPTION_*).
struct Fsr2Options {
  bool hdr_color_input = false;        ///< HDR_COLOR_INPUT
  bool low_res_motion_vectors = true;  ///< LOW_RESOLUTION_MOTION_VECTORS (aalab's are at render size)
  bool jittered_motion_vectors = false;
  bool inverted_depth = false;  ///< INVERTED_DEPTH (1 = near, 0 = far)
  /// How a store into a 16-bit float image rounds (Vulkan leaves it to the implementation:
  /// round to nearest even or toward zero). false: nearest even (what D3D requires of GPUs and
  /// aalab's default); true: toward zero, as Mesa's lavapipe stores (the oracle's setting).
  bool half_toward_zero = false;
  /// REPROJECT_USE_LANCZOS_TYPE: false (0) the history is reprojected with the reference
  /// Lanczos 2 (sin); true (1) with the Lanczos look-up table (Fsr2AccumulateIn::lanczos_lut).
  /// FSR2's backends build both and pick the table on GPUs whose wave size is 32 to 64.
  bool reproject_lanczos_lut = false;
  /// APPLY_SHARPENING: accumulate then leaves the output to RCAS (no upscaled output).
  bool apply_sharpening = false;
  /// The accumulate pass's exp2 / log2 / sin (pow and exp go through them as Mesa lowers
  /// them); null: the C library's. Not owned.
  const Fsr2Math* math = nullptr;
};

/// A float image of `c` channels, row-major, texel (x, y) channel k at v[(y·w + x)·c + k].
struct Fsr2Plane {
  int w = 0, h = 0, c = 1;
  std::vector<float> v;
  Fsr2Plane() = default;
  Fsr2Plane(int width, int height, int channels)
      : w(width),
        h(height),
        c(channels),
        v(static_cast<size_t>(width) * static_cast<size_t>(height) * static_cast<size_t>(channels)) {}
  /// texelFetch: the texel, or 0 outside the image (robust image access).
  float Fetch(int x, int y, int k) const;
  size_t Index(int x, int y, int k) const {
    return (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * static_cast<size_t>(c) +
           static_cast<size_t>(k);
  }
  float& At(int x, int y, int k) { return v[Index(x, y, k)]; }
  float At(int x, int y, int k) const { return v[Index(x, y, k)]; }
};

/// `f` as IEEE binary16 bits: what a store to an r16f / rg16f / rgba16f image writes. Round to
/// nearest even (overflow to infinity), or toward zero (overflow to ±65504); NaN stays NaN.
uint16_t Fsr2HalfBits(float f, bool toward_zero = false);
/// The float value of binary16 bits `h` (exact).
float Fsr2HalfToFloat(uint16_t h);
/// `f` rounded to binary16 and back: Fsr2HalfToFloat(Fsr2HalfBits(f, toward_zero)).
float Fsr2Half(float f, bool toward_zero = false);

/// ComputeLockInputLuma before its store: pow(perceived luma of max(0, rgb) / pre-exposure ·
/// exposure (tonemapped with hdr_color_input), 1/6), unrounded. `exposure`: the texel.
float Fsr2LockInputLuma(const Fsr2Constants& k, const Fsr2Options& o, float r, float g, float b, float exposure);

/// ReconstructAndDilate (ffx_fsr2_reconstruct_dilated_velocity_and_previous_depth.h), the
/// "reconstruct previous depth" pass, over the render size: for every pixel the nearest depth of
/// its 3×3 neighbourhood and the motion vector there (dilated_depth r16f, dilated_motion rg16f),
/// that depth pushed to the previous frame's pixels it lands on (prev_depth: float bits,
/// atomic min, or max with inverted depth; the caller initialises it, as FSR2's lock pass does
/// to the far depth; if it is not render-size long it is set to the far depth first) and the lock luma (lock_luma
/// r16f). `exposure`: the texel the exposure texture holds (0 reads as 1).
struct Fsr2ReconstructOut {
  Fsr2Plane dilated_depth, dilated_motion, lock_luma;
  std::vector<uint32_t> prev_depth;
};
void Fsr2ReconstructAndDilate(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& color,
                              const Fsr2Plane& depth, const Fsr2Plane& motion, float exposure, Fsr2ReconstructOut* out);

/// ComputeLock (ffx_fsr2_lock.h), the lock pass, over the render size (every invocation of its
/// 8×8-group dispatch): where a pixel's lock luma is a thin feature (a ridge against its 3×3
/// neighbours that no similar 2×2 corner covers), new_locks (display size, r8 unorm) gets 1 at
/// the display pixel under the pixel's jittered centre; prev_depth (render size) is reset to
/// the far depth for the next frame. `lock_luma` as the reconstruct pass stored it.
void Fsr2ComputeLock(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& lock_luma, Fsr2Plane* new_locks,
                     std::vector<uint32_t>* prev_depth);

/// What the depth-clip pass (ffx_fsr2_depth_clip_pass.glsl, DepthClip) reads: this frame's
/// reconstruct outputs, the previous frame's dilated motion (rg16f, sampled bilinearly), the
/// app's inputs, and optional reactive / transparency-and-composition masks (r8 unorm values;
/// empty planes read 0, as the API's default 1×1 zero masks do).
struct Fsr2DepthClipIn {
  const std::vector<uint32_t>* prev_depth = nullptr;  ///< reconstructed previous nearest depth (float bits)
  const Fsr2Plane* dilated_motion = nullptr;
  const Fsr2Plane* dilated_depth = nullptr;
  const Fsr2Plane* previous_dilated_motion = nullptr;
  const Fsr2Plane* motion = nullptr;  ///< the app's motion vectors (scaled by the constants)
  const Fsr2Plane* color = nullptr;
  const Fsr2Plane* depth = nullptr;
  Fsr2Plane reactive, composition;
  float exposure = 0.0f;  ///< the exposure texel (0 reads as 1)
};
/// Its outputs: prepared colour (render size, rgba16f: YCoCg of the exposed colour, alpha the
/// depth clip) and the dilated reactive masks (rg8 unorm: reactive, motion divergence).
struct Fsr2DepthClipOut {
  Fsr2Plane prepared_color, reactive_masks;
};
void Fsr2DepthClip(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2DepthClipIn& in, Fsr2DepthClipOut* out);

/// The RCAS pass (ffx_fsr2_rcas_pass.glsl: FsrRcasF of FSR 2's ffx_fsr1.h with
/// FSR_RCAS_DENOISE, 16×16 tiles) over the display size: `upscaled` (the accumulate pass's
/// colour, rgba) read through PrepareRgb (/ pre-exposure · exposure, clamped to [0, 65504]),
/// sharpened with con.x = `con_x` (FsrRcasCon's bits of exp2(−(2 − 2·sharpness))), then
/// UnprepareRgb; rgb floats (3 per pixel) as the shader computes them before its store.
/// Neighbours outside the image read 0 (the shader's texelFetch with robust access).
std::vector<float> Fsr2Rcas(const Fsr2Constants& k, const Fsr2Plane& upscaled, float exposure, uint32_t con_x);

/// The API's RCAS constant for sharpness s in [0, 1]: the bits of exp2(−((−2·s) + 2)).
uint32_t Fsr2RcasCon(float sharpness);

/// What the accumulate pass (ffx_fsr2_accumulate_pass.glsl) reads. Planes are the textures'
/// texel values (16-bit float images as halves, 8-bit UNORM ones as k/255); the textures at the
/// render size may be larger (FSR2 allocates them at the maximum render size).
struct Fsr2AccumulateIn {
  float exposure = 0.0f;                              ///< the exposure texel (0 reads as 1)
  const Fsr2Plane* dilated_reactive_masks = nullptr;  ///< depth clip's rg8 output (render size)
  const Fsr2Plane* dilated_motion = nullptr;          ///< low_res_motion_vectors: reconstruct's rg16f output
  const Fsr2Plane* motion = nullptr;                  ///< otherwise: the app's display-size motion vectors
  const Fsr2Plane* history = nullptr;                 ///< last frame's internal upscaled colour (rgba16f, display size)
  const Fsr2Plane* lock_status = nullptr;             ///< last frame's lock status (rg16f: lifetime, temporal luma)
  const Fsr2Plane* prepared_color = nullptr;          ///< depth clip's rgba16f output (YCoCg, depth clip)
  const Fsr2Plane* lanczos_lut = nullptr;  ///< the r16 snorm Lanczos 2 table (128×1), with reproject_lanczos_lut
  /// The luminance pyramid's level luma_mip_level (log luma, r16f, luma_mip_size), sampled
  /// bilinearly for the lock's shading change.
  const Fsr2Plane* luma_mip = nullptr;
  const Fsr2Plane* luma_history = nullptr;  ///< last frame's luma history (rgba8 unorm, display size)
  Fsr2Plane* new_locks = nullptr;           ///< this frame's new locks (r8, display size): read, then cleared
};
/// Its outputs, display size: the internal upscaled colour (rgba16f: rgb, temporal reactive
/// factor, negative when the pixel moves), the lock status (rg16f), the luma history (rgba8
/// unorm, as k/255) and the upscaled output (rgb floats before the app's store; empty with
/// apply_sharpening).
struct Fsr2AccumulateOut {
  Fsr2Plane internal_upscaled, lock_status, luma_history, output;
};
/// The accumulate pass (ffx_fsr2_accumulate.h, Accumulate) over the display size: reprojects
/// the history (Lanczos 2 or its table, with deringing) and the lock status (bilinear),
/// updates the locks with the shading change of the luma mip, upsamples the jittered prepared
/// colour with the approximate Lanczos 2 kernel and builds the rectification box, rectifies and
/// accumulates; clears `in.new_locks`. `lanczos_lut` and the maximum-bias table: only the first
/// is read (2.2.1's accumulate declares the second and does not sample it).
void Fsr2Accumulate(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2AccumulateIn& in, Fsr2AccumulateOut* out);

/// ffx's 8-bit UNORM store: clamp to [0, 1], ·255, round to nearest even, as a float code/255.
float Fsr2Unorm8(float v);

}  // namespace aalab
