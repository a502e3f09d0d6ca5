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
#include <cuda_fp16.h>

#include <stdexcept>
#include <vector>

#include "methods/cuda/device_ops.cuh"
#include "methods/cuda/taa_common.cuh"
#include "methods/cuda/post_filters_cuda.h"

namespace aalab::cuda {

GpuHistory::GpuHistory(int width, int height, bool half) : width_(width), height_(height), half_(half) {
  if (width < 1 || height < 1) throw std::runtime_error("GpuHistory needs a positive size");
  const cudaChannelFormatDesc desc = half ? cudaCreateChannelDescHalf4() : cudaCreateChannelDesc<float4>();
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
  if (!half_) {
    const size_t row = static_cast<size_t>(width_) * 16;
    Check(cudaMemcpy2DFromArray(rgba, row, array_, 0, 0, row, height_, cudaMemcpyDeviceToHost), "download");
    return;
  }
  const size_t n = 4 * static_cast<size_t>(width_) * height_, row = static_cast<size_t>(width_) * 8;
  std::vector<__half> h(n);
  Check(cudaMemcpy2DFromArray(h.data(), row, array_, 0, 0, row, height_, cudaMemcpyDeviceToHost), "download");
  for (size_t i = 0; i < n; ++i) rgba[i] = __half2float(h[i]);
}

namespace {

using namespace taa_detail;

template <bool kSoft>
__global__ void TaaKernel(cudaTextureObject_t frame, const float* __restrict__ previous, cudaTextureObject_t hist_pt,
                          cudaTextureObject_t hist_lin, cudaSurfaceObject_t hist_out, cudaSurfaceObject_t out, int w,
                          int h, TaaArgs a, const float* __restrict__ decode_g, const float* __restrict__ starts_g) {
  __shared__ BlockShared sh;
  StageBlock(sh, frame, w, h, decode_g, starts_g);
  const float* decode = sh.decode;
  const float* starts = sh.starts;
  const int bx = blockIdx.x * blockDim.x, by = blockIdx.y * blockDim.y;
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
      SoftBilinearHistory(hist_pt, px, py, w, h, hrgb);
    } else {
      const float4 H = tex2D<float4>(hist_lin, px, py);
      hrgb[0] = H.x, hrgb[1] = H.y, hrgb[2] = H.z;
    }
    Ycc hy = ToYCoCg(hrgb[0], hrgb[1], hrgb[2]);
    if (a.clip != 2) hy = RectifyInTile(sh, hy, a.clip, a.gamma);  // TaaState::Rectify + ClipToBox
    const int own = (threadIdx.y + 1) * kTile + threadIdx.x + 1;
    const Ycc cy{sh.tile[0][own], sh.tile[1][own], sh.tile[2][own]};  // = ToYCoCg(c)
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
  if (next.Half() || (history && history->Half()))
    throw std::runtime_error("LaunchTaaResolve: taa's history is RGBA32F");
  if (!history) previous = nullptr;  // no history: every pixel takes the current colour
  const cudaTextureObject_t hp = history ? history->Point() : 0, hl = history ? history->Linear() : 0;
  const dim3 grid = Grid2D(w, h);
  if (software_filter) {
    TaaKernel<true><<<grid, Block2D(), 0, stream>>>(frame.Point(), previous, hp, hl, next.Surface(), out.Surface(), w,
                                                    h, args, decode, encode_starts);
  } else {
    TaaKernel<false><<<grid, Block2D(), 0, stream>>>(frame.Point(), previous, hp, hl, next.Surface(), out.Surface(), w,
                                                     h, args, decode, encode_starts);
  }
}

}  // namespace aalab::cuda
