// SMAA 1x pixel shaders of passes 2 and 3, statement by statement as SMAA.hlsl (internal to
// methods/smaa*.cpp). Pass 2 is a template over the edge-texture reader so that the plain
// implementation (BilinearSampler on the RGBA8 edge texture) and the production path (a
// reader of the same bytes doing the same float operations) run one definition of the
// shader; everything else (which pixels run, data layout, pass 1, skipping) is per path.
// Names follow the shader. mad(a, b, c) is written a * b + c (two roundings; see smaa.cpp).
// The CUDA twin (methods/cuda/smaa.cu) compiles the same WeightsShader and BlendColor with
// device readers: every AALAB_HD function here runs on both sides, so the GPU's software-
// filter mode and the CPU share one text (the math helpers below pick the device intrinsic
// of the same IEEE operation under nvcc: rintf, fabsf, sqrtf, fminf/fmaxf).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/color.h"
#include "core/host_device.h"
#include "core/sampler.h"
#include "methods/smaa.h"

namespace aalab::smaa_detail {

struct F2 {
  float x = 0, y = 0;
};

// HLSL round(): round to nearest, ties to even (the round_ne instruction it compiles to).
AALAB_HD inline float Round(float v) {
#ifdef __CUDA_ARCH__
  return rintf(v);
#else
  return std::nearbyint(v);
#endif
}
AALAB_HD inline float Abs(float v) {
#ifdef __CUDA_ARCH__
  return fabsf(v);
#else
  return std::fabs(v);
#endif
}
AALAB_HD inline float Sqrt(float v) {  // correctly rounded on both sides (nvcc's default -prec-sqrt)
#ifdef __CUDA_ARCH__
  return sqrtf(v);
#else
  return std::sqrt(v);
#endif
}
// saturate(); the weights are never NaN (their inputs are 8-bit fetches).
AALAB_HD inline float Saturate(float v) {
#ifdef __CUDA_ARCH__
  return fminf(fmaxf(v, 0.0f), 1.0f);
#else
  return std::clamp(v, 0.0f, 1.0f);
#endif
}
AALAB_HD inline float Max(float a, float b) {
#ifdef __CUDA_ARCH__
  return fmaxf(a, b);
#else
  return std::max(a, b);
#endif
}

// The render-target metrics SMAA_RT_METRICS = (1/W, 1/H, W, H) and a pixel's texcoord.
struct Frame {
  float W = 0, H = 0, rx = 0, ry = 0;
  AALAB_HD Frame(int w, int h)
      : W(static_cast<float>(w)),
        H(static_cast<float>(h)),
        rx(1.0f / static_cast<float>(w)),
        ry(1.0f / static_cast<float>(h)) {}
  AALAB_HD F2 Texcoord(int x, int y) const {
    return {(static_cast<float>(x) + 0.5f) / W, (static_cast<float>(y) + 0.5f) / H};
  }
};

// The edge-texture reader of the plain path: BilinearSampler on the RGBA8 edge texture,
// returning (r, g) at texel-space (u, v).
class SamplerEdges {
 public:
  explicit SamplerEdges(BilinearSampler& s) : s_(s) {}
  F2 Sample(float u, float v) {
    const Float4 t = s_.Sample(u, v);
    return {t.r, t.g};
  }

 private:
  BilinearSampler& s_;
};

// SMAABlendingWeightCalculationPS with its search, area and corner functions, for one
// pixel. E: an edge reader as above; T: BilinearSampler (or a reader with the same
// SampleNormalized, operation for operation) on SmaaAreaTexture() and SmaaSearchTexture();
// P: SmaaParams, or the CUDA twin's SmaaArgs (the same fields read here).
template <class E, class T = BilinearSampler, class P = SmaaParams>
class WeightsShader {
 public:
  AALAB_HD WeightsShader(E& edges, T& area, T& search, const P& p, const Frame& f)
      : edges_(edges), area_(area), search_(search), p_(p), f_(f) {}

  // Returns the four weights (r, g, b, a) of pixel (x, y), before the 8-bit store.
  AALAB_HD Float4 Run(int x, int y) {
    const float rx = f_.rx, ry = f_.ry;
    const F2 tc = f_.Texcoord(x, y);
    const F2 pix{tc.x * f_.W, tc.y * f_.H};
    // SMAABlendingWeightCalculationVS.
    const float o0x = rx * -0.25f + tc.x, o0y = ry * -0.125f + tc.y, o0z = rx * 1.25f + tc.x, o0w = ry * -0.125f + tc.y;
    const float o1x = rx * -0.125f + tc.x, o1y = ry * -0.25f + tc.y, o1z = rx * -0.125f + tc.x, o1w = ry * 1.25f + tc.y;
    const float n = static_cast<float>(p_.max_search_steps);
    const float o2x = rx * (-2.0f * n) + o0x, o2y = rx * (2.0f * n) + o0z;
    const float o2z = ry * (-2.0f * n) + o1y, o2w = ry * (2.0f * n) + o1w;

    Float4 w{0, 0, 0, 0};
    F2 e = Ed(tc.x, tc.y);
    if (e.y > 0.0f) {  // edge at north
      bool ortho = true;
      if (p_.diag) {
        const F2 dw = DiagWeights(tc, e);
        w.r = dw.x;
        w.g = dw.y;
        ortho = w.r == -w.g;
      }
      if (ortho) {
        const float cx = SearchXLeft(o0x, o0y, o2x);
        float cy = o1y;
        F2 d{cx, 0};
        const float e1 = Ed(cx, cy).x;
        const float cz = SearchXRight(o0z, o0w, o2y);
        d.y = cz;
        d.x = Abs(Round(f_.W * d.x + -pix.x));
        d.y = Abs(Round(f_.W * d.y + -pix.x));
        const F2 sq{Sqrt(d.x), Sqrt(d.y)};
        const float e2 = EdOff(cz, cy, 1.0f, 0.0f).x;
        const F2 a = Area(sq, e1, e2);
        w.r = a.x;
        w.g = a.y;
        cy = tc.y;
        if (p_.corner) HorizontalCorner(&w.r, &w.g, cx, cy, cz, cy, d);
      } else {
        e.x = 0.0f;  // skip vertical processing
      }
    }
    if (e.x > 0.0f) {  // edge at west
      const float cy = SearchYUp(o1x, o1y, o2z);
      float cx = o0x;
      F2 d{cy, 0};
      const float e1 = Ed(cx, cy).y;
      const float cz = SearchYDown(o1z, o1w, o2w);
      d.y = cz;
      d.x = Abs(Round(f_.H * d.x + -pix.y));
      d.y = Abs(Round(f_.H * d.y + -pix.y));
      const F2 sq{Sqrt(d.x), Sqrt(d.y)};
      const float e2 = EdOff(cx, cz, 0.0f, 1.0f).y;
      const F2 a = Area(sq, e1, e2);
      w.b = a.x;
      w.a = a.y;
      cx = tc.x;
      if (p_.corner) VerticalCorner(&w.b, &w.a, cx, cy, cx, cz, d);
    }
    return w;
  }

 private:
  // SMAASampleLevelZero(edgesTex, (s, t)) and SMAASampleLevelZeroOffset(..., int2(dx, dy)):
  // the integer offset is added in texel space.
  AALAB_HD F2 Ed(float s, float t) { return edges_.Sample(s * f_.W, t * f_.H); }
  AALAB_HD F2 EdOff(float s, float t, float dx, float dy) { return edges_.Sample(s * f_.W + dx, t * f_.H + dy); }

  AALAB_HD static F2 Decode(F2 e) {  // SMAADecodeDiagBilinearAccess(float2)
    e.x = e.x * Abs(5.0f * e.x - 5.0f * 0.75f);
    return {Round(e.x), Round(e.y)};
  }

  // SMAASearchDiag1 / SMAASearchDiag2: returns coord.zw, writes the last fetch to `end`.
  AALAB_HD F2 SearchDiag(bool second, F2 tc, float dirx, float diry, F2* end) {
    float cx = tc.x, cy = tc.y, cz = -1.0f, cw = 1.0f;
    if (second) cx += 0.25f * f_.rx;
    const float limit = static_cast<float>(p_.max_search_steps_diag - 1);
    while (cz < limit && cw > 0.9f) {
      cx = f_.rx * dirx + cx;
      cy = f_.ry * diry + cy;
      cz = 1.0f * 1.0f + cz;
      F2 e = Ed(cx, cy);
      if (second) e = Decode(e);
      *end = e;
      cw = e.x * 0.5f + e.y * 0.5f;
    }
    return {cz, cw};
  }

  AALAB_HD F2 AreaDiag(F2 dist, F2 e) {  // SMAAAreaDiag, subsample offset 0
    const float px = 1.0f / 160.0f, py = 1.0f / 560.0f;
    float tx = 20.0f * e.x + dist.x;
    float ty = 20.0f * e.y + dist.y;
    tx = px * tx + 0.5f * px;
    ty = py * ty + 0.5f * py;
    tx += 0.5f;
    ty += (1.0f / 7.0f) * 0.0f;
    const Float4 a = area_.SampleNormalized(tx, ty);
    return {a.r, a.g};
  }

  AALAB_HD F2 DiagWeights(F2 tc, F2 e) {  // SMAACalculateDiagWeights
    const float rx = f_.rx, ry = f_.ry;
    F2 weights{0, 0};
    F2 end{0, 0};  // an HLSL out value the loop always writes for max_search_steps_diag >= 1
    float dx, dy, dz, dw;
    if (e.x > 0.0f) {
      const F2 r = SearchDiag(false, tc, -1.0f, 1.0f, &end);
      dx = r.x;
      dz = r.y;
      dx += end.y > 0.9f ? 1.0f : 0.0f;
    } else {
      dx = 0.0f;
      dz = 0.0f;
    }
    {
      const F2 r = SearchDiag(false, tc, 1.0f, -1.0f, &end);
      dy = r.x;
      dw = r.y;
    }
    if (dx + dy > 2.0f) {
      const float c0x = (-dx + 0.25f) * rx + tc.x, c0y = dx * ry + tc.y;
      const float c1x = dy * rx + tc.x, c1y = (-dy - 0.25f) * ry + tc.y;
      const F2 a = EdOff(c0x, c0y, -1.0f, 0.0f);
      const F2 b = EdOff(c1x, c1y, 1.0f, 0.0f);
      // c.yxwz = SMAADecodeDiagBilinearAccess(c.xyzw): r and b of (a.x, a.y, b.x, b.y).
      const F2 da = Decode(F2{a.x, a.y});
      const F2 db = Decode(F2{b.x, b.y});
      const float cx = da.y, cy = da.x, cz = db.y, cw = db.x;
      F2 cc{2.0f * cx + cy, 2.0f * cz + cw};
      if (dz >= 0.9f) cc.x = 0.0f;  // SMAAMovc(bool2(step(0.9, d.zw)), cc, 0)
      if (dw >= 0.9f) cc.y = 0.0f;
      const F2 ar = AreaDiag({dx, dy}, cc);
      weights.x += ar.x;
      weights.y += ar.y;
    }
    {
      const F2 r = SearchDiag(true, tc, -1.0f, -1.0f, &end);
      dx = r.x;
      dz = r.y;
    }
    if (EdOff(tc.x, tc.y, 1.0f, 0.0f).x > 0.0f) {
      const F2 r = SearchDiag(true, tc, 1.0f, 1.0f, &end);
      dy = r.x;
      dw = r.y;
      dy += end.y > 0.9f ? 1.0f : 0.0f;
    } else {
      dy = 0.0f;
      dw = 0.0f;
    }
    if (dx + dy > 2.0f) {
      const float c0x = -dx * rx + tc.x, c0y = -dx * ry + tc.y;
      const float c1x = dy * rx + tc.x, c1y = dy * ry + tc.y;
      const float cx = EdOff(c0x, c0y, -1.0f, 0.0f).y;
      const float cy = EdOff(c0x, c0y, 0.0f, -1.0f).x;
      const F2 b = EdOff(c1x, c1y, 1.0f, 0.0f);
      const float cz = b.y, cw = b.x;
      F2 cc{2.0f * cx + cy, 2.0f * cz + cw};
      if (dz >= 0.9f) cc.x = 0.0f;
      if (dw >= 0.9f) cc.y = 0.0f;
      const F2 ar = AreaDiag({dx, dy}, cc);
      weights.x += ar.y;  // .gr
      weights.y += ar.x;
    }
    return weights;
  }

  AALAB_HD float SearchLength(F2 e, float offset) {  // SMAASearchLength
    float sx = 66.0f * 0.5f, sy = 33.0f * -1.0f;
    float bx = 66.0f * offset, by = 33.0f * 1.0f;
    sx += -1.0f;
    sy += 1.0f;
    bx += 0.5f;
    by += -0.5f;
    sx *= 1.0f / 64.0f;
    sy *= 1.0f / 16.0f;
    bx *= 1.0f / 64.0f;
    by *= 1.0f / 16.0f;
    return search_.SampleNormalized(sx * e.x + bx, sy * e.y + by).r;
  }

  AALAB_HD float SearchXLeft(float tx, float ty, float end) {
    F2 e{0.0f, 1.0f};
    while (tx > end && e.y > 0.8281f && e.x == 0.0f) {
      e = Ed(tx, ty);
      tx = -2.0f * f_.rx + tx;
    }
    const float offset = -(255.0f / 127.0f) * SearchLength(e, 0.0f) + 3.25f;
    return f_.rx * offset + tx;
  }
  AALAB_HD float SearchXRight(float tx, float ty, float end) {
    F2 e{0.0f, 1.0f};
    while (tx < end && e.y > 0.8281f && e.x == 0.0f) {
      e = Ed(tx, ty);
      tx = 2.0f * f_.rx + tx;
    }
    const float offset = -(255.0f / 127.0f) * SearchLength(e, 0.5f) + 3.25f;
    return -f_.rx * offset + tx;
  }
  AALAB_HD float SearchYUp(float tx, float ty, float end) {
    F2 e{1.0f, 0.0f};
    while (ty > end && e.x > 0.8281f && e.y == 0.0f) {
      e = Ed(tx, ty);
      ty = -2.0f * f_.ry + ty;
    }
    const float offset = -(255.0f / 127.0f) * SearchLength(F2{e.y, e.x}, 0.0f) + 3.25f;
    return f_.ry * offset + ty;
  }
  AALAB_HD float SearchYDown(float tx, float ty, float end) {
    F2 e{1.0f, 0.0f};
    while (ty < end && e.x > 0.8281f && e.y == 0.0f) {
      e = Ed(tx, ty);
      ty = 2.0f * f_.ry + ty;
    }
    const float offset = -(255.0f / 127.0f) * SearchLength(F2{e.y, e.x}, 0.5f) + 3.25f;
    return -f_.ry * offset + ty;
  }

  AALAB_HD F2 Area(F2 dist, float e1, float e2) {  // SMAAArea, subsample offset 0
    const float px = 1.0f / 160.0f, py = 1.0f / 560.0f;
    float tx = 16.0f * Round(4.0f * e1) + dist.x;
    float ty = 16.0f * Round(4.0f * e2) + dist.y;
    tx = px * tx + 0.5f * px;
    ty = py * ty + 0.5f * py;
    ty = (1.0f / 7.0f) * 0.0f + ty;
    const Float4 a = area_.SampleNormalized(tx, ty);
    return {a.r, a.g};
  }

  AALAB_HD float RoundingNorm() const { return static_cast<float>(p_.corner_rounding) / 100.0f; }

  AALAB_HD void HorizontalCorner(float* wx, float* wy, float tx, float ty, float tz, float tw, F2 d) {
    const F2 lr{d.y >= d.x ? 1.0f : 0.0f, d.x >= d.y ? 1.0f : 0.0f};  // step(d.xy, d.yx)
    const float k = 1.0f - RoundingNorm();
    F2 rounding{k * lr.x, k * lr.y};
    const float s = lr.x + lr.y;
    rounding.x /= s;
    rounding.y /= s;
    F2 factor{1.0f, 1.0f};
    factor.x -= rounding.x * EdOff(tx, ty, 0.0f, 1.0f).x;
    factor.x -= rounding.y * EdOff(tz, tw, 1.0f, 1.0f).x;
    factor.y -= rounding.x * EdOff(tx, ty, 0.0f, -2.0f).x;
    factor.y -= rounding.y * EdOff(tz, tw, 1.0f, -2.0f).x;
    *wx *= Saturate(factor.x);
    *wy *= Saturate(factor.y);
  }
  AALAB_HD void VerticalCorner(float* wx, float* wy, float tx, float ty, float tz, float tw, F2 d) {
    const F2 lr{d.y >= d.x ? 1.0f : 0.0f, d.x >= d.y ? 1.0f : 0.0f};
    const float k = 1.0f - RoundingNorm();
    F2 rounding{k * lr.x, k * lr.y};
    const float s = lr.x + lr.y;
    rounding.x /= s;
    rounding.y /= s;
    F2 factor{1.0f, 1.0f};
    factor.x -= rounding.x * EdOff(tx, ty, 1.0f, 0.0f).y;
    factor.x -= rounding.y * EdOff(tz, tw, 1.0f, 1.0f).y;
    factor.y -= rounding.x * EdOff(tx, ty, -2.0f, 0.0f).y;
    factor.y -= rounding.y * EdOff(tz, tw, -2.0f, 1.0f).y;
    *wx *= Saturate(factor.x);
    *wy *= Saturate(factor.y);
  }

  E& edges_;
  T& area_;
  T& search_;
  const P& p_;
  const Frame& f_;
};

// SMAANeighborhoodBlendingPS for pixel (x, y) from its four weights a = (right.a,
// bottom.g, own.b, own.r) as the shader fetches them (BlendPixelColor below): color = the
// input frame through BilinearSampler (or a reader with the same SampleNormalized). Returns
// the blended colour before the 8-bit store (rgb; a unused).
template <class T>
AALAB_HD Float4 BlendColor(const float a[4], T& color, const Frame& f, int x, int y) {
  const F2 tc = f.Texcoord(x, y);
  Float4 c;
  if (((a[0] + a[1]) + a[2]) + a[3] < 1e-5f) {
    c = color.SampleNormalized(tc.x, tc.y);
  } else {
    const bool h = Max(a[0], a[2]) > Max(a[1], a[3]);
    float bo[4] = {0.0f, a[1], 0.0f, a[3]};
    float bw[2] = {a[1], a[3]};
    if (h) {
      bo[0] = a[0], bo[1] = 0.0f, bo[2] = a[2], bo[3] = 0.0f;
      bw[0] = a[0], bw[1] = a[2];
    }
    const float sum = bw[0] * 1.0f + bw[1] * 1.0f;
    bw[0] /= sum;
    bw[1] /= sum;
    const float c0x = bo[0] * f.rx + tc.x, c0y = bo[1] * f.ry + tc.y;
    const float c1x = bo[2] * -f.rx + tc.x, c1y = bo[3] * -f.ry + tc.y;
    const Float4 p = color.SampleNormalized(c0x, c0y);
    const Float4 q = color.SampleNormalized(c1x, c1y);
    c.r = bw[0] * p.r + bw[1] * q.r;
    c.g = bw[0] * p.g + bw[1] * q.g;
    c.b = bw[0] * p.b + bw[1] * q.b;
  }
  return c;
}

// The whole pixel shader: the three blend-texture fetches (SMAANeighborhoodBlendingVS's
// offsets), then BlendColor. blend = the RGBA8 blend texture.
template <class T>
AALAB_HD Float4 BlendPixelColor(T& blend, T& color, const Frame& f, int x, int y) {
  const F2 tc = f.Texcoord(x, y);
  const float ox = f.rx * 1.0f + tc.x, oy = f.ry * 0.0f + tc.y;
  const float oz = f.rx * 0.0f + tc.x, ow = f.ry * 1.0f + tc.y;
  float a[4];
  a[0] = blend.SampleNormalized(ox, oy).a;  // right
  a[1] = blend.SampleNormalized(oz, ow).g;  // bottom pixel's top edge
  const Float4 own = blend.SampleNormalized(tc.x, tc.y);
  a[3] = own.r;
  a[2] = own.b;
  return BlendColor(a, color, f, x, y);
}

// The CPU's store of a blended pixel: rgb rounded to 8 bits, alpha 255.
inline void StoreBlended(const Float4& c, uint8_t* out) {
  out[0] = QuantizeUnorm8(c.r);
  out[1] = QuantizeUnorm8(c.g);
  out[2] = QuantizeUnorm8(c.b);
  out[3] = 255;
}

// BlendColor, stored.
template <class T>
void BlendWithWeights(const float a[4], T& color, const Frame& f, int x, int y, uint8_t* out) {
  StoreBlended(BlendColor(a, color, f, x, y), out);
}

// BlendPixelColor, stored.
template <class T>
void BlendPixel(T& blend, T& color, const Frame& f, int x, int y, uint8_t* out) {
  StoreBlended(BlendPixelColor(blend, color, f, x, y), out);
}

}  // namespace aalab::smaa_detail
