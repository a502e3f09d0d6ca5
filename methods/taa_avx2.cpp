// The AVX2 row kernels of TAA's production step (methods/taa_avx2.h), eight pixels per
// vector, chosen at run time (TaaHasAvx2: GCC on x86-64 and a CPU with AVX2; the build has
// no -march, so each function carries target("avx2") and the SSE2 kernel, taa_sse2.h, stays
// the fallback).
//
// Same values as the scalar forms in methods/taa.cpp, bit for bit: every lane runs the same
// IEEE float32 operations in the same order (adds, multiplies, divisions, int↔float
// conversions are correctly rounded in every instruction set; no FMA: target("avx2") does not
// enable it and the build has -ffp-contract=off). Selects keep the scalar forms' operand
// order, which fixes the NaN and −0 cases: Max(a, b) = a < b ? b : a is _mm256_max_ps(b, a),
// Min(a, b) = b < a ? b : a is _mm256_min_ps(b, a) (both give their second operand when the
// comparison is false or unordered). Table reads (the 8-bit decode, the encode's guess and
// thresholds) are gathers of the same entries. The footprint (taa.cpp FootprintRow) is
// formed in registers instead of a row buffer, the output encoded in registers instead of
// from planar rows: no value changes, less memory traffic. tests/motion/taa_test.cpp compares
// the step with StepReference bit for bit on rows whose lengths reach these kernels, the
// SSE2 kernel and the scalar tail.
#include "methods/taa_avx2.h"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>

namespace aalab::taa_detail {

#define AALAB_TAA_AVX2 __attribute__((target("avx2")))

namespace {

/// a + t·(b − a), per lane.
AALAB_TAA_AVX2 inline __m256 Lerp8(__m256 a, __m256 b, __m256 t) {
  return _mm256_add_ps(a, _mm256_mul_ps(t, _mm256_sub_ps(b, a)));
}

/// mask ? a : b (mask lanes all ones or all zeros).
AALAB_TAA_AVX2 inline __m256 Select8(__m256 mask, __m256 a, __m256 b) { return _mm256_blendv_ps(b, a, mask); }

/// |q|.
AALAB_TAA_AVX2 inline __m256 Abs8(__m256 q) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), q); }

/// Two 4-float unaligned loads into one vector: lo in lanes 0..3, hi in lanes 4..7.
AALAB_TAA_AVX2 inline __m256 Load2x4(const float* lo, const float* hi) {
  return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(lo)), _mm_loadu_ps(hi), 1);
}

/// Channel c (0 = r, 1 = g, 2 = b) of eight RGBA8 pixels, as int32 lanes.
AALAB_TAA_AVX2 inline __m256i Channel8(__m256i px, int c) {
  return _mm256_and_si256(_mm256_srli_epi32(px, 8 * c), _mm256_set1_epi32(0xff));
}

/// Encode8::operator() per lane (same codes): the bucket's entry (one 32-bit gather element
/// per value), then one step where the value's low bits reach the threshold inside the bucket.
AALAB_TAA_AVX2 inline __m256i Codes8(const EncodeTables& t, __m256 v) {
  const __m256i bits = _mm256_and_si256(_mm256_castps_si256(v), _mm256_set1_epi32(0x7fffffff));  // −0 → +0
  const __m256i i = _mm256_min_epi32(_mm256_srli_epi32(bits, static_cast<int>(kEncodeShift)),
                                     _mm256_set1_epi32(static_cast<int>(kEncodeBuckets - 1)));
  const __m256i e = _mm256_i32gather_epi32(reinterpret_cast<const int*>(t.packed), i, 4);
  const __m256i g = _mm256_and_si256(e, _mm256_set1_epi32(0xff)), t1 = _mm256_srli_epi32(e, 8);
  // lo16 ≥ t1 ⟺ lo16 + 1 > t1; a true comparison is −1 as an integer: subtracting adds one.
  const __m256i l1 = _mm256_add_epi32(_mm256_and_si256(bits, _mm256_set1_epi32(0xffff)), _mm256_set1_epi32(1));
  return _mm256_sub_epi32(g, _mm256_cmpgt_epi32(l1, t1));
}

/// Eight pixels' planar linear RGB (each in [0, 1]) to RGBA8 (alpha 255) at out.
AALAB_TAA_AVX2 inline void StoreRgba8(const EncodeTables& t, __m256 r, __m256 g, __m256 b, uint8_t* out) {
  // Little-endian x86: byte k of each 32-bit lane is channel k.
  const __m256i px = _mm256_or_si256(
      _mm256_or_si256(Codes8(t, r), _mm256_slli_epi32(Codes8(t, g), 8)),
      _mm256_or_si256(_mm256_slli_epi32(Codes8(t, b), 16), _mm256_set1_epi32(static_cast<int>(0xff000000u))));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), px);
}

/// ToYCoCg per lane, the scalar expression order.
AALAB_TAA_AVX2 inline void ToYcc8(__m256 r, __m256 g, __m256 b, __m256* y, __m256* co, __m256* cg) {
  const __m256 half = _mm256_set1_ps(0.5f), quarter = _mm256_set1_ps(0.25f), mquarter = _mm256_set1_ps(-0.25f);
  *y = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(quarter, r), _mm256_mul_ps(half, g)), _mm256_mul_ps(quarter, b));
  *co = _mm256_sub_ps(_mm256_mul_ps(half, r), _mm256_mul_ps(half, b));
  *cg = _mm256_sub_ps(_mm256_add_ps(_mm256_mul_ps(mquarter, r), _mm256_mul_ps(half, g)), _mm256_mul_ps(quarter, b));
}

/// min(max(v, 0), m) per int32 lane: std::Clamp0(v, 0, m).
AALAB_TAA_AVX2 inline __m256i Clamp0(__m256i v, __m256i m) {
  return _mm256_min_epi32(_mm256_max_epi32(v, _mm256_setzero_si256()), m);
}

/// 3·v per int32 lane.
AALAB_TAA_AVX2 inline __m256i Times3(__m256i v) { return _mm256_add_epi32(v, _mm256_add_epi32(v, v)); }

/// Clamp01(v) = v < 0 ? 0 : (1 < v ? 1 : v) per lane.
AALAB_TAA_AVX2 inline __m256 Clamp01x8(__m256 v) {
  return _mm256_max_ps(_mm256_setzero_ps(), _mm256_min_ps(_mm256_set1_ps(1.0f), v));
}

/// The footprint of eight pixels (taa.cpp FootprintRow, the same operations): fractions tx,
/// ty and the four texels' offsets into the interleaved history.
struct Footprint8 {
  __m256 tx, ty;
  alignas(32) int32_t off[4][8];  // corners a (x0, y0), b (x1, y0), c (x0, y1), d (x1, y1)
};

AALAB_TAA_AVX2 inline void MakeFootprint8(__m256 qx, __m256 qy, int hw, int hh, Footprint8* fp) {
  const __m256 half = _mm256_set1_ps(0.5f);
  // Min(fw, Max(0, p)): Max(0, p) = 0 < p ? p : 0, Min(fw, v) = v < fw ? v : fw.
  const __m256 px = _mm256_min_ps(_mm256_max_ps(qx, _mm256_setzero_ps()), _mm256_set1_ps(static_cast<float>(hw)));
  const __m256 py = _mm256_min_ps(_mm256_max_ps(qy, _mm256_setzero_ps()), _mm256_set1_ps(static_cast<float>(hh)));
  const __m256 fx = _mm256_sub_ps(px, half), fy = _mm256_sub_ps(py, half);
  const __m256i ix = _mm256_cvttps_epi32(fx), iy = _mm256_cvttps_epi32(fy);
  // floor: truncation minus one where f < trunc(f) (the comparison's −1 added).
  const __m256i x0 = _mm256_add_epi32(ix, _mm256_castps_si256(_mm256_cmp_ps(fx, _mm256_cvtepi32_ps(ix), _CMP_LT_OQ)));
  const __m256i y0 = _mm256_add_epi32(iy, _mm256_castps_si256(_mm256_cmp_ps(fy, _mm256_cvtepi32_ps(iy), _CMP_LT_OQ)));
  fp->tx = _mm256_sub_ps(fx, _mm256_cvtepi32_ps(x0));
  fp->ty = _mm256_sub_ps(fy, _mm256_cvtepi32_ps(y0));
  const __m256i one = _mm256_set1_epi32(1);
  const __m256i wm = _mm256_set1_epi32(hw - 1), hm = _mm256_set1_epi32(hh - 1), w = _mm256_set1_epi32(hw);
  const __m256i xa = Clamp0(x0, wm), xb = Clamp0(_mm256_add_epi32(x0, one), wm);
  const __m256i ra = _mm256_mullo_epi32(Clamp0(y0, hm), w),
                rb = _mm256_mullo_epi32(Clamp0(_mm256_add_epi32(y0, one), hm), w);
  _mm256_store_si256(reinterpret_cast<__m256i*>(fp->off[0]), Times3(_mm256_add_epi32(ra, xa)));
  _mm256_store_si256(reinterpret_cast<__m256i*>(fp->off[1]), Times3(_mm256_add_epi32(ra, xb)));
  _mm256_store_si256(reinterpret_cast<__m256i*>(fp->off[2]), Times3(_mm256_add_epi32(rb, xa)));
  _mm256_store_si256(reinterpret_cast<__m256i*>(fp->off[3]), Times3(_mm256_add_epi32(rb, xb)));
}

/// The bilinear fetch of eight pixels, planar R, G, B out. Pixels j and j + 4 share a vector
/// (lanes 0..3 and 4..7: RGB and one unused value), lerped with their own fractions, then a
/// 4×4 transpose per 128-bit half puts pixel order back.
AALAB_TAA_AVX2 inline void Fetch8(const float* hist, const Footprint8& fp, __m256* r, __m256* g, __m256* b) {
  __m256 p[4];
  for (int j = 0; j < 4; ++j) {
    const __m256i sel = _mm256_setr_epi32(j, j, j, j, j + 4, j + 4, j + 4, j + 4);
    const __m256 tx = _mm256_permutevar8x32_ps(fp.tx, sel), ty = _mm256_permutevar8x32_ps(fp.ty, sel);
    const __m256 a = Load2x4(hist + fp.off[0][j], hist + fp.off[0][j + 4]);
    const __m256 bb = Load2x4(hist + fp.off[1][j], hist + fp.off[1][j + 4]);
    const __m256 c = Load2x4(hist + fp.off[2][j], hist + fp.off[2][j + 4]);
    const __m256 d = Load2x4(hist + fp.off[3][j], hist + fp.off[3][j + 4]);
    p[j] = Lerp8(Lerp8(a, bb, tx), Lerp8(c, d, tx), ty);
  }
  const __m256 t0 = _mm256_unpacklo_ps(p[0], p[1]), t1 = _mm256_unpacklo_ps(p[2], p[3]);
  const __m256 t2 = _mm256_unpackhi_ps(p[0], p[1]), t3 = _mm256_unpackhi_ps(p[2], p[3]);
  *r = _mm256_shuffle_ps(t0, t1, _MM_SHUFFLE(1, 0, 1, 0));
  *g = _mm256_shuffle_ps(t0, t1, _MM_SHUFFLE(3, 2, 3, 2));
  *b = _mm256_shuffle_ps(t2, t3, _MM_SHUFFLE(1, 0, 1, 0));
}

/// Eight pixels' RGB (planar) into the interleaved history at dst: exactly 24 floats written
/// (each 4-float store's last lane is overwritten by the next pixel's; the last pixel's
/// store is 3 floats, so nothing past the eight pixels is touched).
AALAB_TAA_AVX2 inline void StoreRgb8(__m256 r, __m256 g, __m256 b, float* dst) {
  const __m256 zero = _mm256_setzero_ps();
  const __m256 t0 = _mm256_unpacklo_ps(r, g), t1 = _mm256_unpacklo_ps(b, zero);
  const __m256 t2 = _mm256_unpackhi_ps(r, g), t3 = _mm256_unpackhi_ps(b, zero);
  const __m256 q0 = _mm256_shuffle_ps(t0, t1, _MM_SHUFFLE(1, 0, 1, 0));  // pixels 0 | 4
  const __m256 q1 = _mm256_shuffle_ps(t0, t1, _MM_SHUFFLE(3, 2, 3, 2));  // pixels 1 | 5
  const __m256 q2 = _mm256_shuffle_ps(t2, t3, _MM_SHUFFLE(1, 0, 1, 0));  // pixels 2 | 6
  const __m256 q3 = _mm256_shuffle_ps(t2, t3, _MM_SHUFFLE(3, 2, 3, 2));  // pixels 3 | 7
  _mm_storeu_ps(dst, _mm256_castps256_ps128(q0));
  _mm_storeu_ps(dst + 3, _mm256_castps256_ps128(q1));
  _mm_storeu_ps(dst + 6, _mm256_castps256_ps128(q2));
  _mm_storeu_ps(dst + 9, _mm256_castps256_ps128(q3));
  _mm_storeu_ps(dst + 12, _mm256_extractf128_ps(q0, 1));
  _mm_storeu_ps(dst + 15, _mm256_extractf128_ps(q1, 1));
  _mm_storeu_ps(dst + 18, _mm256_extractf128_ps(q2, 1));
  const __m128 last = _mm256_extractf128_ps(q3, 1);
  _mm_storel_pi(reinterpret_cast<__m64*>(dst + 21), last);
  _mm_store_ss(dst + 23, _mm_movehl_ps(last, last));
}

template <bool kClip>
AALAB_TAA_AVX2 int HistoryBlendRow8(const Avx2RowIn& in, int w, float alpha, float* __restrict next,
                                    uint8_t* __restrict rgba) {
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f),
               eps = _mm256_set1_ps(1e-8f), va = _mm256_set1_ps(alpha), fw = _mm256_set1_ps(static_cast<float>(in.hw)),
               fh = _mm256_set1_ps(static_cast<float>(in.hh));
  const int n = w - w % 8;
  Footprint8 fp;
  for (int x = HistoryBlendRow16Avx512(in, w, kClip, alpha, next, rgba); x < n; x += 8) {
    // The previous positions, deinterleaved: x0 y0 x1 y1 ... into qx = x0..x7, qy = y0..y7.
    const __m256 p0 = _mm256_loadu_ps(in.prev + 2 * x), p1 = _mm256_loadu_ps(in.prev + 2 * x + 8);
    const __m256 sx = _mm256_shuffle_ps(p0, p1, _MM_SHUFFLE(2, 0, 2, 0)),
                 sy = _mm256_shuffle_ps(p0, p1, _MM_SHUFFLE(3, 1, 3, 1));  // x0 x1 x4 x5 | x2 x3 x6 x7
    const __m256 qx = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(sx), _MM_SHUFFLE(3, 1, 2, 0)));
    const __m256 qy = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(sy), _MM_SHUFFLE(3, 1, 2, 0)));
    MakeFootprint8(qx, qy, in.hw, in.hh, &fp);
    __m256 r, g, b;
    Fetch8(in.hist, fp, &r, &g, &b);
    __m256 h[3];
    ToYcc8(r, g, b, &h[0], &h[1], &h[2]);
    if constexpr (kClip) {
      __m256 centre[3], v[3], ext[3], near = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
      for (int c = 0; c < 3; ++c) {
        const __m256 hi = _mm256_loadu_ps(in.hi[c] + x), lo = _mm256_loadu_ps(in.lo[c] + x);
        centre[c] = _mm256_mul_ps(half, _mm256_add_ps(hi, lo));
        ext[c] = _mm256_add_ps(_mm256_mul_ps(half, _mm256_sub_ps(hi, lo)), eps);
        v[c] = _mm256_sub_ps(h[c], centre[c]);
        near = _mm256_and_ps(near, _mm256_cmp_ps(Abs8(v[c]), ext[c], _CMP_LE_OQ));
      }
      // As taa_sse2.h: |v| ≤ ext in every channel means |v / ext| ≤ 1 (h stays); only when a
      // lane may be outside are the quotients formed, exactly as ClipToBox forms them.
      if (_mm256_movemask_ps(near) != 0xff) {
        __m256 m = zero;
        for (int c = 0; c < 3; ++c) m = _mm256_max_ps(Abs8(_mm256_div_ps(v[c], ext[c])), m);  // Max(m, |q|)
        const __m256 inside = _mm256_cmp_ps(m, one, _CMP_LE_OQ);
        const __m256 div = Select8(inside, one, m);
        for (int c = 0; c < 3; ++c) {
          h[c] = Select8(inside, h[c], _mm256_add_ps(centre[c], _mm256_div_ps(v[c], div)));
        }
      }
    }
    const __m256 oy = Lerp8(h[0], _mm256_loadu_ps(in.cy + x + 1), va);
    const __m256 oco = Lerp8(h[1], _mm256_loadu_ps(in.cco + x + 1), va);
    const __m256 ocg = Lerp8(h[2], _mm256_loadu_ps(in.ccg + x + 1), va);
    const __m256 t = _mm256_sub_ps(oy, ocg);
    __m256 o0 = Clamp01x8(_mm256_add_ps(t, oco)), o1 = Clamp01x8(_mm256_add_ps(oy, ocg)),
           o2 = Clamp01x8(_mm256_sub_ps(t, oco));
    // Has history: 0 ≤ x ≤ W and 0 ≤ y ≤ H (false for NaN).
    const __m256 ok =
        _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(qx, zero, _CMP_GE_OQ), _mm256_cmp_ps(qx, fw, _CMP_LE_OQ)),
                      _mm256_and_ps(_mm256_cmp_ps(qy, zero, _CMP_GE_OQ), _mm256_cmp_ps(qy, fh, _CMP_LE_OQ)));
    if (_mm256_movemask_ps(ok) != 0xff) {  // a pixel without history takes the current colour
      const __m256i s = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(in.src + 4 * x));
      o0 = Select8(ok, o0, _mm256_i32gather_ps(in.decode, Channel8(s, 0), 4));
      o1 = Select8(ok, o1, _mm256_i32gather_ps(in.decode, Channel8(s, 1), 4));
      o2 = Select8(ok, o2, _mm256_i32gather_ps(in.decode, Channel8(s, 2), 4));
    }
    StoreRgb8(o0, o1, o2, next + 3 * static_cast<size_t>(x));
    StoreRgba8(in.enc, o0, o1, o2, rgba + 4 * static_cast<size_t>(x));
  }
  return n;
}

}  // namespace

bool TaaHasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

int HistoryBlendRow8Avx2(const Avx2RowIn& in, int w, bool clip, float alpha, float* next, uint8_t* rgba) {
  if (!TaaHasAvx2()) return 0;
  return clip ? HistoryBlendRow8<true>(in, w, alpha, next, rgba) : HistoryBlendRow8<false>(in, w, alpha, next, rgba);
}

AALAB_TAA_AVX2 int EncodeRgbaAvx2(const EncodeTables& t, const float* r, const float* g, const float* b, int w,
                                  uint8_t* rgba) {
  if (!TaaHasAvx2()) return 0;
  const int n = w - w % 8;
  for (int x = EncodeRgbaAvx512(t, r, g, b, w, rgba); x < n; x += 8) {
    StoreRgba8(t, _mm256_loadu_ps(r + x), _mm256_loadu_ps(g + x), _mm256_loadu_ps(b + x), rgba + 4 * x);
  }
  return n;
}

AALAB_TAA_AVX2 int YccPlaneRowAvx2(const uint8_t* src, int w, const float* decode, float* y, float* co, float* cg) {
  if (!TaaHasAvx2()) return 0;
  const int n = w - w % 8;
  for (int x = YccPlaneRowAvx512(src, w, decode, y, co, cg); x < n; x += 8) {
    const __m256i s = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + 4 * x));
    __m256 vy, vco, vcg;
    ToYcc8(_mm256_i32gather_ps(decode, Channel8(s, 0), 4), _mm256_i32gather_ps(decode, Channel8(s, 1), 4),
           _mm256_i32gather_ps(decode, Channel8(s, 2), 4), &vy, &vco, &vcg);
    _mm256_storeu_ps(y + x, vy);
    _mm256_storeu_ps(co + x, vco);
    _mm256_storeu_ps(cg + x, vcg);
  }
  return n;
}

}  // namespace aalab::taa_detail

#else  // no AVX2 kernels: the SSE2 and scalar rows do the work

namespace aalab::taa_detail {
bool TaaHasAvx2() { return false; }
int HistoryBlendRow8Avx2(const Avx2RowIn&, int, bool, float, float*, uint8_t*) { return 0; }
int EncodeRgbaAvx2(const EncodeTables&, const float*, const float*, const float*, int, uint8_t*) { return 0; }
int YccPlaneRowAvx2(const uint8_t*, int, const float*, float*, float*, float*) { return 0; }
}  // namespace aalab::taa_detail

#endif
