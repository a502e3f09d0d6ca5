// The production TAA's resolve (methods/taa_production.cpp, TaaProdState::Step) as one CUDA
// kernel, one thread per output pixel, for what a game's TAA pass does: the box
// reconstruction (filter=box: the pixel's own jittered sample), closest-depth dilation,
// disocclusion test, Catmull-Rom (or bilinear) history fetch, YCoCg rectification, adaptive
// or fixed feedback, and the history stored as RGBA32F or RGBA16F (rounded to nearest even by
// the surface store's __float2half_rn, which is RoundToHalf on [0, 1]) with the frames
// accumulated in its alpha. Every expression is the CPU's, in float32 and its order
// (--fmad=false; sqrtf and '/' are IEEE-rounded as std::sqrt and the CPU's division).
//   kSoft = true:  the history fetch from point fetches in the CPU's arithmetic (4 or 16 or
//                  12 texels, float32 fractions and Catmull-Rom weights): bit-identical to the
//                  CPU, checked by `aalab_gpu --self-test --check`;
//   hardware path: the texture unit filters: bilinear = 1 fetch, catmull-rom = 9 bilinear
//                  fetches at the combined taps (w1 + w2 at x0 + w2/(w1 + w2): what UE4's
//                  9-tap fetch computes, Karis 2014), catmull-rom-5 = 5 of them (Jimenez
//                  2016); the 8-bit fixed-point filter weights move a few values by a level.
// Not in the twin (the host refuses them): filter=gauss (expf on the GPU is not glibc's, so
// not bit-identical), sharpen > 0 (a second pass over the output) and TAAU (output ≠ render
// size). The decode/encode tables and the 18×18 YCoCg tile are staged as in taa.cu
// (methods/cuda/taa_common.cuh). Safe choices are the CPU's: a NaN or off-screen previous
// position means no history; an unknown previous motion vector never drops history.
#include <cuda_fp16.h>

#include <stdexcept>

#include "methods/cuda/device_ops.cuh"
#include "methods/cuda/post_filters_cuda.h"
#include "methods/cuda/taa_common.cuh"

namespace aalab::cuda {
namespace {

using namespace taa_detail;

// CatmullRomWeights (methods/taa_production.cpp), same expressions.
__device__ __forceinline__ void CatmullRom(float t, float* w) {
  const float t2 = t * t, t3 = t2 * t;
  w[0] = -0.5f * t3 + t2 - 0.5f * t;
  w[1] = 1.5f * t3 - 2.5f * t2 + 1.0f;
  w[2] = -1.5f * t3 + 2.0f * t2 + 0.5f * t;
  w[3] = 0.5f * t3 - 0.5f * t2;
}

// TaaProdState::FetchHistory at output position (hx, hy).
template <bool kSoft>
__device__ __forceinline__ void FetchHistory(cudaTextureObject_t pt, cudaTextureObject_t lin, float hx, float hy, int w,
                                             int h, int mode, float* out) {
  const float fx = hx - 0.5f, fy = hy - 0.5f;
  const float x0f = floorf(fx), y0f = floorf(fy);
  const float tx = fx - x0f, ty = fy - y0f;
  const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
  if (mode == 0) {  // bilinear
    if constexpr (kSoft) {
      SoftBilinearHistory(pt, hx, hy, w, h, out);
    } else {
      const float4 H = tex2D<float4>(lin, hx, hy);
      out[0] = H.x, out[1] = H.y, out[2] = H.z;
    }
    return;
  }
  float wx[4], wy[4];
  CatmullRom(tx, wx);
  CatmullRom(ty, wy);
  const bool five = mode == 2;
  float acc[3] = {0, 0, 0}, wsum = 0.0f;
  if constexpr (kSoft) {
    for (int b = 0; b < 4; ++b) {
      for (int a = 0; a < 4; ++a) {
        if (five && (a == 0 || a == 3) && (b == 0 || b == 3)) continue;  // the corners
        const float wt = wx[a] * wy[b];
        const float4 t = HistTexel(pt, x0 - 1 + a, y0 - 1 + b, w, h);
        acc[0] += wt * t.x;
        acc[1] += wt * t.y;
        acc[2] += wt * t.z;
        wsum += wt;
      }
    }
  } else {
    // Texels 1 and 2 of each axis merged into one bilinear tap (w1 + w2 ≥ 1 on [0, 1): no
    // division by zero); tap positions in texel coordinates (centres at +0.5).
    const float cwx[3] = {wx[0], wx[1] + wx[2], wx[3]}, cwy[3] = {wy[0], wy[1] + wy[2], wy[3]};
    const float ux[3] = {x0f - 0.5f, x0f + 0.5f + wx[2] / cwx[1], x0f + 2.5f};
    const float uy[3] = {y0f - 0.5f, y0f + 0.5f + wy[2] / cwy[1], y0f + 2.5f};
#pragma unroll
    for (int b = 0; b < 3; ++b) {
#pragma unroll
      for (int a = 0; a < 3; ++a) {
        if (five && a != 1 && b != 1) continue;  // the corner taps
        const float wt = cwx[a] * cwy[b];
        const float4 t = tex2D<float4>(lin, ux[a], uy[b]);
        acc[0] += wt * t.x;
        acc[1] += wt * t.y;
        acc[2] += wt * t.z;
        wsum += wt;
      }
    }
  }
#pragma unroll
  for (int c = 0; c < 3; ++c) out[c] = StdClamp(acc[c] / wsum, 0.0f, 1.0f);
}

// ClosestDepthPixel: the smallest depth of the clamped 3×3, the centre first, then row-major.
__device__ __forceinline__ int ClosestDepth(const float* __restrict__ depth, int w, int h, int x, int y) {
  int best = y * w + x;
  float bd = __ldg(depth + best);
  for (int dy = -1; dy <= 1; ++dy) {
    const int yy = min(max(y + dy, 0), h - 1);
    for (int dx = -1; dx <= 1; ++dx) {
      const int i = yy * w + min(max(x + dx, 0), w - 1);
      const float d = __ldg(depth + i);
      if (d < bd) {
        bd = d;
        best = i;
      }
    }
  }
  return best;
}

template <bool kSoft, bool kHalf>
__global__ void TaaProdKernel(cudaTextureObject_t frame, TaaProdFrame in, cudaTextureObject_t hist_pt,
                              cudaTextureObject_t hist_lin, cudaSurfaceObject_t hist_out, cudaSurfaceObject_t out,
                              int w, int h, TaaProdArgs a, const float* __restrict__ decode_g,
                              const float* __restrict__ starts_g) {
  __shared__ BlockShared sh;
  StageBlock(sh, frame, w, h, decode_g, starts_g);
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= w || y >= h) return;
  // Reconstruct, filter=box at scale 1: the sample whose jittered position is in the box.
  const float px = static_cast<float>(x) + 0.5f, py = static_cast<float>(y) + 0.5f;
  const int kx = min(max(static_cast<int>(floorf(px - a.jitter_x)), 0), w - 1);
  const int ky = min(max(static_cast<int>(floorf(py - a.jitter_y)), 0), h - 1);
  const float4 ct = TexelAt(frame, kx, ky);
  const float cur[3] = {sh.decode[QuantizeUnorm8(ct.x)], sh.decode[QuantizeUnorm8(ct.y)],
                        sh.decode[QuantizeUnorm8(ct.z)]};
  float res[4] = {StdClamp(cur[0], 0.0f, 1.0f), StdClamp(cur[1], 0.0f, 1.0f), StdClamp(cur[2], 0.0f, 1.0f), 1.0f};
  const float2* prev = reinterpret_cast<const float2*>(in.previous);
  do {
    if (!prev) break;  // no history
    const int m = (a.dilate && in.depth) ? ClosestDepth(in.depth, w, h, x, y) : y * w + x;
    const float2 pm = prev[m];
    const float vx = pm.x - (static_cast<float>(m % w) + 0.5f), vy = pm.y - (static_cast<float>(m / w) + 0.5f);
    const float ovx = vx / 1.0f, ovy = vy / 1.0f;  // output pixels (scale 1)
    const float hx = static_cast<float>(x) + 0.5f + ovx, hy = static_cast<float>(y) + 0.5f + ovy;
    if (!(hx >= 0.0f && hx <= static_cast<float>(w) && hy >= 0.0f && hy <= static_cast<float>(h))) break;
    if (a.disocclusion) {
      const int qx = min(max(static_cast<int>(floorf(hx * 1.0f)), 0), w - 1);
      const int qy = min(max(static_cast<int>(floorf(hy * 1.0f)), 0), h - 1);
      const int q = qy * w + qx;
      if (in.depth && in.prev_depth) {
        const float now = __ldg(in.depth + m);
        if (__ldg(in.prev_depth + q) < now * (1.0f - a.disocclusion_depth)) break;
      }
      if (in.prev_previous) {  // an unknown previous vector cannot show a discontinuity
        const float2 pq = reinterpret_cast<const float2*>(in.prev_previous)[q];
        const float dx = (pq.x - (static_cast<float>(qx) + 0.5f)) - vx;
        const float dy = (pq.y - (static_cast<float>(qy) + 0.5f)) - vy;
        if (dx * dx + dy * dy > a.disocclusion_px * a.disocclusion_px) break;
      }
    }
    float hrgb[3];
    FetchHistory<kSoft>(hist_pt, hist_lin, hx, hy, w, h, a.history, hrgb);
    Ycc hyc = ToYCoCg(hrgb[0], hrgb[1], hrgb[2]);
    if (a.clip != 2) hyc = RectifyInTile(sh, hyc, a.clip, a.gamma);
    const Ycc cy = ToYCoCg(cur[0], cur[1], cur[2]);
    const float count =
        tex2D<float4>(hist_pt, static_cast<float>(min(max(static_cast<int>(floorf(hx)), 0), w - 1)) + 0.5f,
                      static_cast<float>(min(max(static_cast<int>(floorf(hy)), 0), h - 1)) + 0.5f)
            .w;
    float alpha = a.alpha;
    if (a.adaptive) {
      const float speed = sqrtf(ovx * ovx + ovy * ovy);
      const float a_motion = a.alpha_min + (a.alpha_max - a.alpha_min) * StdMin(1.0f, speed / a.motion_px);
      alpha = StdMax(1.0f / (count + 1.0f), a_motion);
      if (a.luma_weight) {
        float big = cy.y;  // std::max({cy.y, hy.y, 0.2f}): the first largest
        if (big < hyc.y) big = hyc.y;
        if (big < 0.2f) big = 0.2f;
        const float d = fabsf(cy.y - hyc.y) / big;
        const float k = (1.0f - StdMin(d, 1.0f)) * (1.0f - StdMin(d, 1.0f));
        alpha = StdMax(alpha, a.alpha_max - (a.alpha_max - a.alpha_min) * k);
      }
    }
    res[3] = StdMin(count + 1.0f, 255.0f);
    const Ycc o{hyc.y + alpha * (cy.y - hyc.y), hyc.co + alpha * (cy.co - hyc.co), hyc.cg + alpha * (cy.cg - hyc.cg)};
    const float tt = o.y - o.cg;
    res[0] = StdClamp(tt + o.co, 0.0f, 1.0f);
    res[1] = StdClamp(o.y + o.cg, 0.0f, 1.0f);
    res[2] = StdClamp(tt - o.co, 0.0f, 1.0f);
  } while (false);
  if constexpr (kHalf) {
    const ushort4 hv =
        make_ushort4(__half_as_ushort(__float2half_rn(res[0])), __half_as_ushort(__float2half_rn(res[1])),
                     __half_as_ushort(__float2half_rn(res[2])), __half_as_ushort(__float2half_rn(res[3])));
    surf2Dwrite(hv, hist_out, x * 8, y);
  } else {
    surf2Dwrite(make_float4(res[0], res[1], res[2], res[3]), hist_out, x * 16, y);
  }
  surf2Dwrite(make_uchar4(Encode(res[0], sh.starts), Encode(res[1], sh.starts), Encode(res[2], sh.starts), 255), out,
              x * 4, y);
}

template <bool kSoft>
void Launch(bool half, dim3 grid, cudaStream_t stream, cudaTextureObject_t frame, const TaaProdFrame& in,
            cudaTextureObject_t hp, cudaTextureObject_t hl, cudaSurfaceObject_t next, cudaSurfaceObject_t out, int w,
            int h, const TaaProdArgs& a, const float* decode, const float* starts) {
  if (half) {
    TaaProdKernel<kSoft, true><<<grid, Block2D(), 0, stream>>>(frame, in, hp, hl, next, out, w, h, a, decode, starts);
  } else {
    TaaProdKernel<kSoft, false><<<grid, Block2D(), 0, stream>>>(frame, in, hp, hl, next, out, w, h, a, decode, starts);
  }
}

}  // namespace

void LaunchTaaProdResolve(const GpuFrame& frame, const TaaProdFrame& in, const GpuHistory* history, GpuHistory& next,
                          GpuFrame& out, const TaaProdArgs& args, const float* decode, const float* encode_starts,
                          cudaStream_t stream, bool software_filter) {
  const int w = frame.Width(), h = frame.Height();
  if (next.Width() != w || next.Height() != h || out.Width() != w || out.Height() != h ||
      (history && (history->Width() != w || history->Height() != h))) {
    throw std::runtime_error("LaunchTaaProdResolve: frame, history and output sizes differ");
  }
  if (history && history->Half() != next.Half()) {
    throw std::runtime_error("LaunchTaaProdResolve: the history and the next history differ in precision");
  }
  TaaProdFrame f = in;
  if (!history) f.previous = nullptr;  // no history: every pixel takes the current colour
  const cudaTextureObject_t hp = history ? history->Point() : 0, hl = history ? history->Linear() : 0;
  const dim3 grid = Grid2D(w, h);
  if (software_filter) {
    Launch<true>(next.Half(), grid, stream, frame.Point(), f, hp, hl, next.Surface(), out.Surface(), w, h, args, decode,
                 encode_starts);
  } else {
    Launch<false>(next.Half(), grid, stream, frame.Point(), f, hp, hl, next.Surface(), out.Surface(), w, h, args,
                  decode, encode_starts);
  }
}

}  // namespace aalab::cuda
