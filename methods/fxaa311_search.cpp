// FXAA 3.11's edge pixels eight at a time (methods/fxaa311_search.h), for the production path
// in methods/fxaa311_fast.cpp.
//
// After the early exit, an edge pixel runs a serial chain: nine taps, the edge direction, then
// the end-of-edge search, whose every tap position depends on whether the previous tap ended
// the edge, then a final tap at an address computed from the whole search (issue #41: ~200 ns
// per edge pixel, two thirds of the filter, one dependent chain at a time). Here eight edge
// pixels run side by side, one per AVX2 lane, so eight chains overlap:
//   - texel reads are gathers from the 8-bit luma plane, one per row of a bilinear tap: 4
//     bytes read at the row's first texel, its two texels taken from them (the plane has
//     kPlanePad bytes after its end); the 3x3 taps' footprints are computed as MakeAxis
//     computes TapGrid's;
//   - every statement of EdgePixel (methods/fxaa311_fast.cpp) is the same IEEE float32
//     operation per lane, in the same order: add, sub, mul, div, floor (roundps towards −∞),
//     truncation to int, compares; the build neither contracts nor reassociates
//     (-ffp-contract=off, no fast-math, and the avx2 target has no FMA), so each lane's bits
//     equal the scalar code's;
//   - std::max(a, b) (a < b ? b : a) is maxps(b, a) and std::min(a, b) (b < a ? b : a) is
//     minps(b, a), and std::clamp(v, lo, hi) is maxps(lo, minps(hi, v)): the same results for
//     signed zeros and NaN as the scalar forms (NaN cannot arise: pass 1 sends only pixels with
//     range > 0 here);
//   - a branch `if (c) v = e;` is a blend of e into v under the lane mask c; the search loop
//     runs while any lane is still searching, and a lane whose two ends are done changes
//     nothing (exactly as the scalar loop, which stops there); its taps are masked gathers,
//     counted per lane;
//   - the final rgb tap is scalar per lane (FinalTap), after the lanes' positions are known.
// Lanes beyond n repeat pixel 0 and are neither written nor counted.
// tests/methods/fxaa311_search_test.cpp holds this against the scalar path and the reference
// (bytes and tap counts) with the kernel on and off; tests/equivalence/fxaa_fast_test.cpp
// holds the production path to the reference on every preset and luma mode.
#include "methods/fxaa311_search.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstddef>

#include "core/sampler.h"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#include <immintrin.h>
#define AALAB_FXAA311_X8 1
#endif

namespace aalab::fxaa311_internal {

namespace {
std::atomic<bool> g_x8_enabled{true};

bool CpuHasAvx2() {
#if defined(AALAB_FXAA311_X8)
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}
}  // namespace

bool EdgePixelsX8Available() { return CpuHasAvx2() && g_x8_enabled.load(std::memory_order_relaxed); }

void SetEdgePixelsX8Enabled(bool enabled) { g_x8_enabled.store(enabled, std::memory_order_relaxed); }

#if defined(AALAB_FXAA311_X8)
namespace {

#define AALAB_AVX2 __attribute__((target("avx2"), always_inline)) inline
using V = __m256;   // eight floats; GCC's vector operators are the IEEE lane-wise + − · /
using I = __m256i;  // eight int32

AALAB_AVX2 V Splat(float v) { return _mm256_set1_ps(v); }
AALAB_AVX2 V Max(V a, V b) { return _mm256_max_ps(b, a); }  // std::max(a, b)
AALAB_AVX2 V Min(V a, V b) { return _mm256_min_ps(b, a); }  // std::min(a, b)
AALAB_AVX2 V Abs(V a) { return _mm256_andnot_ps(Splat(-0.0f), a); }
AALAB_AVX2 V Neg(V a) { return _mm256_xor_ps(a, Splat(-0.0f)); }
AALAB_AVX2 V Sel(V m, V a, V b) { return _mm256_blendv_ps(b, a, m); }  // m ? a : b
AALAB_AVX2 V Ge(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_GE_OQ); }
AALAB_AVX2 V Lt(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
AALAB_AVX2 V Not(V m) { return _mm256_xor_ps(m, _mm256_castsi256_ps(_mm256_set1_epi32(-1))); }
AALAB_AVX2 I Clamp(I v, I lo, I hi) { return _mm256_max_epi32(lo, _mm256_min_epi32(hi, v)); }

// The plane as the gathers see it.
struct PlaneX8 {
  const int* base;  // the plane's bytes
  I w, wm1, hm1;
  I wm2;  // max(w − 2, 0): the last column a texel pair's 4-byte read may start at
  V fw, fh;
};

// UnormToFloat of the byte at bit `shift` of the 32-bit words g.
AALAB_AVX2 V Unorm(I g, I shift) {
  const I k = _mm256_and_si256(_mm256_srlv_epi32(g, shift), _mm256_set1_epi32(0xFF));
  return _mm256_cvtepi32_ps(k) * Splat(1.0f / 255.0f);
}

// LumaPlane::Blend: the four clamped texels of footprint (x0, y0, fx, fy), BilinearBlend, in
// the lanes of `mask` (others 0). Each row's two texels (columns xa, xb: adjacent, or equal
// where clamped) come from one 4-byte gather at column xl = min(xa, w − 2), the bytes at
// xa − xl and xb − xl.
AALAB_AVX2 V Blend(const PlaneX8& p, I x0, I y0, V fx, V fy, I mask) {
  const I zero = _mm256_setzero_si256(), one = _mm256_set1_epi32(1);
  const I xa = Clamp(x0, zero, p.wm1), xb = Clamp(_mm256_add_epi32(x0, one), zero, p.wm1);
  const I xl = _mm256_min_epi32(xa, p.wm2);
  const I sa = _mm256_slli_epi32(_mm256_sub_epi32(xa, xl), 3), sb = _mm256_slli_epi32(_mm256_sub_epi32(xb, xl), 3);
  const I ra = _mm256_mullo_epi32(Clamp(y0, zero, p.hm1), p.w);
  const I rb = _mm256_mullo_epi32(Clamp(_mm256_add_epi32(y0, one), zero, p.hm1), p.w);
  const I z = _mm256_setzero_si256();
  const I gt = _mm256_mask_i32gather_epi32(z, p.base, _mm256_add_epi32(ra, xl), mask, 1);
  const I gb = _mm256_mask_i32gather_epi32(z, p.base, _mm256_add_epi32(rb, xl), mask, 1);
  const V a = Unorm(gt, sa), b = Unorm(gt, sb), c = Unorm(gb, sa), d = Unorm(gb, sb);
  const V top = a + fx * (b - a);  // FilterLerp(a, b, fx)
  const V bot = c + fx * (d - c);
  return top + fy * (bot - top);
}

// BilinearAt's footprint along one axis: coordinate u in texels, n texels.
AALAB_AVX2 void Axis(V u, V n, I* i0, V* f) {
  const V x = u - Splat(0.5f);
  const V x0f = _mm256_round_ps(x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
  *f = x - x0f;
  *i0 = _mm256_cvttps_epi32(_mm256_max_ps(Splat(-1.0f), _mm256_min_ps(n, x0f)));  // std::clamp(x0f, -1, n)
}

// LumaPlane::Bilinear(s, t) in the lanes of `mask`.
AALAB_AVX2 V Bilinear(const PlaneX8& p, V s, V t, I mask) {
  I x0, y0;
  V fx, fy;
  Axis(s * p.fw, p.fw, &x0, &fx);
  Axis(t * p.fh, p.fh, &y0, &fy);
  return Blend(p, x0, y0, fx, fy, mask);
}

// One axis of the pixels' 3x3 footprints (TapAxis of each lane's column or row).
struct AxisX8 {
  I i[3];
  V f[3];
};

// The footprints of the 3x3 taps along one axis for the lanes' pixel positions `at` on an
// axis of n texels: MakeAxis (methods/fxaa311_plane.h) operation for operation, so the lanes
// hold exactly the TapGrid entries (computing them costs less than gathering them).
AALAB_AVX2 AxisX8 AxisFootprints(I at, int n, bool glsl) {
  const V fn = Splat(static_cast<float>(n));
  const V pos = (_mm256_cvtepi32_ps(at) + Splat(0.5f)) / fn;  // posM
  const float rcp = 1.0f / static_cast<float>(n);
  AxisX8 a;
  for (int d = -1; d <= 1; ++d) {
    const V u = glsl ? pos * fn + Splat(static_cast<float>(d)) : (pos + Splat(static_cast<float>(d) * rcp)) * fn;
    Axis(u, fn, &a.i[d + 1], &a.f[d + 1]);
  }
  return a;
}

// The luma tap at offset (dx, dy) of the lanes' pixels (TapLuma on the 8-bit plane).
AALAB_AVX2 V Tap3x3(const PlaneX8& p, const AxisX8& cx, const AxisX8& ry, int dx, int dy) {
  return Blend(p, cx.i[dx + 1], ry.i[dy + 1], cx.f[dx + 1], ry.f[dy + 1], _mm256_set1_epi32(-1));
}

}  // namespace

__attribute__((target("avx2"))) uint64_t EdgePixelsX8(const LumaPlane<uint8_t>& pl, const Image8& src, const int* xs,
                                                      const int* ys, int n, const Fxaa311Params& prm, float rcpX,
                                                      float rcpY, Image8& out) {
  const bool glsl = prm.order == Fxaa311Params::Order::kSeed003Glsl;
  const std::vector<float>& P_ = prm.steps;
  int lx[8], ly[8];
  for (int i = 0; i < 8; ++i) {
    lx[i] = xs[i < n ? i : 0];
    ly[i] = ys[i < n ? i : 0];
  }
  const unsigned valid = (1u << n) - 1u;
  // Element by element (a 32-byte load of eight just-stored ints would stall on forwarding).
  const I xi = _mm256_setr_epi32(lx[0], lx[1], lx[2], lx[3], lx[4], lx[5], lx[6], lx[7]);
  const I yi = _mm256_setr_epi32(ly[0], ly[1], ly[2], ly[3], ly[4], ly[5], ly[6], ly[7]);
  const I all = _mm256_set1_epi32(-1);
  PlaneX8 p;
  p.base = reinterpret_cast<const int*>(pl.v.get());
  p.w = _mm256_set1_epi32(pl.w);
  p.wm1 = _mm256_set1_epi32(pl.w - 1);
  p.hm1 = _mm256_set1_epi32(pl.h - 1);
  p.wm2 = _mm256_set1_epi32(std::max(pl.w - 2, 0));
  p.fw = Splat(static_cast<float>(pl.w));
  p.fh = Splat(static_cast<float>(pl.h));
  uint64_t taps = 12u * static_cast<uint64_t>(n);  // 9 + the first pair + the final tap

  V posMx = (_mm256_cvtepi32_ps(xi) + Splat(0.5f)) / p.fw;
  V posMy = (_mm256_cvtepi32_ps(yi) + Splat(0.5f)) / p.fh;
  const AxisX8 cx = AxisFootprints(xi, pl.w, glsl), ry = AxisFootprints(yi, pl.h, glsl);
  const V lumaM = Tap3x3(p, cx, ry, 0, 0);
  V lumaS = Tap3x3(p, cx, ry, 0, 1);
  V lumaE = Tap3x3(p, cx, ry, 1, 0);
  V lumaN = Tap3x3(p, cx, ry, 0, -1);
  V lumaW = Tap3x3(p, cx, ry, -1, 0);
  const V rangeMax = Max(Max(lumaN, lumaW), Max(lumaE, Max(lumaS, lumaM)));
  const V rangeMin = Min(Min(lumaN, lumaW), Min(lumaE, Min(lumaS, lumaM)));
  const V range = rangeMax - rangeMin;

  const V lumaNW = Tap3x3(p, cx, ry, -1, -1);
  const V lumaSE = Tap3x3(p, cx, ry, 1, 1);
  const V lumaNE = Tap3x3(p, cx, ry, 1, -1);
  const V lumaSW = Tap3x3(p, cx, ry, -1, 1);

  const V two = Splat(2.0f), mtwo = Splat(-2.0f), half = Splat(0.5f), zero = Splat(0.0f);
  const V lumaNS = lumaN + lumaS;
  const V lumaWE = lumaW + lumaE;
  const V subpixRcpRange = Splat(1.0f) / range;
  const V subpixNSWE = lumaNS + lumaWE;
  const V edgeHorz1 = (mtwo * lumaM) + lumaNS;
  const V edgeVert1 = (mtwo * lumaM) + lumaWE;

  const V lumaNESE = lumaNE + lumaSE;
  const V lumaNWNE = lumaNW + lumaNE;
  const V edgeHorz2 = (mtwo * lumaE) + lumaNESE;
  const V edgeVert2 = (mtwo * lumaN) + lumaNWNE;

  const V lumaNWSW = lumaNW + lumaSW;
  const V lumaSWSE = lumaSW + lumaSE;
  const V edgeHorz4 = (Abs(edgeHorz1) * two) + Abs(edgeHorz2);
  const V edgeVert4 = (Abs(edgeVert1) * two) + Abs(edgeVert2);
  const V edgeHorz3 = (mtwo * lumaW) + lumaNWSW;
  const V edgeVert3 = (mtwo * lumaS) + lumaSWSE;
  V edgeHorz = Abs(edgeHorz3) + edgeHorz4;
  V edgeVert = Abs(edgeVert3) + edgeVert4;
  if (glsl) {
    edgeHorz = (Abs(edgeHorz3) + Abs(edgeHorz1) * two) + Abs(edgeHorz2);
    edgeVert = (Abs(edgeVert3) + Abs(edgeVert1) * two) + Abs(edgeVert2);
  }

  const V subpixNWSWNESE = lumaNWSW + lumaNESE;
  const V horzSpan = Ge(edgeHorz, edgeVert);
  const V subpixA = subpixNSWE * two + subpixNWSWNESE;

  lumaN = Sel(horzSpan, lumaN, lumaW);  // if (!horzSpan) lumaN = lumaW;
  lumaS = Sel(horzSpan, lumaS, lumaE);
  V lengthSign = Sel(horzSpan, Splat(rcpY), Splat(rcpX));
  V subpixB = (subpixA * Splat(1.0f / 12.0f)) - lumaM;
  if (glsl) {
    const V lumaAverage = Splat(1.0f / 12.0f) * ((two * subpixNSWE + lumaNWSW) + lumaNESE);
    subpixB = lumaAverage - lumaM;
  }

  const V gradientN = lumaN - lumaM;
  const V gradientS = lumaS - lumaM;
  V lumaNN = lumaN + lumaM;
  const V lumaSS = lumaS + lumaM;
  const V pairN = Ge(Abs(gradientN), Abs(gradientS));
  const V gradient = Max(Abs(gradientN), Abs(gradientS));
  lengthSign = Sel(pairN, Neg(lengthSign), lengthSign);
  const V subpixCIn = glsl ? Abs(subpixB) / range : Abs(subpixB) * subpixRcpRange;
  const V subpixC = Min(Max(subpixCIn, zero), Splat(1.0f));

  V posBx = posMx;
  V posBy = posMy;
  const V offNPx = Sel(horzSpan, Splat(rcpX), zero);
  const V offNPy = Sel(horzSpan, zero, Splat(rcpY));
  posBx = Sel(horzSpan, posBx, posBx + lengthSign * half);
  posBy = Sel(horzSpan, posBy + lengthSign * half, posBy);

  const V p0 = Splat(P_[0]);
  V posNx = posBx - offNPx * p0;
  V posNy = posBy - offNPy * p0;
  V posPx = posBx + offNPx * p0;
  V posPy = posBy + offNPy * p0;
  const V subpixD = (mtwo * subpixC) + Splat(3.0f);
  V lumaEndN = Bilinear(p, posNx, posNy, all);
  const V subpixE = subpixC * subpixC;
  V lumaEndP = Bilinear(p, posPx, posPy, all);

  lumaNN = Sel(pairN, lumaNN, lumaSS);
  const V gradientScaled = gradient * Splat(1.0f) / Splat(4.0f);
  const V lumaMM = lumaM - lumaNN * half;
  const V subpixF = glsl ? (subpixD * subpixC) * subpixC : subpixD * subpixE;
  const V lumaMLTZero = Lt(lumaMM, zero);

  lumaEndN = lumaEndN - lumaNN * half;
  lumaEndP = lumaEndP - lumaNN * half;
  V doneN = Ge(Abs(lumaEndN), gradientScaled);
  V doneP = Ge(Abs(lumaEndP), gradientScaled);
  const V p1 = Splat(P_[1]);
  posNx = Sel(doneN, posNx, posNx - offNPx * p1);
  posNy = Sel(doneN, posNy, posNy - offNPy * p1);
  posPx = Sel(doneP, posPx, posPx + offNPx * p1);
  posPy = Sel(doneP, posPy, posPy + offNPy * p1);

  // The scalar loop runs while its pixel's doneNP = !doneN || !doneP; a lane with both ends
  // done fetches nothing and keeps every value, so running on for the other lanes is exact.
  for (size_t k = 2; k < P_.size(); ++k) {
    const V goN = Not(doneN), goP = Not(doneP);
    const unsigned mN = static_cast<unsigned>(_mm256_movemask_ps(goN));
    const unsigned mP = static_cast<unsigned>(_mm256_movemask_ps(goP));
    if ((mN | mP) == 0) break;
    if (mN != 0) {
      lumaEndN = Sel(goN, Bilinear(p, posNx, posNy, _mm256_castps_si256(goN)), lumaEndN);
      taps += static_cast<uint64_t>(std::popcount(mN & valid));
    }
    if (mP != 0) {
      lumaEndP = Sel(goP, Bilinear(p, posPx, posPy, _mm256_castps_si256(goP)), lumaEndP);
      taps += static_cast<uint64_t>(std::popcount(mP & valid));
    }
    lumaEndN = Sel(goN, lumaEndN - lumaNN * half, lumaEndN);
    lumaEndP = Sel(goP, lumaEndP - lumaNN * half, lumaEndP);
    doneN = Ge(Abs(lumaEndN), gradientScaled);
    doneP = Ge(Abs(lumaEndP), gradientScaled);
    const V pk = Splat(P_[k]);
    posNx = Sel(doneN, posNx, posNx - offNPx * pk);
    posNy = Sel(doneN, posNy, posNy - offNPy * pk);
    posPx = Sel(doneP, posPx, posPx + offNPx * pk);
    posPy = Sel(doneP, posPy, posPy + offNPy * pk);
  }

  const V dstN = Sel(horzSpan, posMx - posNx, posMy - posNy);
  const V dstP = Sel(horzSpan, posPx - posMx, posPy - posMy);

  const V goodSpanN = _mm256_xor_ps(Lt(lumaEndN, zero), lumaMLTZero);  // (lumaEndN < 0) != lumaMLTZero
  const V spanLength = (dstP + dstN);
  const V goodSpanP = _mm256_xor_ps(Lt(lumaEndP, zero), lumaMLTZero);
  const V spanLengthRcp = Splat(1.0f) / spanLength;

  const V directionN = Lt(dstN, dstP);
  const V dst = Min(dstN, dstP);
  const V goodSpan = Sel(directionN, goodSpanN, goodSpanP);
  const V subpixG = subpixF * subpixF;
  const V pixelOffset = glsl ? (Neg(dst) / spanLength) + half : (dst * Neg(spanLengthRcp)) + half;
  const V subpixH = subpixG * Splat(prm.subpix);

  const V pixelOffsetGood = Sel(goodSpan, pixelOffset, zero);
  const V pixelOffsetSubpix = Max(pixelOffsetGood, subpixH);
  posMx = Sel(horzSpan, posMx, posMx + pixelOffsetSubpix * lengthSign);
  posMy = Sel(horzSpan, posMy + pixelOffsetSubpix * lengthSign, posMy);

  alignas(32) float fx[8], fy[8];
  _mm256_store_ps(fx, posMx);
  _mm256_store_ps(fy, posMy);
  for (int i = 0; i < n; ++i) {
    float rgb[3];
    FinalTap(src, fx[i], fy[i], rgb);  // tex.SampleNormalized(posMx, posMy).rgb
    uint8_t* o = out.Row(ly[i]) + 4 * lx[i];
    o[0] = StoreUnorm8(rgb[0]);
    o[1] = StoreUnorm8(rgb[1]);
    o[2] = StoreUnorm8(rgb[2]);
    o[3] = 255;
  }
  return taps;
}

#else

uint64_t EdgePixelsX8(const LumaPlane<uint8_t>&, const Image8&, const int*, const int*, int, const Fxaa311Params&,
                      float, float, Image8&) {
  return 0;  // never called: EdgePixelsX8Available() is false without the kernel
}

#endif

}  // namespace aalab::fxaa311_internal
