// TAA's resolve (methods/taa.cpp, TaaState::Step) as one CUDA kernel, one thread per pixel:
// decode the current 8-bit frame to linear RGB (SrgbDecode8's table) and YCoCg, reproject
// the history (linear RGB, float32, an RGBA32F cudaArray that stays on the GPU from frame to
// frame) with the per-pixel previous positions, clip it against the 3×3 neighbourhood's box
// in YCoCg (variance ∩ min/max, min/max, or none), blend exponentially, write the next
// history and the sRGB-encoded 8-bit output (EncodeSrgb8's code thresholds, a binary
// search). Every expression is the CPU's, in float32 and its order (--fmad=false).
//   hardware path: the history fetch is one bilinear fetch of the float texture by the
//                  texture unit (8-bit fixed-point weights, measured by the probe);
//   kSoft = true:  the CPU's FetchHistory (four point fetches, float32 fractions, clamped
//                  texel indices), which reproduces the CPU bit for bit.
// The two tables (256 decode values, 255 encode thresholds) are staged in shared memory
// by each 16×16 block (256 threads: one entry each), and so are the block's 18×18 YCoCg
// values (each texel decoded once instead of once per neighbour: the same values, as each
// is a function of its texel alone).
#include <stdexcept>

#include "methods/cuda/device_ops.cuh"
#include "methods/cuda/post_filters_cuda.h"

namespace aalab::cuda {

GpuHistory::GpuHistory(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::runtime_error("GpuHistory needs a positive size");
  const cudaChannelFormatDesc desc = cudaCreateChannelDesc<float4>();
  Check(cudaMallocArray(&array_, &desc, width, height, cudaArraySurfaceLoadStore), "cudaMallocArray");
  cudaResourceDesc res{};
  res.resType = cudaResourceTypeArray;
  res.res.array.array = array_;
  for (int linear = 0; linear < 2; ++linear) {
    cudaTextureDesc td{};
    td.addressMode[0] = cudaAddressModeClamp;
    td.addressMode[1] = cudaAddressModeClamp;
    td.filterMode = linear ? cudaFilterModeLinear : cudaFilterModePoint;
    td.readMode = cudaReadModeElementType;
    td.normalizedCoords = 0;
    Check(cudaCreateTextureObject(linear ? &linear_ : &point_, &res, &td, nullptr), "cudaCreateTextureObject");
  }
  Check(cudaCreateSurfaceObject(&surface_, &res), "cudaCreateSurfaceObject");
}

GpuHistory::~GpuHistory() {
  cudaDestroySurfaceObject(surface_);
  cudaDestroyTextureObject(linear_);
  cudaDestroyTextureObject(point_);
  cudaFreeArray(array_);
}

void GpuHistory::Download(float* rgba) const {
  const size_t row = static_cast<size_t>(width_) * 16;
  Check(cudaMemcpy2DFromArray(rgba, row, array_, 0, 0, row, height_, cudaMemcpyDeviceToHost), "download");
}

namespace {

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

template <bool kSoft>
__global__ void TaaKernel(cudaTextureObject_t frame, const float* __restrict__ previous, cudaTextureObject_t hist_pt,
                          cudaTextureObject_t hist_lin, cudaSurfaceObject_t hist_out, cudaSurfaceObject_t out, int w,
                          int h, TaaArgs a, const float* __restrict__ decode_g, const float* __restrict__ starts_g) {
  __shared__ float decode[256];
  __shared__ float starts[256];
  __shared__ float tile[3][kTile * kTile];  // YCoCg of the block's pixels and a 1-pixel border
  const int tid = threadIdx.y * blockDim.x + threadIdx.x;  // 16×16 = 256 threads
  decode[tid] = decode_g[tid];
  starts[tid] = tid < 255 ? starts_g[tid] : 2.0f;
  __syncthreads();
  // The 3×3 neighbourhoods of the block, decoded once: tile entry (i, j) holds pixel
  // (bx − 1 + i, by − 1 + j) clamped to the frame, as Rectify clamps each neighbour.
  const int bx = blockIdx.x * blockDim.x, by = blockIdx.y * blockDim.y;
  for (int k = tid; k < kTile * kTile; k += 256) {
    const int tx = min(max(bx - 1 + k % kTile, 0), w - 1);
    const int ty = min(max(by - 1 + k / kTile, 0), h - 1);
    const Ycc v = YccAt(frame, tx, ty, decode);
    tile[0][k] = v.y;
    tile[1][k] = v.co;
    tile[2][k] = v.cg;
  }
  __syncthreads();
  const int x = bx + threadIdx.x;
  const int y = by + threadIdx.y;
  if (x >= w || y >= h) return;
  const float4 t = TexelAt(frame, x, y);
  float c[3] = {decode[QuantizeUnorm8(t.x)], decode[QuantizeUnorm8(t.y)], decode[QuantizeUnorm8(t.z)]};
  float o[3] = {c[0], c[1], c[2]};
  const size_t i = static_cast<size_t>(y) * w + x;
  const float2 pp = previous ? reinterpret_cast<const float2*>(previous)[i] : make_float2(0.0f, 0.0f);
  const float px = pp.x, py = pp.y;
  if (previous && px >= 0.0f && px <= static_cast<float>(w) && py >= 0.0f && py <= static_cast<float>(h)) {
    float hrgb[3];
    if constexpr (kSoft) {  // TaaState::FetchHistory
      const float fx = px - 0.5f, fy = py - 0.5f;
      const float x0f = floorf(fx), y0f = floorf(fy);
      const float tx = fx - x0f, ty = fy - y0f;
      const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
      const int xa = min(max(x0, 0), w - 1), xb = min(max(x0 + 1, 0), w - 1);
      const int ya = min(max(y0, 0), h - 1), yb = min(max(y0 + 1, 0), h - 1);
      const float4 A = tex2D<float4>(hist_pt, xa + 0.5f, ya + 0.5f);
      const float4 B = tex2D<float4>(hist_pt, xb + 0.5f, ya + 0.5f);
      const float4 C = tex2D<float4>(hist_pt, xa + 0.5f, yb + 0.5f);
      const float4 D = tex2D<float4>(hist_pt, xb + 0.5f, yb + 0.5f);
      const float av[3] = {A.x, A.y, A.z}, bv[3] = {B.x, B.y, B.z}, cv[3] = {C.x, C.y, C.z}, dv[3] = {D.x, D.y, D.z};
#pragma unroll
      for (int k = 0; k < 3; ++k) {
        const float top = av[k] + tx * (bv[k] - av[k]);
        const float bot = cv[k] + tx * (dv[k] - cv[k]);
        hrgb[k] = top + ty * (bot - top);
      }
    } else {
      const float4 H = tex2D<float4>(hist_lin, px, py);
      hrgb[0] = H.x, hrgb[1] = H.y, hrgb[2] = H.z;
    }
    Ycc hy = ToYCoCg(hrgb[0], hrgb[1], hrgb[2]);
    if (a.clip != 2) {  // TaaState::Rectify + ClipToBox
      float mn[3] = {1e30f, 1e30f, 1e30f}, mx[3] = {-1e30f, -1e30f, -1e30f};
      float m1[3] = {0, 0, 0}, m2[3] = {0, 0, 0};
#pragma unroll
      for (int dy = 0; dy < 3; ++dy) {
#pragma unroll
        for (int dx = 0; dx < 3; ++dx) {
          const int k = (threadIdx.y + dy) * kTile + threadIdx.x + dx;
          const float av[3] = {tile[0][k], tile[1][k], tile[2][k]};
#pragma unroll
          for (int k = 0; k < 3; ++k) {
            mn[k] = StdMin(mn[k], av[k]);
            mx[k] = StdMax(mx[k], av[k]);
            m1[k] += av[k];
            m2[k] += av[k] * av[k];
          }
        }
      }
      if (a.clip == 0) {
#pragma unroll
        for (int k = 0; k < 3; ++k) {
          const float mu = m1[k] / 9.0f;
          const float sigma = sqrtf(fabsf(m2[k] / 9.0f - mu * mu));
          mn[k] = StdMax(mn[k], mu - a.gamma * sigma);
          mx[k] = StdMin(mx[k], mu + a.gamma * sigma);
        }
      }
      const float hv[3] = {hy.y, hy.co, hy.cg};
      float centre[3], v[3], m = 0.0f;
#pragma unroll
      for (int k = 0; k < 3; ++k) {
        centre[k] = 0.5f * (mx[k] + mn[k]);
        const float ext = 0.5f * (mx[k] - mn[k]) + 1e-8f;
        v[k] = hv[k] - centre[k];
        m = StdMax(m, fabsf(v[k] / ext));
      }
      if (!(m <= 1.0f)) hy = {centre[0] + v[0] / m, centre[1] + v[1] / m, centre[2] + v[2] / m};
    }
    const int own = (threadIdx.y + 1) * kTile + threadIdx.x + 1;
    const Ycc cy{tile[0][own], tile[1][own], tile[2][own]};  // = ToYCoCg(c)
    const Ycc ob{hy.y + a.alpha * (cy.y - hy.y), hy.co + a.alpha * (cy.co - hy.co), hy.cg + a.alpha * (cy.cg - hy.cg)};
    const float tt = ob.y - ob.cg;
    o[0] = StdClamp(tt + ob.co, 0.0f, 1.0f);
    o[1] = StdClamp(ob.y + ob.cg, 0.0f, 1.0f);
    o[2] = StdClamp(tt - ob.co, 0.0f, 1.0f);
  }
  surf2Dwrite(make_float4(o[0], o[1], o[2], 1.0f), hist_out, x * 16, y);
  surf2Dwrite(make_uchar4(Encode(o[0], starts), Encode(o[1], starts), Encode(o[2], starts), 255), out, x * 4, y);
}

}  // namespace

void LaunchTaaResolve(const GpuFrame& frame, const float* previous, const GpuHistory* history, GpuHistory& next,
                      GpuFrame& out, const TaaArgs& args, const float* decode, const float* encode_starts,
                      cudaStream_t stream, bool software_filter) {
  const int w = frame.Width(), h = frame.Height();
  if (next.Width() != w || next.Height() != h || out.Width() != w || out.Height() != h ||
      (history && (history->Width() != w || history->Height() != h))) {
    throw std::runtime_error("LaunchTaaResolve: frame, history and output sizes differ");
  }
  if (!history) previous = nullptr;  // no history: every pixel takes the current colour
  const cudaTextureObject_t hp = history ? history->Point() : 0, hl = history ? history->Linear() : 0;
  const dim3 grid = Grid2D(w, h);
  if (software_filter) {
    TaaKernel<true><<<grid, Block2D(), 0, stream>>>(frame.Point(), previous, hp, hl, next.Surface(), out.Surface(), w,
                                                    h, args, decode, encode_starts);
  } else {
    TaaKernel<false><<<grid, Block2D(), 0, stream>>>(frame.Point(), previous, hp, hl, next.Surface(), out.Surface(),
                                                     w, h, args, decode, encode_starts);
  }
}

}  // namespace aalab::cuda
