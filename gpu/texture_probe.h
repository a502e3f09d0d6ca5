/// A measurement of the texture unit's bilinear weights: how finely the hardware resolves
/// the sub-texel fraction, which is what makes GPU and CPU post-filter outputs differ.
#pragma once
#include <string>

namespace aalab {

/// Result of ProbeTextureFilter, errors in 8-bit code units (1/255).
struct TextureProbe {
  int samples = 0;            ///< fractions probed: f = i/4096, i = 0..4096
  double err_float = 0;       ///< max |GPU − lerp with the float32 fraction| (the CPU model)
  double err_round256 = 0;    ///< max |GPU − lerp with the fraction rounded to 1/256|
  double err_trunc256 = 0;    ///< max |GPU − lerp with the fraction truncated to 1/256|
  int distinct_values = 0;    ///< distinct filtered values seen between texels 0 and 255
  int unorm_mismatches = 0;   ///< point fetches of k = 0..255 whose float is not k / 255.0f
  int unorm_mismatches_cpu = 0;  ///< ... whose float is not the CPU's UnormToFloat(k) = k·fl(1/255)
  int half_pairs = 0;         ///< texel pairs (a, b) fetched halfway between their centres
  int half_mismatches = 0;    ///< of those, results that differ from the CPU sampler's (float32)
  double half_max_err = 0;    ///< their largest |difference| (float units, not levels)
};

/// Samples a 2×1 RGBA8 texture holding 0 and 255 (red) through a bilinear, unnormalised view
/// at u = 0.5 + i/4096 and compares with the three weight models; then point-fetches all 256
/// UNORM8 values, and fetches every pair (a, b) halfway between the two texels, against the
/// CPU sampler's float32 arithmetic. Throws on a CUDA error.
TextureProbe ProbeTextureFilter();

}  // namespace aalab
