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

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "methods/fxaa311.h"
#include "methods/fxaa311_plane.h"
#include "methods/fxaa311_rows.h"
#include "methods/fxaa311_search.h"
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
//      The 8-bit rows are computed in SSE2 / AVX2 with the pre-pass's float operations
//      (methods/fxaa311_rows.cpp).
//   2. The early-exit contrast test over whole rows, 16 pixels at a time on 8-bit lumas
//      (SSE2: max − min of N, W, M, E, S against the largest difference that always exits;
//      only the pixels above it look up the shader's decision in a table), listing the
//      candidates (edge pixels and near ties) per chunk of rows. Pixels that exit (and the
//      range = 0 pixels, see above) copy the input; the output row is first written as a
//      copy, so only edge pixels are touched again.
//   3. Only the listed pixels run the rest of the shader (EdgePixel below: ShadePixel's
//      statements from the corner fetches on, with the same luma values), in a function
//      built for AVX2 and the baseline (EdgeList; the same IEEE operations, no FMA). On the
//      8-bit plane with AVX2 they go eight at a time, one per lane (EdgeListX8,
//      methods/fxaa311_search.cpp: the same operations per lane, so the same bits and taps),
//      the input texels of their final taps and their output pixels prefetched ahead.
// The 3x3 taps are fetched where the shader fetches them, a hair off the texel centres in
// many columns and rows (methods/fxaa311_plane.h, TapGrid): step 2 decides those pixels from
// texel lumas unless the test is within the taps' deviation of a tie, and then with the real
// taps; step 3 filters them like the reference.
// Steps 1 and 2 run as one parallel pass over chunks of rows (issue #41): a chunk writes its
// plane rows, tests them and copies its output rows while the input rows are in cache (the
// rows just outside the chunk are recomputed locally: a neighbour may not have written them
// yet). Near ties (which read taps around the pixel) and step 3 (whose search reads plane
// rows anywhere) wait for a second pass, when the whole plane exists.
// Tap counts are those of the reference: 5 for a pixel that exits, 9 + search + final
// for an edge pixel. Tests compare this path with Fxaa311Reference bit for bit on real
// and adversarial frames (tests/equivalence/fxaa_fast_test.cpp).

namespace {
using namespace fxaa311_internal;

// One row of the luma plane for the mode (step 1): `p` is an input row, `o` receives w lumas.
inline void PlaneRow(const uint8_t* p, int w, Luma luma, uint8_t* o) { PlaneRow8(p, w, luma, o); }
inline void PlaneRow(const uint8_t* p, int w, Luma, float* o) { PlaneRowF(p, w, o); }  // kRec601Rgb

// Step 2: edge[x] = 1 where the pixel passes the early exit and has range > 0. max/min are
// exact, so their nesting does not matter; k -> UnormToFloat(k) is increasing, so the max
// (min) of the lumas is the luma of the max (min) byte.
// True when the test range < max(thr_min, rangeMax·thr) on texel lumas is within `margin`
// of flipping: taps that deviate by d from the texels move range by <= 2d and the clamped
// threshold by <= d·thr, so margin = 3·deviation covers them.
inline bool NearTie(float range_max, float range, float thr, float thr_min, float margin) {
  const float clamped = std::max(thr_min, range_max * thr);
  return std::fabs(range - clamped) <= margin;
}

// Mark of a pixel in step 2's edge row: exits, goes on to the search, or must be decided with
// the real taps (EdgeByTaps) once every plane row exists.
constexpr uint8_t kExit = 0, kEdge = 1, kTie = 2;

// A pixel step 2 did not mark kExit: its position and mark (kEdge or kTie). Pass 1 lists a
// chunk's candidates in row order; pass 2 visits only them.
struct Candidate {
  int x, y;
  uint8_t mark;
};

// The plane rows around row y: north, middle, south (clamped at the frame's border).
template <typename P>
struct RowTriple {
  const P* n;
  const P* m;
  const P* s;
};

// Step 2 for one row of float lumas (rec601-rgb): appends the pixels not marked kExit to
// `out`. Pixels whose taps are off the texel centres and whose texel-luma test is a near tie
// (NearTie) are marked kTie.
void ContrastRow(RowTriple<float> r, int w, const TapGrid& g, int y, const Fxaa311Params& prm, float margin,
                 std::vector<Candidate>& out) {
  const float thr = prm.edge_threshold, thr_min = prm.edge_threshold_min;
  const bool row_exact = g.rows[y].exact;
  const float *rn = r.n, *rm = r.m, *rs = r.s;
  for (int x = 0; x < w; ++x) {
    const float n = rn[x], m = rm[x], s = rs[x], wv = rm[std::max(x - 1, 0)], e = rm[std::min(x + 1, w - 1)];
    const float mx = std::max(std::max(n, wv), std::max(m, std::max(e, s)));
    const float mn = std::min(std::min(n, wv), std::min(m, std::min(e, s)));
    const float range = mx - mn;
    const float clamped = std::max(thr_min, mx * thr);
    uint8_t mark = kExit;
    if (!(row_exact && g.cols[x].exact) && NearTie(mx, range, thr, thr_min, margin)) {
      mark = kTie;
    } else {
      mark = (range < clamped || range == 0.0f) ? kExit : kEdge;
    }
    if (mark != kExit) out.push_back({x, y, mark});
  }
}

// The early-exit decision for 8-bit lumas depends only on the (max, min) byte pair: a
// 256×256 table evaluated with the shader's float expressions, plus the largest byte
// difference `safe` for which every pair exits (so a vectorised max − min <= safe test
// settles most pixels without the table).
struct ExitTable {
  std::vector<uint8_t> edge;  // [max·256 + min] = 1 when the pixel goes on to the search
  std::vector<uint8_t> near;  // [max·256 + min] = 1 when taps off the texel centres by up to
                              // `margin` could flip the decision (see TapGrid)
  int safe = -1;              // max − min <= safe always exits and is never a near tie
};

ExitTable MakeExitTable(float thr, float thr_min, float margin) {
  ExitTable t;
  t.edge.assign(256 * 256, 0);
  t.near.assign(256 * 256, 0);
  int safe = 255;
  for (int mx = 0; mx < 256; ++mx) {
    for (int mn = 0; mn <= mx; ++mn) {
      const float range_max = LumaValue(static_cast<uint8_t>(mx));
      const float range = range_max - LumaValue(static_cast<uint8_t>(mn));
      const float clamped = std::max(thr_min, range_max * thr);
      const bool exit = range < clamped || range == 0.0f;
      t.edge[mx * 256 + mn] = exit ? 0 : 1;
      t.near[mx * 256 + mn] = NearTie(range_max, range, thr, thr_min, margin) ? 1 : 0;
      if (!exit || t.near[mx * 256 + mn]) safe = std::min(safe, mx - mn - 1);
    }
  }
  t.safe = safe;
  return t;
}

// Step 2 for one row of 8-bit lumas, through the table: appends the pixels not marked kExit
// to `out`. Pixels whose taps are off the texel centres and whose byte pair is a near tie are
// marked kTie; near-tie pairs are always candidates (ExitTable::safe). The interior goes 16
// pixels at a time (SSE2): max − min of the five bytes against `safe`, and only the pixels
// above it look up the table.
void ContrastRowBytes(RowTriple<uint8_t> r, int w, const TapGrid& g, int y, const ExitTable& tab,
                      std::vector<Candidate>& out) {
  const bool row_exact = g.rows[y].exact;
  const uint8_t *rn = r.n, *rm = r.m, *rs = r.s;
  auto mark = [&](int x) {
    const uint8_t n = rn[x], wv = rm[std::max(x - 1, 0)], m = rm[x], e = rm[std::min(x + 1, w - 1)], s = rs[x];
    const uint8_t mx = std::max(std::max(n, wv), std::max(m, std::max(e, s)));
    const uint8_t mn = std::min(std::min(n, wv), std::min(m, std::min(e, s)));
    uint8_t k = tab.edge[mx * 256 + mn];
    if (tab.near[mx * 256 + mn] && !(row_exact && g.cols[x].exact)) k = kTie;
    if (k != kExit) out.push_back({x, y, k});
  };
  if (tab.safe < 0 || w <= 2) {  // every pixel is a candidate
    for (int x = 0; x < w; ++x) mark(x);
    return;
  }
  mark(0);
  int x = 1;
#if defined(__SSE2__)
  const __m128i safe = _mm_set1_epi8(static_cast<char>(tab.safe));
  const __m128i zero = _mm_setzero_si128();
  auto load = [](const uint8_t* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); };
  for (; x + 16 <= w - 1; x += 16) {
    const __m128i n = load(rn + x), s = load(rs + x), m = load(rm + x), l = load(rm + x - 1), e = load(rm + x + 1);
    const __m128i mx = _mm_max_epu8(_mm_max_epu8(n, l), _mm_max_epu8(m, _mm_max_epu8(e, s)));
    const __m128i mn = _mm_min_epu8(_mm_min_epu8(n, l), _mm_min_epu8(m, _mm_min_epu8(e, s)));
    // max − min > safe  <=>  (max − min) −sat safe != 0
    const __m128i over = _mm_subs_epu8(_mm_sub_epi8(mx, mn), safe);
    unsigned bits = ~static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(over, zero))) & 0xFFFFu;
    while (bits != 0) {
      mark(x + std::countr_zero(bits));
      bits &= bits - 1;
    }
  }
#endif
  for (; x < w - 1; ++x) {
    const uint8_t mx = std::max(std::max(rn[x], rm[x - 1]), std::max(rm[x], std::max(rm[x + 1], rs[x])));
    const uint8_t mn = std::min(std::min(rn[x], rm[x - 1]), std::min(rm[x], std::min(rm[x + 1], rs[x])));
    if (mx - mn > tab.safe) mark(x);
  }
  mark(w - 1);
}

// Pass 2 reads a candidate's input texels (the final tap, rows y − 1 .. y + 1) and plane rows
// long after pass 1 streamed them: they are fetched kPrefetch candidates ahead.
constexpr size_t kPrefetch = 8;
template <typename P>
[[gnu::always_inline]] inline void Prefetch(const Image8& in, const LumaPlane<P>& pl, const Candidate& c) {
  const int ya = std::max(c.y - 1, 0), yb = std::min(c.y + 1, in.Height() - 1);
  __builtin_prefetch(in.Row(ya) + 4 * c.x);
  __builtin_prefetch(in.Row(c.y) + 4 * c.x);
  __builtin_prefetch(in.Row(yb) + 4 * c.x);
  __builtin_prefetch(pl.Row(ya) + c.x);
  __builtin_prefetch(pl.Row(yb) + c.x);
}

// The input texels around (x, y) that the final tap reads (rows y − 1 .. y + 1) and the
// output pixel it writes (pass 1 wrote it long before). EdgeListX8
// fetches them kPrefetchX8 candidates ahead: three batches, since a batch's final taps come
// after its whole search.
// Forced inline: GCC 12 finds a function whose only statements are prefetches `const` and
// drops calls to it (no prefetch instruction was left in this file before).
constexpr size_t kPrefetchX8 = 24;
[[gnu::always_inline]] inline void PrefetchInput(const Image8& in, Image8& out, int x, int y) {
  const int ya = std::max(y - 1, 0), yb = std::min(y + 1, in.Height() - 1);
  __builtin_prefetch(in.Row(ya) + 4 * x);
  __builtin_prefetch(in.Row(y) + 4 * x);
  __builtin_prefetch(in.Row(yb) + 4 * x);
  __builtin_prefetch(out.Row(y) + 4 * x, 1);  // the pixel's output, for writing
}

// ShadePixel for a pixel that passed the early exit with range > 0, lumas from the plane.
// Statement order and float expressions are ShadePixel's; returns the taps it took.
template <typename P>
[[gnu::always_inline]] inline uint64_t EdgePixel(const LumaPlane<P>& pl, const TapGrid& grid, BilinearSampler& tex,
                                                 const Image8& src, int x, int y, const Fxaa311Params& prm, float rcpX,
                                                 float rcpY, uint8_t* out) {
  const bool glsl = prm.order == Order::kSeed003Glsl;
  const bool rgb_taps = prm.luma == Luma::kRec601Rgb;  // bilinear lumas need filtered rgb
  const std::vector<float>& P_ = prm.steps;
  auto tap = [&](float s, float t) __attribute__((always_inline)) {
    return rgb_taps ? Fxaa311TapLuma(tex.SampleNormalized(s, t), prm.luma) : pl.Bilinear(s, t);
  };
  uint64_t taps = 9;
  const int W = pl.w, H = pl.h;
  float posMx = (static_cast<float>(x) + 0.5f) / static_cast<float>(W);
  float posMy = (static_cast<float>(y) + 0.5f) / static_cast<float>(H);
  const TapAxis& cx = grid.cols[x];
  const TapAxis& ry = grid.rows[y];
  auto L = [&](int dx, int dy) __attribute__((always_inline)) {
    return TapLuma(pl, src, cx, ry, x, y, dx, dy, prm.luma);
  };
  const float lumaM = L(0, 0);
  float lumaS = L(0, 1);
  float lumaE = L(1, 0);
  float lumaN = L(0, -1);
  float lumaW = L(-1, 0);
  const float rangeMax = std::max(std::max(lumaN, lumaW), std::max(lumaE, std::max(lumaS, lumaM)));
  const float rangeMin = std::min(std::min(lumaN, lumaW), std::min(lumaE, std::min(lumaS, lumaM)));
  const float range = rangeMax - rangeMin;

  const float lumaNW = L(-1, -1);
  const float lumaSE = L(1, 1);
  const float lumaNE = L(1, -1);
  const float lumaSW = L(-1, 1);

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
  out[0] = StoreUnorm8(rgb[0]);
  out[1] = StoreUnorm8(rgb[1]);
  out[2] = StoreUnorm8(rgb[2]);
  out[3] = 255;
  return taps;
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_FXAA311_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define AALAB_FXAA311_CLONES
#endif

// Pass 2 over one chunk's candidates: near ties decided with the real taps, then EdgePixel
// for the edge pixels. Returns the taps and adds the edge pixels to *edges. Built twice
// (AVX2 and the baseline, chosen at run time): the AVX2 clone rounds floor() in one
// instruction (roundss); both run the same IEEE operations (no FMA: -ffp-contract=off), so
// the bits are the same.
template <typename P>
AALAB_FXAA311_CLONES uint64_t EdgeList(const std::vector<Candidate>& list, const LumaPlane<P>& plane,
                                       const TapGrid& grid, BilinearSampler& tex, const Image8& in,
                                       const Fxaa311Params& params, float rcpX, float rcpY, Image8& out,
                                       uint64_t* edges) {
  uint64_t taps = 0;
  for (size_t i = 0; i < list.size(); ++i) {
    const Candidate& c = list[i];
    if (i + kPrefetch < list.size()) Prefetch(in, plane, list[i + kPrefetch]);
    if (c.mark == kTie && !EdgeByTaps(plane, in, grid, c.x, c.y, params)) continue;
    ++*edges;
    taps += EdgePixel(plane, grid, tex, in, c.x, c.y, params, rcpX, rcpY, out.Row(c.y) + 4 * c.x);
  }
  return taps;
}

// EdgeList on the 8-bit plane with EdgePixelsX8: the edge pixels go through the shader eight
// at a time (methods/fxaa311_search.cpp; same bits, same taps). Near ties are decided first,
// one by one, as above.
uint64_t EdgeListX8(const std::vector<Candidate>& list, const LumaPlane<uint8_t>& plane, const TapGrid& grid,
                    const Image8& in, const Fxaa311Params& params, float rcpX, float rcpY, Image8& out,
                    uint64_t* edges) {
  uint64_t taps = 0;
  int xs[8], ys[8], n = 0;
  for (size_t i = 0; i < list.size(); ++i) {
    const Candidate& c = list[i];
    if (i + kPrefetchX8 < list.size()) PrefetchInput(in, out, list[i + kPrefetchX8].x, list[i + kPrefetchX8].y);
    if (c.mark == kTie && !EdgeByTaps(plane, in, grid, c.x, c.y, params)) continue;
    ++*edges;
    xs[n] = c.x;
    ys[n] = c.y;
    if (++n == 8) {
      taps += EdgePixelsX8(plane, in, xs, ys, n, params, rcpX, rcpY, out);
      n = 0;
    }
  }
  if (n > 0) taps += EdgePixelsX8(plane, in, xs, ys, n, params, rcpX, rcpY, out);
  return taps;
}

template <typename P>
Image8 Fxaa311Fast(const Image8& in, const Fxaa311Params& params, PostStats* stats) {
  const int w = in.Width();
  const int h = in.Height();
  const TapGrid grid = MakeTapGrid(w, h, params.order == Order::kSeed003Glsl);
  // Early-exit pixels are written as a copy of the input: the shader returns its centre
  // tap, whose stored bytes are the input's while 255·deviation stays well below 1/2, and
  // near-tie detection needs the deviation far below one 8-bit step. Both hold up to about
  // 10000 pixels a side (the deviation grows with the size); beyond, the reference runs.
  if (255.0f * grid.deviation > 0.25f) return Fxaa311Reference(in, params, stats);
  const float margin = 3.0f * grid.deviation;
  LumaPlane<P> plane;
  plane.w = w;
  plane.h = h;
  // Every row written by pass 1; the 8-bit plane's kPlanePad bytes after the end (read, not
  // used, by EdgePixelsX8's gathers) are zeroed.
  plane.v.reset(new P[static_cast<size_t>(w) * h + kPlanePad]);
  std::fill_n(plane.v.get() + static_cast<size_t>(w) * h, kPlanePad, P{0});
  bool x8 = false;
  if constexpr (std::is_same_v<P, uint8_t>) {
    x8 = EdgePixelsX8Available() && static_cast<size_t>(w) * h + kPlanePad < (size_t{1} << 31);
  }
  ExitTable exit_table;
  if constexpr (std::is_same_v<P, uint8_t>) {
    exit_table = MakeExitTable(params.edge_threshold, params.edge_threshold_min, margin);
  }
  const float rcpX = 1.0f / static_cast<float>(w);
  const float rcpY = 1.0f / static_cast<float>(h);
  Image8 out(w, h, 4, kUninitialized);  // every row written whole by pass 1 (CopyRowOpaque)
  // 16 rows a chunk: pass 1 computes the two plane rows around a chunk again (1/8 more plane
  // work; 1/4 with 8 rows), and 68 chunks of a 1080-row frame still balance two threads.
  constexpr int kGrain = 16;
  // Step 2's candidates (kEdge / kTie) per chunk of rows, in row order.
  std::vector<std::vector<Candidate>> candidates(static_cast<size_t>((h + kGrain - 1) / kGrain));
  // Pass 1 (steps 1 and 2 fused): a chunk's plane rows, its contrast test and the early exit's
  // copy while the input rows are in cache. The rows just above and below the chunk belong to
  // other chunks that may not have written them yet: they are computed here too (same bytes).
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    thread_local std::vector<P> above, below;
    if (above.size() < static_cast<size_t>(w)) above.resize(static_cast<size_t>(w));
    if (below.size() < static_cast<size_t>(w)) below.resize(static_cast<size_t>(w));
    P* pv = plane.v.get();
    auto prow = [&](int y) { return pv + static_cast<size_t>(y) * w; };
    for (int y = y0; y < y1; ++y) PlaneRow(in.Row(y), w, params.luma, prow(y));
    const P* row_above = prow(0);
    if (y0 > 0) {
      PlaneRow(in.Row(y0 - 1), w, params.luma, above.data());
      row_above = above.data();
    }
    const P* row_below = prow(h - 1);
    if (y1 < h) {
      PlaneRow(in.Row(y1), w, params.luma, below.data());
      row_below = below.data();
    }
    std::vector<Candidate>& list = candidates[static_cast<size_t>(y0 / kGrain)];
    for (int y = y0; y < y1; ++y) {
      // Every pixel first as the early exit writes it: input rgb, alpha 255.
      CopyRowOpaque(in.Row(y), out.Row(y), w);
      const RowTriple<P> r{y == y0 ? row_above : prow(y - 1), prow(y), y == y1 - 1 ? row_below : prow(y + 1)};
      if constexpr (std::is_same_v<P, uint8_t>) {
        ContrastRowBytes(r, w, grid, y, exit_table, list);
      } else {
        ContrastRow(r, w, grid, y, params, margin, list);
      }
    }
  });
  // Pass 2 (step 3), with the whole plane: near ties decided with the real taps, then the
  // edge pixels' search, for the listed candidates only. The shader takes 5 taps at every
  // pixel that exits.
  std::vector<uint64_t> taps(candidates.size(), 0);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    BilinearSampler tex(in);  // rgb taps: the prepared frame's rgb is the input's rgb
    uint64_t chunk_taps = 0, edges = 0;
    const std::vector<Candidate>& list = candidates[static_cast<size_t>(y0 / kGrain)];
    if constexpr (std::is_same_v<P, uint8_t>) {
      if (x8) {
        chunk_taps += EdgeListX8(list, plane, grid, in, params, rcpX, rcpY, out, &edges);
      } else {
        chunk_taps += EdgeList(list, plane, grid, tex, in, params, rcpX, rcpY, out, &edges);
      }
    } else {
      chunk_taps += EdgeList(list, plane, grid, tex, in, params, rcpX, rcpY, out, &edges);
    }
    chunk_taps += 5 * (static_cast<uint64_t>(y1 - y0) * static_cast<uint64_t>(w) - edges);
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
  if (params.sampler != SamplerArithmetic::kGl) return Fxaa311Reference(in, params, stats);  // no fast path
  if (params.luma == Luma::kRec601Rgb) return Fxaa311Fast<float>(in, params, stats);
  return Fxaa311Fast<uint8_t>(in, params, stats);
}

}  // namespace aalab
