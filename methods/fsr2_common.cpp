// AMD FidelityFX Super Resolution 2.2.1 (GPUOpen-Effects/FidelityFX-FSR2, MIT, © 2023 Advanced
// Micro Devices, Inc.), ported from the GLSL shaders of its Vulkan backend
// (src/ffx-fsr2-api/shaders/*.glsl with their *.h), fp32 path (FFX_HALF=0). This is aalab's
// own code written from the shaders; the originals are not in the repository: the oracle
// (tests/oracle/fsr2_oracle_test.cpp) reads them from ../shared/third_party/fidelityfx-fsr2.
//
// Each pass is a function over whole planes that computes, for every invocation the shader's
// dispatch covers, what it stores; every arithmetic step is a float operation in the order the
// shader writes it (no fused multiply-adds: -ffp-contract=off). Stores into 16-bit float
// images go through Fsr2Half, as the image formats the shaders declare round them: to nearest
// even by default, toward zero with Fsr2Options::half_toward_zero (what lavapipe does; Vulkan
// allows either, so the oracle runs the port that way).
//
// Ported and proven against the shader (docs/fsr2.md has the figures):
//   - ReconstructAndDilate (ffx_fsr2_reconstruct_previous_depth_pass.glsl);
//   - ComputeLock (ffx_fsr2_lock_pass.glsl);
//   - DepthClip (ffx_fsr2_depth_clip_pass.glsl);
//   - RCAS (ffx_fsr2_rcas_pass.glsl: FsrRcasF of FSR 2's ffx_fsr1.h, FSR_RCAS_DENOISE);
//   - Accumulate (ffx_fsr2_accumulate_pass.glsl; fsr2_accumulate.cpp's doc block).
// Not yet: the luminance pyramid (SPD) and the frame sequence; so no registry rows.
//
// The passes are split by family: fsr2_common.cpp (this file: planes, the 16-bit and 8-bit
// store conversions, lock luma), fsr2_reconstruct.cpp, fsr2_lock.cpp, fsr2_depth_clip.cpp,
// fsr2_rcas.cpp, fsr2_accumulate.cpp; their shared helpers are in fsr2_internal.h.
// In RCAS, min/max are std::fmin/fmax (IEEE minNum/maxNum, the non-NaN operand), as lavapipe
// evaluates GLSL's min/max: RCAS's limiter makes 0·∞ = NaN on a black ring.
//
// Dispatch extent: every pass's dispatch covers whole 8×8 groups. Invocations past the render
// size only matter where they can store inside: ReconstructAndDilate's previous-depth atomics
// (their reprojected positions can land on screen), so that loop runs the whole extent; the
// others stop at the render size (their stores outside are discarded).
// Where the shader reads outside an image (FindNearestDepth's 3×3 at the border), the port
// reads 0 (robust image access) and, as the shader does, ignores those samples.
// pow(x, y) is computed as exp2(y·log2(x)), as Mesa lowers it; lavapipe evaluates exp2 and
// log2 with its own polynomials, so a pow result can differ from ours in the last bits: a
// difference the 16-bit store hides except at rounding ties (docs/fsr2.md, measured).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "methods/fsr2.h"
#include "methods/fsr2_internal.h"

namespace aalab {

using namespace fsr2_detail;  // NOLINT(google-build-using-namespace): the passes' shared helpers

float Fsr2Plane::Fetch(int x, int y, int k) const {
  if (x < 0 || y < 0 || x >= w || y >= h) return 0.0f;
  return v[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * static_cast<size_t>(c) +
           static_cast<size_t>(k)];
}

uint16_t Fsr2HalfBits(float f, bool toward_zero) {
  const uint32_t x = Bits(f);
  const uint32_t sign = (x >> 16) & 0x8000u, ax = x & 0x7fffffffu;
  if (ax >= 0x7f800000u) return static_cast<uint16_t>(sign | (ax > 0x7f800000u ? 0x7e00u : 0x7c00u));  // NaN, ∞
  if (ax < 0x38800000u) {  // below 2^-14: a subnormal half, |f|·2^24 (exact) rounded to an integer
    const float q = FloatOfBits(ax) * 16777216.0f;
    return static_cast<uint16_t>(sign | static_cast<uint32_t>(toward_zero ? std::floor(q) : std::nearbyint(q)));
  }
  const uint32_t e = (ax >> 23) - 127u + 15u, m = ax & 0x7fffffu;
  if (e >= 31u) return static_cast<uint16_t>(sign | (toward_zero ? 0x7bffu : 0x7c00u));  // ≥ 65536
  uint32_t h = (e << 10) | (m >> 13);
  const uint32_t rest = m & 0x1fffu;
  if (!toward_zero && (rest > 0x1000u || (rest == 0x1000u && (h & 1u)))) ++h;  // a carry may reach ∞: right
  return static_cast<uint16_t>(sign | h);
}

float Fsr2HalfToFloat(uint16_t h) {
  const uint32_t sign = (static_cast<uint32_t>(h) & 0x8000u) << 16, e = (h >> 10) & 0x1fu, m = h & 0x3ffu;
  if (e == 0) {
    const float v = static_cast<float>(m) * (1.0f / 16777216.0f);
    return sign ? -v : v;
  }
  if (e == 31) return FloatOfBits(sign | 0x7f800000u | (m << 13));
  return FloatOfBits(sign | ((e - 15u + 127u) << 23) | (m << 13));
}

float Fsr2Half(float f, bool toward_zero) { return Fsr2HalfToFloat(Fsr2HalfBits(f, toward_zero)); }

float Fsr2LockInputLuma(const Fsr2Constants& k, const Fsr2Options& o, float r, float g, float b, float exposure_texel) {
  const float exposure = ExposureOf(exposure_texel);
  r = std::max(0.0f, r);
  g = std::max(0.0f, g);
  b = std::max(0.0f, b);
  r = r / k.pre_exposure;
  g = g / k.pre_exposure;
  b = b / k.pre_exposure;
  r = r * exposure;
  g = g * exposure;
  b = b * exposure;
  if (o.hdr_color_input) {  // Tonemap
    const float d = std::max(std::max(0.0f, r), std::max(g, b)) + 1.0f;
    r = r / d;
    g = g / d;
    b = b / d;
  }
  return Pow(PerceivedLuma(r, g, b), 1.0f / 6.0f);
}

float Fsr2Unorm8(float v) {
  float c = 0.0f;
  if (v >= 1.0f) {
    c = 255.0f;
  } else if (v > 0.0f) {
    c = std::nearbyint(v * 255.0f);
  }
  return c / 255.0f;
}

}  // namespace aalab
