// FXAA 3.11 production path internals (methods/fxaa311_fast.cpp only): the luma plane and
// the shader's 3x3 tap footprints. Not part of the methods API.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

#include "core/image.h"
#include "core/sampler.h"
#include "methods/fxaa311.h"

namespace aalab::fxaa311_internal {

using Luma = Fxaa311Params::Luma;

// The texel value as BilinearSampler::Fetch reads it.
inline float Unorm(uint8_t k) { return UnormToFloat(k); }
inline float LumaValue(uint8_t k) { return Unorm(k); }
inline float LumaValue(float v) { return v; }

// A luma plane: one value per pixel, row-major; P = uint8_t (value k means UnormToFloat(k))
// or float.
template <typename P>
struct LumaPlane {
  int w = 0, h = 0;
  std::unique_ptr<P[]> v;  // w·h values, left uninitialised until BuildPlane writes them
  const P* Row(int y) const { return v.get() + static_cast<size_t>(y) * w; }
  // Texel read with clamp-to-edge (BilinearSampler::Fetch), as a luma.
  [[gnu::always_inline]] float Texel(int x, int y) const {
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return LumaValue(v[static_cast<size_t>(y) * w + x]);
  }
  // The 2×2 block of footprint `f` blended (BilinearBlend of the four clamped texels): two
  // row and two column clamps for the four reads.
  [[gnu::always_inline]] float Blend(const BilinearFootprint& f) const {
    const int xa = std::clamp(f.x0, 0, w - 1), xb = std::clamp(f.x0 + 1, 0, w - 1);
    const P* ra = Row(std::clamp(f.y0, 0, h - 1));
    const P* rb = Row(std::clamp(f.y0 + 1, 0, h - 1));
    return BilinearBlend(LumaValue(ra[xa]), LumaValue(ra[xb]), LumaValue(rb[xa]), LumaValue(rb[xb]), f);
  }
  // The luma channel of BilinearSampler::SampleNormalized(s, t), operation for operation.
  [[gnu::always_inline]] float Bilinear(float s, float t) const {
    return Blend(BilinearAt(s * static_cast<float>(w), t * static_cast<float>(h), w, h));
  }
};

// The rgb of BilinearSampler::Sample's blend over footprint `f` on `img` (Fetch's clamp and
// UnormToFloat, BilinearBlend), without the alpha channel.
inline void BlendRgb(const Image8& img, const BilinearFootprint& f, float rgb[3]) {
  const int W = img.Width(), H = img.Height();
  const int xa = std::clamp(f.x0, 0, W - 1), xb = std::clamp(f.x0 + 1, 0, W - 1);
  const int ya = std::clamp(f.y0, 0, H - 1), yb = std::clamp(f.y0 + 1, 0, H - 1);
  const uint8_t *ra = img.Row(ya), *rb = img.Row(yb);
  const uint8_t *a = ra + 4 * xa, *b = ra + 4 * xb, *c = rb + 4 * xa, *d = rb + 4 * xb;
  for (int k = 0; k < 3; ++k) rgb[k] = BilinearBlend(Unorm(a[k]), Unorm(b[k]), Unorm(c[k]), Unorm(d[k]), f);
}

// The rgb of BilinearSampler::SampleNormalized(s, t) on `img`.
inline void FinalTap(const Image8& img, float s, float t, float rgb[3]) {
  const int W = img.Width(), H = img.Height();
  BlendRgb(img, BilinearAt(s * static_cast<float>(W), t * static_cast<float>(H), W, H), rgb);
}

// The footprints of a pixel's 3×3 taps along one axis (columns: x, rows: y). The shader
// fetches them at pixel-centre coordinates plus offsets: texture2D(tex, posM + off·rcp)
// in FXAA 3.11 (seed 004), textureLodOffset in seed 003. The coordinate is rounded to float
// on the way, so a tap may land a hair off the texel centre (fraction ~1e-6, or ~1 − 1e-6
// one texel back) and then filters in a bit of the neighbour: ~40% of the columns of a
// 1920-wide frame. An axis is `exact` when every fraction is 0 (the taps are the texels).
struct TapAxis {
  int i[3] = {0, 0, 0};  // x0 (or y0) of offsets -1, 0, +1
  float f[3] = {0, 0, 0};
  bool exact = true;
};

struct TapGrid {
  std::vector<TapAxis> cols, rows;
  float deviation = 0.0f;  // bound on |tap luma − texel luma| over every tap of the frame
};

inline TapAxis MakeAxis(int p, int n, bool glsl) {
  const float pos = (static_cast<float>(p) + 0.5f) / static_cast<float>(n);  // posM
  const float rcp = 1.0f / static_cast<float>(n);
  TapAxis a;
  for (int d = -1; d <= 1; ++d) {
    const float u = glsl ? pos * static_cast<float>(n) + static_cast<float>(d)
                         : (pos + static_cast<float>(d) * rcp) * static_cast<float>(n);
    const BilinearFootprint f = BilinearAt(u, 0.5f, n, 1);
    a.i[d + 1] = f.x0;
    a.f[d + 1] = f.fx;
    a.exact = a.exact && f.fx == 0.0f;
  }
  return a;
}

inline TapGrid MakeTapGrid(int w, int h, bool glsl) {
  TapGrid g;
  float dev_x = 0.0f, dev_y = 0.0f;
  g.cols.resize(static_cast<size_t>(w));
  g.rows.resize(static_cast<size_t>(h));
  for (int x = 0; x < w; ++x) {
    g.cols[x] = MakeAxis(x, w, glsl);
    for (float f : g.cols[x].f) dev_x = std::max(dev_x, std::min(f, 1.0f - f));
  }
  for (int y = 0; y < h; ++y) {
    g.rows[y] = MakeAxis(y, h, glsl);
    for (float f : g.rows[y].f) dev_y = std::max(dev_y, std::min(f, 1.0f - f));
  }
  // Lumas lie in [0, 1]: a lerp towards a neighbour by a fraction f (or back from one by
  // 1 − f) moves the value by at most that fraction, plus a few float roundings.
  g.deviation = dev_x + dev_y + 1e-6f;
  return g;
}

// The luma of the tap at offset (dx, dy) of pixel (cx, ry), as ShadePixel fetches it: the
// luma channel of the filtered prepared frame (alpha / green planes), or the luma of the
// filtered rgb (rec601-rgb). Exact taps read the plane.
template <typename P>
[[gnu::always_inline]] inline float TapLuma(const LumaPlane<P>& pl, const Image8& src, const TapAxis& cx,
                                            const TapAxis& ry, int x, int y, int dx, int dy, Luma luma) {
  const float fx = cx.f[dx + 1], fy = ry.f[dy + 1];
  BilinearFootprint f;
  f.x0 = cx.i[dx + 1];
  f.y0 = ry.i[dy + 1];
  f.fx = fx;
  f.fy = fy;
  (void)x;
  (void)y;
  if constexpr (std::is_same_v<P, uint8_t>) {
    // Always the blend, without a branch on the column's and row's pattern (which a branch
    // predictor misses): with fx = fy = 0 it returns the texel exactly (a + 0·(b − a) = a).
    (void)src;
    (void)luma;
    return pl.Blend(f);
  }
  if (fx == 0.0f && fy == 0.0f) return pl.Texel(f.x0, f.y0);
  float rgb[3];  // float plane (rec601-rgb): the luma of the filtered rgb
  BlendRgb(src, f, rgb);
  return Fxaa311TapLuma(Float4{rgb[0], rgb[1], rgb[2], 0.0f}, luma);
}

// The shader's early-exit test with the real taps, for pixels whose taps are not all
// exact and whose texel lumas put the test within the grid's deviation of a tie: true
// when the pixel goes on (passes the test and has range > 0).
template <typename P>
bool EdgeByTaps(const LumaPlane<P>& pl, const Image8& src, const TapGrid& g, int x, int y, const Fxaa311Params& prm) {
  const TapAxis& cx = g.cols[x];
  const TapAxis& ry = g.rows[y];
  auto L = [&](int dx, int dy) __attribute__((always_inline)) {
    return TapLuma(pl, src, cx, ry, x, y, dx, dy, prm.luma);
  };
  const float lumaM = L(0, 0), lumaS = L(0, 1), lumaE = L(1, 0), lumaN = L(0, -1), lumaW = L(-1, 0);
  const float rangeMax = std::max(std::max(lumaN, lumaW), std::max(lumaE, std::max(lumaS, lumaM)));
  const float rangeMin = std::min(std::min(lumaN, lumaW), std::min(lumaE, std::min(lumaS, lumaM)));
  const float range = rangeMax - rangeMin;
  const float clamped = std::max(prm.edge_threshold_min, rangeMax * prm.edge_threshold);
  return !(range < clamped) && range != 0.0f;
}

}  // namespace aalab::fxaa311_internal
