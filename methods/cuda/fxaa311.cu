// FXAA 3.11 Quality (methods/fxaa311.cpp, ShadePixel) as a CUDA kernel: the shader's
// statements in its order, float32, built with --fmad=false (the CPU build's
// -ffp-contract=off), one thread per pixel; the step table and the luma source are
// arguments (Fxaa311Args), filled from the CPU side's tables by the caller.
//
// Fetches go through the texture units, every one bilinear as in the shader text:
//   FxaaTexTop / FxaaTexOff (M and the 8 neighbours)  texture2D(tex, posM + off·rcp) in
//                                                      normalised coordinates (linear_norm);
//                                                      fxaa-iter12: textureLodOffset, i.e. a
//                                                      fetch at posM·size + off (linear_px);
//   search taps and the final tap                      normalised coordinates, as the shader.
// Outputs are stored as an RGBA8 render target stores them (StoreUnorm8, ties to even).
// Where the results can differ from the CPU (reported per method by the gpu tool): texel
// values (the texture unit's k/255 against the CPU's k·fl(1/255), the last bit of 126 codes),
// and the
// texture unit converts the normalised coordinate to texel space and filters with 8-bit
// fixed-point weights (1/256 of a texel), the CPU with the float32 fraction. Search taps sit
// at half-texel positions across the edge, so their weights are exact; the final tap's
// sub-pixel offset (any value in [0, 0.5]) is rounded to 1/256 of a texel.
#include "methods/cuda/device_ops.cuh"
#include "methods/cuda/post_filters_cuda.h"

namespace aalab::cuda {
namespace {

// Fxaa311TapLuma.
__device__ __forceinline__ float TapLuma(const float4& t, LumaSource luma) {
  switch (luma) {
    case LumaSource::kRec601:
    case LumaSource::kSqrtLuminance: return t.w;
    case LumaSource::kGreen: return t.y;
    case LumaSource::kRec601Rgb: return t.x * 0.299f + (t.y * 0.587f + t.z * 0.114f);
  }
  return t.w;
}

template <bool kSoft>
__global__ void Fxaa311Kernel(cudaTextureObject_t pt, cudaTextureObject_t lin, cudaTextureObject_t lin_px,
                              cudaSurfaceObject_t out, int w, int h, Fxaa311Args prm) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= w || y >= h) return;
  const LumaSource lm = prm.luma;
  const bool glsl = prm.seed003_order != 0;
  const float rcpX = 1.0f / static_cast<float>(w);
  const float rcpY = 1.0f / static_cast<float>(h);

  float posMx = (static_cast<float>(x) + 0.5f) / static_cast<float>(w);
  float posMy = (static_cast<float>(y) + 0.5f) / static_cast<float>(h);
  // The 3x3 taps as the shader writes them (methods/fxaa311.cpp "Taps"): texture2D(tex,
  // posM + off·rcp) in normalised coordinates, or textureLodOffset (seed 003) = a fetch at
  // posM·size + off in texel coordinates.
  auto tap = [&](int dx, int dy) {
    if (glsl) {
      return BilinearPx<kSoft>(lin_px, pt, posMx * static_cast<float>(w) + static_cast<float>(dx),
                               posMy * static_cast<float>(h) + static_cast<float>(dy), w, h);
    }
    return BilinearNorm<kSoft>(lin, pt, posMx + static_cast<float>(dx) * rcpX, posMy + static_cast<float>(dy) * rcpY, w,
                               h);
  };
  const float4 rgbyM = tap(0, 0);
  const float lumaM = TapLuma(rgbyM, lm);
  float lumaS = TapLuma(tap(0, 1), lm);
  float lumaE = TapLuma(tap(1, 0), lm);
  float lumaN = TapLuma(tap(0, -1), lm);
  float lumaW = TapLuma(tap(-1, 0), lm);

  const float maxSM = fmaxf(lumaS, lumaM);
  const float minSM = fminf(lumaS, lumaM);
  const float maxESM = fmaxf(lumaE, maxSM);
  const float minESM = fminf(lumaE, minSM);
  const float maxWN = fmaxf(lumaN, lumaW);
  const float minWN = fminf(lumaN, lumaW);
  const float rangeMax = fmaxf(maxWN, maxESM);
  const float rangeMin = fminf(minWN, minESM);
  const float rangeMaxScaled = rangeMax * prm.edge_threshold;
  const float range = rangeMax - rangeMin;
  const float rangeMaxClamped = fmaxf(prm.edge_threshold_min, rangeMaxScaled);
  if (range < rangeMaxClamped) {  // return rgbyM
    StoreRgb(out, x, y, rgbyM.x, rgbyM.y, rgbyM.z);
    return;
  }
  if (range == 0.0f) {  // the CPU's guard (no 1/0): the input pixel
    const float4 in = TexelAt(pt, x, y);
    WriteRgb(out, x, y, in.x, in.y, in.z);
    return;
  }

  const float lumaNW = TapLuma(tap(-1, -1), lm);
  const float lumaSE = TapLuma(tap(1, 1), lm);
  const float lumaNE = TapLuma(tap(1, -1), lm);
  const float lumaSW = TapLuma(tap(-1, 1), lm);

  const float lumaNS = lumaN + lumaS;
  const float lumaWE = lumaW + lumaE;
  const float subpixRcpRange = 1.0f / range;
  const float subpixNSWE = lumaNS + lumaWE;
  const float edgeHorz1 = (-2.0f * lumaM) + lumaNS;
  const float edgeVert1 = (-2.0f * lumaM) + lumaWE;
  const float lumaNESE = lumaNE + lumaSE;
  const float lumaNWNE = lumaNW + lumaNE;
  const float edgeHorz2 = (-2.0f * lumaE) + lumaNESE;
  const float edgeVert2 = (-2.0f * lumaN) + lumaNWNE;
  const float lumaNWSW = lumaNW + lumaSW;
  const float lumaSWSE = lumaSW + lumaSE;
  const float edgeHorz4 = (fabsf(edgeHorz1) * 2.0f) + fabsf(edgeHorz2);
  const float edgeVert4 = (fabsf(edgeVert1) * 2.0f) + fabsf(edgeVert2);
  const float edgeHorz3 = (-2.0f * lumaW) + lumaNWSW;
  const float edgeVert3 = (-2.0f * lumaS) + lumaSWSE;
  float edgeHorz = fabsf(edgeHorz3) + edgeHorz4;
  float edgeVert = fabsf(edgeVert3) + edgeVert4;
  if (glsl) {
    edgeHorz = (fabsf(edgeHorz3) + fabsf(edgeHorz1) * 2.0f) + fabsf(edgeHorz2);
    edgeVert = (fabsf(edgeVert3) + fabsf(edgeVert1) * 2.0f) + fabsf(edgeVert2);
  }

  const float subpixNWSWNESE = lumaNWSW + lumaNESE;
  float lengthSign = rcpX;
  const bool horzSpan = edgeHorz >= edgeVert;
  const float subpixA = subpixNSWE * 2.0f + subpixNWSWNESE;
  if (!horzSpan) lumaN = lumaW;
  if (!horzSpan) lumaS = lumaE;
  if (horzSpan) lengthSign = rcpY;
  float subpixB = (subpixA * (1.0f / 12.0f)) - lumaM;
  if (glsl) subpixB = ((1.0f / 12.0f) * ((2.0f * subpixNSWE + lumaNWSW) + lumaNESE)) - lumaM;

  const float gradientN = lumaN - lumaM;
  const float gradientS = lumaS - lumaM;
  float lumaNN = lumaN + lumaM;
  const float lumaSS = lumaS + lumaM;
  const bool pairN = fabsf(gradientN) >= fabsf(gradientS);
  const float gradient = fmaxf(fabsf(gradientN), fabsf(gradientS));
  if (pairN) lengthSign = -lengthSign;
  const float subpixCIn = glsl ? fabsf(subpixB) / range : fabsf(subpixB) * subpixRcpRange;
  const float subpixC = fminf(fmaxf(subpixCIn, 0.0f), 1.0f);

  float posBx = posMx;
  float posBy = posMy;
  const float offNPx = (!horzSpan) ? 0.0f : rcpX;
  const float offNPy = (horzSpan) ? 0.0f : rcpY;
  if (!horzSpan) posBx += lengthSign * 0.5f;
  if (horzSpan) posBy += lengthSign * 0.5f;

  const float* P = prm.steps;
  float posNx = posBx - offNPx * P[0];
  float posNy = posBy - offNPy * P[0];
  float posPx = posBx + offNPx * P[0];
  float posPy = posBy + offNPy * P[0];
  const float subpixD = ((-2.0f) * subpixC) + 3.0f;
  float lumaEndN = TapLuma(BilinearNorm<kSoft>(lin, pt, posNx, posNy, w, h), lm);
  const float subpixE = subpixC * subpixC;
  float lumaEndP = TapLuma(BilinearNorm<kSoft>(lin, pt, posPx, posPy, w, h), lm);

  if (!pairN) lumaNN = lumaSS;
  const float gradientScaled = gradient * 1.0f / 4.0f;
  const float lumaMM = lumaM - lumaNN * 0.5f;
  const float subpixF = glsl ? (subpixD * subpixC) * subpixC : subpixD * subpixE;
  const bool lumaMLTZero = lumaMM < 0.0f;

  lumaEndN -= lumaNN * 0.5f;
  lumaEndP -= lumaNN * 0.5f;
  bool doneN = fabsf(lumaEndN) >= gradientScaled;
  bool doneP = fabsf(lumaEndP) >= gradientScaled;
  if (!doneN) posNx -= offNPx * P[1];
  if (!doneN) posNy -= offNPy * P[1];
  bool doneNP = (!doneN) || (!doneP);
  if (!doneP) posPx += offNPx * P[1];
  if (!doneP) posPy += offNPy * P[1];

    // The shader's nested if(doneNP) blocks; unrolled so P[k] has constant indices.
#pragma unroll
  for (int k = 2; k < kMaxFxaaSteps; ++k) {
    if (k >= prm.step_count || !doneNP) break;
    if (!doneN) lumaEndN = TapLuma(BilinearNorm<kSoft>(lin, pt, posNx, posNy, w, h), lm);
    if (!doneP) lumaEndP = TapLuma(BilinearNorm<kSoft>(lin, pt, posPx, posPy, w, h), lm);
    if (!doneN) lumaEndN = lumaEndN - lumaNN * 0.5f;
    if (!doneP) lumaEndP = lumaEndP - lumaNN * 0.5f;
    doneN = fabsf(lumaEndN) >= gradientScaled;
    doneP = fabsf(lumaEndP) >= gradientScaled;
    if (!doneN) posNx -= offNPx * P[k];
    if (!doneN) posNy -= offNPy * P[k];
    doneNP = (!doneN) || (!doneP);
    if (!doneP) posPx += offNPx * P[k];
    if (!doneP) posPy += offNPy * P[k];
  }

  float dstN = posMx - posNx;
  float dstP = posPx - posMx;
  if (!horzSpan) dstN = posMy - posNy;
  if (!horzSpan) dstP = posPy - posMy;
  const bool goodSpanN = (lumaEndN < 0.0f) != lumaMLTZero;
  const float spanLength = (dstP + dstN);
  const bool goodSpanP = (lumaEndP < 0.0f) != lumaMLTZero;
  const float spanLengthRcp = 1.0f / spanLength;
  const bool directionN = dstN < dstP;
  const float dst = fminf(dstN, dstP);
  const bool goodSpan = directionN ? goodSpanN : goodSpanP;
  const float subpixG = subpixF * subpixF;
  const float pixelOffset = glsl ? (-dst / spanLength) + 0.5f : (dst * (-spanLengthRcp)) + 0.5f;
  const float subpixH = subpixG * prm.subpix;
  const float pixelOffsetGood = goodSpan ? pixelOffset : 0.0f;
  const float pixelOffsetSubpix = fmaxf(pixelOffsetGood, subpixH);
  if (!horzSpan) posMx += pixelOffsetSubpix * lengthSign;
  if (horzSpan) posMy += pixelOffsetSubpix * lengthSign;
  const float4 c = BilinearNorm<kSoft>(lin, pt, posMx, posMy, w, h);
  StoreRgb(out, x, y, c.x, c.y, c.z);
}

}  // namespace

void LaunchFxaa311(const GpuFrame& in, GpuFrame& out, const Fxaa311Args& args, cudaStream_t stream,
                   bool software_filter) {
  if (software_filter) {
    Fxaa311Kernel<true><<<Grid2D(in.Width(), in.Height()), Block2D(), 0, stream>>>(
        in.Point(), in.LinearNorm(), in.LinearPx(), out.Surface(), in.Width(), in.Height(), args);
  } else {
    Fxaa311Kernel<false><<<Grid2D(in.Width(), in.Height()), Block2D(), 0, stream>>>(
        in.Point(), in.LinearNorm(), in.LinearPx(), out.Surface(), in.Width(), in.Height(), args);
  }
}

}  // namespace aalab::cuda
