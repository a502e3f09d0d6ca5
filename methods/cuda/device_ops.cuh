// Device helpers shared by the CUDA post filters (methods/cuda/*.cu): the CPU side's
// QuantizeUnorm8, texel reads through the point view, pixel writes through the surface.
#pragma once
#include <cuda_runtime.h>

namespace aalab::cuda {

/// core/color.cpp QuantizeUnorm8: 0 for v <= 0 (and NaN), 255 for v >= 1, else
/// lround(v·255) with the product rounded to float first.
__device__ __forceinline__ unsigned char QuantizeUnorm8(float v) {
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  return static_cast<unsigned char>(lroundf(v * 255.0f));
}

/// Exact read of texel (x, y), clamp-to-edge: a point fetch at its centre.
__device__ __forceinline__ float4 TexelAt(cudaTextureObject_t point, int x, int y) {
  return tex2D<float4>(point, static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
}

/// core/sampler.h StoreUnorm8: GL's float-to-UNORM8 store of a render target
/// (clamp, ·255, round to nearest with ties to even), as the CPU's FXAA 3.11 writes.
__device__ __forceinline__ unsigned char StoreUnorm8(float v) {
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  return static_cast<unsigned char>(rintf(v * 255.0f));
}

/// The CPU's texel value for the code k behind a texture read: UnormToFloat(k) = k·fl(1/255)
/// (what llvmpipe returns; the CPU reference follows it). The texture unit returns k/255
/// correctly rounded instead (measured: gpu/texture_probe.cu); the two differ in the last bit
/// for 126 of the 256 codes. `hw` is the texture unit's value, from which k is exact.
__device__ __forceinline__ float CpuUnorm(float hw) {
  return static_cast<float>(lroundf(hw * 255.0f)) * (1.0f / 255.0f);
}

/// A texel read: the texture unit's value (kSoft = false) or the CPU's (kSoft = true).
template <bool kSoft>
__device__ __forceinline__ float4 Texel(cudaTextureObject_t point, int x, int y) {
  const float4 t = TexelAt(point, x, y);
  if constexpr (kSoft) {
    return make_float4(CpuUnorm(t.x), CpuUnorm(t.y), CpuUnorm(t.z), CpuUnorm(t.w));
  } else {
    return t;
  }
}

/// sampler.h FilterLerp / BilinearBlend: lerp(lerp(a, b, fx), lerp(c, d, fx), fy), a + w·(b − a).
__device__ __forceinline__ float FilterLerp(float a, float b, float w) { return a + w * (b - a); }

/// The four CPU-decoded texels at corner (x0f, y0f) (clamped to [-1, w] × [-1, h]; the
/// fetches clamp to the edge) blended with fractions (fx, fy) in sampler.h's order: the
/// shared tail of SoftBilinear and of SMAA's software sampler (methods/cuda/smaa.cu).
__device__ __forceinline__ float4 SoftBlendAt(cudaTextureObject_t point, float x0f, float y0f, float fx, float fy,
                                              int w, int h) {
  const int x0 = static_cast<int>(fminf(fmaxf(x0f, -1.0f), static_cast<float>(w)));
  const int y0 = static_cast<int>(fminf(fmaxf(y0f, -1.0f), static_cast<float>(h)));
  const float4 a = Texel<true>(point, x0, y0);
  const float4 b = Texel<true>(point, x0 + 1, y0);
  const float4 c = Texel<true>(point, x0, y0 + 1);
  const float4 d = Texel<true>(point, x0 + 1, y0 + 1);
  auto blend = [fx, fy](float ta, float tb, float tc, float td) {
    return FilterLerp(FilterLerp(ta, tb, fx), FilterLerp(tc, td, fx), fy);
  };
  return make_float4(blend(a.x, b.x, c.x, d.x), blend(a.y, b.y, c.y, d.y), blend(a.z, b.z, c.z, d.z),
                     blend(a.w, b.w, c.w, d.w));
}

/// The CPU's BilinearSampler::Sample (core/sampler.h: BilinearAt, BilinearBlend,
/// UnormToFloat texels) from four point fetches, in float32 with the CPU's operation order:
/// the "software filter" variant the gpu tool uses to show that every GPU/CPU difference
/// comes from the texture unit (with it, outputs are bit-identical to the CPU).
__device__ __forceinline__ float4 SoftBilinear(cudaTextureObject_t point, float u, float v, int w, int h) {
  const float x = u - 0.5f;
  const float y = v - 0.5f;
  const float x0f = floorf(x);
  const float y0f = floorf(y);
  return SoftBlendAt(point, x0f, y0f, x - x0f, y - y0f, w, h);
}

/// A bilinear fetch at texel coordinates (u, v): the texture unit (kSoft = false) or
/// SoftBilinear (kSoft = true).
template <bool kSoft>
__device__ __forceinline__ float4 BilinearPx(cudaTextureObject_t lin_px, cudaTextureObject_t point, float u, float v,
                                             int w, int h) {
  if constexpr (kSoft) {
    return SoftBilinear(point, u, v, w, h);
  } else {
    return tex2D<float4>(lin_px, u, v);
  }
}

/// A bilinear fetch at normalised coordinates (s, t), as GL's texture(): the texture unit, or
/// the CPU's SampleNormalized (u = s·W, v = t·H in float32, then SoftBilinear).
template <bool kSoft>
__device__ __forceinline__ float4 BilinearNorm(cudaTextureObject_t lin_norm, cudaTextureObject_t point, float s,
                                               float t, int w, int h) {
  if constexpr (kSoft) {
    return SoftBilinear(point, s * static_cast<float>(w), t * static_cast<float>(h), w, h);
  } else {
    return tex2D<float4>(lin_norm, s, t);
  }
}

/// Writes rgb rounded to 8 bits (QuantizeUnorm8) and alpha 255 to pixel (x, y) of the surface.
__device__ __forceinline__ void WriteRgb(cudaSurfaceObject_t out, int x, int y, float r, float g, float b) {
  surf2Dwrite(make_uchar4(QuantizeUnorm8(r), QuantizeUnorm8(g), QuantizeUnorm8(b), 255), out, x * 4, y);
}

/// Writes rgb with StoreUnorm8 (ties to even) and alpha 255.
__device__ __forceinline__ void StoreRgb(cudaSurfaceObject_t out, int x, int y, float r, float g, float b) {
  surf2Dwrite(make_uchar4(StoreUnorm8(r), StoreUnorm8(g), StoreUnorm8(b), 255), out, x * 4, y);
}

/// The launch shape every 2D kernel here uses: 16 × 16 threads, one thread per output pixel.
inline dim3 Block2D() { return dim3(16, 16); }
inline dim3 Grid2D(int w, int h) { return dim3((w + 15) / 16, (h + 15) / 16); }

}  // namespace aalab::cuda
