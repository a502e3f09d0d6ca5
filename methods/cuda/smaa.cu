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
// Passes 2 and 3 compile the CPU's own shader text (smaa_shader.h: WeightsShader,
// BlendPixelColor, marked AALAB_HD) over the device readers below; pass 1 is written here
// statement by statement as smaa.cpp's. Every expression is float32 in the CPU's order, built with
// --fmad=false as the CPU build has -ffp-contract=off. The hardware path filters in the
// texture unit; kSoft = true replaces every fetch by the CPU's BilinearSampler arithmetic
// (UnormToFloat texels, the sub-texel mode of the method: 8-bit fractions by default) from
// point fetches, which reproduces the CPU bit for bit (gpu tool's software-filter check).
// The edge and blend targets are whole-frame RGBA8 cudaArrays (the reference's RG8/RGBA8
// render targets widened to RGBA8: same values, one texture format for every frame here).
#include "methods/cuda/device_ops.cuh"
#include "methods/cuda/post_filters_cuda.h"
#include "methods/smaa_shader.h"

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

// The readers smaa_detail::WeightsShader and BlendPixelColor fetch through: the edge target
// in texel coordinates, and the area, search, blend and colour textures in normalised ones.
template <bool kSoft>
struct EdgeReader {
  Tex t;
  bool fixed8;
  __device__ smaa_detail::F2 Sample(float u, float v) const {
    const float4 e = SamplePx<kSoft>(t, u, v, fixed8);
    return {e.x, e.y};
  }
};

template <bool kSoft>
struct NormReader {
  Tex t;
  bool fixed8;
  __device__ Float4 SampleNormalized(float s, float tt) const {
    const float4 c = SampleNorm<kSoft>(t, s, tt, fixed8);
    return {c.x, c.y, c.z, c.w};
  }
};

// SMAABlendingWeightCalculationPS: the CPU's shader text (smaa_shader.h) over device readers.
template <bool kSoft>
__global__ void WeightsKernel(Tex edges, Tex area, Tex search, cudaSurfaceObject_t out, SmaaArgs p) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= edges.w || y >= edges.h) return;
  const bool fixed8 = p.fixed8 != 0;
  EdgeReader<kSoft> er{edges, fixed8};
  NormReader<kSoft> ar{area, fixed8};
  NormReader<kSoft> sr{search, fixed8};
  const smaa_detail::Frame f(edges.w, edges.h);
  smaa_detail::WeightsShader<EdgeReader<kSoft>, NormReader<kSoft>, SmaaArgs> shader(er, ar, sr, p, f);
  const Float4 w = shader.Run(x, y);
  surf2Dwrite(make_uchar4(QuantizeUnorm8(w.r), QuantizeUnorm8(w.g), QuantizeUnorm8(w.b), QuantizeUnorm8(w.a)), out,
              x * 4, y);
}

// ---------------------------------------------------------------------------------- pass 3

// SMAANeighborhoodBlendingPS: smaa_detail::BlendPixelColor over device readers.
template <bool kSoft>
__global__ void BlendKernel(Tex blend, Tex color, cudaSurfaceObject_t out, SmaaArgs p) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= color.w || y >= color.h) return;
  const bool fixed8 = p.fixed8 != 0;
  NormReader<kSoft> br{blend, fixed8};
  NormReader<kSoft> cr{color, fixed8};
  const smaa_detail::Frame f(color.w, color.h);
  const Float4 c = smaa_detail::BlendPixelColor(br, cr, f, x, y);
  WriteRgb(out, x, y, c.r, c.g, c.b);
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
    WeightsKernel<true>
        <<<grid, Block2D(), 0, stream>>>(TexOf(edges), TexOf(area), TexOf(search), blend.Surface(), args);
  } else {
    WeightsKernel<false>
        <<<grid, Block2D(), 0, stream>>>(TexOf(edges), TexOf(area), TexOf(search), blend.Surface(), args);
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
