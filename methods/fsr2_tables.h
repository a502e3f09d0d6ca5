/// FSR 2.2.1's host-side tables and jitter (api/ffx_fsr2.cpp of GPUOpen-Effects/FidelityFX-FSR2,
/// MIT): the jitter phase count and the Halton jitter of frame i as the API computes them, and
/// the two look-up textures the API creates at context creation (the Lanczos-2 weights and the
/// maximum upsample bias) as their R16_SNORM codes and the floats a shader reads from them.
/// docs/fsr2.md says where each is used; tests/methods/fsr2_tables_test.cpp checks them.
#pragma once
#include <array>
#include <cstdint>

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

}  // namespace aalab
