// The AVX-512 row kernels of TAA's production step (methods/taa_avx2.h), sixteen pixels per
// vector, chosen at run time (TaaHasAvx512: GCC on x86-64 and a CPU with AVX-512F); the AVX2
// kernels (methods/taa_avx2.cpp) call these first and finish the row's last W mod 16 pixels.
//
// The same operations per lane as methods/taa_avx2.cpp, which holds the reasoning for the
// same bits (correctly rounded IEEE operations in the scalar order, no FMA: target
// "avx512f" does not contract and the build has -ffp-contract=off; every select in the
// scalar operand order: _mm512_max_ps / _mm512_min_ps return their second operand on NaN
// like their AVX forms). What differs is only data movement: the previous positions are
// deinterleaved and the new history interleaved by two-source permutes (exactly 48 floats
// stored per 16 pixels), comparisons give mask registers, and where the sixteen pixels'
// footprint is contiguous (Contiguous16) the history texels are fetched by four vector
// loads and nine permutes per row instead of 32 4-float loads (FetchContiguous16); the
// current frame's planes decode from the 256-entry table held in 16 registers (DecodeRegs16:
// permutes and blends, measured faster than three 16-lane gathers per 16 pixels).
// tests/motion/taa_test.cpp's bit-for-bit tests use widths that reach this kernel, the AVX2
// and SSE2 kernels and the scalar tail, and smooth motion that takes the contiguous fetch.
#include "methods/taa_avx2.h"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
// GCC 12's avx512fintrin.h builds the undefined-source intrinsics from a self-initialised
// variable, which -Wmaybe-uninitialized reports at every use (a false positive of the
// header, not of this file).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include <cstddef>

namespace aalab::taa_detail {

#define AALAB_TAA_AVX512 __attribute__((target("avx512f")))

namespace {

AALAB_TAA_AVX512 inline __m512 Lerp16(__m512 a, __m512 b, __m512 t) {
  return _mm512_add_ps(a, _mm512_mul_ps(t, _mm512_sub_ps(b, a)));
}

AALAB_TAA_AVX512 inline __m512 Abs16(__m512 q) {
  return _mm512_castsi512_ps(_mm512_and_si512(_mm512_castps_si512(q), _mm512_set1_epi32(0x7fffffff)));
}

/// Clamp01(v) = v < 0 ? 0 : (1 < v ? 1 : v) per lane.
AALAB_TAA_AVX512 inline __m512 Clamp01x16(__m512 v) {
  return _mm512_max_ps(_mm512_setzero_ps(), _mm512_min_ps(_mm512_set1_ps(1.0f), v));
}

/// Channel c of sixteen RGBA8 pixels, as int32 lanes.
AALAB_TAA_AVX512 inline __m512i Channel16(__m512i px, int c) {
  return _mm512_and_si512(_mm512_srli_epi32(px, static_cast<unsigned>(8 * c)), _mm512_set1_epi32(0xff));
}

/// Encode8::operator() per lane (taa_avx2.cpp Codes8, the same table entry and comparisons).
AALAB_TAA_AVX512 inline __m512i Codes16(const EncodeTables& t, __m512 v) {
  const __m512i bits = _mm512_and_si512(_mm512_castps_si512(v), _mm512_set1_epi32(0x7fffffff));  // −0 → +0
  const __m512i i =
      _mm512_min_epi32(_mm512_srli_epi32(bits, kEncodeShift), _mm512_set1_epi32(static_cast<int>(kEncodeBuckets - 1)));
  const __m512i e = _mm512_i32gather_epi32(i, t.packed, 4);
  const __m512i g = _mm512_and_si512(e, _mm512_set1_epi32(0xff)), t1 = _mm512_srli_epi32(e, 8);
  const __m512i l = _mm512_and_si512(bits, _mm512_set1_epi32(0xffff));
  return _mm512_mask_add_epi32(g, _mm512_cmpge_epu32_mask(l, t1), g, _mm512_set1_epi32(1));
}

AALAB_TAA_AVX512 inline void StoreRgba16(const EncodeTables& t, __m512 r, __m512 g, __m512 b, uint8_t* out) {
  const __m512i px = _mm512_or_si512(
      _mm512_or_si512(Codes16(t, r), _mm512_slli_epi32(Codes16(t, g), 8)),
      _mm512_or_si512(_mm512_slli_epi32(Codes16(t, b), 16), _mm512_set1_epi32(static_cast<int>(0xff000000u))));
  _mm512_storeu_si512(out, px);
}

/// ToYCoCg per lane. Cg's −0.25 r + 0.5 g is formed as 0.5 g − 0.25 r, reusing Y's 0.25 r:
/// RN(−0.25 r) = −RN(0.25 r) and a + (−b) is a − b in IEEE arithmetic (signed zeros too), so
/// the same bits with one multiplication fewer.
AALAB_TAA_AVX512 inline void ToYcc16(__m512 r, __m512 g, __m512 b, __m512* y, __m512* co, __m512* cg) {
  const __m512 half = _mm512_set1_ps(0.5f), quarter = _mm512_set1_ps(0.25f);
  const __m512 qr = _mm512_mul_ps(quarter, r), hg = _mm512_mul_ps(half, g), qb = _mm512_mul_ps(quarter, b);
  *y = _mm512_add_ps(_mm512_add_ps(qr, hg), qb);
  *co = _mm512_sub_ps(_mm512_mul_ps(half, r), _mm512_mul_ps(half, b));
  *cg = _mm512_sub_ps(_mm512_sub_ps(hg, qr), qb);
}

/// x / 9 per lane, the same bits as _mm512_div_ps(x, 9) for every finite x but −0 (which
/// gives +0): the product with RN(1/9), then one FMA step on the exact remainder
/// (Markstein's correction), instead of a 16-lane division (10 cycles of the divider on
/// Skylake-SP, where the box's two divisions per channel held the step back).
/// tests/motion/taa_test.cpp checks it against the division for every float of magnitude
/// up to 16 (the box's sums lie within ±9, and are never −0: they start from +0).
AALAB_TAA_AVX512 inline __m512 Div9x16(__m512 x) {
  const __m512 ninth = _mm512_set1_ps(1.0f / 9.0f);
  const __m512 q = _mm512_mul_ps(x, ninth);
  return _mm512_fmadd_ps(_mm512_fnmadd_ps(q, _mm512_set1_ps(9.0f), x), ninth, q);
}

/// Rectify's box for one channel of sixteen pixels at x, as taa.cpp BoxRow forms it: rows
/// are the padded plane rows above, at and below (texel x at x + 1). The min/max in any
/// order (the planes hold no NaN and no −0: BoxRow's reasoning), the sums in BoxRow's order
/// (rows top to bottom, columns left to right), then μ ± γσ with Max / Min in the scalar
/// operand order. Everything starts from the first texel v instead of Rectify's 1e30, −1e30,
/// 0, 0: min(1e30, v) = max(−1e30, v) = v (the planes lie in [−1, 1]), 0 + v = v (v is not
/// −0) and 0 + v·v = v·v (a square is ≥ +0), so the same bits with four operations fewer.
template <bool kVariance>
AALAB_TAA_AVX512 inline void Box16(const float* const* rows, int x, float gamma, __m512* lo, __m512* hi) {
  const __m512 v0 = _mm512_loadu_ps(rows[0] + x);
  __m512 mn = v0, mx = v0, m1 = v0, m2 = _mm512_mul_ps(v0, v0);
  for (int k = 0; k < 3; ++k) {
    for (int d = k == 0 ? 1 : 0; d < 3; ++d) {
      const __m512 v = _mm512_loadu_ps(rows[k] + x + d);
      mn = _mm512_min_ps(mn, v);
      mx = _mm512_max_ps(mx, v);
      if constexpr (kVariance) {
        m1 = _mm512_add_ps(m1, v);
        m2 = _mm512_add_ps(m2, _mm512_mul_ps(v, v));
      }
    }
  }
  if constexpr (kVariance) {
    const __m512 g = _mm512_set1_ps(gamma);
    const __m512 mu = Div9x16(m1);  // m1 / 9, m2 / 9: the same bits (Div9x16)
    const __m512 sigma = _mm512_sqrt_ps(Abs16(_mm512_sub_ps(Div9x16(m2), _mm512_mul_ps(mu, mu))));
    mn = _mm512_max_ps(_mm512_sub_ps(mu, _mm512_mul_ps(g, sigma)), mn);  // Max(mn, t) = mn < t ? t : mn
    mx = _mm512_min_ps(_mm512_add_ps(mu, _mm512_mul_ps(g, sigma)), mx);  // Min(mx, t) = t < mx ? t : mx
  }
  *lo = mn;
  *hi = mx;
}

/// The footprint of sixteen pixels (taa.cpp FootprintRow, the same operations): the
/// fractions and the integer texel x0, y0 (before the clamp to the history); Offsets16 adds
/// the four corners' float offsets into the history, a (x0, y0), b (x1, y0), c (x0, y1),
/// d (x1, y1), where the fetch needs them per pixel.
struct Footprint16 {
  __m512 tx, ty;
  __m512i x0, y0;
  __m512i off[4];
};

AALAB_TAA_AVX512 inline void MakeFootprint16(__m512 px, __m512 py, Footprint16* fp) {
  const __m512 half = _mm512_set1_ps(0.5f);
  const __m512 fx = _mm512_sub_ps(px, half), fy = _mm512_sub_ps(py, half);
  const __m512i ix = _mm512_cvttps_epi32(fx), iy = _mm512_cvttps_epi32(fy);
  const __m512i one = _mm512_set1_epi32(1);
  // floor: truncation minus one where f < trunc(f).
  fp->x0 = _mm512_mask_sub_epi32(ix, _mm512_cmp_ps_mask(fx, _mm512_cvtepi32_ps(ix), _CMP_LT_OQ), ix, one);
  fp->y0 = _mm512_mask_sub_epi32(iy, _mm512_cmp_ps_mask(fy, _mm512_cvtepi32_ps(iy), _CMP_LT_OQ), iy, one);
  fp->tx = _mm512_sub_ps(fx, _mm512_cvtepi32_ps(fp->x0));
  fp->ty = _mm512_sub_ps(fy, _mm512_cvtepi32_ps(fp->y0));
}

/// The corners' offsets: x0, x0 + 1, y0, y0 + 1 clamped to the history, 3 (y w + x).
AALAB_TAA_AVX512 inline void Offsets16(int hw, int hh, Footprint16* fp) {
  const __m512i zero = _mm512_setzero_si512(), one = _mm512_set1_epi32(1), wm = _mm512_set1_epi32(hw - 1),
                hm = _mm512_set1_epi32(hh - 1), w = _mm512_set1_epi32(hw);
  const __m512i xa = _mm512_min_epi32(_mm512_max_epi32(fp->x0, zero), wm);
  const __m512i xb = _mm512_min_epi32(_mm512_max_epi32(_mm512_add_epi32(fp->x0, one), zero), wm);
  const __m512i ra = _mm512_mullo_epi32(_mm512_min_epi32(_mm512_max_epi32(fp->y0, zero), hm), w);
  const __m512i rb = _mm512_mullo_epi32(_mm512_min_epi32(_mm512_max_epi32(_mm512_add_epi32(fp->y0, one), zero), hm), w);
  const __m512i three = _mm512_set1_epi32(3);
  fp->off[0] = _mm512_mullo_epi32(_mm512_add_epi32(ra, xa), three);
  fp->off[1] = _mm512_mullo_epi32(_mm512_add_epi32(ra, xb), three);
  fp->off[2] = _mm512_mullo_epi32(_mm512_add_epi32(rb, xa), three);
  fp->off[3] = _mm512_mullo_epi32(_mm512_add_epi32(rb, xb), three);
}

/// Whether the footprint is contiguous, and then the float offsets of corner a and c of
/// pixel 0 (*a, *c): every pixel's y0 is pixel 0's and its x0 pixel 0's + i, and no x is
/// clamped (0 ≤ x0 of pixel 0, x0 + 1 of pixel 15 ≤ w − 1). Then corner a of pixel i is
/// pixel 0's + i texels and corner b the texel after a, likewise c and d, so the sixteen a/b
/// texels are the 17 consecutive texels from a's of pixel 0 (c/d: from c's); the rows are
/// clamped as Offsets16 clamps them. The common case (a still or panning camera, any motion
/// that varies by less than a pixel between neighbours); false where a clamp at the left or
/// right border would make b = a.
AALAB_TAA_AVX512 inline bool Contiguous16(const Footprint16& fp, int hw, int hh, int* a, int* c) {
  const __m512i step = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const int x0 = _mm_cvtsi128_si32(_mm512_castsi512_si128(fp.x0));
  const int y0 = _mm_cvtsi128_si32(_mm512_castsi512_si128(fp.y0));
  if (x0 < 0 || x0 + 16 > hw - 1) return false;
  const __mmask16 m = _mm512_cmpeq_epi32_mask(fp.x0, _mm512_add_epi32(_mm512_set1_epi32(x0), step)) &
                      _mm512_cmpeq_epi32_mask(fp.y0, _mm512_set1_epi32(y0));
  if (m != 0xffff) return false;
  const int ya = y0 < 0 ? 0 : (y0 > hh - 1 ? hh - 1 : y0), yb = y0 + 1 < 0 ? 0 : (y0 + 1 > hh - 1 ? hh - 1 : y0 + 1);
  *a = 3 * (ya * hw + x0);
  *c = 3 * (yb * hw + x0);
  return true;
}

/// The deinterleave of 17 consecutive texels (51 floats, the last at most 1 float before the
/// history's end: it holds one float of padding) into planar R, G, B of texels 0..15 (a or
/// c) and of texels 1..16 (b or d) by two-source permutes: 4 loads and 9 permutes in place
/// of 32 unaligned 4-float loads and 24 inserts. The indices are those of the float order.
struct DeinterleaveIndex {
  alignas(64) int32_t first[3][16];   ///< channel c of texel i from floats 0..31 (3i + c < 32)
  alignas(64) int32_t second[3][16];  ///< kept (i) or from floats 32..47 (16 + 3i + c − 32)
  alignas(64) int32_t shift[3][16];   ///< texel i + 1: lane i + 1, lane 15 from floats 48..50
};
constexpr DeinterleaveIndex MakeDeinterleaveIndex() {
  DeinterleaveIndex t{};
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < 16; ++i) {
      const int f = 3 * i + c;
      t.first[c][i] = f < 32 ? f : 0;
      t.second[c][i] = f < 32 ? i : 16 + f - 32;
      t.shift[c][i] = i < 15 ? i + 1 : 16 + c;
    }
  }
  return t;
}
constexpr DeinterleaveIndex kDeinterleave = MakeDeinterleaveIndex();

/// Planar R, G, B of texels 0..15 (lo) and 1..16 (hi) of the 17 texels at p.
AALAB_TAA_AVX512 inline void Texels17(const float* p, __m512 lo[3], __m512 hi[3]) {
  const __m512 v0 = _mm512_loadu_ps(p), v1 = _mm512_loadu_ps(p + 16), v2 = _mm512_loadu_ps(p + 32);
  const __m512 v3 = _mm512_castps128_ps512(_mm_loadu_ps(p + 48));  // floats 48..51: 51 is padding at most
  for (int c = 0; c < 3; ++c) {
    const __m512 t = _mm512_permutex2var_ps(v0, _mm512_load_si512(kDeinterleave.first[c]), v1);
    lo[c] = _mm512_permutex2var_ps(t, _mm512_load_si512(kDeinterleave.second[c]), v2);
    hi[c] = _mm512_permutex2var_ps(lo[c], _mm512_load_si512(kDeinterleave.shift[c]), v3);
  }
}

/// Fetch16 for a contiguous footprint (Contiguous16): the same lerps per value in the same
/// order (a + tx (b − a), c + tx (d − c), then top + ty (bot − top)), on planar vectors.
AALAB_TAA_AVX512 inline void FetchContiguous16(const float* hist, const Footprint16& fp, int oa, int oc, __m512* r,
                                               __m512* g, __m512* b) {
  __m512 a[3], bb[3], c[3], d[3];
  Texels17(hist + oa, a, bb);
  Texels17(hist + oc, c, d);
  __m512 out[3];
  for (int k = 0; k < 3; ++k) out[k] = Lerp16(Lerp16(a[k], bb[k], fp.tx), Lerp16(c[k], d[k], fp.tx), fp.ty);
  *r = out[0];
  *g = out[1];
  *b = out[2];
}

/// Four 4-float unaligned loads into one vector (128-bit lanes 0..3).
AALAB_TAA_AVX512 inline __m512 Load4x4(const float* hist, const int32_t* o, int j) {
  const __m512 v = _mm512_castps128_ps512(_mm_loadu_ps(hist + o[j]));
  return _mm512_insertf32x4(
      _mm512_insertf32x4(_mm512_insertf32x4(v, _mm_loadu_ps(hist + o[j + 4]), 1), _mm_loadu_ps(hist + o[j + 8]), 2),
      _mm_loadu_ps(hist + o[j + 12]), 3);
}

/// The bilinear fetch of sixteen pixels (any footprint): pixels j, j + 4, j + 8, j + 12
/// share a vector, then a 4×4 transpose per 128-bit lane puts pixel order back (planar R, G,
/// B out).
AALAB_TAA_AVX512 inline void Fetch16(const float* hist, const Footprint16& fp, __m512* r, __m512* g, __m512* b) {
  alignas(64) int32_t off[4][16];
  for (int k = 0; k < 4; ++k) _mm512_store_si512(off[k], fp.off[k]);
  __m512 p[4];
  for (int j = 0; j < 4; ++j) {
    const __m512i sel = _mm512_setr_epi32(j, j, j, j, j + 4, j + 4, j + 4, j + 4, j + 8, j + 8, j + 8, j + 8, j + 12,
                                          j + 12, j + 12, j + 12);
    const __m512 tx = _mm512_permutexvar_ps(sel, fp.tx), ty = _mm512_permutexvar_ps(sel, fp.ty);
    const __m512 a = Load4x4(hist, off[0], j), bb = Load4x4(hist, off[1], j);
    const __m512 c = Load4x4(hist, off[2], j), d = Load4x4(hist, off[3], j);
    p[j] = Lerp16(Lerp16(a, bb, tx), Lerp16(c, d, tx), ty);
  }
  const __m512 t0 = _mm512_unpacklo_ps(p[0], p[1]), t1 = _mm512_unpacklo_ps(p[2], p[3]);
  const __m512 t2 = _mm512_unpackhi_ps(p[0], p[1]), t3 = _mm512_unpackhi_ps(p[2], p[3]);
  *r = _mm512_shuffle_ps(t0, t1, _MM_SHUFFLE(1, 0, 1, 0));
  *g = _mm512_shuffle_ps(t0, t1, _MM_SHUFFLE(3, 2, 3, 2));
  *b = _mm512_shuffle_ps(t2, t3, _MM_SHUFFLE(1, 0, 1, 0));
}

/// Sixteen pixels' planar RGB interleaved into exactly 48 floats at dst: output vector k,
/// element e holds float 16k + e, pixel (16k + e) / 3, channel (16k + e) mod 3 (first R and
/// G merged, then B).
struct InterleaveIndex {
  alignas(64) int32_t rg[3][16];   ///< from R (0..15) or G (16..31)
  alignas(64) int32_t rgb[3][16];  ///< the R/G vector's element (0..15) or B (16..31)
};
constexpr InterleaveIndex MakeInterleaveIndex() {
  InterleaveIndex t{};
  for (int k = 0; k < 3; ++k) {
    for (int e = 0; e < 16; ++e) {
      const int i = 16 * k + e, p = i / 3, c = i % 3;
      t.rg[k][e] = c == 0 ? p : (c == 1 ? 16 + p : 0);
      t.rgb[k][e] = c == 2 ? 16 + p : e;
    }
  }
  return t;
}
constexpr InterleaveIndex kInterleave = MakeInterleaveIndex();

AALAB_TAA_AVX512 inline void StoreRgb16(__m512 r, __m512 g, __m512 b, float* dst) {
  for (int k = 0; k < 3; ++k) {
    const __m512 t = _mm512_permutex2var_ps(r, _mm512_load_si512(kInterleave.rg[k]), g);
    _mm512_storeu_ps(dst + 16 * k, _mm512_permutex2var_ps(t, _mm512_load_si512(kInterleave.rgb[k]), b));
  }
}

template <bool kClip, bool kVariance>
AALAB_TAA_AVX512 int HistoryBlendRow16(const Avx2RowIn& in, int w, float alpha, float* __restrict next,
                                       uint8_t* __restrict rgba) {
  const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f), half = _mm512_set1_ps(0.5f),
               eps = _mm512_set1_ps(1e-8f), va = _mm512_set1_ps(alpha), fw = _mm512_set1_ps(static_cast<float>(in.hw)),
               fh = _mm512_set1_ps(static_cast<float>(in.hh));
  const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
  const __m512i odd = _mm512_add_epi32(even, _mm512_set1_epi32(1));
  const int n = w - w % 16;
  Footprint16 fp;
  for (int x = 0; x < n; x += 16) {
    const __m512 p0 = _mm512_loadu_ps(in.prev + 2 * x), p1 = _mm512_loadu_ps(in.prev + 2 * x + 16);
    const __m512 qx = _mm512_permutex2var_ps(p0, even, p1), qy = _mm512_permutex2var_ps(p0, odd, p1);
    // The position clamped into [0, w] × [0, h] (FootprintRow): unchanged exactly where the
    // pixel has history, so that is where it equals the position (false for NaN; −0 == +0).
    const __m512 px = _mm512_min_ps(_mm512_max_ps(qx, zero), fw), py = _mm512_min_ps(_mm512_max_ps(qy, zero), fh);
    MakeFootprint16(px, py, &fp);
    __m512 r, g, b;
    int oa, oc;
    if (Contiguous16(fp, in.hw, in.hh, &oa, &oc)) {
      FetchContiguous16(in.hist, fp, oa, oc, &r, &g, &b);
    } else {
      Offsets16(in.hw, in.hh, &fp);
      Fetch16(in.hist, fp, &r, &g, &b);
    }
    __m512 h[3];
    ToYcc16(r, g, b, &h[0], &h[1], &h[2]);
    if constexpr (kClip) {
      __m512 centre[3], v[3], ext[3];
      __mmask16 near = 0xffff;
      for (int c = 0; c < 3; ++c) {
        __m512 lo, hi;
        Box16<kVariance>(in.box[c], x, in.gamma, &lo, &hi);
        centre[c] = _mm512_mul_ps(half, _mm512_add_ps(hi, lo));
        ext[c] = _mm512_add_ps(_mm512_mul_ps(half, _mm512_sub_ps(hi, lo)), eps);
        v[c] = _mm512_sub_ps(h[c], centre[c]);
        near &= _mm512_cmp_ps_mask(Abs16(v[c]), ext[c], _CMP_LE_OQ);
      }
      if (near != 0xffff) {  // taa_avx2.cpp: only then are ClipToBox's quotients formed
        __m512 m = zero;
        for (int c = 0; c < 3; ++c) m = _mm512_max_ps(Abs16(_mm512_div_ps(v[c], ext[c])), m);  // Max(m, |q|)
        const __mmask16 inside = _mm512_cmp_ps_mask(m, one, _CMP_LE_OQ);
        const __m512 div = _mm512_mask_blend_ps(inside, m, one);
        for (int c = 0; c < 3; ++c) {
          h[c] = _mm512_mask_blend_ps(inside, _mm512_add_ps(centre[c], _mm512_div_ps(v[c], div)), h[c]);
        }
      }
    }
    const __m512 oy = Lerp16(h[0], _mm512_loadu_ps(in.cy + x + 1), va);
    const __m512 oco = Lerp16(h[1], _mm512_loadu_ps(in.cco + x + 1), va);
    const __m512 ocg = Lerp16(h[2], _mm512_loadu_ps(in.ccg + x + 1), va);
    const __m512 t = _mm512_sub_ps(oy, ocg);
    __m512 o0 = Clamp01x16(_mm512_add_ps(t, oco)), o1 = Clamp01x16(_mm512_add_ps(oy, ocg)),
           o2 = Clamp01x16(_mm512_sub_ps(t, oco));
    // Has history: 0 ≤ x ≤ W and 0 ≤ y ≤ H (false for NaN), i.e. the clamp left it as it was.
    const __mmask16 ok = _mm512_cmp_ps_mask(px, qx, _CMP_EQ_OQ) & _mm512_cmp_ps_mask(py, qy, _CMP_EQ_OQ);
    if (ok != 0xffff) {  // a pixel without history takes the current colour
      const __m512i s = _mm512_loadu_si512(in.src + 4 * x);
      o0 = _mm512_mask_blend_ps(ok, _mm512_i32gather_ps(Channel16(s, 0), in.decode, 4), o0);
      o1 = _mm512_mask_blend_ps(ok, _mm512_i32gather_ps(Channel16(s, 1), in.decode, 4), o1);
      o2 = _mm512_mask_blend_ps(ok, _mm512_i32gather_ps(Channel16(s, 2), in.decode, 4), o2);
    }
    StoreRgb16(o0, o1, o2, next + 3 * static_cast<size_t>(x));
    StoreRgba16(in.enc, o0, o1, o2, rgba + 4 * static_cast<size_t>(x));
  }
  return n;
}

}  // namespace

bool TaaHasAvx512() {
  // With AVX2 too: the AVX2 entry points run this kernel, and StepFast leaves the boxes of
  // [0, w − w mod 16) to it only when it runs.
  static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx2");
  return has;
}

int HistoryBlendRow16Avx512(const Avx2RowIn& in, int w, bool clip, float alpha, float* next, uint8_t* rgba) {
  if (!TaaHasAvx512()) return 0;
  if (!clip) return HistoryBlendRow16<false, false>(in, w, alpha, next, rgba);
  return in.variance ? HistoryBlendRow16<true, true>(in, w, alpha, next, rgba)
                     : HistoryBlendRow16<true, false>(in, w, alpha, next, rgba);
}

AALAB_TAA_AVX512 int EncodeRgbaAvx512(const EncodeTables& t, const float* r, const float* g, const float* b, int w,
                                      uint8_t* rgba) {
  if (!TaaHasAvx512()) return 0;
  const int n = w - w % 16;
  for (int x = 0; x < n; x += 16) {
    StoreRgba16(t, _mm512_loadu_ps(r + x), _mm512_loadu_ps(g + x), _mm512_loadu_ps(b + x), rgba + 4 * x);
  }
  return n;
}

/// decode[v] per lane (v in 0..255) from the table held in 16 registers (t[k]: entries
/// 16k..16k + 15): per 32 entries one two-source permute on v's low 5 bits, then v's bits
/// 5, 6, 7 select among the eight by blends. The same values as a gather of the table.
AALAB_TAA_AVX512 inline __m512 DecodeRegs16(const __m512* t, __m512i v) {
  __m512 u[8];
  for (int j = 0; j < 8; ++j) u[j] = _mm512_permutex2var_ps(t[2 * j], v, t[2 * j + 1]);
  const __mmask16 b5 = _mm512_test_epi32_mask(v, _mm512_set1_epi32(32));
  const __mmask16 b6 = _mm512_test_epi32_mask(v, _mm512_set1_epi32(64));
  const __mmask16 b7 = _mm512_test_epi32_mask(v, _mm512_set1_epi32(128));
  for (int j = 0; j < 4; ++j) u[j] = _mm512_mask_blend_ps(b5, u[2 * j], u[2 * j + 1]);
  for (int j = 0; j < 2; ++j) u[j] = _mm512_mask_blend_ps(b6, u[2 * j], u[2 * j + 1]);
  return _mm512_mask_blend_ps(b7, u[0], u[1]);
}

AALAB_TAA_AVX512 int YccPlaneRowAvx512(const uint8_t* src, int w, const float* decode, float* y, float* co, float* cg) {
  if (!TaaHasAvx512()) return 0;
  const int n = w - w % 16;
  __m512 t[16];
  for (int k = 0; k < 16; ++k) t[k] = _mm512_loadu_ps(decode + 16 * k);
  for (int x = 0; x < n; x += 16) {
    const __m512i s = _mm512_loadu_si512(src + 4 * x);
    __m512 vy, vco, vcg;
    ToYcc16(DecodeRegs16(t, Channel16(s, 0)), DecodeRegs16(t, Channel16(s, 1)), DecodeRegs16(t, Channel16(s, 2)), &vy,
            &vco, &vcg);
    _mm512_storeu_ps(y + x, vy);
    _mm512_storeu_ps(co + x, vco);
    _mm512_storeu_ps(cg + x, vcg);
  }
  return n;
}

AALAB_TAA_AVX512 int Div9Avx512(const float* x, int w, float* q) {
  if (!TaaHasAvx512()) return 0;
  const int n = w - w % 16;
  for (int i = 0; i < n; i += 16) _mm512_storeu_ps(q + i, Div9x16(_mm512_loadu_ps(x + i)));
  return n;
}

}  // namespace aalab::taa_detail

#else  // no AVX-512 kernels

namespace aalab::taa_detail {
bool TaaHasAvx512() { return false; }
int HistoryBlendRow16Avx512(const Avx2RowIn&, int, bool, float, float*, uint8_t*) { return 0; }
int EncodeRgbaAvx512(const EncodeTables&, const float*, const float*, const float*, int, uint8_t*) { return 0; }
int YccPlaneRowAvx512(const uint8_t*, int, const float*, float*, float*, float*) { return 0; }
int Div9Avx512(const float*, int, float*) { return 0; }
}  // namespace aalab::taa_detail

#endif
