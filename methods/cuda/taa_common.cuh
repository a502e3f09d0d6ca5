// Device pieces shared by the two TAA resolves (methods/cuda/taa.cu for `taa`,
// methods/cuda/taa_production.cu for `taa-prod`): YCoCg, the std::min/max/clamp comparisons,
// the 8-bit sRGB encode by binary search over EncodeSrgb8's thresholds, the block's staged
// tables and 18×18 YCoCg tile, and the 3×3 box rectification (methods/taa.cpp Rectify +
// ClipToBox, methods/taa_production.cpp Box + ClipToBox: the same float32 expressions in the
// same order, so with --fmad=false they give the CPU's bits).
#pragma once
#include <cuda_runtime.h>

#include "methods/cuda/device_ops.cuh"

namespace aalab::cuda::taa_detail {

struct Ycc {
  float y, co, cg;
};

__device__ __forceinline__ Ycc ToYCoCg(float r, float g, float b) {
  return {0.25f * r + 0.5f * g + 0.25f * b, 0.5f * r - 0.5f * b, -0.25f * r + 0.5f * g - 0.25f * b};
}

// std::max / std::min / std::clamp exactly (their comparisons, not fmaxf's NaN rule).
__device__ __forceinline__ float StdMax(float a, float b) { return a < b ? b : a; }
__device__ __forceinline__ float StdMin(float a, float b) { return b < a ? b : a; }
__device__ __forceinline__ float StdClamp(float v, float lo, float hi) { return v < lo ? lo : (hi < v ? hi : v); }

__device__ __forceinline__ Ycc YccAt(cudaTextureObject_t frame, int x, int y, const float* decode) {
  const float4 t = TexelAt(frame, x, y);
  return ToYCoCg(decode[QuantizeUnorm8(t.x)], decode[QuantizeUnorm8(t.y)], decode[QuantizeUnorm8(t.z)]);
}

// History texel (x, y), clamped to the w × h history: an exact point fetch (float or half
// texels widened to float).
__device__ __forceinline__ float4 HistTexel(cudaTextureObject_t pt, int x, int y, int w, int h) {
  return tex2D<float4>(pt, static_cast<float>(min(max(x, 0), w - 1)) + 0.5f,
                       static_cast<float>(min(max(y, 0), h - 1)) + 0.5f);
}

// The CPU's bilinear history fetch (TaaState::FetchHistory, TaaProdState::FetchHistory with
// history=bilinear) at texel coordinates (hx, hy): four point fetches, float32 fractions,
// lerp(lerp(a, b, tx), lerp(c, d, tx), ty) in that order.
__device__ __forceinline__ void SoftBilinearHistory(cudaTextureObject_t pt, float hx, float hy, int w, int h,
                                                    float* out) {
  const float fx = hx - 0.5f, fy = hy - 0.5f;
  const float x0f = floorf(fx), y0f = floorf(fy);
  const float tx = fx - x0f, ty = fy - y0f;
  const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
  const float4 A = HistTexel(pt, x0, y0, w, h), B = HistTexel(pt, x0 + 1, y0, w, h);
  const float4 C = HistTexel(pt, x0, y0 + 1, w, h), D = HistTexel(pt, x0 + 1, y0 + 1, w, h);
  const float av[3] = {A.x, A.y, A.z}, bv[3] = {B.x, B.y, B.z}, cv[3] = {C.x, C.y, C.z}, dv[3] = {D.x, D.y, D.z};
#pragma unroll
  for (int c = 0; c < 3; ++c) {
    const float top = av[c] + tx * (bv[c] - av[c]);
    const float bot = cv[c] + tx * (dv[c] - cv[c]);
    out[c] = top + ty * (bot - top);
  }
}

// Encode8::operator(): the number of code thresholds at or below v (v in [0, 1]).
__device__ __forceinline__ unsigned char Encode(float v, const float* starts) {
  int lo = 0, hi = 255;
  while (lo < hi) {
    const int mid = (lo + hi) >> 1;
    if (starts[mid] <= v) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return static_cast<unsigned char>(lo);
}

constexpr int kTile = 18;  // 16 + a border of 1 on each side

// Shared memory of one 16×16 block: the decode table (256 values), the encode thresholds
// (255, padded with 2), and the YCoCg of the block's pixels with a 1-pixel border.
struct BlockShared {
  float decode[256];
  float starts[256];
  float tile[3][kTile * kTile];
};

// Fills `s` (all 256 threads of the block take part; ends with a barrier). Tile entry (i, j)
// holds pixel (bx − 1 + i, by − 1 + j) clamped to the frame, as the CPU clamps each neighbour.
__device__ __forceinline__ void StageBlock(BlockShared& s, cudaTextureObject_t frame, int w, int h,
                                           const float* __restrict__ decode_g, const float* __restrict__ starts_g) {
  const int tid = threadIdx.y * blockDim.x + threadIdx.x;
  s.decode[tid] = decode_g[tid];
  s.starts[tid] = tid < 255 ? starts_g[tid] : 2.0f;
  __syncthreads();
  const int bx = blockIdx.x * blockDim.x, by = blockIdx.y * blockDim.y;
  for (int k = tid; k < kTile * kTile; k += 256) {
    const int tx = min(max(bx - 1 + k % kTile, 0), w - 1);
    const int ty = min(max(by - 1 + k / kTile, 0), h - 1);
    const Ycc v = YccAt(frame, tx, ty, s.decode);
    s.tile[0][k] = v.y;
    s.tile[1][k] = v.co;
    s.tile[2][k] = v.cg;
  }
  __syncthreads();
}

// The history hy clipped toward the centre of the 3×3 box (in the tile) around this thread's
// pixel: clip 0 = variance (μ ± γσ) ∩ min/max, 1 = min/max; extents + 1e-8 (no division by 0).
__device__ __forceinline__ Ycc RectifyInTile(const BlockShared& s, Ycc hy, int clip, float gamma) {
  float mn[3] = {1e30f, 1e30f, 1e30f}, mx[3] = {-1e30f, -1e30f, -1e30f};
  float m1[3] = {0, 0, 0}, m2[3] = {0, 0, 0};
#pragma unroll
  for (int dy = 0; dy < 3; ++dy) {
#pragma unroll
    for (int dx = 0; dx < 3; ++dx) {
      const int k = (threadIdx.y + dy) * kTile + threadIdx.x + dx;
      const float av[3] = {s.tile[0][k], s.tile[1][k], s.tile[2][k]};
#pragma unroll
      for (int c = 0; c < 3; ++c) {
        mn[c] = StdMin(mn[c], av[c]);
        mx[c] = StdMax(mx[c], av[c]);
        m1[c] += av[c];
        m2[c] += av[c] * av[c];
      }
    }
  }
  if (clip == 0) {
#pragma unroll
    for (int c = 0; c < 3; ++c) {
      const float mu = m1[c] / 9.0f;
      const float sigma = sqrtf(fabsf(m2[c] / 9.0f - mu * mu));
      mn[c] = StdMax(mn[c], mu - gamma * sigma);
      mx[c] = StdMin(mx[c], mu + gamma * sigma);
    }
  }
  const float hv[3] = {hy.y, hy.co, hy.cg};
  float centre[3], v[3], m = 0.0f;
#pragma unroll
  for (int c = 0; c < 3; ++c) {
    centre[c] = 0.5f * (mx[c] + mn[c]);
    const float ext = 0.5f * (mx[c] - mn[c]) + 1e-8f;
    v[c] = hv[c] - centre[c];
    m = StdMax(m, fabsf(v[c] / ext));
  }
  if (!(m <= 1.0f)) return {centre[0] + v[0] / m, centre[1] + v[1] / m, centre[2] + v[2] / m};
  return hy;
}

}  // namespace aalab::cuda::taa_detail
