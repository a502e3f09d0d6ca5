// SMAA 1x production path internals shared by methods/smaa_fast.cpp (pass 1, the unfused
// passes 2 and 3, debug views) and methods/smaa_fused.cpp (passes 2 and 3 fused): the edge
// plane and the inline samplers. Not part of the methods API; see the block at the top of
// methods/smaa_fast.cpp.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "core/sampler.h"
#include "methods/smaa.h"
#include "methods/smaa_rows.h"
#include "methods/smaa_shader.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace aalab::smaa_internal {

using smaa_detail::F2;

/// Frames up to this size a side take the shortcuts of 8-bit sub-texel fetches.
constexpr int kMaxShortcutSize = 8192;
constexpr uint8_t kLeft = 1;  ///< edge-plane bits: r (left edge) and g (top edge)
constexpr uint8_t kTop = 2;

// The edge texture as one byte per pixel (bit 0 = r, bit 1 = g), plus one flag per row
// (any edge in the row). The bytes are allocated uninitialised: the parallel pass that
// fills a row clears it first (no serial zero-fill of the whole plane).
// With `xs`, each row's edge pixels are also listed (columns ascending, in xs at offset
// y·w, count in n[y]): the fused weight and blend pass visits only those.
struct EdgePlane {
  int w = 0, h = 0;
  std::unique_ptr<uint8_t[]> e;
  std::vector<uint8_t> row_any;
  std::unique_ptr<uint16_t[]> xs;  // uninitialised; only each row's first n[y] entries are written
  std::vector<int> n;
  void ListRow(int y, bool any) {
    if (!xs) return;
    n[static_cast<size_t>(y)] = any ? smaa_internal::ListNonZero(Row(y), w, List(y)) : 0;
  }
  uint16_t* List(int y) { return xs.get() + static_cast<size_t>(y) * w; }
  const uint16_t* List(int y) const { return xs.get() + static_cast<size_t>(y) * w; }
  const uint8_t* Row(int y) const { return e.get() + static_cast<size_t>(y) * w; }
  uint8_t* Row(int y) { return e.get() + static_cast<size_t>(y) * w; }
};

#if defined(__SSE2__)
/// BilinearAt(u, v, w, h, SubTexel::kFixed8) from one rounding per axis: with
/// x = fl(u − 0.5), x·256 is exact and, where BilinearAt's frac = x − floor(x) is exact,
/// nearbyint(x·256) = floor(x)·256 + nearbyint(frac·256) (adding a multiple of 256, an even
/// integer, commutes with the rounding), so its bits above the low 8 are BilinearAt's x0
/// after the wrap of a fraction that rounds to 1 and its low 8 bits the numerator of the
/// 8-bit fraction. frac is exact except for x in (−1, 0) (1 − |x| rounds): there both read
/// column 0 alone, each with x0 = −1 (both columns clamp to 0; a lerp between equal values
/// returns them, whatever fx) or, after a wrap, x0 = 0 and fx = 0 (a + 0·(b − a) = a). So
/// the footprints read the same texels with the same weights
/// (tests/methods/smaa_fetch_test.cpp): the same fetched values.
/// cvtps2dq rounds in the current mode, as nearbyint does. For |u|, |v| < 2^22 (SMAA's
/// coordinates stay within a few hundred texels of a frame or texture).
/// BilinearAt8's rounding kept in registers: x0 and y0 before BilinearAt8's clamp to [−1, w]
/// and [−1, h], the 8-bit fractions fx and fy in every lane (for the fetches that read their
/// four texels themselves, InlineSampler's and PlaneEdges' Sample8).
struct Footprint8 {
  int x0, y0;
  __m128 fx, fy;
};
[[gnu::always_inline]] inline Footprint8 Round8(float u, float v) {
  const __m128 x = _mm_sub_ps(_mm_setr_ps(u, v, 0.0f, 0.0f), _mm_set1_ps(0.5f));
  const __m128i t = _mm_cvtps_epi32(_mm_mul_ps(x, _mm_set1_ps(256.0f)));
  const __m128 fr = _mm_mul_ps(_mm_cvtepi32_ps(_mm_and_si128(t, _mm_set1_epi32(255))), _mm_set1_ps(1.0f / 256.0f));
  const __m128i i0 = _mm_srai_epi32(t, 8);
  return {_mm_cvtsi128_si32(i0), _mm_cvtsi128_si32(_mm_shuffle_epi32(i0, 1)), _mm_shuffle_ps(fr, fr, 0x00),
          _mm_shuffle_ps(fr, fr, 0x55)};
}

[[gnu::always_inline]] inline BilinearFootprint BilinearAt8(float u, float v, int w, int h) {
  const Footprint8 r = Round8(u, v);
  BilinearFootprint f;
  f.fx = _mm_cvtss_f32(r.fx);
  f.fy = _mm_cvtss_f32(r.fy);
  f.x0 = std::clamp(r.x0, -1, w);
  f.y0 = std::clamp(r.y0, -1, h);
  return f;
}

/// BilinearBlend in every lane: FilterLerp's a + w·(b − a) along x on both rows, then along y.
[[gnu::always_inline]] inline __m128 Blend4(__m128 ta, __m128 tb, __m128 tc, __m128 td, __m128 fx, __m128 fy) {
  const __m128 top = _mm_add_ps(ta, _mm_mul_ps(fx, _mm_sub_ps(tb, ta)));
  const __m128 bot = _mm_add_ps(tc, _mm_mul_ps(fx, _mm_sub_ps(td, tc)));
  return _mm_add_ps(top, _mm_mul_ps(fy, _mm_sub_ps(bot, top)));
}
#endif

/// BilinearAt for the samplers below: BilinearAt8 for 8-bit fractions (same fetched values).
[[gnu::always_inline]] inline BilinearFootprint FootprintAt(float u, float v, int w, int h, SubTexel mode) {
#if defined(__SSE2__)
  if (mode == SubTexel::kFixed8) return BilinearAt8(u, v, w, h);
#endif
  return BilinearAt(u, v, w, h, mode);
}

// BilinearSampler::SampleNormalized, operation for operation (BilinearAt, clamped reads,
// UnormToFloat, BilinearBlend), inline and with its own tap counter.
// An RGBA8 texture: the fast path's own buffers and Image8 alike.
struct Tex8 {
  const uint8_t* data = nullptr;
  int w = 0, h = 0;
  explicit Tex8(const Image8& img) : data(img.Data().data()), w(img.Width()), h(img.Height()) {
    AALAB_CHECK(img.Channels() == 4, "SMAA textures are RGBA8");
  }
  Tex8(const uint8_t* d, int width, int height) : data(d), w(width), h(height) {}
  const uint8_t* Pixel(int x, int y) const { return data + 4 * (static_cast<size_t>(y) * w + x); }
  const uint8_t* Row(int y) const { return Pixel(0, y); }
};

class InlineSampler {
 public:
  InlineSampler(Tex8 img, SubTexel mode) : img_(img), w_(img.w), h_(img.h), mode_(mode) {}
  [[gnu::always_inline]] Float4 SampleNormalized(float s, float t) {
    ++taps_;
#if defined(__SSE2__)
    if (mode_ == SubTexel::kFixed8) return Sample8(s * static_cast<float>(w_), t * static_cast<float>(h_));
#endif
    const BilinearFootprint f = FootprintAt(s * static_cast<float>(w_), t * static_cast<float>(h_), w_, h_, mode_);
    const int xa = std::clamp(f.x0, 0, w_ - 1), xb = std::clamp(f.x0 + 1, 0, w_ - 1);
    const int ya = std::clamp(f.y0, 0, h_ - 1), yb = std::clamp(f.y0 + 1, 0, h_ - 1);
    const uint8_t* a = img_.Pixel(xa, ya);
    const uint8_t* b = img_.Pixel(xb, ya);
    const uint8_t* c = img_.Pixel(xa, yb);
    const uint8_t* d = img_.Pixel(xb, yb);
    Float4 r;
#if defined(__SSE2__)
    // The four channels' BilinearBlend in the lanes of one vector: per lane the same
    // operations (k·fl(1/255), then FilterLerp's a + w·(b − a) three times), so the same bits.
    float v[4];
    _mm_storeu_ps(v, Blend4(U4(a), U4(b), U4(c), U4(d), _mm_set1_ps(f.fx), _mm_set1_ps(f.fy)));
    r = {v[0], v[1], v[2], v[3]};
#else
    r.r = BilinearBlend(U(a[0]), U(b[0]), U(c[0]), U(d[0]), f);
    r.g = BilinearBlend(U(a[1]), U(b[1]), U(c[1]), U(d[1]), f);
    r.b = BilinearBlend(U(a[2]), U(b[2]), U(c[2]), U(d[2]), f);
    r.a = BilinearBlend(U(a[3]), U(b[3]), U(c[3]), U(d[3]), f);
#endif
    return r;
  }
  uint64_t Taps() const { return taps_; }
  void CountTap() { ++taps_; }  // a fetch MemoSampler answered from its table
  const Tex8& Texture() const { return img_; }
  SubTexel Mode() const { return mode_; }

 private:
  static float U(uint8_t k) { return UnormToFloat(k); }  // BilinearSampler::Fetch
#if defined(__SSE2__)
  // SampleNormalized for 8-bit fractions: BilinearAt8's rounding (the same x0, y0, fx, fy);
  // inside the texture (0 <= x0 < w − 1, 0 <= y0 < h − 1) no clamp moves the footprint, so
  // the four texels are read from one address, else clamped as SampleNormalized (clamping x0
  // to [−1, w] first changes no clamped column). The same texels and lerps: the same bits.
  [[gnu::always_inline]] Float4 Sample8(float u, float v) {
    const Footprint8 f = Round8(u, v);
    const int x0 = f.x0, y0 = f.y0;
    const uint8_t *a, *b, *c, *d;
    if (static_cast<unsigned>(x0) < static_cast<unsigned>(w_ - 1) &&
        static_cast<unsigned>(y0) < static_cast<unsigned>(h_ - 1)) {
      a = img_.Pixel(x0, y0), b = a + 4, c = a + 4 * static_cast<size_t>(w_), d = c + 4;
    } else {
      const int xa = std::clamp(x0, 0, w_ - 1), xb = std::clamp(x0 + 1, 0, w_ - 1);
      const int ya = std::clamp(y0, 0, h_ - 1), yb = std::clamp(y0 + 1, 0, h_ - 1);
      a = img_.Pixel(xa, ya), b = img_.Pixel(xb, ya), c = img_.Pixel(xa, yb), d = img_.Pixel(xb, yb);
    }
    float r[4];
    _mm_storeu_ps(r, Blend4(U4(a), U4(b), U4(c), U4(d), f.fx, f.fy));
    return {r[0], r[1], r[2], r[3]};
  }
  // U of the four bytes at p, in the lanes of a vector (byte → int32 → float, × fl(1/255)).
  [[gnu::always_inline]] static __m128 U4(const uint8_t* p) {
    uint32_t v;
    std::memcpy(&v, p, 4);
    const __m128i z = _mm_setzero_si128();
    const __m128i x = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(static_cast<int>(v)), z), z);
    return _mm_mul_ps(_mm_cvtepi32_ps(x), _mm_set1_ps(1.0f / 255.0f));
  }
#endif
  Tex8 img_;
  int w_, h_;
  SubTexel mode_;
  uint64_t taps_ = 0;
};

// The table of a MemoSampler: 2^kBits (key, value) entries and the texture and mode they
// were filled for. A table may outlive its samplers (the fused pass keeps one per thread for
// the area and one for the search texture, so that its entries serve every band and call);
// a sampler on another texture (its pixels' address and size) or mode empties it first. Only
// for textures that stay unchanged at one address as long as the table (the static area and
// search textures).
template <int kBits>
struct MemoTable {
  const uint8_t* data = nullptr;
  int w = 0, h = 0;
  SubTexel mode = SubTexel::kExact;
  std::vector<uint64_t> keys = std::vector<uint64_t>(size_t{1} << kBits, ~uint64_t{0});
  std::vector<Float4> vals = std::vector<Float4>(size_t{1} << kBits);
};

// InlineSampler::SampleNormalized through a direct-mapped MemoTable keyed by the exact bits
// of (s, t): with the texture and the mode fixed the fetch is a pure function of them, so a
// hit returns the same four floats the fetch would; its tap is counted all the same. For the
// area and search textures, whose fetch coordinates take few distinct values (distances,
// rounded edge values). The all-ones key (a NaN pair, which the shader never passes)
// bypasses the table.
template <int kBits>
class MemoSampler {
 public:
  MemoSampler(InlineSampler& s, MemoTable<kBits>& t) : s_(s), t_(t) {
    const Tex8& tex = s.Texture();
    if (t.data != tex.data || t.w != tex.w || t.h != tex.h || t.mode != s.Mode()) {
      std::fill(t.keys.begin(), t.keys.end(), ~uint64_t{0});
      t.data = tex.data, t.w = tex.w, t.h = tex.h, t.mode = s.Mode();
    }
  }
  [[gnu::always_inline]] Float4 SampleNormalized(float s, float t) {
    uint32_t a, b;
    std::memcpy(&a, &s, 4);
    std::memcpy(&b, &t, 4);
    const uint64_t key = (static_cast<uint64_t>(a) << 32) | b;
    const size_t slot = static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> (64 - kBits));
    if (t_.keys[slot] == key && key != ~uint64_t{0}) {
      s_.CountTap();
      return t_.vals[slot];
    }
    const Float4 r = s_.SampleNormalized(s, t);
    t_.keys[slot] = key;
    t_.vals[slot] = r;
    return r;
  }

 private:
  InlineSampler& s_;
  MemoTable<kBits>& t_;
};

// The edge-texture reader of the production path: BilinearSampler::Sample's footprint and
// clamp, texel values 0 or 1 (= UnormToFloat(255)) per bit, BilinearBlend as Sample.
class PlaneEdges {
 public:
  PlaneEdges(const EdgePlane& pl, SubTexel mode) : pl_(pl), e_(pl.e.get()), w_(pl.w), h_(pl.h), mode_(mode) {}
  F2 Sample(float u, float v) {
    ++taps_;
#if defined(__SSE2__)
    if (mode_ == SubTexel::kFixed8) return Sample8(u, v);
#endif
    const int w = pl_.w, h = pl_.h;
    const BilinearFootprint f = FootprintAt(u, v, w, h, mode_);
    const int xa = std::clamp(f.x0, 0, w - 1), xb = std::clamp(f.x0 + 1, 0, w - 1);
    const int ya = std::clamp(f.y0, 0, h - 1), yb = std::clamp(f.y0 + 1, 0, h - 1);
    const uint8_t a = pl_.Row(ya)[xa], b = pl_.Row(ya)[xb], c = pl_.Row(yb)[xa], d = pl_.Row(yb)[xb];
#if defined(__SSE2__)
    // r and g in two lanes: the texels' (bit 0, bit 1) as floats from kPair, then the same
    // three FilterLerps per lane as BilinearBlend.
    return Pair(a, b, c, d, _mm_set1_ps(f.fx), _mm_set1_ps(f.fy));
#else
    static constexpr float kBit[2] = {0.0f, 1.0f};
    return {BilinearBlend(kBit[a & 1], kBit[b & 1], kBit[c & 1], kBit[d & 1], f),
            BilinearBlend(kBit[a >> 1], kBit[b >> 1], kBit[c >> 1], kBit[d >> 1], f)};
#endif
  }
  uint64_t Taps() const { return taps_; }
  void CountTaps(int n) { taps_ += static_cast<uint64_t>(n); }  // fetches settled from the bytes (DiagSurelyZero)

 private:
#if defined(__SSE2__)
  // Sample for 8-bit fractions, the searches' and corners' hot fetch: BilinearAt8's rounding
  // (the same x0, y0, fx, fy), then the texels. Clamping x0 to [−1, w] and then x0 and x0 + 1
  // to [0, w − 1] equals clamping x0 and x0 + 1 to [0, w − 1] directly; where the footprint
  // lies inside the plane (0 <= x0 < w − 1, 0 <= y0 < h − 1) no clamp moves it, so the four
  // texels are read from one address. The same four bytes and the same lerps as Sample,
  // so the same bits (tests/methods/smaa_fetch_test.cpp).
  [[gnu::always_inline]] F2 Sample8(float u, float v) {
    const int w = w_, h = h_;
    const Footprint8 f = Round8(u, v);
    const int x0 = f.x0, y0 = f.y0;
    uint8_t a, b, c, d;
    if (static_cast<unsigned>(x0) < static_cast<unsigned>(w - 1) &&
        static_cast<unsigned>(y0) < static_cast<unsigned>(h - 1)) {
      const uint8_t* p = e_ + static_cast<size_t>(y0) * w + x0;
      a = p[0], b = p[1], c = p[w], d = p[w + 1];
    } else {
      const int xa = std::clamp(x0, 0, w - 1), xb = std::clamp(x0 + 1, 0, w - 1);
      const uint8_t* ra = e_ + static_cast<size_t>(std::clamp(y0, 0, h - 1)) * w;
      const uint8_t* rb = e_ + static_cast<size_t>(std::clamp(y0 + 1, 0, h - 1)) * w;
      a = ra[xa], b = ra[xb], c = rb[xa], d = rb[xb];
    }
    return Pair(a, b, c, d, f.fx, f.fy);
  }
  // r and g of the four edge bytes' footprint in two lanes: the texels' (bit 0, bit 1) as
  // floats from kPair, then BilinearBlend per lane (Blend4).
  [[gnu::always_inline]] static F2 Pair(uint8_t a, uint8_t b, uint8_t c, uint8_t d, __m128 fx, __m128 fy) {
    const __m128 rg =
        Blend4(_mm_load_ps(kPair[a]), _mm_load_ps(kPair[b]), _mm_load_ps(kPair[c]), _mm_load_ps(kPair[d]), fx, fy);
    return {_mm_cvtss_f32(rg), _mm_cvtss_f32(_mm_shuffle_ps(rg, rg, 1))};
  }
  // (bit 0, bit 1) of an edge byte as floats.
  alignas(16) static constexpr float kPair[4][4] = {{0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {1, 1, 0, 0}};
#endif
  const EdgePlane& pl_;
  const uint8_t* e_;  // pl_'s bytes and size, read once
  int w_, h_;
  SubTexel mode_;
  uint64_t taps_ = 0;
};

/// Whether SMAACalculateDiagWeights (smaa_shader.h's DiagWeights) returns (0, 0) for pixel
/// (x, y), whose own edge byte has the top bit, decided from the edge bytes alone; then *taps
/// is the number of fetches it makes. For 8-bit sub-texel fetches on frames up to
/// kMaxShortcutSize and max_search_steps_diag >= 1; false (undecided: run the shader's
/// diagonal search) for pixels within two columns or one row of the border and wherever a
/// search's first step continues. Its fetches land on the footprints of the texel centres
/// (x − 1, y + 1), (x + 1, y − 1), (x + 1, y) and of (x − 0.75, y − 1), (x + 1.25, y + 1)
/// (SearchDiag2's x + 0.25): the coordinates carry at most four float roundings, < 0.001
/// texel on frames up to 8192 px, under the 1/512 at which the 8-bit fraction would round
/// elsewhere. A centre fetch returns the texel's (r, g) bits; SearchDiag2's, decoded,
/// returns (r of the right texel, g of the left one). A search whose first fetch has
/// cw <= 0.9 stops with cz = 0, so d.x + d.y <= 1 in both pairs and no area fetch adds to
/// the weights.
inline bool DiagSurelyZero(const EdgePlane& pl, int x, int y, int* taps) {
  if (x < 1 || x > pl.w - 3 || y < 1 || y > pl.h - 2) return false;
  const uint8_t* r0 = pl.Row(y - 1);
  const uint8_t* r1 = pl.Row(y);
  const uint8_t* r2 = pl.Row(y + 1);
  constexpr uint8_t kBoth = kLeft | kTop;
  int n = 3;            // SearchDiag1 (1, −1), SearchDiag2 (−1, −1), the right texel's r
  if (r1[x] & kLeft) {  // SearchDiag1 (−1, 1) runs
    if (r2[x - 1] == kBoth) return false;
    ++n;
  }
  if (r0[x + 1] == kBoth) return false;
  if ((r0[x] & kLeft) && (r0[x - 1] & kTop)) return false;
  if (r1[x + 1] & kLeft) {  // SearchDiag2 (1, 1) runs
    if ((r2[x + 2] & kLeft) && (r2[x + 1] & kTop)) return false;
    ++n;
  }
  *taps = n;
  return true;
}

/// Passes 2 and 3 fused (8-bit fetches, frames up to kMaxShortcutSize, edges listed): blends
/// into *out, which holds the input with alpha 255 (pass 1 copies each row), the pixels whose
/// weights are non-zero; adds the two passes' taps to *taps. methods/smaa_fused.cpp.
void WeightsAndBlendFused(const Image8& in, const EdgePlane& edges, const SmaaParams& p, Image8* out, uint64_t* taps);

}  // namespace aalab::smaa_internal
