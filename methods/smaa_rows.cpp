// SMAA 1x pass 1's rows (methods/smaa_rows.h), for the production path in
// methods/smaa_fast.cpp.
//
// LumaRow: per lane the scalar expression's IEEE float32 operations in its order,
// ((k·fl(1/255))·0.2126 + (k·fl(1/255))·0.7152) + (k·fl(1/255))·0.0722 with k the byte as a
// float (exact); SSE2 (the x86-64 baseline) four pixels a vector, AVX2 eight, chosen at run
// time with __builtin_cpu_supports. Vector mul/add and int→float conversion round like their
// scalar forms and the build neither contracts nor reassociates (-ffp-contract=off, no
// fast-math), so every lane is the scalar value; tests/methods/smaa_rows_test.cpp checks all
// 2^24 colours and row lengths that reach each block and the tail.
// EdgeRowLuma: SSE2 four columns a step, AVX2 eight: |c − l| and |c − t| against the
// threshold first, and where no lane reaches it (most of a frame) the bytes are 0 at once;
// otherwise the scalar form's deltas (sub, then the sign bit cleared, = std::fabs), their
// max (max_ps equals the scalar select on non-negative, non-NaN values) and the two compares,
// per lane. tests/methods/smaa_rows_test.cpp compares it with EdgeRowLumaScalar on rows near
// the threshold and the contrast limit, ties included.
// ListNonZero: a 16-byte compare and movemask per step, set bits listed in order.
#include "methods/smaa_rows.h"

#include <cmath>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#include <immintrin.h>
#define AALAB_SMAA_ROWS_AVX2 1
#endif

namespace aalab::smaa_internal {

namespace {

constexpr float kInv255 = 1.0f / 255.0f;
constexpr float kWr = 0.2126f, kWg = 0.7152f, kWb = 0.0722f;

inline float LumaOf(const uint8_t* p) {
  const float r = static_cast<float>(p[0]) * kInv255 * kWr;
  const float g = static_cast<float>(p[1]) * kInv255 * kWg;
  const float b = static_cast<float>(p[2]) * kInv255 * kWb;
  return (r + g) + b;
}

#if defined(__SSE2__)
// Four lumas of the four RGBA8 pixels at p.
inline __m128 Luma4(const uint8_t* p) {
  const __m128i px = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  const __m128i m = _mm_set1_epi32(0xff);
  const __m128 k = _mm_set1_ps(kInv255);
  const __m128 r = _mm_mul_ps(_mm_mul_ps(_mm_cvtepi32_ps(_mm_and_si128(px, m)), k), _mm_set1_ps(kWr));
  const __m128 g =
      _mm_mul_ps(_mm_mul_ps(_mm_cvtepi32_ps(_mm_and_si128(_mm_srli_epi32(px, 8), m)), k), _mm_set1_ps(kWg));
  const __m128 b =
      _mm_mul_ps(_mm_mul_ps(_mm_cvtepi32_ps(_mm_and_si128(_mm_srli_epi32(px, 16), m)), k), _mm_set1_ps(kWb));
  return _mm_add_ps(_mm_add_ps(r, g), b);
}
#endif

#if defined(AALAB_SMAA_ROWS_AVX2)
#define AALAB_AVX2 __attribute__((target("avx2")))
AALAB_AVX2 inline __m256 Luma8(const uint8_t* p) {
  const __m256i px = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
  const __m256i m = _mm256_set1_epi32(0xff);
  const __m256 k = _mm256_set1_ps(kInv255);
  const __m256 r = _mm256_mul_ps(_mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_and_si256(px, m)), k), _mm256_set1_ps(kWr));
  const __m256 g = _mm256_mul_ps(_mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_and_si256(_mm256_srli_epi32(px, 8), m)), k),
                                 _mm256_set1_ps(kWg));
  const __m256 b = _mm256_mul_ps(_mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_and_si256(_mm256_srli_epi32(px, 16), m)), k),
                                 _mm256_set1_ps(kWb));
  return _mm256_add_ps(_mm256_add_ps(r, g), b);
}

// The AVX2 blocks of LumaRow: returns the number of pixels done (a multiple of 8).
AALAB_AVX2 int LumaRowAvx2(const uint8_t* src, int w, float* o) {
  int x = 0;
  for (; x + 8 <= w; x += 8) _mm256_storeu_ps(o + x, Luma8(src + 4 * x));
  return x;
}

bool HasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#endif

}  // namespace

void LumaRowScalar(const uint8_t* src, int w, float* l) {
  float* o = l + 2;
  for (int x = 0; x < w; ++x) o[x] = LumaOf(src + 4 * x);
  l[0] = l[1] = o[0];
  l[w + 2] = o[w - 1];
}

void LumaRow(const uint8_t* src, int w, float* l) {
  float* o = l + 2;
  int x = 0;
#if defined(AALAB_SMAA_ROWS_AVX2)
  if (HasAvx2()) x = LumaRowAvx2(src, w, o);
#endif
#if defined(__SSE2__)
  for (; x + 4 <= w; x += 4) _mm_storeu_ps(o + x, Luma4(src + 4 * x));
#endif
  for (; x < w; ++x) o[x] = LumaOf(src + 4 * x);
  l[0] = l[1] = o[0];
  l[w + 2] = o[w - 1];
}

namespace {
// std::max of floats as a select (std::max(a, b) is a < b ? b : a).
inline float MaxF(float a, float b) { return a < b ? b : a; }

// The scalar form of EdgeRowLuma for columns [x0, w): returns the kept count, ORs into *any.
int EdgeRowLumaFrom(const float* lc, const float* lt, const float* ltt, const float* lb, int x0, int w, float thr,
                    float lcf, uint8_t* out, uint8_t* any) {
  int kept = 0;
  uint8_t seen = 0;
  for (int x = x0; x < w; ++x) {
    const float c = lc[x + 2], l = lc[x + 1], t = lt[x + 2];
    const float dx = std::fabs(c - l), dy = std::fabs(c - t), dr = std::fabs(c - lc[x + 3]);
    const float db = std::fabs(c - lb[x + 2]), dll = std::fabs(l - lc[x]), dtt = std::fabs(t - ltt[x + 2]);
    const int ex = dx >= thr, ey = dy >= thr;
    const float final_delta = MaxF(MaxF(MaxF(dx, dr), dll), MaxF(MaxF(dy, db), dtt));
    const int bx = ex & (lcf * dx >= final_delta), by = ey & (lcf * dy >= final_delta);
    const uint8_t bits = static_cast<uint8_t>(bx | by << 1);
    out[x] = bits;
    seen |= bits;
    kept += ex | ey;
  }
  *any |= seen;
  return kept;
}

// kSpread[m]: byte i = bit i of m (eight lanes' compare mask as bytes).
struct Spread {
  uint64_t v[256];
};
const Spread& Spreads() {
  static const Spread s = [] {
    Spread t{};
    for (int m = 0; m < 256; ++m) {
      for (int i = 0; i < 8; ++i) t.v[m] |= static_cast<uint64_t>((m >> i) & 1) << (8 * i);
    }
    return t;
  }();
  return s;
}

#if defined(__SSE2__)
// Columns [x, x + 4) of EdgeRowLuma: dx and dy first; when no lane reaches the threshold (most
// of a frame) the four bytes are 0, else the other four deltas and the decision per lane.
// |v| clears the sign bit (std::fabs); max_ps = MaxF on these non-negative, non-NaN deltas.
// Returns the kept count of the four and ORs the bits into *seen.
inline int Edge4(const float* lc, const float* lt, const float* ltt, const float* lb, int x, __m128 thr, __m128 lcf,
                 uint8_t* out, uint8_t* seen) {
  const __m128 abs = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 c = _mm_loadu_ps(lc + x + 2), l = _mm_loadu_ps(lc + x + 1), t = _mm_loadu_ps(lt + x + 2);
  const __m128 dx = _mm_and_ps(_mm_sub_ps(c, l), abs), dy = _mm_and_ps(_mm_sub_ps(c, t), abs);
  const __m128 ex = _mm_cmpge_ps(dx, thr), ey = _mm_cmpge_ps(dy, thr);
  const int m = _mm_movemask_ps(_mm_or_ps(ex, ey));
  uint32_t bytes = 0;
  if (m != 0) {
    const __m128 dr = _mm_and_ps(_mm_sub_ps(c, _mm_loadu_ps(lc + x + 3)), abs);
    const __m128 db = _mm_and_ps(_mm_sub_ps(c, _mm_loadu_ps(lb + x + 2)), abs);
    const __m128 dll = _mm_and_ps(_mm_sub_ps(l, _mm_loadu_ps(lc + x)), abs);
    const __m128 dtt = _mm_and_ps(_mm_sub_ps(t, _mm_loadu_ps(ltt + x + 2)), abs);
    const __m128 fin = _mm_max_ps(_mm_max_ps(_mm_max_ps(dx, dr), dll), _mm_max_ps(_mm_max_ps(dy, db), dtt));
    const int bx = _mm_movemask_ps(_mm_and_ps(ex, _mm_cmpge_ps(_mm_mul_ps(lcf, dx), fin)));
    const int by = _mm_movemask_ps(_mm_and_ps(ey, _mm_cmpge_ps(_mm_mul_ps(lcf, dy), fin)));
    const Spread& s = Spreads();
    bytes = static_cast<uint32_t>(s.v[bx] | s.v[by] << 1);
    *seen |= static_cast<uint8_t>(bx | by);
  }
  std::memcpy(out + x, &bytes, 4);
  return __builtin_popcount(static_cast<unsigned>(m));
}
#endif

#if defined(AALAB_SMAA_ROWS_AVX2)
// Columns [x, x + 8) of EdgeRowLuma with AVX2: Edge4's operations on eight lanes.
AALAB_AVX2 inline int Edge8(const float* lc, const float* lt, const float* ltt, const float* lb, int x, __m256 thr,
                            __m256 lcf, uint8_t* out, uint8_t* seen) {
  const __m256 abs = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  const __m256 c = _mm256_loadu_ps(lc + x + 2), l = _mm256_loadu_ps(lc + x + 1), t = _mm256_loadu_ps(lt + x + 2);
  const __m256 dx = _mm256_and_ps(_mm256_sub_ps(c, l), abs), dy = _mm256_and_ps(_mm256_sub_ps(c, t), abs);
  const __m256 ex = _mm256_cmp_ps(dx, thr, _CMP_GE_OQ), ey = _mm256_cmp_ps(dy, thr, _CMP_GE_OQ);
  const int m = _mm256_movemask_ps(_mm256_or_ps(ex, ey));
  uint64_t bytes = 0;
  if (m != 0) {
    const __m256 dr = _mm256_and_ps(_mm256_sub_ps(c, _mm256_loadu_ps(lc + x + 3)), abs);
    const __m256 db = _mm256_and_ps(_mm256_sub_ps(c, _mm256_loadu_ps(lb + x + 2)), abs);
    const __m256 dll = _mm256_and_ps(_mm256_sub_ps(l, _mm256_loadu_ps(lc + x)), abs);
    const __m256 dtt = _mm256_and_ps(_mm256_sub_ps(t, _mm256_loadu_ps(ltt + x + 2)), abs);
    const __m256 fin =
        _mm256_max_ps(_mm256_max_ps(_mm256_max_ps(dx, dr), dll), _mm256_max_ps(_mm256_max_ps(dy, db), dtt));
    const int bx = _mm256_movemask_ps(_mm256_and_ps(ex, _mm256_cmp_ps(_mm256_mul_ps(lcf, dx), fin, _CMP_GE_OQ)));
    const int by = _mm256_movemask_ps(_mm256_and_ps(ey, _mm256_cmp_ps(_mm256_mul_ps(lcf, dy), fin, _CMP_GE_OQ)));
    const Spread& s = Spreads();
    bytes = s.v[bx] | s.v[by] << 1;
    *seen |= static_cast<uint8_t>(bx | by);
  }
  std::memcpy(out + x, &bytes, 8);
  return __builtin_popcount(static_cast<unsigned>(m));
}

AALAB_AVX2 int EdgeRowLumaAvx2(const float* lc, const float* lt, const float* ltt, const float* lb, int w, float thr,
                               float lcf, uint8_t* out, uint8_t* seen, int* kept) {
  const __m256 vt = _mm256_set1_ps(thr), vl = _mm256_set1_ps(lcf);
  int x = 0;
  for (; x + 8 <= w; x += 8) *kept += Edge8(lc, lt, ltt, lb, x, vt, vl, out, seen);
  return x;
}
#endif
}  // namespace

int EdgeRowLuma(const float* lc, const float* lt, const float* ltt, const float* lb, int w, float thr, float lcf,
                uint8_t* out, uint8_t* any) {
  int kept = 0, x = 0;
  uint8_t seen = 0;
#if defined(AALAB_SMAA_ROWS_AVX2)
  if (HasAvx2()) x = EdgeRowLumaAvx2(lc, lt, ltt, lb, w, thr, lcf, out, &seen, &kept);
#endif
#if defined(__SSE2__)
  const __m128 vt = _mm_set1_ps(thr), vl = _mm_set1_ps(lcf);
  for (; x + 4 <= w; x += 4) kept += Edge4(lc, lt, ltt, lb, x, vt, vl, out, &seen);
#endif
  *any = seen;
  return kept + EdgeRowLumaFrom(lc, lt, ltt, lb, x, w, thr, lcf, out, any);
}

int EdgeRowLumaScalar(const float* lc, const float* lt, const float* ltt, const float* lb, int w, float thr, float lcf,
                      uint8_t* out, uint8_t* any) {
  *any = 0;
  return EdgeRowLumaFrom(lc, lt, ltt, lb, 0, w, thr, lcf, out, any);
}

int ListNonZero(const uint8_t* row, int w, uint16_t* xs) {
  int n = 0, x = 0;
#if defined(__SSE2__)
  const __m128i zero = _mm_setzero_si128();
  for (; x + 16 <= w; x += 16) {
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + x));
    unsigned m = ~static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, zero))) & 0xFFFFu;
    while (m != 0) {
      xs[n++] = static_cast<uint16_t>(x + __builtin_ctz(m));
      m &= m - 1;
    }
  }
#endif
  for (; x < w; ++x) {
    if (row[x] != 0) xs[n++] = static_cast<uint16_t>(x);
  }
  return n;
}

}  // namespace aalab::smaa_internal
