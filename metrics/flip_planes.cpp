// LDR-FLIP, production path (metrics/flip_fast.cpp): the image to YCxCz planes, float32
// (the achromatic plane as Ŷ = (Y + 16)/116 = Y_xyz / Yn; metrics/flip_fast_internal.h tells
// why), row-major, in parallel chunks of kChunkRows rows.
//
// Decoding: a row whose every value is exactly k/255 (every 8-bit frame a run scores) is
// decoded in vector lanes (codes checked, linear values gathered from a table, the same double
// arithmetic); any other row per pixel, by the table where a value is a code and the formula
// otherwise. The linear values go to X/Xn, Y/Yn, Z/Zn in double (one fixed order of
// operations), then Cx = 500·(X/Xn − Y/Yn), Cz = 200·(Y/Yn − Z/Zn), each rounded to float once.
// The lanes' kernel is compiled for AVX-512, AVX2 and the baseline (target_clones) with
// separate multiplies and adds (-ffp-contract=off): both paths, every clone and every thread
// count give the same bits. A value outside [0, 1] or NaN is no code: the scalar path decodes
// it by the formula (SrgbToLinear, metrics/flip.cpp).
#include <array>
#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "metrics/flip.h"
#include "metrics/flip_fast_internal.h"

namespace aalab {
namespace flip {
namespace fast_detail {
namespace {

// Linear value of the 8-bit code k, indexed by k; a value is looked up when it equals
// float(k) / 255 exactly (ToFloat's conversion).
struct SrgbTable {
  std::array<float, 256> code{};
  std::array<double, 256> linear{};
  SrgbTable() {
    for (int k = 0; k < 256; ++k) {
      code[k] = static_cast<float>(k) / 255.0f;
      linear[k] = SrgbToLinear(code[k]);
    }
  }
};

double DecodeSrgb(float v, const SrgbTable& t) {
  if (v >= 0.0f && v <= 1.0f) {
    const int k = static_cast<int>(v * 255.0f + 0.5f);
    if (t.code[k] == v) return t.linear[k];
  }
  return SrgbToLinear(v);
}

// XYZ / white of linear R, G, B: row i holds the i-th of X/Xn, Y/Yn, Z/Zn.
const std::array<Color, 3>& XyzOverWhiteRows() {
  static const std::array<Color, 3> rows = [] {
    std::array<Color, 3> r{};
    for (int c = 0; c < 3; ++c) {
      Color e{};
      e[c] = 1.0;
      const Color xyz = LinearRgbToXyz(e);
      for (int i = 0; i < 3; ++i) r[i][c] = xyz[i] / kWhite[i];
    }
    return r;
  }();
  return rows;
}

// One pixel's YCxCz from its linear r, g, b (double, in this order of operations).
struct YcxczRows {
  double m[9];
};

// One row, every value an exact 8-bit code k/255 (what a run scores): the codes, checked
// (float(k)/255 == v, the table's own test), then the linear values by table and the same
// double arithmetic as the scalar row, so the compiler runs it in vector lanes (gathers).
// Returns false, writing nothing, when some value is not such a code (the row then takes
// the scalar path). Same bits as the scalar row on every clone.
AALAB_FLIP_CLONES
bool PlanesRowCodes(const float* __restrict src, int w, const double* __restrict linear, const YcxczRows& m,
                    int32_t* __restrict codes, float* __restrict oy, float* __restrict ocx, float* __restrict ocz) {
  const int n = 3 * w;
  int bad = 0;
  for (int i = 0; i < n; ++i) {
    const float v = src[i];
    float c = v > 0.0f ? v : 0.0f;  // NaN → 0, then found not equal to its code
    c = c < 1.0f ? c : 1.0f;
    const int k = static_cast<int>(c * 255.0f + 0.5f);
    bad |= static_cast<float>(k) / 255.0f != v;
    codes[i] = k;
  }
  if (bad) return false;
  for (int x = 0; x < w; ++x) {
    const double r = linear[codes[3 * x]], g = linear[codes[3 * x + 1]], b = linear[codes[3 * x + 2]];
    const double xn = m.m[0] * r + m.m[1] * g + m.m[2] * b;  // X / Xn
    const double yn = m.m[3] * r + m.m[4] * g + m.m[5] * b;  // Y / Yn = Ŷ
    const double zn = m.m[6] * r + m.m[7] * g + m.m[8] * b;  // Z / Zn
    oy[x] = static_cast<float>(yn);
    ocx[x] = static_cast<float>(500.0 * (xn - yn));
    ocz[x] = static_cast<float>(200.0 * (yn - zn));
  }
  return true;
}

}  // namespace

Planes ToPlanes(const ImageF& img) {
  static const SrgbTable table;
  Planes p;
  p.w = img.Width();
  p.h = img.Height();
  const size_t n = img.PixelCount();
  p.y.resize(n);
  p.cx.resize(n);
  p.cz.resize(n);
  const int ch = img.Channels();
  const std::array<Color, 3>& rows = XyzOverWhiteRows();
  YcxczRows m;
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) m.m[3 * i + c] = rows[i][c];
  ParallelForChunks(p.h, kChunkRows, [&](int y0, int y1) {
    std::vector<int32_t> codes(ch == 3 ? static_cast<size_t>(3) * p.w : 0);
    for (int y = y0; y < y1; ++y) {
      const float* src = img.Row(y);
      const size_t row = static_cast<size_t>(y) * p.w;
      if (ch == 3 && PlanesRowCodes(src, p.w, table.linear.data(), m, codes.data(), p.y.data() + row, p.cx.data() + row,
                                    p.cz.data() + row)) {
        continue;
      }
      for (int x = 0; x < p.w; ++x) {
        const float* px = src + static_cast<size_t>(x) * ch;
        const double r = DecodeSrgb(px[0], table), g = DecodeSrgb(px[1], table), b = DecodeSrgb(px[2], table);
        const double xn = rows[0][0] * r + rows[0][1] * g + rows[0][2] * b;  // X / Xn
        const double yn = rows[1][0] * r + rows[1][1] * g + rows[1][2] * b;  // Y / Yn = Ŷ
        const double zn = rows[2][0] * r + rows[2][1] * g + rows[2][2] * b;  // Z / Zn
        const size_t i = row + x;
        p.y[i] = static_cast<float>(yn);  // Ŷ = (Y + 16) / 116, without the offset's cancellation
        p.cx[i] = static_cast<float>(500.0 * (xn - yn));
        p.cz[i] = static_cast<float>(200.0 * (yn - zn));
      }
    }
  });
  return p;
}

}  // namespace fast_detail
}  // namespace flip
}  // namespace aalab
