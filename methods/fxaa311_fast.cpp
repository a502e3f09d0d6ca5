// FXAA 3.11 Quality: the production path (the filter `Fxaa311` that methods run).
//
// The same shader as Fxaa311Reference in methods/fxaa311.cpp — same float operations in the
// same order, same tie-breaks, same taps — organised for a CPU; see the block below. Its
// parameters, sources and deviations are documented at the top of methods/fxaa311.cpp.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <type_traits>
#include <vector>

#include "harness/core/color.h"
#include "harness/core/error.h"
#include "harness/core/parallel.h"
#include "methods/fxaa311.h"
#include "methods/row_ops.h"

namespace aalab {

namespace {
using Luma = Fxaa311Params::Luma;
using Order = Fxaa311Params::Order;
}  // namespace
// ---------------------------------------------------------------------------------------
// The production path. Same shader, same float operations in the same order, organised
// for a CPU instead of one invocation per pixel:
//   1. Luma once per frame, into a plane (what the GPU's first pass writes into alpha):
//      8-bit for rec601 / sqrt-luminance (the stored alpha) and green (the green byte),
//      float for rec601-rgb (the per-tap dot of an exact texel read). Texel lumas are read
//      from the plane; bilinear luma taps filter the plane (alpha-stored modes: exactly the
//      alpha channel of the bilinear fetch; rec601-rgb filters rgb through the sampler).
//   2. The early-exit contrast test over whole rows, in a loop the compiler vectorises (max
//      and min of N, W, M, E, S, then the shader's float comparison). Pixels that exit
//      (and the range = 0 pixels, see above) copy the input; the output row is first
//      written as a copy, so only edge pixels are touched again.
//   3. Only edge pixels run the rest of the shader (EdgePixel below: ShadePixel's
//      statements from the corner fetches on, with the same luma values).
// Tap counts are those of the reference: 5 for a pixel that exits, 9 + search + final
// for an edge pixel. Tests compare this path with Fxaa311Reference bit for bit on real
// and adversarial frames (tests/methods/fxaa_fast_test.cpp).

namespace {

// k / 255 as BilinearSampler::Fetch computes it (uint8 promoted, converted, divided).
inline float Unorm(uint8_t k) { return static_cast<float>(k) / 255.0f; }
inline float LumaValue(uint8_t k) { return Unorm(k); }
inline float LumaValue(float v) { return v; }

// QuantizeUnorm8 for values already known to lie in (0, 1): lround(w) for w = v·255 > 0 is
// floor(w + 0.5), and w + 0.5 is exact in double (w < 256 has a 24-bit significand).
inline uint8_t QuantizeInterior(float v) {
  return static_cast<uint8_t>(static_cast<int>(static_cast<double>(v * 255.0f) + 0.5));
}
inline uint8_t QuantizeFast(float v) {
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  return QuantizeInterior(v);
}

// A luma plane: one value per pixel, row-major; P = uint8_t (value k means k/255) or float.
template <typename P>
struct LumaPlane {
  int w = 0, h = 0;
  std::unique_ptr<P[]> v;  // w·h values, left uninitialised until BuildPlane writes them
  const P* Row(int y) const { return v.get() + static_cast<size_t>(y) * w; }
  // Texel read with clamp-to-edge (BilinearSampler::Fetch), as a luma.
  [[gnu::always_inline]] float Texel(int x, int y) const {
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return LumaValue(v[static_cast<size_t>(y) * w + x]);
  }
  // The luma channel of BilinearSampler::SampleNormalized(s, t), operation for operation.
  [[gnu::always_inline]] float Bilinear(float s, float t) const {
    const BilinearFootprint f = BilinearAt(s * static_cast<float>(w), t * static_cast<float>(h), w, h);
    const float a = Texel(f.x0, f.y0);
    const float b = Texel(f.x0 + 1, f.y0);
    const float c = Texel(f.x0, f.y0 + 1);
    const float d = Texel(f.x0 + 1, f.y0 + 1);
    return BilinearBlend(a, b, c, d, f);
  }
};

// Per-channel products of the luma dot, one table per weight: entry k is the product the
// reference computes for channel value k (k/255·w, or SrgbDecode8(k)·w), so the sums below
// add exactly the same floats in the same order.
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
      const float u = Unorm(static_cast<uint8_t>(k));
      x.r[k] = u * 0.299f;
      x.g[k] = u * 0.587f;
      x.b[k] = u * 0.114f;
    }
    return x;
  }();
  return t;
}

// Luma plane of the frame for the mode (step 1), rows in parallel.
void BuildPlane(const Image8& in, Luma luma, LumaPlane<uint8_t>* plane) {
  const int w = in.Width(), h = in.Height();
  plane->w = w;
  plane->h = h;
  plane->v.reset(new uint8_t[static_cast<size_t>(w) * h]);
  const LumaTables& rec = Rec601Tables();
  const LumaTables& sq = SqrtLuminanceTables();
  ParallelForChunks(h, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const uint8_t* p = in.Row(y);
      uint8_t* o = plane->v.get() + static_cast<size_t>(y) * w;
      if (luma == Luma::kGreen) {
        for (int x = 0; x < w; ++x) o[x] = p[4 * x + 1];
      } else if (luma == Luma::kRec601) {
        // Fxaa311LumaFrame: QuantizeUnorm8((r·0.299 + g·0.587) + b·0.114), r = k/255.
        for (int x = 0; x < w; ++x) {
          o[x] = QuantizeFast((rec.r[p[4 * x]] + rec.g[p[4 * x + 1]]) + rec.b[p[4 * x + 2]]);
        }
      } else {  // kSqrtLuminance: QuantizeUnorm8(sqrt((R·0.2126729 + G·0.7151522) + B·0.0721750))
        for (int x = 0; x < w; ++x) {
          o[x] = QuantizeFast(std::sqrt((sq.r[p[4 * x]] + sq.g[p[4 * x + 1]]) + sq.b[p[4 * x + 2]]));
        }
      }
    }
  });
}

void BuildPlane(const Image8& in, Luma, LumaPlane<float>* plane) {  // kRec601Rgb
  const int w = in.Width(), h = in.Height();
  plane->w = w;
  plane->h = h;
  plane->v.reset(new float[static_cast<size_t>(w) * h]);
  ParallelForChunks(h, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const uint8_t* p = in.Row(y);
      float* o = plane->v.get() + static_cast<size_t>(y) * w;
      for (int x = 0; x < w; ++x) {
        const float r = Unorm(p[4 * x]), g = Unorm(p[4 * x + 1]), b = Unorm(p[4 * x + 2]);
        o[x] = (r * 0.299f + g * 0.587f) + b * 0.114f;  // Fxaa311TapLuma(kRec601Rgb)
      }
    }
  });
}

// Step 2 for one row: edge[x] = 1 where the pixel passes the early exit and has range > 0.
// max/min are exact, so their nesting does not matter; k -> k/255 is increasing, so the
// max (min) of the lumas is the luma of the max (min) byte.
template <typename P>
int ContrastRow(const LumaPlane<P>& pl, int y, float thr, float thr_min, uint8_t* edge) {
  const int w = pl.w;
  const P* rn = pl.Row(std::max(y - 1, 0));
  const P* rm = pl.Row(y);
  const P* rs = pl.Row(std::min(y + 1, pl.h - 1));
  auto test = [&](P n, P wv, P m, P e, P s) -> uint8_t {
    const P mx = std::max(std::max(n, wv), std::max(m, std::max(e, s)));
    const P mn = std::min(std::min(n, wv), std::min(m, std::min(e, s)));
    const float range_max = LumaValue(mx);
    const float range = range_max - LumaValue(mn);
    const float clamped = std::max(thr_min, range_max * thr);
    return (range < clamped || range == 0.0f) ? 0 : 1;
  };
  if (w == 1) {
    edge[0] = test(rn[0], rm[0], rm[0], rm[0], rs[0]);
  } else {
    edge[0] = test(rn[0], rm[0], rm[0], rm[1], rs[0]);
    for (int x = 1; x < w - 1; ++x) edge[x] = test(rn[x], rm[x - 1], rm[x], rm[x + 1], rs[x]);
    edge[w - 1] = test(rn[w - 1], rm[w - 2], rm[w - 1], rm[w - 1], rs[w - 1]);
  }
  int count = 0;
  for (int x = 0; x < w; ++x) count += edge[x];
  return count;
}

// The early-exit decision for 8-bit lumas depends only on the (max, min) byte pair: a
// 256×256 table evaluated with the shader's float expressions, plus the largest byte
// difference `safe` for which every pair exits (so a vectorised max − min <= safe test
// settles most pixels without the table).
struct ExitTable {
  std::vector<uint8_t> edge;  // [max·256 + min] = 1 when the pixel goes on to the search
  int safe = -1;              // max − min <= safe always exits
};

ExitTable MakeExitTable(float thr, float thr_min) {
  ExitTable t;
  t.edge.assign(256 * 256, 0);
  int safe = 255;
  for (int mx = 0; mx < 256; ++mx) {
    for (int mn = 0; mn <= mx; ++mn) {
      const float range_max = LumaValue(static_cast<uint8_t>(mx));
      const float range = range_max - LumaValue(static_cast<uint8_t>(mn));
      const float clamped = std::max(thr_min, range_max * thr);
      const bool exit = range < clamped || range == 0.0f;
      t.edge[mx * 256 + mn] = exit ? 0 : 1;
      if (!exit) safe = std::min(safe, mx - mn - 1);
    }
  }
  t.safe = safe;
  return t;
}

// Step 2 for one row of 8-bit lumas, through the table: returns the number of edge pixels.
int ContrastRowBytes(const LumaPlane<uint8_t>& pl, int y, const ExitTable& tab, uint8_t* edge) {
  const int w = pl.w;
  const uint8_t* rn = pl.Row(std::max(y - 1, 0));
  const uint8_t* rm = pl.Row(y);
  const uint8_t* rs = pl.Row(std::min(y + 1, pl.h - 1));
  auto exact = [&](uint8_t n, uint8_t wv, uint8_t m, uint8_t e, uint8_t s) -> uint8_t {
    const uint8_t mx = std::max(std::max(n, wv), std::max(m, std::max(e, s)));
    const uint8_t mn = std::min(std::min(n, wv), std::min(m, std::min(e, s)));
    return tab.edge[mx * 256 + mn];
  };
  if (w <= 2) {
    for (int x = 0; x < w; ++x) {
      edge[x] = exact(rn[x], rm[std::max(x - 1, 0)], rm[x], rm[std::min(x + 1, w - 1)], rs[x]);
    }
  } else {
    edge[0] = exact(rn[0], rm[0], rm[0], rm[1], rs[0]);
    edge[w - 1] = exact(rn[w - 1], rm[w - 2], rm[w - 1], rm[w - 1], rs[w - 1]);
    // Vectorisable: candidates where max − min exceeds the always-exit difference.
    const uint8_t safe = static_cast<uint8_t>(std::max(tab.safe, 0));
    const bool none_safe = tab.safe < 0;
    for (int x = 1; x < w - 1; ++x) {
      const uint8_t mx = std::max(std::max(rn[x], rm[x - 1]), std::max(rm[x], std::max(rm[x + 1], rs[x])));
      const uint8_t mn = std::min(std::min(rn[x], rm[x - 1]), std::min(rm[x], std::min(rm[x + 1], rs[x])));
      edge[x] = static_cast<uint8_t>(mx - mn) > safe || none_safe;
    }
    for (int x = 1; x < w - 1; ++x) {
      if ((x & 7) == 0 && x + 8 <= w - 1) {  // skip 8 candidates at a time when none is set
        uint64_t word;
        std::memcpy(&word, edge + x, 8);
        if (word == 0) {
          x += 7;
          continue;
        }
      }
      if (edge[x]) edge[x] = exact(rn[x], rm[x - 1], rm[x], rm[x + 1], rs[x]);
    }
  }
  int count = 0;
  for (int x = 0; x < w; ++x) count += edge[x];
  return count;
}

// The rgb of BilinearSampler::SampleNormalized(s, t) on `img`, operation for operation
// (Sample's floor/clamp/weights, Fetch's clamp and k/255), without the alpha channel.
inline void FinalTap(const Image8& img, float s, float t, float rgb[3]) {
  const int W = img.Width(), H = img.Height();
  const float u = s * static_cast<float>(W);
  const float v = t * static_cast<float>(H);
  const float x = u - 0.5f;
  const float y = v - 0.5f;
  const float x0f = std::floor(x);
  const float y0f = std::floor(y);
  const float fx = x - x0f;
  const float fy = y - y0f;
  const int x0 = static_cast<int>(std::clamp(x0f, -1.0f, static_cast<float>(W)));
  const int y0 = static_cast<int>(std::clamp(y0f, -1.0f, static_cast<float>(H)));
  const int xa = std::clamp(x0, 0, W - 1), xb = std::clamp(x0 + 1, 0, W - 1);
  const int ya = std::clamp(y0, 0, H - 1), yb = std::clamp(y0 + 1, 0, H - 1);
  const uint8_t* a = img.Pixel(xa, ya);
  const uint8_t* b = img.Pixel(xb, ya);
  const uint8_t* c = img.Pixel(xa, yb);
  const uint8_t* d = img.Pixel(xb, yb);
  const float wa = (1.0f - fx) * (1.0f - fy);
  const float wb = fx * (1.0f - fy);
  const float wc = (1.0f - fx) * fy;
  const float wd = fx * fy;
  for (int k = 0; k < 3; ++k) rgb[k] = Unorm(a[k]) * wa + Unorm(b[k]) * wb + Unorm(c[k]) * wc + Unorm(d[k]) * wd;
}

// ShadePixel for a pixel that passed the early exit with range > 0, lumas from the plane.
// Statement order and float expressions are ShadePixel's; returns the taps it took.
template <typename P>
uint64_t EdgePixel(const LumaPlane<P>& pl, BilinearSampler& tex, const Image8& src, int x, int y,
                   const Fxaa311Params& prm, float rcpX, float rcpY, uint8_t* out) {
  const bool glsl = prm.order == Order::kSeed003Glsl;
  const bool rgb_taps = prm.luma == Luma::kRec601Rgb;  // bilinear lumas need filtered rgb
  const std::vector<float>& P_ = prm.steps;
  auto tap = [&](float s, float t) {
    return rgb_taps ? Fxaa311TapLuma(tex.SampleNormalized(s, t), prm.luma) : pl.Bilinear(s, t);
  };
  uint64_t taps = 9;
  const int W = pl.w, H = pl.h;
  float posMx = (static_cast<float>(x) + 0.5f) / static_cast<float>(W);
  float posMy = (static_cast<float>(y) + 0.5f) / static_cast<float>(H);
  const float lumaM = pl.Texel(x, y);
  float lumaS = pl.Texel(x, y + 1);
  float lumaE = pl.Texel(x + 1, y);
  float lumaN = pl.Texel(x, y - 1);
  float lumaW = pl.Texel(x - 1, y);
  const float rangeMax = std::max(std::max(lumaN, lumaW), std::max(lumaE, std::max(lumaS, lumaM)));
  const float rangeMin = std::min(std::min(lumaN, lumaW), std::min(lumaE, std::min(lumaS, lumaM)));
  const float range = rangeMax - rangeMin;

  const float lumaNW = pl.Texel(x - 1, y - 1);
  const float lumaSE = pl.Texel(x + 1, y + 1);
  const float lumaNE = pl.Texel(x + 1, y - 1);
  const float lumaSW = pl.Texel(x - 1, y + 1);

  const float lumaNS = lumaN + lumaS;
  const float lumaWE = lumaW + lumaE;
  const float subpixRcpRange = 1.0f / range;
  const float subpixNSWE = lumaNS + lumaWE;
  const float edgeHorz1 = (-2.0f * lumaM) + lumaNS;
  const float edgeVert1 = (-2.0f * lumaM) + lumaWE;

  const float lumaNESE = lumaNE + lumaSE;
  const float lumaNWNE = lumaNW + lumaNE;
  const float edgeHorz2 = (-2.0f * lumaE) + lumaNESE;
  const float edgeVert2 = (-2.0f * lumaN) + lumaNWNE;

  const float lumaNWSW = lumaNW + lumaSW;
  const float lumaSWSE = lumaSW + lumaSE;
  const float edgeHorz4 = (std::fabs(edgeHorz1) * 2.0f) + std::fabs(edgeHorz2);
  const float edgeVert4 = (std::fabs(edgeVert1) * 2.0f) + std::fabs(edgeVert2);
  const float edgeHorz3 = (-2.0f * lumaW) + lumaNWSW;
  const float edgeVert3 = (-2.0f * lumaS) + lumaSWSE;
  float edgeHorz = std::fabs(edgeHorz3) + edgeHorz4;
  float edgeVert = std::fabs(edgeVert3) + edgeVert4;
  if (glsl) {
    edgeHorz = (std::fabs(edgeHorz3) + std::fabs(edgeHorz1) * 2.0f) + std::fabs(edgeHorz2);
    edgeVert = (std::fabs(edgeVert3) + std::fabs(edgeVert1) * 2.0f) + std::fabs(edgeVert2);
  }

  const float subpixNWSWNESE = lumaNWSW + lumaNESE;
  float lengthSign = rcpX;
  const bool horzSpan = edgeHorz >= edgeVert;
  const float subpixA = subpixNSWE * 2.0f + subpixNWSWNESE;

  if (!horzSpan) lumaN = lumaW;
  if (!horzSpan) lumaS = lumaE;
  if (horzSpan) lengthSign = rcpY;
  float subpixB = (subpixA * (1.0f / 12.0f)) - lumaM;
  if (glsl) {
    const float lumaAverage = (1.0f / 12.0f) * ((2.0f * subpixNSWE + lumaNWSW) + lumaNESE);
    subpixB = lumaAverage - lumaM;
  }

  const float gradientN = lumaN - lumaM;
  const float gradientS = lumaS - lumaM;
  float lumaNN = lumaN + lumaM;
  const float lumaSS = lumaS + lumaM;
  const bool pairN = std::fabs(gradientN) >= std::fabs(gradientS);
  const float gradient = std::max(std::fabs(gradientN), std::fabs(gradientS));
  if (pairN) lengthSign = -lengthSign;
  const float subpixCIn = glsl ? std::fabs(subpixB) / range : std::fabs(subpixB) * subpixRcpRange;
  const float subpixC = std::min(std::max(subpixCIn, 0.0f), 1.0f);

  float posBx = posMx;
  float posBy = posMy;
  const float offNPx = (!horzSpan) ? 0.0f : rcpX;
  const float offNPy = (horzSpan) ? 0.0f : rcpY;
  if (!horzSpan) posBx += lengthSign * 0.5f;
  if (horzSpan) posBy += lengthSign * 0.5f;

  float posNx = posBx - offNPx * P_[0];
  float posNy = posBy - offNPy * P_[0];
  float posPx = posBx + offNPx * P_[0];
  float posPy = posBy + offNPy * P_[0];
  const float subpixD = ((-2.0f) * subpixC) + 3.0f;
  float lumaEndN = tap(posNx, posNy);
  const float subpixE = subpixC * subpixC;
  float lumaEndP = tap(posPx, posPy);
  taps += 2;

  if (!pairN) lumaNN = lumaSS;
  const float gradientScaled = gradient * 1.0f / 4.0f;
  const float lumaMM = lumaM - lumaNN * 0.5f;
  const float subpixF = glsl ? (subpixD * subpixC) * subpixC : subpixD * subpixE;
  const bool lumaMLTZero = lumaMM < 0.0f;

  lumaEndN -= lumaNN * 0.5f;
  lumaEndP -= lumaNN * 0.5f;
  bool doneN = std::fabs(lumaEndN) >= gradientScaled;
  bool doneP = std::fabs(lumaEndP) >= gradientScaled;
  if (!doneN) posNx -= offNPx * P_[1];
  if (!doneN) posNy -= offNPy * P_[1];
  bool doneNP = (!doneN) || (!doneP);
  if (!doneP) posPx += offNPx * P_[1];
  if (!doneP) posPy += offNPy * P_[1];

  for (size_t k = 2; k < P_.size() && doneNP; ++k) {
    if (!doneN) {
      lumaEndN = tap(posNx, posNy);
      ++taps;
    }
    if (!doneP) {
      lumaEndP = tap(posPx, posPy);
      ++taps;
    }
    if (!doneN) lumaEndN = lumaEndN - lumaNN * 0.5f;
    if (!doneP) lumaEndP = lumaEndP - lumaNN * 0.5f;
    doneN = std::fabs(lumaEndN) >= gradientScaled;
    doneP = std::fabs(lumaEndP) >= gradientScaled;
    if (!doneN) posNx -= offNPx * P_[k];
    if (!doneN) posNy -= offNPy * P_[k];
    doneNP = (!doneN) || (!doneP);
    if (!doneP) posPx += offNPx * P_[k];
    if (!doneP) posPy += offNPy * P_[k];
  }

  float dstN = posMx - posNx;
  float dstP = posPx - posMx;
  if (!horzSpan) dstN = posMy - posNy;
  if (!horzSpan) dstP = posPy - posMy;

  const bool goodSpanN = (lumaEndN < 0.0f) != lumaMLTZero;
  const float spanLength = (dstP + dstN);
  const bool goodSpanP = (lumaEndP < 0.0f) != lumaMLTZero;
  const float spanLengthRcp = 1.0f / spanLength;

  const bool directionN = dstN < dstP;
  const float dst = std::min(dstN, dstP);
  const bool goodSpan = directionN ? goodSpanN : goodSpanP;
  const float subpixG = subpixF * subpixF;
  const float pixelOffset = glsl ? (-dst / spanLength) + 0.5f : (dst * (-spanLengthRcp)) + 0.5f;
  const float subpixH = subpixG * prm.subpix;

  const float pixelOffsetGood = goodSpan ? pixelOffset : 0.0f;
  const float pixelOffsetSubpix = std::max(pixelOffsetGood, subpixH);
  if (!horzSpan) posMx += pixelOffsetSubpix * lengthSign;
  if (horzSpan) posMy += pixelOffsetSubpix * lengthSign;
  float rgb[3];
  FinalTap(src, posMx, posMy, rgb);  // tex.SampleNormalized(posMx, posMy).rgb
  ++taps;
  out[0] = QuantizeFast(rgb[0]);
  out[1] = QuantizeFast(rgb[1]);
  out[2] = QuantizeFast(rgb[2]);
  out[3] = 255;
  return taps;
}


template <typename P>
Image8 Fxaa311Fast(const Image8& in, const Fxaa311Params& params, PostStats* stats) {
  LumaPlane<P> plane;
  BuildPlane(in, params.luma, &plane);
  ExitTable exit_table;
  if constexpr (std::is_same_v<P, uint8_t>) exit_table = MakeExitTable(params.edge_threshold, params.edge_threshold_min);
  const int w = in.Width();
  const int h = in.Height();
  const float rcpX = 1.0f / static_cast<float>(w);
  const float rcpY = 1.0f / static_cast<float>(h);
  Image8 out(w, h, 4);
  constexpr int kGrain = 8;
  std::vector<uint64_t> taps(static_cast<size_t>((h + kGrain - 1) / kGrain), 0);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    BilinearSampler tex(in);  // rgb taps: the prepared frame's rgb is the input's rgb
    thread_local std::vector<uint8_t> edge;
    if (edge.size() < static_cast<size_t>(w)) edge.resize(static_cast<size_t>(w));
    uint64_t chunk_taps = 0;
    for (int y = y0; y < y1; ++y) {
      // Every pixel first as the early exit writes it: input rgb, alpha 255.
      uint8_t* orow = out.Row(y);
      CopyRowOpaque(in.Row(y), orow, w);
      int edges;
      if constexpr (std::is_same_v<P, uint8_t>) {
        edges = ContrastRowBytes(plane, y, exit_table, edge.data());
      } else {
        edges = ContrastRow(plane, y, params.edge_threshold, params.edge_threshold_min, edge.data());
      }
      chunk_taps += 5 * static_cast<uint64_t>(w - edges);
      if (edges == 0) continue;
      for (int x = 0; x < w; ++x) {
        if ((x & 7) == 0 && x + 8 <= w) {  // skip 8 pixels at a time when none is an edge
          uint64_t word;
          std::memcpy(&word, edge.data() + x, 8);
          if (word == 0) {
            x += 7;
            continue;
          }
        }
        if (!edge[x]) continue;
        chunk_taps += EdgePixel(plane, tex, in, x, y, params, rcpX, rcpY, orow + 4 * x);
      }
    }
    taps[static_cast<size_t>(y0 / kGrain)] = chunk_taps;
  });
  if (stats) {
    for (uint64_t t : taps) stats->taps += t;
  }
  return out;
}

}  // namespace

Image8 Fxaa311(const Image8& in, const Fxaa311Params& params, PostStats* stats) {
  AALAB_CHECK(in.Channels() == 4, "FXAA needs an RGBA8 frame");
  AALAB_CHECK(params.steps.size() >= 2, "FXAA 3.11 needs at least two search steps");
  if (in.Empty()) return in;
  if (params.luma == Luma::kRec601Rgb) return Fxaa311Fast<float>(in, params, stats);
  return Fxaa311Fast<uint8_t>(in, params, stats);
}

}  // namespace aalab
