/// The AVX2 and AVX-512 row kernels of TAA's production step (methods/taa.cpp, StepFast),
/// chosen at run time where the CPU has them (methods/taa_avx2.cpp, methods/taa_avx512.cpp;
/// the AVX2 entry points run the AVX-512 kernel first where there is one; without AVX2 every
/// function does nothing and returns 0, and the SSE2 and scalar rows do the work). Same float operations in the
/// same order as StepReference, eight pixels at a time, so the same bits.
#pragma once
#include <cstdint>

namespace aalab::taa_detail {

/// The sRGB encode's table (taa.cpp's Encode8) per bucket of float bit patterns (bits >>
/// kEncodeShift): the first guess g of the 8-bit code (bits 0..7) and t1, the low 16 bits of
/// the next code threshold's pattern where it lies inside the bucket (bits 8..24; 65536 where
/// not): code = g + (lo ≥ t1), lo = the value's low 16 bits. No bucket holds two thresholds
/// (Encode8's constructor checks it).
inline constexpr uint32_t kEncodeShift = 16;
inline constexpr uint32_t kEncodeBuckets = (0x3f800000u >> kEncodeShift) + 1;  ///< up to 1.0f
struct EncodeTables {
  const uint32_t* packed;  ///< kEncodeBuckets entries
};

/// True where the AVX2 kernels run (the CPU has AVX2 and the build is GCC on x86-64).
bool TaaHasAvx2();
/// True where the AVX-512 kernels run (methods/taa_avx512.cpp: the CPU has AVX-512F and AVX2).
bool TaaHasAvx512();

/// One row's inputs for HistoryBlendRow8Avx2 (arrays indexed by the pixel x of the row).
struct Avx2RowIn {
  const float* hist;            ///< the history, 3 floats per pixel, readable 1 float past its end
  const float* prev;            ///< previous positions, x and y per pixel
  int hw, hh;                   ///< the frame's (and history's) size
  const float *lo[3], *hi[3];   ///< the box per YCoCg channel (read only when clipping)
  const float *cy, *cco, *ccg;  ///< current YCoCg planes, padded: texel x at x + 1
  const uint8_t* src;           ///< the current frame's row, RGBA8
  const float* decode;          ///< linear value of each 8-bit code
  EncodeTables enc;             ///< the output encode
  /// The AVX-512 kernel forms the box itself (taa.cpp BoxRow's values), from the current
  /// YCoCg plane rows above, at and below per channel (padded: texel x at x + 1); lo and hi
  /// are read from x = w − w mod 16 on only (BoxRow need not fill them before).
  const float* box[3][3];
  bool variance;  ///< clip=variance (else minmax)
  float gamma;
};

/// The whole step of pixels [0, n) of a row, n = w rounded down to a multiple of 8: the
/// history's footprint (FootprintRow), the bilinear fetch (four unaligned 4-float loads per
/// pixel), ToYCoCg, the clip (when `clip`), the blend, FromYCoCg, the clamp, the current
/// colour where there is no history, the new history (3 floats per pixel into `next`) and
/// the sRGB-encoded RGBA8 output (`rgba`). Returns n (0 without AVX2). Where the CPU has
/// AVX-512, HistoryBlendRow16Avx512 does the first w − w mod 16 pixels.
int HistoryBlendRow8Avx2(const Avx2RowIn& in, int w, bool clip, float alpha, float* next, uint8_t* rgba);

/// The same with AVX-512 for pixels [0, n), n = w rounded down to a multiple of 16 (0
/// without AVX-512); HistoryBlendRow8Avx2 runs it first and continues from n. Where the 16
/// pixels' footprint is contiguous (pixel i's texels are pixel 0's + i) it fetches the two
/// history rows by vector loads and permutes instead. Likewise EncodeRgbaAvx512 and
/// YccPlaneRowAvx512 below for the two functions after this one (YccPlaneRowAvx512 decodes
/// from the table held in registers, no gathers).
int HistoryBlendRow16Avx512(const Avx2RowIn& in, int w, bool clip, float alpha, float* next, uint8_t* rgba);
int EncodeRgbaAvx512(const EncodeTables& t, const float* r, const float* g, const float* b, int w, uint8_t* rgba);
int YccPlaneRowAvx512(const uint8_t* src, int w, const float* decode, float* y, float* co, float* cg);

/// x[i] / 9 for i in [0, n), n = w rounded down to a multiple of 16, as the AVX-512 kernel's
/// box divides its sums (a product and an FMA correction; the same bits as the division for
/// finite x other than −0). Returns n (0 without AVX-512). For tests.
int Div9Avx512(const float* x, int w, float* q);

/// Encode8::Rgba of pixels [0, n), n = w rounded down to a multiple of 8 (gathers for the
/// three table reads per value). Returns n (0 without AVX2).
int EncodeRgbaAvx2(const EncodeTables& t, const float* r, const float* g, const float* b, int w, uint8_t* rgba);

/// The current frame's YCoCg planes for pixels [0, n) of a row, n = w rounded down to a
/// multiple of 8: decode (table, by gathers) then ToYCoCg. Returns n (0 without AVX2).
int YccPlaneRowAvx2(const uint8_t* src, int w, const float* decode, float* y, float* co, float* cg);

}  // namespace aalab::taa_detail
