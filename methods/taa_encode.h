/// TAA's output encode (methods/taa.cpp): QuantizeUnorm8(SrgbEncode(v)) by a table search
/// instead of a pow per value, scalar and four pixels at a time with SSE2; its table for the
/// AVX2 and AVX-512 kernels (methods/taa_avx2.h EncodeTables). taa.h's EncodeSrgb8 and
/// EncodeSrgb8Rgba are its public face, tests/motion/taa_test.cpp checks them.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/color.h"
#include "core/error.h"
#include "methods/taa_avx2.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace aalab::taa_detail {

/// QuantizeUnorm8(SrgbEncode(v)) for v in [0, 1], bit for bit, without a pow per channel:
/// the function is non-decreasing in v, so code k starts at the smallest float where it is
/// reached; those 255 thresholds are found by bisection over the float bit patterns of
/// [0, 1] (ordered like the values). A lookup takes a first guess from the value's high 16
/// bits (exponent and 8 mantissa bits: the code of the smallest float with those bits, a
/// lower bound) and adds the number of the next two thresholds the value reaches (no branch;
/// the constructor checks that no bucket spans more than two). tests/motion/taa_test.cpp
/// checks it against the direct formula on a dense grid.
class Encode8 {
 public:
  Encode8() {
    for (int k = 1; k < 256; ++k) {
      uint32_t lo = 0, hi = 0x3f800000u;  // bit patterns of 0.0f and 1.0f
      while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (Direct(FromBits(mid)) >= k) {
          hi = mid;
        } else {
          lo = mid + 1;
        }
      }
      start_[static_cast<size_t>(k - 1)] = FromBits(lo);
    }
    // A first guess per bucket of float bit patterns (the high 16 bits): the code of the
    // bucket's smallest float (a lower bound for every value in it, the function being
    // non-decreasing). Buckets hold at most 2^16 ulps: under one code step above 1/64 and
    // far less below (the linear segment's 12.92·255 codes per unit meets ulps of 1e-10).
    for (uint32_t b = 0; b < kBuckets; ++b) {
      const float v = FromBits(b << kShift);
      guess_[b] = static_cast<uint8_t>(std::upper_bound(start_.begin(), start_.begin() + 255, v) - start_.begin());
    }
    // The lookup's fixed number of steps (no data-dependent branch): enough for every bucket,
    // checked here over each bucket's largest float (the code is non-decreasing in v).
    start_[255] = start_[256] = std::numeric_limits<float>::infinity();  // code 255 never steps further
    for (uint32_t b = 0; b < kBuckets; ++b) {
      const float last = FromBits(std::min((b << kShift) | ((1u << kShift) - 1), 0x3f800000u));
      const auto code = std::upper_bound(start_.begin(), start_.begin() + 255, last) - start_.begin();
      AALAB_CHECK(code - guess_[b] <= kSteps, "Encode8: a bucket needs more than kSteps steps");
    }
    // The same lookup in one 32-bit entry per bucket for the AVX2 and AVX-512 kernels: the
    // guess g and where start_[g] lies inside the bucket, as the low 16 bits of its pattern
    // (non-negative floats are ordered like their bit patterns, so v ≥ start_[g] exactly when
    // v's low 16 bits reach them); 65536 where it lies in a later bucket (never reached;
    // start_[g] is never the bucket's first float, whose code is g). One threshold per
    // bucket is enough: start_[g + 1] never lies inside (checked; above 1/64 a bucket spans
    // under one code step, below it far less).
    for (uint32_t b = 0; b < kBuckets; ++b) {
      const unsigned g = guess_[b];
      auto inside = [&](float t) -> uint32_t {
        uint32_t tb;
        std::memcpy(&tb, &t, sizeof tb);
        return (tb >> kShift) == b ? (tb & 0xffffu) : 0x10000u;
      };
      AALAB_CHECK(inside(start_[g + 1]) == 0x10000u, "Encode8: a bucket holds two code thresholds");
      packed_[b] = g | (inside(start_[g]) << 8);
    }
  }
  /// v in [0, 1] (NaN excluded; -0 reads as 0); step up from the guess to the exact code.
  uint8_t operator()(float v) const {
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    bits &= 0x7fffffffu;  // -0 → +0 (every other input is non-negative)
    const unsigned g = guess_[std::min(bits >> kShift, kBuckets - 1)];
    // start_ increases, so reaching start_[g + 1] implies reaching start_[g]: the two loads
    // do not wait for each other's comparison.
    return static_cast<uint8_t>(g + (v >= start_[g] ? 1u : 0u) + (v >= start_[g + 1] ? 1u : 0u));
  }
  /// w pixels of planar linear RGB (each in [0, 1]) to RGBA8 (alpha 255): operator() per
  /// value; with AVX2 eight pixels at a time (taa_avx2.cpp, gathers for the table reads);
  /// with SSE2 four at a time (the bucket, the comparisons and the packing in vectors, the
  /// three table reads per value scalar: SSE2 has no gather).
  void Rgba(const float* r, const float* g, const float* b, int w, uint8_t* out) const {
    int x = EncodeRgbaAvx2(Tables(), r, g, b, w, out);
#if defined(__SSE2__)
    const __m128i abs = _mm_set1_epi32(0x7fffffff), last = _mm_set1_epi32(static_cast<int>(kBuckets - 1));
    auto codes = [&](const float* p) {
      const __m128 v = _mm_loadu_ps(p);
      __m128i i = _mm_srli_epi32(_mm_and_si128(_mm_castps_si128(v), abs), kShift);
      const __m128i over = _mm_cmpgt_epi32(i, last);
      i = _mm_or_si128(_mm_and_si128(over, last), _mm_andnot_si128(over, i));  // min(i, kBuckets − 1)
      const unsigned g0 = guess_[static_cast<unsigned>(_mm_cvtsi128_si32(i))],
                     g1 = guess_[static_cast<unsigned>(_mm_extract_epi16(i, 2))],
                     g2 = guess_[static_cast<unsigned>(_mm_extract_epi16(i, 4))],
                     g3 = guess_[static_cast<unsigned>(_mm_extract_epi16(i, 6))];
      const __m128 t1 = _mm_setr_ps(start_[g0], start_[g1], start_[g2], start_[g3]);
      const __m128 t2 = _mm_setr_ps(start_[g0 + 1], start_[g1 + 1], start_[g2 + 1], start_[g3 + 1]);
      const __m128i gv =
          _mm_setr_epi32(static_cast<int>(g0), static_cast<int>(g1), static_cast<int>(g2), static_cast<int>(g3));
      // A true comparison is −1 as an integer: subtracting adds one step.
      return _mm_sub_epi32(_mm_sub_epi32(gv, _mm_castps_si128(_mm_cmpge_ps(v, t1))),
                           _mm_castps_si128(_mm_cmpge_ps(v, t2)));
    };
    const __m128i alpha = _mm_set1_epi32(static_cast<int>(0xff000000u));
    for (; x + 4 <= w; x += 4) {
      // Little-endian x86: byte k of each 32-bit lane is channel k.
      const __m128i px = _mm_or_si128(_mm_or_si128(codes(r + x), _mm_slli_epi32(codes(g + x), 8)),
                                      _mm_or_si128(_mm_slli_epi32(codes(b + x), 16), alpha));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 4 * x), px);
    }
#endif
    for (; x < w; ++x) {
      const uint8_t px[4] = {(*this)(r[x]), (*this)(g[x]), (*this)(b[x]), 255};
      std::memcpy(out + 4 * x, px, 4);
    }
  }
  static int Direct(float v) { return QuantizeUnorm8(SrgbEncode(v)); }
  /// The tables, for the AVX2 kernels' gathers.
  EncodeTables Tables() const { return {packed_.data()}; }

 private:
  static float FromBits(uint32_t b) {
    float f;
    std::memcpy(&f, &b, sizeof f);
    return f;
  }
  static constexpr uint32_t kShift = kEncodeShift;
  static constexpr uint32_t kBuckets = kEncodeBuckets;  // up to 1.0f
  static constexpr int kSteps = 2;                      ///< thresholds a bucket may span (operator() compares with two)
  /// start_[k − 1]: the smallest float whose code is ≥ k; start_[255], start_[256] = +inf
  std::array<float, 257> start_{};
  std::array<uint8_t, kBuckets> guess_{};
  /// Per bucket: guess_ (bits 0..7), start_[g]'s low 16 bits inside the bucket (bits 8..24;
  /// 65536: not inside)
  std::array<uint32_t, kBuckets> packed_{};
};

/// The one encoder (its tables are built on first use).
inline const Encode8& Encoder() {
  static const Encode8 e;
  return e;
}

}  // namespace aalab::taa_detail
