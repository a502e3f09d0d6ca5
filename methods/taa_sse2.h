/// The SSE2 row kernel of TAA's production step (methods/taa.cpp, StepFast): the history
/// fetch's gather and lerps, ToYCoCg, the clip, the blend, FromYCoCg, the clamp and the
/// select of the current colour where there is no history, four pixels at a time, with the
/// same float operations in the same order as StepReference (no FMA: the build has
/// -ffp-contract=off, and SSE2 has none), so the results are the same bits.
/// Selects are written so that each equals the scalar form it replaces, NaN and −0 included:
/// `a < b ? b : a` is _mm_max_ps(b, a), `b < a ? b : a` is _mm_min_ps(b, a) (both return
/// their second operand when the comparison is false or unordered). Only for x86 builds with
/// SSE2 (every x86-64 one); taa.cpp falls back to its scalar rows elsewhere and for the last
/// W mod 4 pixels of a row.
#pragma once
#if defined(__SSE2__)
#include <emmintrin.h>

#include <cstdint>

namespace aalab::taa_detail {

/// One row's inputs for HistoryBlendRow4 (every array indexed by the pixel x of the row).
struct Sse2RowIn {
  const float* hist;            ///< the history, 3 floats per pixel, readable 1 float past its end
  const float *tx, *ty;         ///< the footprint's fractions (FootprintRow)
  const int32_t* off;           ///< the footprint's four texel offsets per pixel (FootprintRow)
  const float* prev;            ///< previous positions, x and y per pixel
  float fw, fh;                 ///< the frame's size: a position inside [0, fw] × [0, fh] has history
  const float *lo[3], *hi[3];   ///< the box per YCoCg channel (read only when clipping)
  const float *cy, *cco, *ccg;  ///< current YCoCg planes, padded: texel x at x + 1
  const uint8_t* src;           ///< the current frame's row, RGBA8
  const float* decode;          ///< linear value of each 8-bit code
};

/// max(m, |q|) as Max(m, std::fabs(q)) = (m < |q| ? |q| : m).
inline __m128 MaxAbs(__m128 m, __m128 q) {
  const __m128 abs = _mm_andnot_ps(_mm_set1_ps(-0.0f), q);
  return _mm_max_ps(abs, m);
}

/// mask ? a : b.
inline __m128 Select(__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); }

/// a + t·(b − a), per lane.
inline __m128 Lerp(__m128 a, __m128 b, __m128 t) { return _mm_add_ps(a, _mm_mul_ps(t, _mm_sub_ps(b, a))); }

/// Pixels [x0, x1) of a row, x1 − x0 a multiple of 4: writes the new history (3 floats per
/// pixel, `next`) and the planar output colour (outr, outg, outb).
template <bool kClip>
inline void HistoryBlendRow4(const Sse2RowIn& in, int x0, int x1, float alpha, float* __restrict next,
                             float* __restrict outr, float* __restrict outg, float* __restrict outb) {
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), half = _mm_set1_ps(0.5f), quarter = _mm_set1_ps(0.25f),
               mquarter = _mm_set1_ps(-0.25f), eps = _mm_set1_ps(1e-8f), va = _mm_set1_ps(alpha),
               fw = _mm_set1_ps(in.fw), fh = _mm_set1_ps(in.fh);
  for (int x = x0; x < x1; x += 4) {
    // The bilinear fetch per pixel (RGB in lanes 0..2; lane 3 is a neighbour's value, unused).
    __m128 px[4];
    for (int j = 0; j < 4; ++j) {
      const int32_t* o = in.off + 4 * (x + j);
      const __m128 a = _mm_loadu_ps(in.hist + o[0]), b = _mm_loadu_ps(in.hist + o[1]);
      const __m128 c = _mm_loadu_ps(in.hist + o[2]), d = _mm_loadu_ps(in.hist + o[3]);
      const __m128 tx = _mm_set1_ps(in.tx[x + j]), ty = _mm_set1_ps(in.ty[x + j]);
      const __m128 top = Lerp(a, b, tx), bot = Lerp(c, d, tx);
      px[j] = Lerp(top, bot, ty);
    }
    _MM_TRANSPOSE4_PS(px[0], px[1], px[2], px[3]);  // px[0..2]: R, G, B of the four pixels
    const __m128 r = px[0], g = px[1], b = px[2];
    // ToYCoCg, the scalar expression order.
    __m128 h[3] = {_mm_add_ps(_mm_add_ps(_mm_mul_ps(quarter, r), _mm_mul_ps(half, g)), _mm_mul_ps(quarter, b)),
                   _mm_sub_ps(_mm_mul_ps(half, r), _mm_mul_ps(half, b)),
                   _mm_sub_ps(_mm_add_ps(_mm_mul_ps(mquarter, r), _mm_mul_ps(half, g)), _mm_mul_ps(quarter, b))};
    if constexpr (kClip) {
      __m128 centre[3], v[3], ext[3], near = _mm_castsi128_ps(_mm_set1_epi32(-1));
      for (int c = 0; c < 3; ++c) {
        const __m128 hi = _mm_loadu_ps(in.hi[c] + x), lo = _mm_loadu_ps(in.lo[c] + x);
        centre[c] = _mm_mul_ps(half, _mm_add_ps(hi, lo));
        ext[c] = _mm_add_ps(_mm_mul_ps(half, _mm_sub_ps(hi, lo)), eps);
        v[c] = _mm_sub_ps(h[c], centre[c]);
        near = _mm_and_ps(near, _mm_cmple_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), v[c]), ext[c]));
      }
      // |v| ≤ ext in every channel means |v / ext| ≤ 1 (the rounded quotient of an exact one
      // ≤ 1 is ≤ 1; v = ext = 0 gives NaN, which Max ignores): inside, h stays. Only when a
      // lane may be outside are the quotients formed, exactly as ClipToBox forms them.
      if (_mm_movemask_ps(near) != 0xf) {
        __m128 m = zero;
        for (int c = 0; c < 3; ++c) m = MaxAbs(m, _mm_div_ps(v[c], ext[c]));
        const __m128 inside = _mm_cmple_ps(m, one);
        const __m128 div = Select(inside, one, m);
        for (int c = 0; c < 3; ++c) h[c] = Select(inside, h[c], _mm_add_ps(centre[c], _mm_div_ps(v[c], div)));
      }
    }
    const __m128 oy = Lerp(h[0], _mm_loadu_ps(in.cy + x + 1), va);
    const __m128 oco = Lerp(h[1], _mm_loadu_ps(in.cco + x + 1), va);
    const __m128 ocg = Lerp(h[2], _mm_loadu_ps(in.ccg + x + 1), va);
    const __m128 t = _mm_sub_ps(oy, ocg);
    // Clamp01(v) = v < 0 ? 0 : (1 < v ? 1 : v) = max(0, min(1, v)) in the operand order above.
    auto clamp01 = [&](__m128 v) { return _mm_max_ps(zero, _mm_min_ps(one, v)); };
    // Has history: 0 ≤ x ≤ W and 0 ≤ y ≤ H (false for NaN).
    const __m128 p0 = _mm_loadu_ps(in.prev + 2 * x), p1 = _mm_loadu_ps(in.prev + 2 * x + 4);
    const __m128 qx = _mm_shuffle_ps(p0, p1, _MM_SHUFFLE(2, 0, 2, 0)),
                 qy = _mm_shuffle_ps(p0, p1, _MM_SHUFFLE(3, 1, 3, 1));
    const __m128 ok = _mm_and_ps(_mm_and_ps(_mm_cmpge_ps(qx, zero), _mm_cmple_ps(qx, fw)),
                                 _mm_and_ps(_mm_cmpge_ps(qy, zero), _mm_cmple_ps(qy, fh)));
    __m128 o0 = clamp01(_mm_add_ps(t, oco)), o1 = clamp01(_mm_add_ps(oy, ocg)), o2 = clamp01(_mm_sub_ps(t, oco));
    if (_mm_movemask_ps(ok) != 0xf) {  // a pixel without history takes the current colour
      const uint8_t* s = in.src + 4 * x;
      const float* dc = in.decode;
      o0 = Select(ok, o0, _mm_setr_ps(dc[s[0]], dc[s[4]], dc[s[8]], dc[s[12]]));
      o1 = Select(ok, o1, _mm_setr_ps(dc[s[1]], dc[s[5]], dc[s[9]], dc[s[13]]));
      o2 = Select(ok, o2, _mm_setr_ps(dc[s[2]], dc[s[6]], dc[s[10]], dc[s[14]]));
    }
    _mm_storeu_ps(outr + x, o0);
    _mm_storeu_ps(outg + x, o1);
    _mm_storeu_ps(outb + x, o2);
    __m128 o3 = zero;
    _MM_TRANSPOSE4_PS(o0, o1, o2, o3);  // o0..o3: RGB_ of each pixel
    float* dst = next + 3 * static_cast<size_t>(x);
    _mm_storeu_ps(dst, o0);  // lane 3 is overwritten by the next store
    _mm_storeu_ps(dst + 3, o1);
    _mm_storeu_ps(dst + 6, o2);
    _mm_storel_pi(reinterpret_cast<__m64*>(dst + 9), o3);  // the last pixel: exactly 3 floats
    _mm_store_ss(dst + 11, _mm_movehl_ps(o3, o3));
  }
}

}  // namespace aalab::taa_detail
#endif
