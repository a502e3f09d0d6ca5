/// One emulation of GPU bilinear texture filtering, shared by every post filter.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/image.h"

namespace aalab {

/// Which arithmetic every texel read and bilinear fetch of the CPU post filters uses (a
/// run-level setting, `--sampler`; docs/gpu.md "A CPU mode that predicts the GPU's bits").
///   kGl:         Mesa llvmpipe's float path (UnormToFloat texels, float32 lerps): the default,
///                what the original shaders return on the GL oracle (tests/oracle).
///   kGpuTexture: the NVIDIA texture unit's fixed-point filter as measured on the H100 by
///                `aalab_gpu --probe-dump` (HwUnorm8ToFloat, HwWeights, HwFilter8): what the
///                CUDA twins' texture path returns.
enum class SamplerArithmetic { kGl, kGpuTexture };

/// "gl" or "gpu-texture".
const char* SamplerArithmeticName(SamplerArithmetic a);
/// Parses "gl" / "gpu-texture"; throws UserError naming the allowed values otherwise.
SamplerArithmetic ParseSamplerArithmetic(const std::string& name);

/// kHwUnorm16[q] = q/65535 correctly rounded to float, q in 0..65535 (filled at start-up).
extern const std::array<float, 65536> kHwUnorm16;
/// The texture unit's float for a 16-bit fixed-point filter result q in 0..65535: q/65535
/// correctly rounded to float (for q = k·257 this is k/255, the UNORM8 texel value).
[[gnu::always_inline]] inline float HwUnorm16ToFloat(uint32_t q) { return kHwUnorm16[q & 0xffffu]; }
/// The texture unit's value of UNORM8 code k: k/255 correctly rounded (measured for all 256).
[[gnu::always_inline]] inline float HwUnorm8ToFloat(uint8_t k) { return HwUnorm16ToFloat(257u * k); }

/// The texture unit's footprint of a bilinear fetch: top-left texel (x0, y0) (x0 in
/// [-1, W], y0 in [-1, H]; reads clamp to the edge) and 8-bit fractions kx, ky in 0..255
/// (units of 1/256 texel).
struct HwFootprint {
  int x0 = 0, y0 = 0;
  int kx = 0, ky = 0;
};
/// The fetch at unnormalised coordinates (u, v) (exact values, e.g. a float widened to
/// double): t = floor((u − 0.5)·256 + 0.5), x0 = floor(t/256), kx = t mod 256 — the
/// coordinate rounded to 1/256 texel, ties upwards (towards +∞, negative coordinates too).
/// A NaN coordinate reads as 0.
HwFootprint HwFootprintAt(double u, double v, int width, int height);
/// Normalised coordinates (s, t): each is first truncated to a multiple of 2^-21 (floor),
/// then scaled by the size exactly: u = floor(s·2^21)·W/2^21, v alike, then HwFootprintAt.
HwFootprint HwFootprintNormalized(float s, float t, int width, int height);

/// The four 8-bit weights of a footprint, in 1/256, summing to 256: d = round(kx·ky/256)
/// with ties upwards, b = kx − d, c = ky − d, a = 256 − kx − ky + d (texels a = (x0, y0),
/// b = (x0+1, y0), c = (x0, y0+1), d = (x0+1, y0+1)).
struct HwWeights {
  int a = 256, b = 0, c = 0, d = 0;
};
[[gnu::always_inline]] inline HwWeights HwWeightsOf(int kx, int ky) {
  HwWeights w;
  w.d = (kx * ky + 128) >> 8;
  w.b = kx - w.d;
  w.c = ky - w.d;
  w.a = 256 - kx - ky + w.d;
  return w;
}
/// One channel of an RGBA8 fetch: S = Σ W_i·k_i exactly (units of 1/(256·255)), rescaled to
/// 16 bits with ties upwards, q = floor((257·S + 128)/256), returned as HwUnorm16ToFloat(q).
[[gnu::always_inline]] inline float HwFilter8(uint8_t a, uint8_t b, uint8_t c, uint8_t d, const HwWeights& w) {
  const uint32_t s = static_cast<uint32_t>(w.a * a + w.b * b + w.c * c + w.d * d);
  return HwUnorm16ToFloat((257u * s + 128u) >> 8);
}
/// One channel of an RGBA32F fetch (TAA's history on the GPU): the exact Σ W_i·v_i / 256
/// rounded to float with ties upwards (measured on non-negative values; the sum is formed in
/// double, exact unless the four terms span more than 20 binary orders of magnitude).
float HwFilterFloat(float a, float b, float c, float d, const HwWeights& w);

/// Four float channels, as a shader's float4.
struct Float4 {
  float r = 0, g = 0, b = 0, a = 0;
};

/// The float a GL implementation reads for UNORM8 value k: k · fl(1/255), the product
/// rounded to float (Mesa llvmpipe's float path; it differs from k/255 in the last bit for
/// 126 of the 256 values). Every 8-bit texel read in aalab goes through this.
[[gnu::always_inline]] inline float UnormToFloat(uint8_t k) { return static_cast<float>(k) * (1.0f / 255.0f); }

/// The texel value of code k under arithmetic `a`.
[[gnu::always_inline]] inline float TexelValue(uint8_t k, SamplerArithmetic a) {
  return a == SamplerArithmetic::kGl ? UnormToFloat(k) : HwUnorm8ToFloat(k);
}

/// GL's float-to-UNORM8 store of a render target: clamp to [0, 1], scale by 255, round to
/// nearest with ties to even (what llvmpipe's conversion does; NaN stores 0).
[[gnu::always_inline]] inline uint8_t StoreUnorm8(float v) {
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  // v·255 in (0, 255): adding and removing 2^23 rounds it to an integer, ties to even (the
  // default rounding mode; no fast-math, so the sum is not folded away). = nearbyint.
  const float w = v * 255.0f;
  return static_cast<uint8_t>((w + 8388608.0f) - 8388608.0f);
}

/// One linear interpolation step of the filter: a + w·(b − a), two roundings, no FMA.
[[gnu::always_inline]] inline float FilterLerp(float a, float b, float w) { return a + w * (b - a); }

/// The footprint of one bilinear fetch at texture-space pixel coordinates (u, v): the
/// top-left texel (x0, y0) of the 2×2 block (x0 in [-1, W], y0 in [-1, H]; the caller clamps
/// each texel read to the edge) and the fractions fx = (u − 0.5) − floor(u − 0.5), fy alike.
/// The single definition every bilinear fetch in aalab uses (the sampler below, the
/// float-image sampler, and the fast luma-plane paths).
struct BilinearFootprint {
  int x0 = 0, y0 = 0;
  float fx = 0, fy = 0;
};
/// Precision of the bilinear fraction (fx, fy).
///   kExact:  the float32 fraction as computed (the default; what FXAA, rescale and the GL
///            oracle's float path use).
///   kFixed8: the fraction rounded to 8 bits of sub-texel precision, round to nearest with
///            ties to even (fx := nearbyint(fx·256)/256). A fraction that rounds to 1 moves
///            the footprint one texel on with fraction 0, so the whole weight goes to the
///            second texel exactly. Direct3D 10+ requires at least 8 bits of sub-texel
///            precision and GPUs filter with such fixed-point fractions, so a coordinate that
///            misses a texel centre or a quarter position by a float rounding error
///            (< 1/512 texel) returns exactly what the exact position would. SMAA relies on
///            that (methods/smaa.cpp, docs/smaa.md).
enum class SubTexel { kExact, kFixed8 };

[[gnu::always_inline]] inline BilinearFootprint BilinearAt(float u, float v, int width, int height,
                                                           SubTexel mode = SubTexel::kExact) {
  const float x = u - 0.5f;
  const float y = v - 0.5f;
  float x0f = std::floor(x);
  float y0f = std::floor(y);
  float fx = x - x0f;
  float fy = y - y0f;
  if (mode == SubTexel::kFixed8) {
    fx = std::nearbyint(fx * 256.0f) * (1.0f / 256.0f);
    fy = std::nearbyint(fy * 256.0f) * (1.0f / 256.0f);
    if (fx == 1.0f) {
      x0f += 1.0f;
      fx = 0.0f;
    }
    if (fy == 1.0f) {
      y0f += 1.0f;
      fy = 0.0f;
    }
  }
  BilinearFootprint f;
  f.fx = fx;
  f.fy = fy;
  f.x0 = static_cast<int>(std::clamp(x0f, -1.0f, static_cast<float>(width)));
  f.y0 = static_cast<int>(std::clamp(y0f, -1.0f, static_cast<float>(height)));
  return f;
}

/// The filter of one channel over the footprint's texels a = (x0, y0), b = (x0+1, y0),
/// c = (x0, y0+1), d = (x0+1, y0+1): lerp(lerp(a, b, fx), lerp(c, d, fx), fy), as Mesa's
/// llvmpipe filters in float (lp_build_lerp_2d) on a CPU without FMA. With clamped texels
/// a lerp between equal values returns them exactly, so clamp-to-edge needs no special case.
[[gnu::always_inline]] inline float BilinearBlend(float a, float b, float c, float d, const BilinearFootprint& f) {
  return FilterLerp(FilterLerp(a, b, f.fx), FilterLerp(c, d, f.fx), f.fy);
}

/// Reads an 8-bit RGBA frame as a UNORM texture (UnormToFloat) with bilinear filtering:
/// texel centres at +0.5, clamp-to-edge addressing, float32 fractions, BilinearBlend.
/// This is bit for bit what Mesa's llvmpipe returns with GALLIVM_PERF=no_aos_sampling on a
/// CPU without FMA (tests/oracle checks it against llvmpipe).
///
/// Deviation from GPUs (documented): hardware quantises the bilinear fraction to 8 bits of
/// sub-texel precision (so does llvmpipe's default RGBA8 path); this sampler uses the exact
/// float32 fraction unless constructed with SubTexel::kFixed8 (which SMAA uses). Every call
/// counts one tap in the sampler's counter (fetches, not texels).
///
/// With SamplerArithmetic::kGpuTexture every read follows the texture unit instead: texels
/// HwUnorm8ToFloat, Sample at HwFootprintAt, SampleNormalized at HwFootprintNormalized,
/// SampleNormalizedOffset as the CUDA twins' textureLodOffset (s·W + dx in float, then
/// unnormalised), filtered by HwFilter8; `mode` is then irrelevant (the unit always uses 8-bit
/// fractions).
class BilinearSampler {
 public:
  explicit BilinearSampler(const Image8& img, SubTexel mode = SubTexel::kExact,
                           SamplerArithmetic arithmetic = SamplerArithmetic::kGl);
  /// Sample at texture-space pixel coordinates (u, v) in pixels: the centre of texel (x, y)
  /// is (x + 0.5, y + 0.5).
  Float4 Sample(float u, float v);
  /// Sample at normalised texture coordinates (s, t) in [0, 1] as a shader passes them:
  /// u = s·W and v = t·H in float32, then as Sample(u, v).
  Float4 SampleNormalized(float s, float t);
  /// Sample at (s, t) with an integer texel offset (dx, dy), as textureLodOffset: the
  /// offset is added to the scaled coordinate, Sample(s·W + dx, t·H + dy) in float (what
  /// llvmpipe does; tests/oracle checks it).
  Float4 SampleNormalizedOffset(float s, float t, int dx, int dy);
  /// Exact read of texel (x, y) with clamp-to-edge: what a bilinear fetch at the texel
  /// centre returns (like texelFetch / FxaaTexTop / FxaaTexOff with integer offsets).
  Float4 Texel(int x, int y);
  /// Number of Sample/Texel calls so far.
  uint64_t Taps() const { return taps_; }
  int Width() const { return img_.Width(); }
  int Height() const { return img_.Height(); }

 private:
  Float4 Fetch(int x, int y) const;
  Float4 Blend(const BilinearFootprint& f);
  Float4 BlendHw(const HwFootprint& f);
  const Image8& img_;
  SubTexel mode_ = SubTexel::kExact;
  SamplerArithmetic arithmetic_ = SamplerArithmetic::kGl;
  uint64_t taps_ = 0;
};

/// The same filtering for a float RGB(A) image (used by rescaling); no tap counter.
Float4 SampleBilinear(const ImageF& img, float u, float v);

}  // namespace aalab
