/// What the two TAA resolves share (methods/taa.cpp `taa`, methods/taa_production.cpp
/// `taa-prod`): the YCoCg transform both rectify and blend in, and the clip of a history
/// colour toward the centre of the neighbourhood's box. Inline, float32, one expression
/// order (the CUDA twins, methods/cuda/taa_common.cuh, repeat it bit for bit).
#pragma once
#include <algorithm>
#include <cmath>

namespace aalab::taa_detail {

/// A colour in YCoCg (Y = R/4 + G/2 + B/4, Co = (R − B)/2, Cg = −R/4 + G/2 − B/4).
struct Ycc {
  float y, co, cg;
};

/// RGB (3 floats) to YCoCg.
inline Ycc ToYCoCg(const float* rgb) {
  return {0.25f * rgb[0] + 0.5f * rgb[1] + 0.25f * rgb[2], 0.5f * rgb[0] - 0.5f * rgb[2],
          -0.25f * rgb[0] + 0.5f * rgb[1] - 0.25f * rgb[2]};
}

/// YCoCg back to RGB (3 floats).
inline void FromYCoCg(Ycc v, float* rgb) {
  const float t = v.y - v.cg;
  rgb[0] = t + v.co;
  rgb[1] = v.y + v.cg;
  rgb[2] = t - v.co;
}

/// Adds the neighbour `v` to the box statistics of the 3×3 neighbourhood: per channel the
/// minimum, maximum, sum and sum of squares.
inline void AddToBox(Ycc v, float* mn, float* mx, float* m1, float* m2) {
  const float a[3] = {v.y, v.co, v.cg};
  for (int c = 0; c < 3; ++c) {
    mn[c] = std::min(mn[c], a[c]);
    mx[c] = std::max(mx[c], a[c]);
    m1[c] += a[c];
    m2[c] += a[c] * a[c];
  }
}

/// Variance clipping (Salvi 2016): narrows the min/max box [mn, mx] of 9 samples (sums m1,
/// m2) to its intersection with μ ± γσ.
inline void NarrowToVariance(float* mn, float* mx, const float* m1, const float* m2, float gamma) {
  for (int c = 0; c < 3; ++c) {
    const float mu = m1[c] / 9.0f;
    const float sigma = std::sqrt(std::fabs(m2[c] / 9.0f - mu * mu));
    mn[c] = std::max(mn[c], mu - gamma * sigma);
    mx[c] = std::min(mx[c], mu + gamma * sigma);
  }
}

/// Moves `h` toward the centre of [lo, hi] until it lies inside the box (component-wise
/// box in YCoCg), along the line to the centre (Playdead's clip_aabb); each extent + 1e-8, so
/// a flat box does not divide by zero.
inline Ycc ClipToBox(Ycc h, const float* lo, const float* hi) {
  const float hv[3] = {h.y, h.co, h.cg};
  float centre[3], v[3], m = 0.0f;
  for (int c = 0; c < 3; ++c) {
    centre[c] = 0.5f * (hi[c] + lo[c]);
    const float ext = 0.5f * (hi[c] - lo[c]) + 1e-8f;
    v[c] = hv[c] - centre[c];
    m = std::max(m, std::fabs(v[c] / ext));
  }
  if (m <= 1.0f) return h;
  return {centre[0] + v[0] / m, centre[1] + v[1] / m, centre[2] + v[2] / m};
}

}  // namespace aalab::taa_detail
