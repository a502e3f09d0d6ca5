// SMAA 1x production path internals (methods/smaa_fast.cpp and its tests): pass 1's rows in
// SIMD and the per-row edge lists. Not part of the methods API.
#pragma once
#include <cstdint>

namespace aalab::smaa_internal {

/// QuantizeUnorm8 (core/color.h: clamp to [0, 1], lround(v·255)) inline, without the libm
/// call: for v in (0, 1), w = v·255 in (0, 255), i = trunc(w) and w − i (exact: a multiple of
/// w's ulp below 1) ≥ 0.5 rounds half away from zero as lround does.
[[gnu::always_inline]] inline uint8_t Quantize8(float v) {
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  const float w = v * 255.0f;
  const int i = static_cast<int>(w);
  return static_cast<uint8_t>(i + (w - static_cast<float>(i) >= 0.5f ? 1 : 0));
}

/// One padded luma row of luma edge detection: l[x + 2] = (r + g) + b of the input pixel
/// src[4x..4x+3], each channel k·fl(1/255)·weight (weights 0.2126, 0.7152, 0.0722; the
/// reference's Luma of UnormToFloat texels), and the clamped neighbours l[0] = l[1] = L(0),
/// l[w + 2] = L(w − 1); l holds w + 3 floats. SSE2, four pixels a vector (eight with AVX2
/// where the CPU has it); the same IEEE float32 operations in the same order per lane as
/// LumaRowScalar.
void LumaRow(const uint8_t* src, int w, float* l);

/// The scalar form of LumaRow, kept as its reference.
void LumaRowScalar(const uint8_t* src, int w, float* l);

/// EdgePixel's luma deltas and decision for every pixel of a row, from the padded luma rows
/// of the pixel's row (lc), the rows above (lt), two above (ltt) and below (lb): out[x] gets
/// bit 0 (left edge) and bit 1 (top edge); 0 for a pixel the shader discards. Returns the
/// number of pixels the shader does not discard (dx or dy ≥ thr); *any is non-zero iff some
/// byte is. SSE2 four columns a step (AVX2 eight where the CPU has it); the rows need no alignment.
int EdgeRowLuma(const float* lc, const float* lt, const float* ltt, const float* lb, int w, float thr, float lcf,
                uint8_t* out, uint8_t* any);

/// The scalar form of EdgeRowLuma, kept as its reference.
int EdgeRowLumaScalar(const float* lc, const float* lt, const float* ltt, const float* lb, int w, float thr, float lcf,
                      uint8_t* out, uint8_t* any);

/// The columns x in [0, w) with row[x] != 0, ascending, into xs (room for w entries);
/// returns their number. SSE2, sixteen bytes a compare.
int ListNonZero(const uint8_t* row, int w, uint16_t* xs);

}  // namespace aalab::smaa_internal
