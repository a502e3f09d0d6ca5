// FXAA 1.0 (methods/fxaa1.cpp) as a CUDA kernel: Fxaa1TracePixel's normal output, statement
// by statement in float32 (built with --fmad=false, like the CPU's -ffp-contract=off), one
// thread per pixel.
//
// Fetches go through the texture units:
//   N/W/M/E/S and the corners   point fetches at texel centres (exact, clamp-to-edge);
//   search and the final fetch  bilinear fetches in texel coordinates (linear_px view).
// Where the results can differ from the CPU (reported per method by the gpu tool):
//   - Texel values: the texture unit returns k/255 correctly rounded, the CPU k·fl(1/255)
//     (llvmpipe's conversion); they differ in the last bit for 126 of the 256 codes.
//   - The texture unit filters with 8-bit fixed-point weights (1/256 steps); the CPU uses the
//     float32 fraction. Search fetches sit at fractions 0 and 1/2 (exact in 8 bits), so only
//     the rounding of the filtered sum can differ there; the final fetch at the sub-pixel
//     shift 0.5 − dst/span is quantised to 1/256 of a texel.
//   - Search acceleration N > 1: like the CPU emulation, N bilinear probes averaged (not the
//     hardware's anisotropic filter, whose footprint is implementation-defined).
//   - Debug views are not ported (they are a CPU diagnostic).
#include "methods/cuda/device_ops.cuh"
#include "methods/cuda/post_filters_cuda.h"

namespace aalab::cuda {
namespace {

constexpr float kLumaGreen = static_cast<float>(0.587 / 0.299);

__device__ __forceinline__ float Luma(const float4& c) { return c.y * kLumaGreen + c.x; }

__device__ __forceinline__ float3 Add(float3 a, float3 b) { return make_float3(a.x + b.x, a.y + b.y, a.z + b.z); }
__device__ __forceinline__ float3 Rgb(const float4& c) { return make_float3(c.x, c.y, c.z); }

// SearchFetch: one bilinear fetch, or the mean of n probes along the edge.
template <bool kSoft>
__device__ __forceinline__ float3 SearchFetch(cudaTextureObject_t lin, cudaTextureObject_t pt, float u, float v,
                                              float ax, float ay, int n, int w, int h) {
  if (n == 1) return Rgb(BilinearPx<kSoft>(lin, pt, u, v, w, h));
  float3 sum = make_float3(0.0f, 0.0f, 0.0f);
  for (int k = 0; k < n; ++k) {
    const float o = static_cast<float>(k) - static_cast<float>(n - 1) * 0.5f;
    sum = Add(sum, Rgb(BilinearPx<kSoft>(lin, pt, u + ax * o, v + ay * o, w, h)));
  }
  const float nf = static_cast<float>(n);
  return make_float3(sum.x / nf, sum.y / nf, sum.z / nf);
}

__device__ __forceinline__ float Lerp3(float a, float b, float amount_of_a) {
  return (-amount_of_a * b) + ((a * amount_of_a) + b);
}

template <bool kSoft>
__global__ void Fxaa1Kernel(cudaTextureObject_t pt, cudaTextureObject_t lin, cudaSurfaceObject_t out, int w, int h,
                            Fxaa1Args p) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= w || y >= h) return;
  const float4 cn = Texel<kSoft>(pt, x, y - 1);
  const float4 cw = Texel<kSoft>(pt, x - 1, y);
  const float4 cm = Texel<kSoft>(pt, x, y);
  const float4 ce = Texel<kSoft>(pt, x + 1, y);
  const float4 cs = Texel<kSoft>(pt, x, y + 1);
  const float ln = Luma(cn), lw = Luma(cw), lm = Luma(cm), le = Luma(ce), ls = Luma(cs);
  // LocalContrastExit.
  const float range_min = fminf(lm, fminf(fminf(ln, lw), fminf(ls, le)));
  const float range_max = fmaxf(lm, fmaxf(fmaxf(ln, lw), fmaxf(ls, le)));
  const float range = range_max - range_min;
  if (range < fmaxf(p.edge_threshold_min, range_max * p.edge_threshold)) {
    WriteRgb(out, x, y, cm.x, cm.y, cm.z);
    return;
  }
  // SubpixBlend.
  const float luma_l = (ln + lw + le + ls) * 0.25f;
  const float range_l = fabsf(luma_l - lm);
  const float ratio = range > 0.0f ? range_l / range : 0.0f;
  const float trim_scale = 1.0f / (1.0f - p.subpix_trim);
  const float blend_l = fminf(p.subpix_cap, fmaxf(0.0f, ratio - p.subpix_trim) * trim_scale);
  // Corners and Lowpass.
  const float4 cnw = Texel<kSoft>(pt, x - 1, y - 1);
  const float4 cne = Texel<kSoft>(pt, x + 1, y - 1);
  const float4 csw = Texel<kSoft>(pt, x - 1, y + 1);
  const float4 cse = Texel<kSoft>(pt, x + 1, y + 1);
  float3 rgb_l;
  if (p.subpix_faster) {
    const float3 s = Add(Add(Add(Add(Rgb(cn), Rgb(cw)), Rgb(ce)), Rgb(cs)), Rgb(cm));
    const float k = 1.0f / 5.0f;
    rgb_l = make_float3(s.x * k, s.y * k, s.z * k);
  } else {
    float3 s = Add(Add(Add(Add(Rgb(cn), Rgb(cw)), Rgb(cm)), Rgb(ce)), Rgb(cs));
    s = Add(s, Add(Add(Add(Rgb(cnw), Rgb(cne)), Rgb(csw)), Rgb(cse)));
    const float k = 1.0f / 9.0f;
    rgb_l = make_float3(s.x * k, s.y * k, s.z * k);
  }
  // EdgeOrientation.
  const float nw = Luma(cnw), ne = Luma(cne), sw = Luma(csw), se = Luma(cse);
  const float edge_vert = fabsf((0.25f * nw) + (-0.5f * ln) + (0.25f * ne)) +
                          fabsf((0.50f * lw) + (-1.0f * lm) + (0.50f * le)) +
                          fabsf((0.25f * sw) + (-0.5f * ls) + (0.25f * se));
  const float edge_horz = fabsf((0.25f * nw) + (-0.5f * lw) + (0.25f * sw)) +
                          fabsf((0.50f * ln) + (-1.0f * lm) + (0.50f * ls)) +
                          fabsf((0.25f * ne) + (-0.5f * le) + (0.25f * se));
  const bool horz = edge_horz >= edge_vert;
  // PairNeighbour.
  const float luma_a = horz ? ln : lw;
  const float luma_b = horz ? ls : le;
  const float gradient_a = fabsf(luma_a - lm);
  const float gradient_b = fabsf(luma_b - lm);
  const bool pair_n = gradient_a >= gradient_b;
  const float luma_pair = pair_n ? (luma_a + lm) * 0.5f : (luma_b + lm) * 0.5f;
  const float gradient = (pair_n ? gradient_a : gradient_b) * p.search_threshold;
  const float side = pair_n ? -1.0f : 1.0f;
  // SearchEnds.
  const float cu = static_cast<float>(x) + 0.5f;
  const float cv = static_cast<float>(y) + 0.5f;
  const float ax = horz ? 1.0f : 0.0f;
  const float ay = horz ? 0.0f : 1.0f;
  const int accel = p.search_acceleration;
  const float pu = cu + (horz ? 0.0f : side * 0.5f);
  const float pv = cv + (horz ? side * 0.5f : 0.0f);
  const float start = static_cast<float>(accel + 1) * 0.5f;
  const float step = static_cast<float>(accel);
  float nu = pu - ax * start, nv = pv - ay * start;
  float qu = pu + ax * start, qv = pv + ay * start;
  float end_n = luma_pair, end_p = luma_pair;
  bool done_n = false, done_p = false;
  for (int i = 0; i < p.search_steps; ++i) {
    if (!done_n) {
      const float3 c = SearchFetch<kSoft>(lin, pt, nu, nv, ax, ay, accel, w, h);
      end_n = c.y * kLumaGreen + c.x;
    }
    if (!done_p) {
      const float3 c = SearchFetch<kSoft>(lin, pt, qu, qv, ax, ay, accel, w, h);
      end_p = c.y * kLumaGreen + c.x;
    }
    done_n = done_n || (fabsf(end_n - luma_pair) >= gradient);
    done_p = done_p || (fabsf(end_p - luma_pair) >= gradient);
    if (done_n && done_p) break;
    if (!done_n) {
      nu -= ax * step;
      nv -= ay * step;
    }
    if (!done_p) {
      qu += ax * step;
      qv += ay * step;
    }
  }
  const float dst_n = horz ? cu - nu : cv - nv;
  const float dst_p = horz ? qu - cu : qv - cv;
  // SubPixelShift.
  const bool direction_n = dst_n < dst_p;
  const float luma_end = direction_n ? end_n : end_p;
  float length_sign = side;
  if (((lm - luma_pair) < 0.0f) == ((luma_end - luma_pair) < 0.0f)) length_sign = 0.0f;
  const float span_length = dst_p + dst_n;
  const float dst = direction_n ? dst_n : dst_p;
  const float offset = span_length > 0.0f ? (0.5f + (dst * (-1.0f / span_length))) * length_sign : 0.0f;
  // Re-sample and blend.
  const float4 f = BilinearPx<kSoft>(lin, pt, cu + (horz ? 0.0f : offset), cv + (horz ? offset : 0.0f), w, h);
  WriteRgb(out, x, y, Lerp3(rgb_l.x, f.x, blend_l), Lerp3(rgb_l.y, f.y, blend_l), Lerp3(rgb_l.z, f.z, blend_l));
}

}  // namespace

void LaunchFxaa1(const GpuFrame& in, GpuFrame& out, const Fxaa1Args& args, cudaStream_t stream, bool software_filter) {
  if (software_filter) {
    Fxaa1Kernel<true><<<Grid2D(in.Width(), in.Height()), Block2D(), 0, stream>>>(
        in.Point(), in.LinearPx(), out.Surface(), in.Width(), in.Height(), args);
  } else {
    Fxaa1Kernel<false><<<Grid2D(in.Width(), in.Height()), Block2D(), 0, stream>>>(
        in.Point(), in.LinearPx(), out.Surface(), in.Width(), in.Height(), args);
  }
}

}  // namespace aalab::cuda
