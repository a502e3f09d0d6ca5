// RescaleFrame (methods/rescale.cpp) as a CUDA kernel, one thread per output pixel:
//   bilinear  one bilinear fetch at the output pixel centre in normalised coordinates
//             (linear_norm view), as the CPU's SampleNormalized;
//   bicubic   the B-spline folded into four bilinear fetches in texel coordinates
//             (linear_px view), with BsplineCubicTaps' expressions in float32.
// Deviation from the CPU (reported by the gpu tool): the texture unit's 8-bit fixed-point
// filter weights and its k/255 texel values (the CPU: k·fl(1/255)). At the 4/3 scale the fractions are multiples of 1/8
// for bilinear (exact in 8 bits) but arbitrary for the bicubic taps (w1/g0, w3/g1), which the hardware rounds to 1/256
// of a texel.
#include "methods/cuda/device_ops.cuh"
#include "methods/cuda/post_filters_cuda.h"

namespace aalab::cuda {
namespace {

struct Axis {
  float tap0, tap1, g0, g1;
};

// BicubicAxis + BsplineCubicTaps (methods/rescale.cpp), same float expressions.
__device__ __forceinline__ Axis BicubicAxis(int X, int n_out, int n_in) {
  const float s = (static_cast<float>(X) + 0.5f) / static_cast<float>(n_out);
  const float u = s * static_cast<float>(n_in);
  const float xx = u - 0.5f;
  const float i = floorf(xx);
  const float t = xx - i;
  const float sm = 1.0f - t;
  const float t2 = t * t;
  const float t3 = t2 * t;
  const float w0 = (sm * sm * sm) / 6.0f;
  const float w1 = ((3.0f * t3 - 6.0f * t2) + 4.0f) / 6.0f;
  const float w2 = (((-3.0f * t3 + 3.0f * t2) + 3.0f * t) + 1.0f) / 6.0f;
  const float w3 = t3 / 6.0f;
  Axis a;
  a.g0 = w0 + w1;
  a.g1 = w2 + w3;
  const float h0 = w1 / a.g0;
  const float h1 = w3 / a.g1;
  a.tap0 = ((i - 1.0f) + h0) + 0.5f;
  a.tap1 = ((i + 1.0f) + h1) + 0.5f;
  return a;
}

template <bool kSoft>
__global__ void BilinearKernel(cudaTextureObject_t lin_norm, cudaTextureObject_t pt, cudaSurfaceObject_t out, int in_w,
                               int in_h, int out_w, int out_h) {
  const int X = blockIdx.x * blockDim.x + threadIdx.x;
  const int Y = blockIdx.y * blockDim.y + threadIdx.y;
  if (X >= out_w || Y >= out_h) return;
  const float s = (static_cast<float>(X) + 0.5f) / static_cast<float>(out_w);
  const float t = (static_cast<float>(Y) + 0.5f) / static_cast<float>(out_h);
  const float4 c = BilinearNorm<kSoft>(lin_norm, pt, s, t, in_w, in_h);
  WriteRgb(out, X, Y, c.x, c.y, c.z);
}

template <bool kSoft>
__global__ void BicubicKernel(cudaTextureObject_t lin_px, cudaTextureObject_t pt, cudaSurfaceObject_t out, int in_w,
                              int in_h, int out_w, int out_h) {
  const int X = blockIdx.x * blockDim.x + threadIdx.x;
  const int Y = blockIdx.y * blockDim.y + threadIdx.y;
  if (X >= out_w || Y >= out_h) return;
  const Axis ax = BicubicAxis(X, out_w, in_w);
  const Axis ay = BicubicAxis(Y, out_h, in_h);
  const float4 c00 = BilinearPx<kSoft>(lin_px, pt, ax.tap0, ay.tap0, in_w, in_h);
  const float4 c10 = BilinearPx<kSoft>(lin_px, pt, ax.tap1, ay.tap0, in_w, in_h);
  const float4 c01 = BilinearPx<kSoft>(lin_px, pt, ax.tap0, ay.tap1, in_w, in_h);
  const float4 c11 = BilinearPx<kSoft>(lin_px, pt, ax.tap1, ay.tap1, in_w, in_h);
  const float r = ay.g0 * (ax.g0 * c00.x + ax.g1 * c10.x) + ay.g1 * (ax.g0 * c01.x + ax.g1 * c11.x);
  const float g = ay.g0 * (ax.g0 * c00.y + ax.g1 * c10.y) + ay.g1 * (ax.g0 * c01.y + ax.g1 * c11.y);
  const float b = ay.g0 * (ax.g0 * c00.z + ax.g1 * c10.z) + ay.g1 * (ax.g0 * c01.z + ax.g1 * c11.z);
  WriteRgb(out, X, Y, r, g, b);
}

}  // namespace

void LaunchRescale(const GpuFrame& in, GpuFrame& out, bool bicubic, cudaStream_t stream, bool software_filter) {
  const dim3 grid = Grid2D(out.Width(), out.Height());
  const int iw = in.Width(), ih = in.Height(), ow = out.Width(), oh = out.Height();
  if (bicubic && software_filter) {
    BicubicKernel<true><<<grid, Block2D(), 0, stream>>>(in.LinearPx(), in.Point(), out.Surface(), iw, ih, ow, oh);
  } else if (bicubic) {
    BicubicKernel<false><<<grid, Block2D(), 0, stream>>>(in.LinearPx(), in.Point(), out.Surface(), iw, ih, ow, oh);
  } else if (software_filter) {
    BilinearKernel<true><<<grid, Block2D(), 0, stream>>>(in.LinearNorm(), in.Point(), out.Surface(), iw, ih, ow, oh);
  } else {
    BilinearKernel<false><<<grid, Block2D(), 0, stream>>>(in.LinearNorm(), in.Point(), out.Surface(), iw, ih, ow, oh);
  }
}

}  // namespace aalab::cuda
