/// FSR 2.2.1's host-side tables and jitter (api/ffx_fsr2.cpp of GPUOpen-Effects/FidelityFX-FSR2,
/// MIT): the jitter phase count and the Halton jitter of frame i as the API computes them, and
/// the two look-up textures the API creates at context creation (the Lanczos-2 weights and the
/// maximum upsample bias) as their R16_SNORM codes and the floats a shader reads from them.
/// docs/fsr2.md says where each is used; tests/methods/fsr2_tables_test.cpp checks them.
#pragma once
#include <array>
#include <cstdint>

#include "methods/fsr2.h"

namespace aalab {

/// ffxFsr2GetJitterPhaseCount: int32(8 · (display_width / render_width)²) in float arithmetic
/// (18 for 1.5×, 32 for 2×, 72 for 3×, 8 for 1×). Throws std::invalid_argument unless both
/// widths are positive.
int Fsr2JitterPhaseCount(int render_width, int display_width);

/// The API's Halton radical inverse of `index` in `base`, float for float: f /= base,
/// result += f · (index mod base), index = floor(index / base) (all in float).
float Fsr2Halton(int32_t index, int32_t base);

/// ffxFsr2GetJitterOffset: the jitter of frame `index` in render pixels, each in [−0.5, 0.5):
/// (Halton((index mod n) + 1, 2) − 0.5, Halton((index mod n) + 1, 3) − 0.5), n = phase_count.
/// Throws std::invalid_argument when phase_count ≤ 0 (the API returns
/// FFX_ERROR_INVALID_ARGUMENT) or index < 0 (the API would give (−0.5, −0.5) or a Halton of a
/// negative index; aalab refuses it).
struct Fsr2Jitter {
  float x = 0.0f, y = 0.0f;
};
Fsr2Jitter Fsr2JitterOffset(int32_t index, int32_t phase_count);

/// The API's lanczos2(x): 1 when |x| < 1e-6, else sinc(πx)·sinc(πx/2) as
/// (sinf(π·x) / (π·x)) · (sinf(0.5·π·x) / (0.5·π·x)) in float, π = 3.141592653589793f.
float Fsr2Lanczos2(float x);

/// R16_SNORM code → the float a shader reads: max(code / 32767, −1) (the Vulkan and D3D
/// conversion; the division correctly rounded here).
float Fsr2Snorm16ToFloat(int16_t code);

/// The Lanczos look-up texture (FSR2_LanczosLutData, 128×1 R16_SNORM): code i is
/// int16(roundf(lanczos2(2·i / 127) · 32767)), x from 0 to 2.
constexpr int kFsr2LanczosLutWidth = 128;
std::array<int16_t, kFsr2LanczosLutWidth> Fsr2LanczosLutCodes();
/// The same texture as the floats a shader reads (Fsr2Snorm16ToFloat of each code).
std::array<float, kFsr2LanczosLutWidth> Fsr2LanczosLut();

/// The maximum upsample bias texture (FSR2_MaximumUpsampleBias, 16×16 R16_SNORM): AMD's table
/// ffxFsr2MaximumBias (api/ffx_fsr2_maximum_bias.h, values 1.319..2, row-major) stored halved,
/// code int16(roundf(v / 2 · 32767)); the shader reads 2 · the texel (SampleUpsampleMaximumBias).
constexpr int kFsr2MaximumBiasSize = 16;
/// AMD's table as floats, entry (x, y) at [y · 16 + x].
const std::array<float, kFsr2MaximumBiasSize * kFsr2MaximumBiasSize>& Fsr2MaximumBiasTable();
std::array<int16_t, kFsr2MaximumBiasSize * kFsr2MaximumBiasSize> Fsr2MaximumBiasCodes();
/// The texels as a shader reads them (Fsr2Snorm16ToFloat of each code; multiply by 2 for the bias).
std::array<float, kFsr2MaximumBiasSize * kFsr2MaximumBiasSize> Fsr2MaximumBiasLut();

/// The context creation parameters the per-frame constants depend on (FfxFsr2ContextDescription
/// and its flags).
struct Fsr2ContextParams {
  int max_render_size[2] = {0, 0};
  int display_size[2] = {0, 0};
  bool display_resolution_motion_vectors = false;  ///< FFX_FSR2_ENABLE_DISPLAY_RESOLUTION_MOTION_VECTORS
  bool motion_vector_jitter_cancellation = false;  ///< FFX_FSR2_ENABLE_MOTION_VECTORS_JITTER_CANCELLATION
  bool inverted_depth = false;                     ///< FFX_FSR2_ENABLE_DEPTH_INVERTED
  bool infinite_depth = false;                     ///< FFX_FSR2_ENABLE_DEPTH_INFINITE
};

/// The part of FfxFsr2DispatchDescription the constants depend on.
struct Fsr2DispatchParams {
  float jitter[2] = {0, 0};               ///< render pixels (Fsr2JitterOffset)
  float motion_vector_scale[2] = {0, 0};  ///< the app's scale from its motion vectors to pixels of their size
  int render_size[2] = {0, 0};            ///< 0: the colour texture's size
  int input_color_size[2] = {0, 0};       ///< the colour texture's size
  float frame_time_delta_ms = 0.0f;
  float pre_exposure = 0.0f;  ///< 0 reads as 1
  bool reset = false;
  float camera_near = 0.1f, camera_far = 100.0f;
  float camera_fov_vertical = 1.0471976f;  ///< radians
  float view_space_to_meters = 0.0f;       ///< ≤ 0 reads as 1
};

/// The context state ffxFsr2ContextDispatch carries from frame to frame.
struct Fsr2ContextState {
  Fsr2Constants constants;            ///< cbFSR2, updated in place each frame
  bool first_execution = true;        ///< a fresh context resets on its first dispatch
  uint32_t resource_frame_index = 0;  ///< 0..15 (FSR2_MAX_QUEUED_FRAMES); its parity picks the ping-pong side
  float previous_jitter[2] = {0, 0};  ///< for the jitter cancellation
};

/// What one dispatch decides besides cbFSR2: whether it resets the accumulation (params.reset or
/// the first dispatch: the API then clears the history it reads: lock status, upscaled colour,
/// the luminance mips, the auto exposure to (−1, 1e8)), and which side of the ping-pong it uses.
/// `odd`: the frame reads LOCK_STATUS_2, INTERNAL_UPSCALED_COLOR_2, LUMA_HISTORY_2 and writes the
/// _1 resources, writes INTERNAL_DILATED_MOTION_VECTORS_2 and reads _1 as the previous frame's;
/// an even frame the other way round.
struct Fsr2FrameSetup {
  bool reset = false;
  bool odd = false;
};

/// ffxFsr2ContextDispatch's update of cbFSR2 for one frame, float for float: jitter, render,
/// display and colour sizes, the device-to-view-depth parameters, the horizontal tan(fov/2),
/// downscale factor, pre-exposure (and the previous one), motion-vector scale (divided by the
/// motion vectors' size) and jitter cancellation (previous − current jitter, divided alike, with
/// the flag), the jitter phase count (set on reset, else moved one step toward the new ratio's),
/// Δt in seconds clamped to [0, 1], the frame index (0 on reset), the luma mip level 4 and its
/// size. Advances `state` to the next frame. Throws std::invalid_argument for a render size that
/// is not positive (after the colour-size fallback) or a max render or display size ≤ 0.
Fsr2FrameSetup Fsr2NextFrameConstants(const Fsr2ContextParams& ctx, const Fsr2DispatchParams& params,
                                      Fsr2ContextState* state);

}  // namespace aalab
