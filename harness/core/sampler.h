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

/// The footprint of one bilinear fetch at texture-space pixel coordinates (u, v): the
/// top-left texel (x0, y0) of the 2×2 block (x0 in [-1, W], y0 in [-1, H]; the caller clamps
/// each texel read to the edge) and the weights in summation order
/// wa = (1-fx)(1-fy) for (x0, y0), wb = fx(1-fy) for (x0+1, y0), wc = (1-fx)fy for
/// (x0, y0+1), wd = fx·fy for (x0+1, y0+1). The single definition every bilinear fetch in
/// aalab uses (the sampler below, the float-image sampler, and the fast luma-plane paths).
struct BilinearFootprint {
  int x0 = 0, y0 = 0;
  float wa = 0, wb = 0, wc = 0, wd = 0;
};

/// Precision of the bilinear fraction (fx, fy).
///   kExact:  the float32 fraction as computed (the default; what every filter used so far).
///   kFixed8: the fraction rounded to 8 bits of sub-texel precision, round to nearest with
///            ties to even (fx := nearbyint(fx·256)/256, which may give 1: then the whole
///            weight goes to the second texel). Direct3D 10+ requires at least 8 bits of
///            sub-texel precision; GPUs filter with such fixed-point fractions, so a
///            coordinate that misses a texel centre or a quarter position by a float
///            rounding error (< 1/512 texel) returns exactly what the exact position would.
///            SMAA relies on that (methods/smaa.cpp, docs/smaa.md).
enum class SubTexel { kExact, kFixed8 };

[[gnu::always_inline]] inline BilinearFootprint BilinearAt(float u, float v, int width, int height,
                                                           SubTexel mode = SubTexel::kExact) {
  const float x = u - 0.5f;
  const float y = v - 0.5f;
  const float x0f = std::floor(x);
  const float y0f = std::floor(y);
  float fx = x - x0f;
  float fy = y - y0f;
  if (mode == SubTexel::kFixed8) {
    fx = std::nearbyint(fx * 256.0f) * (1.0f / 256.0f);
    fy = std::nearbyint(fy * 256.0f) * (1.0f / 256.0f);
  }
  BilinearFootprint f;
  f.x0 = static_cast<int>(std::clamp(x0f, -1.0f, static_cast<float>(width)));
  f.y0 = static_cast<int>(std::clamp(y0f, -1.0f, static_cast<float>(height)));
  f.wa = (1.0f - fx) * (1.0f - fy);
  f.wb = fx * (1.0f - fy);
  f.wc = (1.0f - fx) * fy;
  f.wd = fx * fy;
  return f;
}

/// Reads an 8-bit RGBA frame as a UNORM texture (k / 255) with bilinear filtering:
/// texel centres at +0.5, clamp-to-edge addressing, float32 weights.
///
/// Deviation from GPUs (documented): hardware quantises the bilinear fraction to 8 bits of
/// sub-texel precision; this sampler uses the exact float32 fraction unless constructed with
/// SubTexel::kFixed8 (which SMAA uses). Weights are
/// (1-fx)(1-fy), fx(1-fy), (1-fx)fy, fx·fy and the four products are summed in that order.
/// Every call counts one tap in the sampler's counter (fetches, not texels).
class BilinearSampler {
 public:
  explicit BilinearSampler(const Image8& img, SubTexel mode = SubTexel::kExact);
  /// Sample at texture-space pixel coordinates (u, v) in pixels: the centre of texel (x, y)
  /// is (x + 0.5, y + 0.5).
  Float4 Sample(float u, float v);
  /// Sample at normalised texture coordinates (s, t) in [0, 1] as a shader passes them:
  /// u = s·W and v = t·H in float32, then as Sample(u, v).
  Float4 SampleNormalized(float s, float t);
  /// Exact read of texel (x, y) with clamp-to-edge: what a bilinear fetch at the texel
  /// centre returns (like texelFetch / FxaaTexTop / FxaaTexOff with integer offsets).
  Float4 Texel(int x, int y);
  /// Number of Sample/Texel calls so far.
  uint64_t Taps() const { return taps_; }
  int Width() const { return img_.Width(); }
  int Height() const { return img_.Height(); }

 private:
  Float4 Fetch(int x, int y) const;
  const Image8& img_;
  SubTexel mode_ = SubTexel::kExact;
  uint64_t taps_ = 0;
};

/// The same filtering for a float RGB(A) image (used by rescaling); no tap counter.
Float4 SampleBilinear(const ImageF& img, float u, float v);

}  // namespace aalab
