// GpuFrame (a cudaArray with its texture and surface views), the two copy floors and the
// FXAA 3.11 luma pre-pass. See post_filters_cuda.h.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "methods/cuda/device_ops.cuh"
#include "methods/cuda/post_filters_cuda.h"

namespace aalab::cuda {

void Check(cudaError_t err, const char* what) {
  if (err != cudaSuccess) {
    throw std::runtime_error(std::string("CUDA error in ") + what + ": " + cudaGetErrorString(err));
  }
}

namespace {

cudaTextureObject_t MakeTexture(cudaArray_t array, cudaTextureFilterMode filter, bool normalized) {
  cudaResourceDesc res{};
  res.resType = cudaResourceTypeArray;
  res.res.array.array = array;
  cudaTextureDesc td{};
  td.addressMode[0] = cudaAddressModeClamp;
  td.addressMode[1] = cudaAddressModeClamp;
  td.filterMode = filter;
  td.readMode = cudaReadModeNormalizedFloat;  // UNORM: k / 255
  td.normalizedCoords = normalized ? 1 : 0;
  cudaTextureObject_t t = 0;
  Check(cudaCreateTextureObject(&t, &res, &td, nullptr), "cudaCreateTextureObject");
  return t;
}

}  // namespace

GpuFrame::GpuFrame(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::runtime_error("GpuFrame needs a positive size");
  const cudaChannelFormatDesc desc = cudaCreateChannelDesc<uchar4>();
  Check(cudaMallocArray(&array_, &desc, width, height, cudaArraySurfaceLoadStore), "cudaMallocArray");
  point_ = MakeTexture(array_, cudaFilterModePoint, false);
  linear_px_ = MakeTexture(array_, cudaFilterModeLinear, false);
  linear_norm_ = MakeTexture(array_, cudaFilterModeLinear, true);
  cudaResourceDesc res{};
  res.resType = cudaResourceTypeArray;
  res.res.array.array = array_;
  Check(cudaCreateSurfaceObject(&surface_, &res), "cudaCreateSurfaceObject");
}

GpuFrame::~GpuFrame() {
  cudaDestroySurfaceObject(surface_);
  cudaDestroyTextureObject(linear_norm_);
  cudaDestroyTextureObject(linear_px_);
  cudaDestroyTextureObject(point_);
  cudaFreeArray(array_);
}

void GpuFrame::Upload(const uint8_t* rgba) {
  const size_t row = static_cast<size_t>(width_) * 4;
  Check(cudaMemcpy2DToArray(array_, 0, 0, rgba, row, row, height_, cudaMemcpyHostToDevice), "upload");
}

void GpuFrame::Download(uint8_t* rgba) const {
  const size_t row = static_cast<size_t>(width_) * 4;
  Check(cudaMemcpy2DFromArray(rgba, row, array_, 0, 0, row, height_, cudaMemcpyDeviceToHost), "download");
}

namespace {

// The texture-path floor: one point fetch and one surface write per pixel. The fetch
// converts to k/255 and the write back to k (QuantizeUnorm8 of k/255 is k), the same
// conversions every filter does on its early-exit pixels.
__global__ void CopyTextureKernel(cudaTextureObject_t in, cudaSurfaceObject_t out, int w, int h) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= w || y >= h) return;
  const float4 c = TexelAt(in, x, y);
  surf2Dwrite(make_uchar4(QuantizeUnorm8(c.x), QuantizeUnorm8(c.y), QuantizeUnorm8(c.z), QuantizeUnorm8(c.w)), out,
              x * 4, y);
}

__global__ void CopyLinearKernel(const uint4* __restrict__ in, uint4* __restrict__ out, size_t n) {
  for (size_t i = blockIdx.x * static_cast<size_t>(blockDim.x) + threadIdx.x; i < n;
       i += static_cast<size_t>(gridDim.x) * blockDim.x) {
    out[i] = in[i];
  }
}

// Fxaa311LumaFrame on the GPU: same expressions, alpha = StoreUnorm8(luma) (an RGBA8 target).
template <bool kSoft>
__global__ void LumaKernel(cudaTextureObject_t in, cudaSurfaceObject_t out, int w, int h, int sqrt_luminance,
                           const float* __restrict__ decode) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= w || y >= h) return;
  const float4 c = Texel<kSoft>(in, x, y);
  float l;
  if (!sqrt_luminance) {
    l = c.x * 0.299f + (c.y * 0.587f + c.z * 0.114f);  // Fxaa311TapLuma(kRec601Rgb)
  } else {
    const float r = decode[QuantizeUnorm8(c.x)];
    const float g = decode[QuantizeUnorm8(c.y)];
    const float b = decode[QuantizeUnorm8(c.z)];
    l = sqrtf((r * 0.2126729f + g * 0.7151522f) + b * 0.0721750f);
  }
  surf2Dwrite(make_uchar4(QuantizeUnorm8(c.x), QuantizeUnorm8(c.y), QuantizeUnorm8(c.z), StoreUnorm8(l)), out, x * 4,
              y);
}

}  // namespace

void LaunchCopyTexture(const GpuFrame& in, GpuFrame& out, cudaStream_t stream) {
  CopyTextureKernel<<<Grid2D(in.Width(), in.Height()), Block2D(), 0, stream>>>(in.Point(), out.Surface(), in.Width(),
                                                                               in.Height());
}

void LaunchCopyLinear(const void* in, void* out, size_t bytes, cudaStream_t stream) {
  const size_t n = bytes / 16;
  const int threads = 256;
  const int blocks = static_cast<int>(std::min<size_t>((n + threads - 1) / threads, 132 * 16));
  CopyLinearKernel<<<blocks, threads, 0, stream>>>(static_cast<const uint4*>(in), static_cast<uint4*>(out), n);
}

void LaunchLumaPrepass(const GpuFrame& in, GpuFrame& out, LumaSource luma, const float* srgb_decode,
                       cudaStream_t stream, bool software_filter) {
  if (luma != LumaSource::kRec601 && luma != LumaSource::kSqrtLuminance) {
    throw std::runtime_error("LaunchLumaPrepass: this luma source has no pre-pass");
  }
  const int sq = luma == LumaSource::kSqrtLuminance ? 1 : 0;
  if (software_filter) {
    LumaKernel<true><<<Grid2D(in.Width(), in.Height()), Block2D(), 0, stream>>>(in.Point(), out.Surface(), in.Width(),
                                                                                in.Height(), sq, srgb_decode);
  } else {
    LumaKernel<false><<<Grid2D(in.Width(), in.Height()), Block2D(), 0, stream>>>(in.Point(), out.Surface(), in.Width(),
                                                                                 in.Height(), sq, srgb_decode);
  }
}

}  // namespace aalab::cuda
