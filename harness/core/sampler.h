/// One emulation of GPU bilinear texture filtering, shared by every post filter.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "harness/core/image.h"

namespace aalab {

/// Four float channels, as a shader's float4.
struct Float4 {
  float r = 0, g = 0, b = 0, a = 0;
};

/// The float a GL implementation reads for UNORM8 value k: k · fl(1/255), the product
/// rounded to float (Mesa llvmpipe's float path; it differs from k/255 in the last bit for
/// 126 of the 256 values). Every 8-bit texel read in aalab goes through this.
[[gnu::always_inline]] inline float UnormToFloat(uint8_t k) {
  return static_cast<float>(k) * (1.0f / 255.0f);
}

/// GL's float-to-UNORM8 store of a render target: clamp to [0, 1], scale by 255, round to
/// nearest with ties to even (what llvmpipe's conversion does; NaN stores 0).
[[gnu::always_inline]] inline uint8_t StoreUnorm8(float v) {
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  return static_cast<uint8_t>(std::nearbyint(v * 255.0f));  // default rounding: ties to even
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
[[gnu::always_inline]] inline BilinearFootprint BilinearAt(float u, float v, int width, int height) {
  const float x = u - 0.5f;
  const float y = v - 0.5f;
  const float x0f = std::floor(x);
  const float y0f = std::floor(y);
  BilinearFootprint f;
  f.fx = x - x0f;
  f.fy = y - y0f;
  f.x0 = static_cast<int>(std::clamp(x0f, -1.0f, static_cast<float>(width)));
  f.y0 = static_cast<int>(std::clamp(y0f, -1.0f, static_cast<float>(height)));
  return f;
}

/// The filter of one channel over the footprint's texels a = (x0, y0), b = (x0+1, y0),
/// c = (x0, y0+1), d = (x0+1, y0+1): lerp(lerp(a, b, fx), lerp(c, d, fx), fy), as Mesa's
/// llvmpipe filters in float (lp_build_lerp_2d) on a CPU without FMA. With clamped texels
/// a lerp between equal values returns them exactly, so clamp-to-edge needs no special case.
[[gnu::always_inline]] inline float BilinearBlend(float a, float b, float c, float d,
                                                  const BilinearFootprint& f) {
  return FilterLerp(FilterLerp(a, b, f.fx), FilterLerp(c, d, f.fx), f.fy);
}

/// Reads an 8-bit RGBA frame as a UNORM texture (UnormToFloat) with bilinear filtering:
/// texel centres at +0.5, clamp-to-edge addressing, float32 fractions, BilinearBlend.
/// This is bit for bit what Mesa's llvmpipe returns with GALLIVM_PERF=no_aos_sampling on a
/// CPU without FMA (tests/oracle checks it against llvmpipe).
///
/// Deviation from GPUs (documented): hardware quantises the bilinear fraction to 8 bits of
/// sub-texel precision (so does llvmpipe's default RGBA8 path); this sampler uses the exact
/// float32 fraction. Every call counts one tap in the sampler's counter (fetches, not texels).
class BilinearSampler {
 public:
  explicit BilinearSampler(const Image8& img);
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
  const Image8& img_;
  uint64_t taps_ = 0;
};

/// The same filtering for a float RGB(A) image (used by rescaling); no tap counter.
Float4 SampleBilinear(const ImageF& img, float u, float v);

}  // namespace aalab
