// SMAA 1x (methods/smaa.cpp, smaa_shader.h) as three CUDA kernels, one thread per pixel:
//   smaa-edges    SMAALumaEdgeDetectionPS / SMAAColorEdgeDetectionPS: point fetches of the
//                 frame, an RGBA8 edge target (r = left, g = top, 0 or 255; b = a = 0, and 0
//                 everywhere where the shader discards: the target is cleared first);
//   smaa-weights  SMAABlendingWeightCalculationPS: bilinear fetches of the edge target in
//                 texel coordinates (SMAASampleLevelZero(Offset) on s·W + dx), of the area
//                 texture (160×560) and the search texture (64×16) in normalised coordinates;
//                 an RGBA8 blend target;
//   smaa-blend    SMAANeighborhoodBlendingPS: bilinear fetches of the blend target and the
//                 frame in normalised coordinates.
// Every expression is the CPU's (smaa_shader.h), in float32 and its order, built with
// --fmad=false as the CPU build has -ffp-contract=off. The hardware path filters in the
// texture unit; kSoft = true replaces every fetch by the CPU's BilinearSampler arithmetic
// (UnormToFloat texels, the sub-texel mode of the method: 8-bit fractions by default) from
// point fetches, which reproduces the CPU bit for bit (gpu tool's software-filter check).
// The edge and blend targets are whole-frame RGBA8 cudaArrays (the reference's RG8/RGBA8
// render targets widened to RGBA8: same values, one texture format for every frame here).
#include "methods/cuda/device_ops.cuh"
#include "methods/cuda/post_filters_cuda.h"

namespace aalab::cuda {
namespace {

// BilinearAt (core/sampler.h) + BilinearBlend from four point fetches: the CPU's
// BilinearSampler::Sample at texel coordinates (u, v), fixed8 = SubTexel::kFixed8.
__device__ __forceinline__ float4 SoftSample(cudaTextureObject_t point, float u, float v, int w, int h, bool fixed8) {
  const float x = u - 0.5f;
  const float y = v - 0.5f;
  float x0f = floorf(x);
  float y0f = floorf(y);
  float fx = x - x0f;
  float fy = y - y0f;
  if (fixed8) {
    fx = rintf(fx * 256.0f) * (1.0f / 256.0f);
    fy = rintf(fy * 256.0f) * (1.0f / 256.0f);
    if (fx == 1.0f) {
      x0f += 1.0f;
      fx = 0.0f;
    }
    if (fy == 1.0f) {
      y0f += 1.0f;
      fy = 0.0f;
    }
  }
  return SoftBlendAt(point, x0f, y0f, fx, fy, w, h);
}

// One texture as the shader reads it: the texture unit or SoftSample.
struct Tex {
  cudaTextureObject_t point, lin_px, lin_norm;
  int w, h;
};

template <bool kSoft>
__device__ __forceinline__ float4 SamplePx(const Tex& t, float u, float v, bool fixed8) {
  if constexpr (kSoft) {
    return SoftSample(t.point, u, v, t.w, t.h, fixed8);
  } else {
    return tex2D<float4>(t.lin_px, u, v);
  }
}

// SampleNormalized: u = s·W, v = t·H in float32 (soft); the texture unit takes (s, t).
template <bool kSoft>
__device__ __forceinline__ float4 SampleNorm(const Tex& t, float s, float tt, bool fixed8) {
  if constexpr (kSoft) {
    return SoftSample(t.point, s * static_cast<float>(t.w), tt * static_cast<float>(t.h), t.w, t.h, fixed8);
  } else {
    return tex2D<float4>(t.lin_norm, s, tt);
  }
}

__device__ __forceinline__ float Luma(float4 c) { return (c.x * 0.2126f + c.y * 0.7152f) + c.z * 0.0722f; }

__device__ __forceinline__ float MaxAbsDiff(float4 a, float4 b) {
  return fmaxf(fmaxf(fabsf(a.x - b.x), fabsf(a.y - b.y)), fabsf(a.z - b.z));
}

// ---------------------------------------------------------------------------------- pass 1

template <bool kSoft>
__global__ void EdgesKernel(cudaTextureObject_t pt, cudaSurfaceObject_t out, int w, int h, SmaaArgs p) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= w || y >= h) return;
  const float thr = p.threshold;
  float dx, dy, mx, my, ex, ey;
  if (!p.color) {
    const float L = Luma(Texel<kSoft>(pt, x, y));
    const float Lleft = Luma(Texel<kSoft>(pt, x - 1, y));
    const float Ltop = Luma(Texel<kSoft>(pt, x, y - 1));
    dx = fabsf(L - Lleft);
    dy = fabsf(L - Ltop);
    ex = dx >= thr ? 1.0f : 0.0f;
    ey = dy >= thr ? 1.0f : 0.0f;
    if (ex * 1.0f + ey * 1.0f == 0.0f) {
      surf2Dwrite(make_uchar4(0, 0, 0, 0), out, x * 4, y);
      return;
    }
    const float Lright = Luma(Texel<kSoft>(pt, x + 1, y));
    const float Lbottom = Luma(Texel<kSoft>(pt, x, y + 1));
    mx = fmaxf(dx, fabsf(L - Lright));
    my = fmaxf(dy, fabsf(L - Lbottom));
    const float Lleftleft = Luma(Texel<kSoft>(pt, x - 2, y));
    const float Ltoptop = Luma(Texel<kSoft>(pt, x, y - 2));
    mx = fmaxf(mx, fabsf(Lleft - Lleftleft));
    my = fmaxf(my, fabsf(Ltop - Ltoptop));
  } else {
    const float4 C = Texel<kSoft>(pt, x, y);
    dx = MaxAbsDiff(C, Texel<kSoft>(pt, x - 1, y));
    dy = MaxAbsDiff(C, Texel<kSoft>(pt, x, y - 1));
    ex = dx >= thr ? 1.0f : 0.0f;
    ey = dy >= thr ? 1.0f : 0.0f;
    if (ex * 1.0f + ey * 1.0f == 0.0f) {
      surf2Dwrite(make_uchar4(0, 0, 0, 0), out, x * 4, y);
      return;
    }
    mx = fmaxf(dx, MaxAbsDiff(C, Texel<kSoft>(pt, x + 1, y)));
    my = fmaxf(dy, MaxAbsDiff(C, Texel<kSoft>(pt, x, y + 1)));
    mx = fmaxf(mx, MaxAbsDiff(C, Texel<kSoft>(pt, x - 2, y)));
    my = fmaxf(my, MaxAbsDiff(C, Texel<kSoft>(pt, x, y - 2)));
  }
  const float final_delta = fmaxf(mx, my);
  ex *= p.local_contrast * dx >= final_delta ? 1.0f : 0.0f;
  ey *= p.local_contrast * dy >= final_delta ? 1.0f : 0.0f;
  surf2Dwrite(make_uchar4(QuantizeUnorm8(ex), QuantizeUnorm8(ey), 0, 0), out, x * 4, y);
}

// ---------------------------------------------------------------------------------- pass 2

struct F2 {
  float x, y;
};

// smaa_detail::WeightsShader, member for member (names as the shader's).
template <bool kSoft>
struct Weights {
  Tex edges, area, search;
  const SmaaArgs& p;
  float W, H, rx, ry;

  __device__ F2 Ed(float s, float t) const {
    const float4 e = SamplePx<kSoft>(edges, s * W, t * H, p.fixed8);
    return {e.x, e.y};
  }
  __device__ F2 EdOff(float s, float t, float dx, float dy) const {
    const float4 e = SamplePx<kSoft>(edges, s * W + dx, t * H + dy, p.fixed8);
    return {e.x, e.y};
  }
  __device__ static F2 Decode(F2 e) {
    e.x = e.x * fabsf(5.0f * e.x - 5.0f * 0.75f);
    return {rintf(e.x), rintf(e.y)};
  }

  __device__ F2 SearchDiag(bool second, F2 tc, float dirx, float diry, F2* end) const {
    float cx = tc.x, cy = tc.y, cz = -1.0f, cw = 1.0f;
    if (second) cx += 0.25f * rx;
    const float limit = static_cast<float>(p.max_search_steps_diag - 1);
    while (cz < limit && cw > 0.9f) {
      cx = rx * dirx + cx;
      cy = ry * diry + cy;
      cz = 1.0f * 1.0f + cz;
      F2 e = Ed(cx, cy);
      if (second) e = Decode(e);
      *end = e;
      cw = e.x * 0.5f + e.y * 0.5f;
    }
    return {cz, cw};
  }

  __device__ F2 AreaDiag(F2 dist, F2 e) const {
    const float px = 1.0f / 160.0f, py = 1.0f / 560.0f;
    float tx = 20.0f * e.x + dist.x;
    float ty = 20.0f * e.y + dist.y;
    tx = px * tx + 0.5f * px;
    ty = py * ty + 0.5f * py;
    tx += 0.5f;
    ty += (1.0f / 7.0f) * 0.0f;
    const float4 a = SampleNorm<kSoft>(area, tx, ty, p.fixed8);
    return {a.x, a.y};
  }

  __device__ F2 DiagWeights(F2 tc, F2 e) const {
    F2 weights{0, 0};
    F2 end{0, 0};
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
      const F2 da = Decode(a);
      const F2 db = Decode(b);
      const float cx = da.y, cy = da.x, cz = db.y, cw = db.x;
      F2 cc{2.0f * cx + cy, 2.0f * cz + cw};
      if (dz >= 0.9f) cc.x = 0.0f;
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
      weights.x += ar.y;
      weights.y += ar.x;
    }
    return weights;
  }

  __device__ float SearchLength(F2 e, float offset) const {
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
    return SampleNorm<kSoft>(search, sx * e.x + bx, sy * e.y + by, p.fixed8).x;
  }

  __device__ float SearchXLeft(float tx, float ty, float end) const {
    F2 e{0.0f, 1.0f};
    while (tx > end && e.y > 0.8281f && e.x == 0.0f) {
      e = Ed(tx, ty);
      tx = -2.0f * rx + tx;
    }
    const float offset = -(255.0f / 127.0f) * SearchLength(e, 0.0f) + 3.25f;
    return rx * offset + tx;
  }
  __device__ float SearchXRight(float tx, float ty, float end) const {
    F2 e{0.0f, 1.0f};
    while (tx < end && e.y > 0.8281f && e.x == 0.0f) {
      e = Ed(tx, ty);
      tx = 2.0f * rx + tx;
    }
    const float offset = -(255.0f / 127.0f) * SearchLength(e, 0.5f) + 3.25f;
    return -rx * offset + tx;
  }
  __device__ float SearchYUp(float tx, float ty, float end) const {
    F2 e{1.0f, 0.0f};
    while (ty > end && e.x > 0.8281f && e.y == 0.0f) {
      e = Ed(tx, ty);
      ty = -2.0f * ry + ty;
    }
    const float offset = -(255.0f / 127.0f) * SearchLength(F2{e.y, e.x}, 0.0f) + 3.25f;
    return ry * offset + ty;
  }
  __device__ float SearchYDown(float tx, float ty, float end) const {
    F2 e{1.0f, 0.0f};
    while (ty < end && e.x > 0.8281f && e.y == 0.0f) {
      e = Ed(tx, ty);
      ty = 2.0f * ry + ty;
    }
    const float offset = -(255.0f / 127.0f) * SearchLength(F2{e.y, e.x}, 0.5f) + 3.25f;
    return -ry * offset + ty;
  }

  __device__ F2 Area(F2 dist, float e1, float e2) const {
    const float px = 1.0f / 160.0f, py = 1.0f / 560.0f;
    float tx = 16.0f * rintf(4.0f * e1) + dist.x;
    float ty = 16.0f * rintf(4.0f * e2) + dist.y;
    tx = px * tx + 0.5f * px;
    ty = py * ty + 0.5f * py;
    ty = (1.0f / 7.0f) * 0.0f + ty;
    const float4 a = SampleNorm<kSoft>(area, tx, ty, p.fixed8);
    return {a.x, a.y};
  }

  __device__ float RoundingNorm() const { return static_cast<float>(p.corner_rounding) / 100.0f; }

  __device__ void HorizontalCorner(float* wx, float* wy, float tx, float ty, float tz, float tw, F2 d) const {
    const F2 lr{d.y >= d.x ? 1.0f : 0.0f, d.x >= d.y ? 1.0f : 0.0f};
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
    *wx *= fminf(fmaxf(factor.x, 0.0f), 1.0f);
    *wy *= fminf(fmaxf(factor.y, 0.0f), 1.0f);
  }
  __device__ void VerticalCorner(float* wx, float* wy, float tx, float ty, float tz, float tw, F2 d) const {
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
    *wx *= fminf(fmaxf(factor.x, 0.0f), 1.0f);
    *wy *= fminf(fmaxf(factor.y, 0.0f), 1.0f);
  }

  __device__ float4 Run(int x, int y) const {
    const F2 tc{(static_cast<float>(x) + 0.5f) / W, (static_cast<float>(y) + 0.5f) / H};
    const F2 pix{tc.x * W, tc.y * H};
    const float o0x = rx * -0.25f + tc.x, o0y = ry * -0.125f + tc.y, o0z = rx * 1.25f + tc.x, o0w = ry * -0.125f + tc.y;
    const float o1x = rx * -0.125f + tc.x, o1y = ry * -0.25f + tc.y, o1z = rx * -0.125f + tc.x, o1w = ry * 1.25f + tc.y;
    const float n = static_cast<float>(p.max_search_steps);
    const float o2x = rx * (-2.0f * n) + o0x, o2y = rx * (2.0f * n) + o0z;
    const float o2z = ry * (-2.0f * n) + o1y, o2w = ry * (2.0f * n) + o1w;

    float4 w = make_float4(0, 0, 0, 0);
    F2 e = Ed(tc.x, tc.y);
    if (e.y > 0.0f) {
      bool ortho = true;
      if (p.diag) {
        const F2 dw = DiagWeights(tc, e);
        w.x = dw.x;
        w.y = dw.y;
        ortho = w.x == -w.y;
      }
      if (ortho) {
        const float cx = SearchXLeft(o0x, o0y, o2x);
        float cy = o1y;
        F2 d{cx, 0};
        const float e1 = Ed(cx, cy).x;
        const float cz = SearchXRight(o0z, o0w, o2y);
        d.y = cz;
        d.x = fabsf(rintf(W * d.x + -pix.x));
        d.y = fabsf(rintf(W * d.y + -pix.x));
        const F2 sq{sqrtf(d.x), sqrtf(d.y)};
        const float e2 = EdOff(cz, cy, 1.0f, 0.0f).x;
        const F2 a = Area(sq, e1, e2);
        w.x = a.x;
        w.y = a.y;
        cy = tc.y;
        if (p.corner) HorizontalCorner(&w.x, &w.y, cx, cy, cz, cy, d);
      } else {
        e.x = 0.0f;
      }
    }
    if (e.x > 0.0f) {
      const float cy = SearchYUp(o1x, o1y, o2z);
      float cx = o0x;
      F2 d{cy, 0};
      const float e1 = Ed(cx, cy).y;
      const float cz = SearchYDown(o1z, o1w, o2w);
      d.y = cz;
      d.x = fabsf(rintf(H * d.x + -pix.y));
      d.y = fabsf(rintf(H * d.y + -pix.y));
      const F2 sq{sqrtf(d.x), sqrtf(d.y)};
      const float e2 = EdOff(cx, cz, 0.0f, 1.0f).y;
      const F2 a = Area(sq, e1, e2);
      w.z = a.x;
      w.w = a.y;
      cx = tc.x;
      if (p.corner) VerticalCorner(&w.z, &w.w, cx, cy, cx, cz, d);
    }
    return w;
  }
};

template <bool kSoft>
__global__ void WeightsKernel(Tex edges, Tex area, Tex search, cudaSurfaceObject_t out, SmaaArgs p) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= edges.w || y >= edges.h) return;
  const float W = static_cast<float>(edges.w), H = static_cast<float>(edges.h);
  const Weights<kSoft> shader{edges, area, search, p, W, H, 1.0f / W, 1.0f / H};
  const float4 w = shader.Run(x, y);
  surf2Dwrite(make_uchar4(QuantizeUnorm8(w.x), QuantizeUnorm8(w.y), QuantizeUnorm8(w.z), QuantizeUnorm8(w.w)), out,
              x * 4, y);
}

// ---------------------------------------------------------------------------------- pass 3

// smaa_detail::BlendPixel + BlendWithWeights.
template <bool kSoft>
__global__ void BlendKernel(Tex blend, Tex color, cudaSurfaceObject_t out, SmaaArgs p) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= color.w || y >= color.h) return;
  const float W = static_cast<float>(color.w), H = static_cast<float>(color.h);
  const float rx = 1.0f / W, ry = 1.0f / H;
  const float tcx = (static_cast<float>(x) + 0.5f) / W, tcy = (static_cast<float>(y) + 0.5f) / H;
  const float ox = rx * 1.0f + tcx, oy = ry * 0.0f + tcy;
  const float oz = rx * 0.0f + tcx, ow = ry * 1.0f + tcy;
  float a[4];
  a[0] = SampleNorm<kSoft>(blend, ox, oy, p.fixed8).w;
  a[1] = SampleNorm<kSoft>(blend, oz, ow, p.fixed8).y;
  const float4 own = SampleNorm<kSoft>(blend, tcx, tcy, p.fixed8);
  a[3] = own.x;
  a[2] = own.z;
  float4 c;
  if (((a[0] + a[1]) + a[2]) + a[3] < 1e-5f) {
    c = SampleNorm<kSoft>(color, tcx, tcy, p.fixed8);
  } else {
    const bool h = fmaxf(a[0], a[2]) > fmaxf(a[1], a[3]);
    float bo0 = 0.0f, bo1 = a[1], bo2 = 0.0f, bo3 = a[3];
    float bw0 = a[1], bw1 = a[3];
    if (h) {
      bo0 = a[0], bo1 = 0.0f, bo2 = a[2], bo3 = 0.0f;
      bw0 = a[0], bw1 = a[2];
    }
    const float sum = bw0 * 1.0f + bw1 * 1.0f;
    bw0 /= sum;
    bw1 /= sum;
    const float c0x = bo0 * rx + tcx, c0y = bo1 * ry + tcy;
    const float c1x = bo2 * -rx + tcx, c1y = bo3 * -ry + tcy;
    const float4 q0 = SampleNorm<kSoft>(color, c0x, c0y, p.fixed8);
    const float4 q1 = SampleNorm<kSoft>(color, c1x, c1y, p.fixed8);
    c.x = bw0 * q0.x + bw1 * q1.x;
    c.y = bw0 * q0.y + bw1 * q1.y;
    c.z = bw0 * q0.z + bw1 * q1.z;
  }
  WriteRgb(out, x, y, c.x, c.y, c.z);
}

Tex TexOf(const GpuFrame& f) { return Tex{f.Point(), f.LinearPx(), f.LinearNorm(), f.Width(), f.Height()}; }

}  // namespace

void LaunchSmaaEdges(const GpuFrame& in, GpuFrame& edges, const SmaaArgs& args, cudaStream_t stream,
                     bool software_filter) {
  const dim3 grid = Grid2D(in.Width(), in.Height());
  if (software_filter) {
    EdgesKernel<true><<<grid, Block2D(), 0, stream>>>(in.Point(), edges.Surface(), in.Width(), in.Height(), args);
  } else {
    EdgesKernel<false><<<grid, Block2D(), 0, stream>>>(in.Point(), edges.Surface(), in.Width(), in.Height(), args);
  }
}

void LaunchSmaaWeights(const GpuFrame& edges, const GpuFrame& area, const GpuFrame& search, GpuFrame& blend,
                       const SmaaArgs& args, cudaStream_t stream, bool software_filter) {
  const dim3 grid = Grid2D(edges.Width(), edges.Height());
  if (software_filter) {
    WeightsKernel<true><<<grid, Block2D(), 0, stream>>>(TexOf(edges), TexOf(area), TexOf(search), blend.Surface(),
                                                        args);
  } else {
    WeightsKernel<false><<<grid, Block2D(), 0, stream>>>(TexOf(edges), TexOf(area), TexOf(search), blend.Surface(),
                                                         args);
  }
}

void LaunchSmaaBlend(const GpuFrame& in, const GpuFrame& blend, GpuFrame& out, const SmaaArgs& args,
                     cudaStream_t stream, bool software_filter) {
  const dim3 grid = Grid2D(in.Width(), in.Height());
  if (software_filter) {
    BlendKernel<true><<<grid, Block2D(), 0, stream>>>(TexOf(blend), TexOf(in), out.Surface(), args);
  } else {
    BlendKernel<false><<<grid, Block2D(), 0, stream>>>(TexOf(blend), TexOf(in), out.Surface(), args);
  }
}

}  // namespace aalab::cuda
