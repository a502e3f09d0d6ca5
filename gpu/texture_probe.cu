#include "gpu/texture_probe.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "harness/core/sampler.h"
#include "methods/cuda/post_filters_cuda.h"

namespace aalab {
namespace {

__global__ void ProbeKernel(cudaTextureObject_t lin, float* out, int n) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i > n) return;
  out[i] = tex2D<float4>(lin, 0.5f + static_cast<float>(i) / static_cast<float>(n), 0.5f).x;
}

// Row a of a 512×256 texture holds (a, b) at texels (2b, 2b+1): fetch at u = 2b + 1, the
// midpoint of their centres; also the point fetch of texel (2b+1, a) = b.
__global__ void PairKernel(cudaTextureObject_t lin, cudaTextureObject_t pt, float* half, float* point) {
  const int b = blockIdx.x * blockDim.x + threadIdx.x;
  const int a = blockIdx.y;
  if (b >= 256) return;
  half[a * 256 + b] = tex2D<float4>(lin, 2.0f * b + 1.0f, a + 0.5f).x;
  point[a * 256 + b] = tex2D<float4>(pt, 2.0f * b + 1.5f, a + 0.5f).x;
}

}  // namespace

TextureProbe ProbeTextureFilter() {
  constexpr int kN = 4096;
  cuda::GpuFrame frame(2, 1);
  const uint8_t texels[8] = {0, 0, 0, 255, 255, 0, 0, 255};
  frame.Upload(texels);
  float* d = nullptr;
  cuda::Check(cudaMalloc(&d, (kN + 1) * sizeof(float)), "cudaMalloc");
  ProbeKernel<<<(kN + 256) / 256, 256>>>(frame.LinearPx(), d, kN);
  cuda::Check(cudaGetLastError(), "probe launch");
  std::vector<float> h(kN + 1);
  cuda::Check(cudaMemcpy(h.data(), d, h.size() * sizeof(float), cudaMemcpyDeviceToHost), "probe download");
  cudaFree(d);
  TextureProbe p;
  p.samples = kN + 1;
  std::set<float> distinct;
  for (int i = 0; i <= kN; ++i) {
    const double f = static_cast<double>(i) / kN;
    const double g = h[i] * 255.0;
    p.err_float = std::max(p.err_float, std::fabs(g - f * 255.0));
    p.err_round256 = std::max(p.err_round256, std::fabs(g - std::round(f * 256.0) / 256.0 * 255.0));
    p.err_trunc256 = std::max(p.err_trunc256, std::fabs(g - std::floor(f * 256.0) / 256.0 * 255.0));
    distinct.insert(h[i]);
  }
  p.distinct_values = static_cast<int>(distinct.size());

  cuda::GpuFrame pairs(512, 256);
  std::vector<uint8_t> tex(512 * 256 * 4, 255);
  for (int a = 0; a < 256; ++a) {
    for (int b = 0; b < 256; ++b) {
      tex[(a * 512 + 2 * b) * 4] = static_cast<uint8_t>(a);
      tex[(a * 512 + 2 * b + 1) * 4] = static_cast<uint8_t>(b);
    }
  }
  pairs.Upload(tex.data());
  float *dh = nullptr, *dp = nullptr;
  cuda::Check(cudaMalloc(reinterpret_cast<void**>(&dh), 65536 * sizeof(float)), "cudaMalloc");
  cuda::Check(cudaMalloc(reinterpret_cast<void**>(&dp), 65536 * sizeof(float)), "cudaMalloc");
  PairKernel<<<dim3(1, 256), 256>>>(pairs.LinearPx(), pairs.Point(), dh, dp);
  cuda::Check(cudaGetLastError(), "pair probe launch");
  std::vector<float> hh(65536), hp(65536);
  cuda::Check(cudaMemcpy(hh.data(), dh, hh.size() * sizeof(float), cudaMemcpyDeviceToHost), "probe download");
  cuda::Check(cudaMemcpy(hp.data(), dp, hp.size() * sizeof(float), cudaMemcpyDeviceToHost), "probe download");
  cudaFree(dh);
  cudaFree(dp);
  for (int b = 0; b < 256; ++b) {
    if (hp[b] != static_cast<float>(b) / 255.0f) ++p.unorm_mismatches;
    if (hp[b] != UnormToFloat(static_cast<uint8_t>(b))) ++p.unorm_mismatches_cpu;
  }
  for (int a = 0; a < 256; ++a) {
    for (int b = 0; b < 256; ++b) {
      // BilinearSampler::Sample at fractions (0.5, 0): BilinearBlend = lerp(lerp(a, b, 0.5),
      // lerp(a', b', 0.5), 0) = a + 0.5·(b − a), texels UnormToFloat.
      const float fa = UnormToFloat(static_cast<uint8_t>(a)), fb = UnormToFloat(static_cast<uint8_t>(b));
      const float cpu = FilterLerp(fa, fb, 0.5f);
      const float gpu = hh[a * 256 + b];
      ++p.half_pairs;
      if (gpu != cpu) ++p.half_mismatches;
      p.half_max_err = std::max(p.half_max_err, std::fabs(static_cast<double>(gpu) - cpu));
    }
  }
  return p;
}

}  // namespace aalab
