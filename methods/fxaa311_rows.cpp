// FXAA 3.11's luma plane rows (methods/fxaa311_rows.h), for the production path in
// methods/fxaa311_fast.cpp.
//
// The plane holds, per pixel, the luma the shader reads (the pre-pass's stored alpha, or the
// green byte, or the float dot for rec601-rgb). PlaneRow8 computes it in SSE2, four pixels
// per vector (eight with AVX2 where the CPU has it, chosen at run time: rec601 and
// sqrt-luminance, whose tables are then read by gathers; rec601 sixteen with AVX-512F), with
// the scalar expressions' IEEE
// float32 operations in the same order:
//   rec601:         u = k·fl(1/255) per channel; s = u_r·0.299 + (u_g·0.587 + u_b·0.114)
//   sqrt-luminance: s = sqrt((d_r·0.2126729 + d_g·0.7151522) + d_b·0.0721750), d = SrgbDecode8
//                   (a table per channel, read lane by lane: SSE2 has no gather)
//   stored:         StoreUnorm8(s) = clamp(nearbyint(s·255), 0, 255), nearbyint as
//                   (w + 2^23) − 2^23 in the default rounding mode.
// SSE2/AVX2/AVX-512 add, mul, sqrt and int↔float conversions are IEEE-correctly rounded like their scalar
// forms, and the build neither contracts nor reassociates (-ffp-contract=off, no fast-math),
// so every lane equals the scalar result; tests/methods/fxaa311_rows_test.cpp checks all
// 2^24 colours against the pre-pass (Fxaa311LumaFrame), with row lengths that reach the
// AVX2 blocks (32 pixels), the SSE2 and AVX-512 blocks (16) and the scalar tail, for each
// instruction set the CPU has (SetPlaneRow8IsaCap). The clamp's max/min equal
// StoreUnorm8's two guards for every s the dots produce (s is never NaN; s ≤ 0 gives 0,
// s ≥ 1 gives w ≥ 255).
#include "methods/fxaa311_rows.h"

#include <atomic>
#include <cmath>

#include "core/color.h"
#include "core/sampler.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#include <immintrin.h>
#define AALAB_FXAA311_AVX2 1
#endif

namespace aalab::fxaa311_internal {

namespace {
using Luma = Fxaa311Params::Luma;

// Per-channel products of the luma dot, one table per weight: entry k is the product the
// pre-pass computes for channel value k (UnormToFloat(k)·w, or SrgbDecode8(k)·w).
struct LumaTables {
  float r[256], g[256], b[256];
};

const LumaTables& SqrtLuminanceTables() {
  static const LumaTables t = [] {
    LumaTables x{};
    for (int k = 0; k < 256; ++k) {
      x.r[k] = SrgbDecode8(static_cast<uint8_t>(k)) * 0.2126729f;
      x.g[k] = SrgbDecode8(static_cast<uint8_t>(k)) * 0.7151522f;
      x.b[k] = SrgbDecode8(static_cast<uint8_t>(k)) * 0.0721750f;
    }
    return x;
  }();
  return t;
}

const LumaTables& Rec601Tables() {
  static const LumaTables t = [] {
    LumaTables x{};
    for (int k = 0; k < 256; ++k) {
      const float u = UnormToFloat(static_cast<uint8_t>(k));
      x.r[k] = u * 0.299f;
      x.g[k] = u * 0.587f;
      x.b[k] = u * 0.114f;
    }
    return x;
  }();
  return t;
}

#if defined(__SSE2__)
// StoreUnorm8 of four floats in [0, ~1], as int32 lanes.
inline __m128i StoreUnorm8x4(__m128 s) {
  const __m128 big = _mm_set1_ps(8388608.0f);
  __m128 w = _mm_mul_ps(s, _mm_set1_ps(255.0f));
  w = _mm_sub_ps(_mm_add_ps(w, big), big);
  w = _mm_min_ps(_mm_max_ps(w, _mm_setzero_ps()), _mm_set1_ps(255.0f));
  return _mm_cvttps_epi32(w);
}

// Channel c (0 = r, 1 = g, 2 = b) of four RGBA8 pixels, as int32 lanes.
inline __m128i Channel(__m128i px, int c) {
  const __m128i m = _mm_set1_epi32(0xff);
  if (c == 0) return _mm_and_si128(px, m);
  if (c == 1) return _mm_and_si128(_mm_srli_epi32(px, 8), m);
  return _mm_and_si128(_mm_srli_epi32(px, 16), m);
}

inline __m128i Rec601x4(__m128i px) {
  const __m128 k = _mm_set1_ps(1.0f / 255.0f);
  const __m128 r = _mm_mul_ps(_mm_cvtepi32_ps(Channel(px, 0)), k);
  const __m128 g = _mm_mul_ps(_mm_cvtepi32_ps(Channel(px, 1)), k);
  const __m128 b = _mm_mul_ps(_mm_cvtepi32_ps(Channel(px, 2)), k);
  const __m128 s = _mm_add_ps(_mm_mul_ps(r, _mm_set1_ps(0.299f)),
                              _mm_add_ps(_mm_mul_ps(g, _mm_set1_ps(0.587f)), _mm_mul_ps(b, _mm_set1_ps(0.114f))));
  return StoreUnorm8x4(s);
}

inline __m128i SqrtLuminancex4(const uint8_t* p, const LumaTables& t) {
  const __m128 r = _mm_setr_ps(t.r[p[0]], t.r[p[4]], t.r[p[8]], t.r[p[12]]);
  const __m128 g = _mm_setr_ps(t.g[p[1]], t.g[p[5]], t.g[p[9]], t.g[p[13]]);
  const __m128 b = _mm_setr_ps(t.b[p[2]], t.b[p[6]], t.b[p[10]], t.b[p[14]]);
  return StoreUnorm8x4(_mm_sqrt_ps(_mm_add_ps(_mm_add_ps(r, g), b)));
}

// 16 lumas (four vectors of four int32 in [0, 255]) packed into 16 bytes at o.
inline void Store16(__m128i a, __m128i b, __m128i c, __m128i d, uint8_t* o) {
  _mm_storeu_si128(reinterpret_cast<__m128i*>(o), _mm_packus_epi16(_mm_packs_epi32(a, b), _mm_packs_epi32(c, d)));
}

inline __m128i Load4(const uint8_t* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); }
#endif

#if defined(AALAB_FXAA311_AVX2)
// The same lanes eight at a time, for CPUs with AVX2 (chosen at run time, PlaneRow8).
#define AALAB_AVX2 __attribute__((target("avx2")))
AALAB_AVX2 inline __m256i StoreUnorm8x8(__m256 s) {
  const __m256 big = _mm256_set1_ps(8388608.0f);
  __m256 w = _mm256_mul_ps(s, _mm256_set1_ps(255.0f));
  w = _mm256_sub_ps(_mm256_add_ps(w, big), big);
  w = _mm256_min_ps(_mm256_max_ps(w, _mm256_setzero_ps()), _mm256_set1_ps(255.0f));
  return _mm256_cvttps_epi32(w);
}

AALAB_AVX2 inline __m256i Channel8(__m256i px, int c) {
  const __m256i m = _mm256_set1_epi32(0xff);
  if (c == 0) return _mm256_and_si256(px, m);
  if (c == 1) return _mm256_and_si256(_mm256_srli_epi32(px, 8), m);
  return _mm256_and_si256(_mm256_srli_epi32(px, 16), m);
}

AALAB_AVX2 inline __m256i Rec601x8(const uint8_t* p) {
  const __m256i px = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
  const __m256 k = _mm256_set1_ps(1.0f / 255.0f);
  const __m256 r = _mm256_mul_ps(_mm256_cvtepi32_ps(Channel8(px, 0)), k);
  const __m256 g = _mm256_mul_ps(_mm256_cvtepi32_ps(Channel8(px, 1)), k);
  const __m256 b = _mm256_mul_ps(_mm256_cvtepi32_ps(Channel8(px, 2)), k);
  const __m256 s =
      _mm256_add_ps(_mm256_mul_ps(r, _mm256_set1_ps(0.299f)),
                    _mm256_add_ps(_mm256_mul_ps(g, _mm256_set1_ps(0.587f)), _mm256_mul_ps(b, _mm256_set1_ps(0.114f))));
  return StoreUnorm8x8(s);
}

AALAB_AVX2 inline __m256i SqrtLuminancex8(const uint8_t* p, const LumaTables& t) {
  const __m256i px = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
  const __m256 r = _mm256_i32gather_ps(t.r, Channel8(px, 0), 4);
  const __m256 g = _mm256_i32gather_ps(t.g, Channel8(px, 1), 4);
  const __m256 b = _mm256_i32gather_ps(t.b, Channel8(px, 2), 4);
  return StoreUnorm8x8(_mm256_sqrt_ps(_mm256_add_ps(_mm256_add_ps(r, g), b)));
}

// 32 lumas (four vectors of eight int32 in [0, 255]) packed in order into 32 bytes at o.
AALAB_AVX2 inline void Store32(__m256i a, __m256i b, __m256i c, __m256i d, uint8_t* o) {
  // packs/packus work within 128-bit halves: bytes come out as a0-3 b0-3 c0-3 d0-3 | a4-7 ...
  const __m256i v = _mm256_packus_epi16(_mm256_packs_epi32(a, b), _mm256_packs_epi32(c, d));
  const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(o), _mm256_permutevar8x32_epi32(v, order));
}

// The vector part of PlaneRow8 with AVX2: returns the number of pixels done (a multiple of 32).
AALAB_AVX2 int PlaneRow8Avx2(const uint8_t* p, int w, Luma luma, uint8_t* o) {
  int x = 0;
  if (luma == Luma::kRec601) {
    for (; x + 32 <= w; x += 32) {
      const uint8_t* q = p + 4 * x;
      Store32(Rec601x8(q), Rec601x8(q + 32), Rec601x8(q + 64), Rec601x8(q + 96), o + x);
    }
  } else if (luma == Luma::kSqrtLuminance) {
    const LumaTables& sq = SqrtLuminanceTables();
    for (; x + 32 <= w; x += 32) {
      const uint8_t* q = p + 4 * x;
      Store32(SqrtLuminancex8(q, sq), SqrtLuminancex8(q + 32, sq), SqrtLuminancex8(q + 64, sq),
              SqrtLuminancex8(q + 96, sq), o + x);
    }
  }
  return x;
}

bool HasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

// rec601 sixteen pixels at a time, for CPUs with AVX-512F (chosen at run time, PlaneRow8): the
// same lane operations as Rec601x8; the lumas, clamped to [0, 255], narrow to bytes exactly
// (vpmovusdb).
// (GCC 12's AVX-512 intrinsics start some results from _mm512_undefined_*, which
// -Wmaybe-uninitialized reports once inlined; the lanes are all written.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#define AALAB_AVX512 __attribute__((target("avx512f")))
AALAB_AVX512 inline __m128i Rec601x16(const uint8_t* p) {
  const __m512i px = _mm512_loadu_si512(p);
  const __m512i m = _mm512_set1_epi32(0xff);
  const __m512 k = _mm512_set1_ps(1.0f / 255.0f);
  const __m512 r = _mm512_mul_ps(_mm512_cvtepi32_ps(_mm512_and_si512(px, m)), k);
  const __m512 g = _mm512_mul_ps(_mm512_cvtepi32_ps(_mm512_and_si512(_mm512_srli_epi32(px, 8), m)), k);
  const __m512 b = _mm512_mul_ps(_mm512_cvtepi32_ps(_mm512_and_si512(_mm512_srli_epi32(px, 16), m)), k);
  const __m512 s =
      _mm512_add_ps(_mm512_mul_ps(r, _mm512_set1_ps(0.299f)),
                    _mm512_add_ps(_mm512_mul_ps(g, _mm512_set1_ps(0.587f)), _mm512_mul_ps(b, _mm512_set1_ps(0.114f))));
  const __m512 big = _mm512_set1_ps(8388608.0f);
  __m512 w = _mm512_mul_ps(s, _mm512_set1_ps(255.0f));
  w = _mm512_sub_ps(_mm512_add_ps(w, big), big);
  w = _mm512_min_ps(_mm512_max_ps(w, _mm512_setzero_ps()), _mm512_set1_ps(255.0f));
  return _mm512_cvtusepi32_epi8(_mm512_cvttps_epi32(w));
}

// The vector part of PlaneRow8 for rec601 with AVX-512F: returns the pixels done (a multiple
// of 16).
AALAB_AVX512 int PlaneRow8Rec601Avx512(const uint8_t* p, int w, uint8_t* o) {
  int x = 0;
  for (; x + 16 <= w; x += 16) _mm_storeu_si128(reinterpret_cast<__m128i*>(o + x), Rec601x16(p + 4 * x));
  return x;
}

#pragma GCC diagnostic pop

bool HasAvx512() {
  static const bool has = __builtin_cpu_supports("avx512f");
  return has;
}
#endif
}  // namespace

namespace {
std::atomic<PlaneIsa> g_isa_cap{PlaneIsa::kAvx512};
}  // namespace

void SetPlaneRow8IsaCap(PlaneIsa cap) { g_isa_cap.store(cap, std::memory_order_relaxed); }

void PlaneRow8Scalar(const uint8_t* p, int w, Luma luma, uint8_t* o) {
  if (luma == Luma::kGreen) {
    for (int x = 0; x < w; ++x) o[x] = p[4 * x + 1];
  } else if (luma == Luma::kRec601) {
    // Fxaa311LumaFrame: StoreUnorm8(r·0.299 + (g·0.587 + b·0.114)), r = UnormToFloat.
    const LumaTables& rec = Rec601Tables();
    for (int x = 0; x < w; ++x) {
      o[x] = StoreUnorm8(rec.r[p[4 * x]] + (rec.g[p[4 * x + 1]] + rec.b[p[4 * x + 2]]));
    }
  } else {  // kSqrtLuminance: StoreUnorm8(sqrt((R·0.2126729 + G·0.7151522) + B·0.0721750))
    const LumaTables& sq = SqrtLuminanceTables();
    for (int x = 0; x < w; ++x) {
      o[x] = StoreUnorm8(std::sqrt((sq.r[p[4 * x]] + sq.g[p[4 * x + 1]]) + sq.b[p[4 * x + 2]]));
    }
  }
}

void PlaneRow8(const uint8_t* p, int w, Luma luma, uint8_t* o) {
  int x = 0;
#if defined(AALAB_FXAA311_AVX2)
  const PlaneIsa cap = g_isa_cap.load(std::memory_order_relaxed);
  if (luma == Luma::kRec601 && cap >= PlaneIsa::kAvx512 && HasAvx512()) {
    x = PlaneRow8Rec601Avx512(p, w, o);
  } else if (cap >= PlaneIsa::kAvx2 && HasAvx2()) {
    x = PlaneRow8Avx2(p, w, luma, o);
  }
#endif
#if defined(__SSE2__)
  if (luma == Luma::kRec601) {
    for (; x + 16 <= w; x += 16) {
      const uint8_t* q = p + 4 * x;
      Store16(Rec601x4(Load4(q)), Rec601x4(Load4(q + 16)), Rec601x4(Load4(q + 32)), Rec601x4(Load4(q + 48)), o + x);
    }
  } else if (luma == Luma::kGreen) {
    for (; x + 16 <= w; x += 16) {
      const uint8_t* q = p + 4 * x;
      Store16(Channel(Load4(q), 1), Channel(Load4(q + 16), 1), Channel(Load4(q + 32), 1), Channel(Load4(q + 48), 1),
              o + x);
    }
  } else {
    const LumaTables& sq = SqrtLuminanceTables();
    for (; x + 16 <= w; x += 16) {
      const uint8_t* q = p + 4 * x;
      Store16(SqrtLuminancex4(q, sq), SqrtLuminancex4(q + 16, sq), SqrtLuminancex4(q + 32, sq),
              SqrtLuminancex4(q + 48, sq), o + x);
    }
  }
#endif
  PlaneRow8Scalar(p + 4 * x, w - x, luma, o + x);
}

void PlaneRowF(const uint8_t* p, int w, float* o) {
  for (int x = 0; x < w; ++x) {
    const float r = UnormToFloat(p[4 * x]), g = UnormToFloat(p[4 * x + 1]), b = UnormToFloat(p[4 * x + 2]);
    o[x] = r * 0.299f + (g * 0.587f + b * 0.114f);  // Fxaa311TapLuma(kRec601Rgb)
  }
}

}  // namespace aalab::fxaa311_internal
