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
// Where the 2.2.1 shaders read these textures: the Lanczos LUT only with
// FFX_FSR2_OPTION_UPSAMPLE_USE_LANCZOS_TYPE=1 (the default is 2, the polynomial
// approximation; reprojection uses 0, the reference sinc), and SampleUpsampleMaximumBias is
// defined in the callbacks but called by no pass: the API uploads both, the default
// permutations read neither (docs/fsr2.md).
#include "methods/fsr2_tables.h"

#include <algorithm>
#include <cmath>
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

}  // namespace aalab
