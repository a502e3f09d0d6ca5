// FSR 2.2.1's host-side tables and jitter, written from api/ffx_fsr2.cpp of
// GPUOpen-Effects/FidelityFX-FSR2 2.2.1 (MIT, © 2023 Advanced Micro Devices, Inc.):
// ffxFsr2GetJitterPhaseCount, ffxFsr2GetJitterOffset with its halton(), the Lanczos-2 LUT
// that ffxFsr2ContextCreate uploads (lanczos2()), and the maximum-bias LUT (the table of
// api/ffx_fsr2_maximum_bias.h, AMD's fitted data: its 256 numbers are below, as data, with
// that file's licence; the oracle's tests compare them with the pinned file).
//
// Float for float: every step is the float operation the API's C++ performs, in its order
// (-ffp-contract=off), so that the jitter matches the API's bits. Choices, each stated:
//   - The phase count squares the ratio with pow(r, 2.0f) in the API; here the square is
//     rounded once from the exact product (what a correctly rounded powf gives).
//   - lanczos2 uses `abs(value)`; with MSVC (the API's compiler) that is the float overload.
//     Under libstdc++ an unqualified abs(float) can resolve to int abs(int), which would make
//     every |x| < 1 read as 0 and return 1: aalab uses fabsf, the Windows result.
//   - The API rejects phase_count ≤ 0 (FFX_ERROR_INVALID_ARGUMENT); aalab also rejects a
//     negative frame index, which the API would map to a Halton index ≤ 0 (jitter −0.5).
//   - R16_SNORM to float: max(code / 32767, −1), the division correctly rounded. Vulkan and
//     D3D define the conversion by that formula; hardware may differ in the last bit.
//   - Fsr2NextFrameConstants is ffxFsr2ContextDispatch's constant update. Where the dispatch's
//     render size is 0 the API takes the colour's size for cbFSR2 but still divides by the 0
//     for the field of view, the depth parameters and the phase count; aalab uses the colour's
//     size there too. The float math functions (tan, atan, sinf, cosf) are the C library's.
// Where the 2.2.1 shaders read these textures: the Lanczos LUT only with
// FFX_FSR2_OPTION_UPSAMPLE_USE_LANCZOS_TYPE=1 (the default is 2, the polynomial
// approximation; reprojection uses 0, the reference sinc), and SampleUpsampleMaximumBias is
// defined in the callbacks but called by no pass: the API uploads both, the default
// permutations read neither (docs/fsr2.md).
#include "methods/fsr2_tables.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <stdexcept>
#include <string>

namespace aalab {

namespace {

// ffxFsr2MaximumBias (api/ffx_fsr2_maximum_bias.h), row-major, 16 × 16; symmetric.
const std::array<float, kFsr2MaximumBiasSize* kFsr2MaximumBiasSize> kMaximumBias = {
    2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   1.876f, 1.809f, 1.772f,
    1.753f, 1.748f, 2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   1.869f,
    1.801f, 1.764f, 1.745f, 1.739f, 2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,
    1.976f, 1.841f, 1.774f, 1.737f, 1.716f, 1.71f,  2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,
    2.0f,   2.0f,   1.914f, 1.784f, 1.716f, 1.673f, 1.649f, 1.641f, 2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,
    2.0f,   2.0f,   2.0f,   2.0f,   1.793f, 1.676f, 1.604f, 1.562f, 1.54f,  1.533f, 2.0f,   2.0f,   2.0f,   2.0f,
    2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   1.802f, 1.619f, 1.536f, 1.492f, 1.467f, 1.454f, 1.449f, 2.0f,   2.0f,
    2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   1.812f, 1.575f, 1.496f, 1.456f, 1.432f, 1.416f, 1.408f, 1.405f,
    2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   1.555f, 1.479f, 1.438f, 1.413f, 1.398f, 1.387f,
    1.381f, 1.379f, 2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   1.812f, 1.555f, 1.474f, 1.43f,  1.404f, 1.387f,
    1.376f, 1.368f, 1.363f, 1.362f, 2.0f,   2.0f,   2.0f,   2.0f,   2.0f,   1.802f, 1.575f, 1.479f, 1.43f,  1.401f,
    1.382f, 1.369f, 1.36f,  1.354f, 1.351f, 1.35f,  2.0f,   2.0f,   1.976f, 1.914f, 1.793f, 1.619f, 1.496f, 1.438f,
    1.404f, 1.382f, 1.367f, 1.357f, 1.349f, 1.344f, 1.341f, 1.34f,  1.876f, 1.869f, 1.841f, 1.784f, 1.676f, 1.536f,
    1.456f, 1.413f, 1.387f, 1.369f, 1.357f, 1.347f, 1.341f, 1.336f, 1.333f, 1.332f, 1.809f, 1.801f, 1.774f, 1.716f,
    1.604f, 1.492f, 1.432f, 1.398f, 1.376f, 1.36f,  1.349f, 1.341f, 1.335f, 1.33f,  1.328f, 1.327f, 1.772f, 1.764f,
    1.737f, 1.673f, 1.562f, 1.467f, 1.416f, 1.387f, 1.368f, 1.354f, 1.344f, 1.336f, 1.33f,  1.326f, 1.323f, 1.323f,
    1.753f, 1.745f, 1.716f, 1.649f, 1.54f,  1.454f, 1.408f, 1.381f, 1.363f, 1.351f, 1.341f, 1.333f, 1.328f, 1.323f,
    1.321f, 1.32f,  1.748f, 1.739f, 1.71f,  1.641f, 1.533f, 1.449f, 1.405f, 1.379f, 1.362f, 1.35f,  1.34f,  1.332f,
    1.327f, 1.323f, 1.32f,  1.319f,
};

constexpr float kPi = 3.141592653589793f;  // FFX_PI
constexpr float kEpsilon = 1e-06f;         // FFX_EPSILON

int16_t Snorm16Code(float v) { return static_cast<int16_t>(std::roundf(v * 32767.0f)); }

}  // namespace

int Fsr2JitterPhaseCount(int render_width, int display_width) {
  if (render_width <= 0 || display_width <= 0) {
    throw std::invalid_argument("FSR2 jitter phase count: render and display widths must be positive (got " +
                                std::to_string(render_width) + " and " + std::to_string(display_width) + ")");
  }
  const float r = static_cast<float>(display_width) / static_cast<float>(render_width);
  const float square = static_cast<float>(static_cast<double>(r) * static_cast<double>(r));
  return static_cast<int32_t>(8.0f * square);
}

float Fsr2Halton(int32_t index, int32_t base) {
  float f = 1.0f, result = 0.0f;
  for (int32_t i = index; i > 0;) {
    f /= static_cast<float>(base);
    result = result + f * static_cast<float>(i % base);
    i = static_cast<int32_t>(static_cast<uint32_t>(std::floor(static_cast<float>(i) / static_cast<float>(base))));
  }
  return result;
}

Fsr2Jitter Fsr2JitterOffset(int32_t index, int32_t phase_count) {
  if (phase_count <= 0) {
    throw std::invalid_argument("FSR2 jitter offset: the phase count must be positive (got " +
                                std::to_string(phase_count) + ")");
  }
  if (index < 0) {
    throw std::invalid_argument("FSR2 jitter offset: the frame index must be 0 or more (got " + std::to_string(index) +
                                ")");
  }
  const int32_t i = (index % phase_count) + 1;
  return {Fsr2Halton(i, 2) - 0.5f, Fsr2Halton(i, 3) - 0.5f};
}

float Fsr2Lanczos2(float x) {
  if (std::fabs(x) < kEpsilon) return 1.0f;
  const float a = std::sin(kPi * x) / (kPi * x);
  const float b = std::sin(0.5f * kPi * x) / (0.5f * kPi * x);
  return a * b;
}

float Fsr2Snorm16ToFloat(int16_t code) { return std::max(static_cast<float>(code) / 32767.0f, -1.0f); }

std::array<int16_t, kFsr2LanczosLutWidth> Fsr2LanczosLutCodes() {
  std::array<int16_t, kFsr2LanczosLutWidth> codes{};
  for (uint32_t i = 0; i < static_cast<uint32_t>(kFsr2LanczosLutWidth); ++i) {
    // 2.0f * i / float(127): (2 · float(i)) / 127, in float.
    const float x = 2.0f * static_cast<float>(i) / static_cast<float>(kFsr2LanczosLutWidth - 1);
    codes[i] = Snorm16Code(Fsr2Lanczos2(x));
  }
  return codes;
}

std::array<float, kFsr2LanczosLutWidth> Fsr2LanczosLut() {
  const auto codes = Fsr2LanczosLutCodes();
  std::array<float, kFsr2LanczosLutWidth> out{};
  for (size_t i = 0; i < codes.size(); ++i) out[i] = Fsr2Snorm16ToFloat(codes[i]);
  return out;
}

const std::array<float, kFsr2MaximumBiasSize * kFsr2MaximumBiasSize>& Fsr2MaximumBiasTable() { return kMaximumBias; }

std::array<int16_t, kFsr2MaximumBiasSize * kFsr2MaximumBiasSize> Fsr2MaximumBiasCodes() {
  std::array<int16_t, kFsr2MaximumBiasSize * kFsr2MaximumBiasSize> codes{};
  for (size_t i = 0; i < codes.size(); ++i) codes[i] = Snorm16Code(kMaximumBias[i] / 2.0f);
  return codes;
}

std::array<float, kFsr2MaximumBiasSize * kFsr2MaximumBiasSize> Fsr2MaximumBiasLut() {
  const auto codes = Fsr2MaximumBiasCodes();
  std::array<float, kFsr2MaximumBiasSize * kFsr2MaximumBiasSize> out{};
  for (size_t i = 0; i < codes.size(); ++i) out[i] = Fsr2Snorm16ToFloat(codes[i]);
  return out;
}

namespace {

// setupDeviceDepthToViewSpaceDepthParams.
void DeviceToViewDepth(const Fsr2ContextParams& ctx, const Fsr2DispatchParams& p, int render_w, int render_h,
                       float out[4]) {
  float lo = std::min(p.camera_near, p.camera_far), hi = std::max(p.camera_near, p.camera_far);
  if (ctx.inverted_depth) std::swap(lo, hi);
  const float q = hi / (lo - hi);
  const float eps = std::numeric_limits<float>::epsilon();  // FLT_EPSILON
  const float c = ctx.infinite_depth ? (ctx.inverted_depth ? 0.0f + eps : -1.0f - eps) : q;
  const float e = ctx.infinite_depth ? (ctx.inverted_depth ? hi : -lo - eps) : q * lo;
  out[0] = -1.0f * c;
  out[1] = e;
  const float aspect = static_cast<float>(render_w) / static_cast<float>(render_h);
  const float cot_half_fov_y = std::cos(0.5f * p.camera_fov_vertical) / std::sin(0.5f * p.camera_fov_vertical);
  const float a = cot_half_fov_y / aspect, b = cot_half_fov_y;
  out[2] = 1.0f / a;
  out[3] = 1.0f / b;
}

}  // namespace

Fsr2FrameSetup Fsr2NextFrameConstants(const Fsr2ContextParams& ctx, const Fsr2DispatchParams& params,
                                      Fsr2ContextState* state) {
  Fsr2Constants& k = state->constants;
  const int rw = params.render_size[0] ? params.render_size[0] : params.input_color_size[0];
  const int rh = params.render_size[1] ? params.render_size[1] : params.input_color_size[1];
  if (rw <= 0 || rh <= 0 || ctx.max_render_size[0] <= 0 || ctx.max_render_size[1] <= 0 || ctx.display_size[0] <= 0 ||
      ctx.display_size[1] <= 0) {
    throw std::invalid_argument(
        "FSR2 frame constants: the render, max render and display sizes must be positive (render " +
        std::to_string(rw) + "x" + std::to_string(rh) + ")");
  }
  Fsr2FrameSetup setup;
  setup.odd = (state->resource_frame_index & 1u) != 0;
  setup.reset = params.reset || state->first_execution;
  state->first_execution = false;

  k.display_size[0] = ctx.display_size[0];
  k.display_size[1] = ctx.display_size[1];
  k.jitter[0] = params.jitter[0];
  k.jitter[1] = params.jitter[1];
  k.render_size[0] = rw;
  k.render_size[1] = rh;
  k.max_render_size[0] = ctx.max_render_size[0];
  k.max_render_size[1] = ctx.max_render_size[1];
  k.input_color_size[0] = params.input_color_size[0];
  k.input_color_size[1] = params.input_color_size[1];

  // The horizontal field of view from the vertical one.
  const float aspect = static_cast<float>(rw) / static_cast<float>(rh);
  const float angle_h = std::atan(std::tan(params.camera_fov_vertical / 2.0f) * aspect) * 2.0f;
  k.tan_half_fov = std::tan(angle_h * 0.5f);
  k.view_space_to_meters = params.view_space_to_meters > 0.0f ? params.view_space_to_meters : 1.0f;
  DeviceToViewDepth(ctx, params, rw, rh, k.device_to_view_depth);

  k.downscale_factor[0] = static_cast<float>(rw) / static_cast<float>(ctx.display_size[0]);
  k.downscale_factor[1] = static_cast<float>(rh) / static_cast<float>(ctx.display_size[1]);
  k.previous_pre_exposure = k.pre_exposure;
  k.pre_exposure = params.pre_exposure != 0.0f ? params.pre_exposure : 1.0f;

  const int mv_w = ctx.display_resolution_motion_vectors ? k.display_size[0] : rw;
  const int mv_h = ctx.display_resolution_motion_vectors ? k.display_size[1] : rh;
  k.motion_vector_scale[0] = params.motion_vector_scale[0] / static_cast<float>(mv_w);
  k.motion_vector_scale[1] = params.motion_vector_scale[1] / static_cast<float>(mv_h);
  if (ctx.motion_vector_jitter_cancellation) {
    k.motion_vector_jitter_cancellation[0] = (state->previous_jitter[0] - k.jitter[0]) / static_cast<float>(mv_w);
    k.motion_vector_jitter_cancellation[1] = (state->previous_jitter[1] - k.jitter[1]) / static_cast<float>(mv_h);
    state->previous_jitter[0] = k.jitter[0];
    state->previous_jitter[1] = k.jitter[1];
  }

  const int phase_count = Fsr2JitterPhaseCount(rw, ctx.display_size[0]);
  if (setup.reset || k.jitter_sequence_length == 0.0f) {
    k.jitter_sequence_length = static_cast<float>(phase_count);
  } else {
    const int delta = static_cast<int32_t>(static_cast<float>(phase_count) - k.jitter_sequence_length);
    if (delta > 0) {
      k.jitter_sequence_length = k.jitter_sequence_length + 1.0f;
    } else if (delta < 0) {
      k.jitter_sequence_length = k.jitter_sequence_length - 1.0f;
    }
  }
  k.delta_time = std::max(0.0f, std::min(1.0f, params.frame_time_delta_ms / 1000.0f));
  k.frame_index = setup.reset ? 0 : k.frame_index + 1;

  k.luma_mip_level = 4;  // FFX_FSR2_SHADING_CHANGE_MIP_LEVEL
  const float mip_div = static_cast<float>(2 << k.luma_mip_level);
  k.luma_mip_size[0] = static_cast<int32_t>(static_cast<float>(k.max_render_size[0]) / mip_div);
  k.luma_mip_size[1] = static_cast<int32_t>(static_cast<float>(k.max_render_size[1]) / mip_div);

  state->resource_frame_index = (state->resource_frame_index + 1u) % 16u;
  return setup;
}

}  // namespace aalab
