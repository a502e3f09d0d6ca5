// FXAA 3.11 Quality (PC) — one implementation driven by a step table.
//
// Implements Timothy Lottes' FxaaPixelShader, FXAA_PC 1 quality path (Fxaa3_11.h, 2011-08-12),
// statement by statement in float32 and in the shader's order, with the search unrolled as
// a loop over the step table P0..P(n-1). Methods (all post-only, on the 1x 8-bit frame):
//
//   fxaa311-p10 .. -p15, -p20 .. -p29, -p39   the quality presets (FXAA_QUALITY__PRESET),
//                  step tables exactly as the shader #defines them; luma default rec601.
//   fxaa-low / fxaa-medium / fxaa-high         the Catlike Coding tutorial's three levels
//                  (first step 1, EDGE_STEP_SIZES, LAST_EDGE_STEP_GUESS); luma default
//                  sqrt-luminance (stored in alpha at 8 bits, as the tutorial's default
//                  "FXAA With Luma" pass does).
//   fxaa-iter12    seed 003's GLSL "FXAA with 12 iterations": preset 39's steps, edge
//                  threshold 0.125, min 0.0312, subpix 0.75, luma from rgb at every tap,
//                  evaluated in that GLSL's float order.
//
// Parameters (every method; defaults per method, as listed by `aalab list`):
//   subpix              [0..1]  0.75    fxaaQualitySubpix
//   edge_threshold      [0..1]  0.166   fxaaQualityEdgeThreshold   (iter12: 0.125)
//   edge_threshold_min  [0..1]  0.0833  fxaaQualityEdgeThresholdMin (iter12: 0.0312)
//   luma  {rec601|rec601-rgb|green|sqrt-luminance}
//         rec601 = FXAA_GREEN_AS_LUMA 0 (dot(rgb,(0.299,0.587,0.114)) written to alpha at 8
//         bits by a first pass, GL store rounding); rec601-rgb = the same dot computed from each tap's rgb in
//         float (seed 003); green = FXAA_GREEN_AS_LUMA 1; sqrt-luminance = the tutorial's
//         sqrt(Luminance(linear rgb)) written to alpha at 8 bits.
//         Fxaa3_11.h suggests edge_threshold_min near 0 with green luma ("colors that are
//         mostly not-green will appear very dark"); defaults do not change with `luma`.
//
// Sources:
//   seeds/004 (FrostKiwi, "Analytical Anti-Aliasing", section "FXAA", files post-FXAA.fs and
//     FXAA-interactive.fs): the full FXAA 3.11 PC quality shader and presets 10–39. This file
//     follows FXAA-interactive.fs line by line.
//   seeds/000 (Catlike Coding, Custom SRP 17 "FXAA"): sections 1.3–1.6 (luma), 2 (subpixel
//     blending, thresholds 0.0833/0.166, subpixel 0.75), 3.7 (edge quality low/medium/high).
//   seeds/003 (FXAA notes with a complete GLSL FXAA, ITERATIONS 12, QUALITY(q) macro).
//
// Fidelity and deviations (read with the shader open):
//   * Taps. Every tap is a bilinear fetch, as in the shader text we verify against. Seed 004's
//     GLSL writes FxaaTexTop / FxaaTexOff as texture2D(tex, posM + vec2(off) * rcpFrame), so
//     the centre and its 8 neighbours are fetched at normalised coordinates rounded to float;
//     u·W − 0.5 then often lands ~1e-6 off the texel centre (about 40% of the columns of a
//     1920-wide frame) and a float32 filter mixes in that much of the next texel. Seed 003
//     uses textureLodOffset: the offset is added to u·W in float before −0.5 (llvmpipe's
//     rule). Search taps and the final tap are fetches at the shader's coordinates.
//     Filtering is BilinearSampler's (core/sampler.h): llvmpipe's float32 path,
//     bit for bit. A GPU's 8-bit sub-texel weights differ (see docs/fxaa-fidelity.md).
//   * posM, the "{xy} = center of pixel" input, is ((x+0.5)/W, (y+0.5)/H) rounded to float;
//     fxaaQualityRcpFrame is (1/W, 1/H) rounded to float. Every position update
//     (posB, posN, posP, the final posM) is the shader's, in normalised coordinates.
//   * Float order: the shader's statements in its order, no FMA contraction (the build uses
//     -ffp-contract=off). A GPU compiler may fuse a*b+c into one rounding; intermediates can
//     then differ in the last bit, which flips a decision only where the compared values
//     are within a few ulps of each other (ties in exact arithmetic, see below).
//   * Tie-breaks are the shader's: early exit on range < max(min, rangeMax*threshold)
//     (strict); horzSpan = edgeHorz >= edgeVert; pairN = |gradientN| >= |gradientS|;
//     doneN/doneP = |lumaEnd| >= gradientScaled; directionN = dstN < dstP (a tie takes P,
//     but a tie also gives pixelOffset = 0.5 - dst/(2·dst) = 0, so it never shows).
//     These rules decide float-equal values. Lumas k·fl(1/255) are not dyadic, so sums that tie
//     in exact arithmetic often differ in the last bit and rounding decides; that is why
//     the statement order is kept (seed 003's order of the edgeHorz/edgeVert sums decides
//     ~1% of the pixels of a noise image differently; see the tests).
//     The tutorial breaks the pairN tie differently for vertical spans (it prefers east,
//     "if (gradientP < gradientN)" with P = east; FXAA 3.11 prefers west): fxaa-low/medium/
//     high use FXAA 3.11's rule.
//   * Division by zero: subpixRcpRange = 1/range is reached with range = 0 only when
//     edge_threshold_min = 0 and rangeMax·edge_threshold = 0 (a black cross, or threshold 0).
//     The shader would then compute |subpixB|·inf (inf → subpixC 1, or NaN when subpixB = 0,
//     whose clamp is undefined in GLSL/HLSL). We return the input pixel there. With IEEE
//     min/max the shader would blend M with a neighbour of equal luma; that differs from
//     ours only when that neighbour has the same luma but another colour.
//   * Output: the shader returns (filtered rgb, lumaM) into an RGBA8 target; we store rgb with
//     GL's float-to-UNORM conversion (StoreUnorm8: round to nearest, ties to even, as
//     llvmpipe) and alpha 255. Early exit returns the centre tap rgbyM, stored the same way
//     (it equals the input bytes: the tap is at most ~1e-6 off the texel).
//   * Verified: tests/oracle runs seed 004's FXAA-interactive.fs and seed 003's GLSL on
//     llvmpipe (float32 filtering, no FMA) and compares every preset byte for byte
//     (docs/fxaa-fidelity.md). The luma pre-pass is ours; the oracle is given its alpha.
//   * Colour space: taps read the sRGB-encoded 8-bit values as UNORM and filter them (docs/design.md,
//     "Sampling conventions": post filters run on encoded values). The tutorial samples an sRGB texture, so its GPU
//     filters rgb in linear light; its luma lives in alpha, which is never decoded.
//   * sqrt-luminance uses Unity's Luminance() weights (0.2126729, 0.7151522, 0.0721750; the
//     Y row of the sRGB/Rec.709 primaries), which the tutorial calls; stored in alpha at 8
//     bits because the tutorial's default (Keep Alpha off) computes it once in the colour
//     grading pass into the 8-bit alpha of the intermediate texture. It does not compute it
//     per tap (its per-tap GetLuma was an intermediate step of section 1.3).
//   * The tutorial (seed 000) vs FXAA 3.11: same equations; it divides by range instead of
//     multiplying by 1/range, sums its lowpass in another order and searches the two
//     directions in separate loops (same taps and results as the lock-step search). Its
//     medium level is called "preset 26" in the text, but its numbers (1.5, 2×6, 4; guess 8)
//     give preset 27's table; the English text's second listing of MEDIUM has 9 sizes for
//     EXTRA_EDGE_STEPS 8 (seed 001, the Chinese copy, has the 8 of the first listing). We
//     use the 8-size listing, as docs/design.md does.
//   * seed 003's GLSL vs preset 39: QUALITY(q) = 1,1,1,1,1,1.5,2,2,2,2,4,8 for q = 0..11 and
//     the loop fetches at i = 1..11 after advancing by QUALITY(i-1), then advances by
//     QUALITY(i): exactly preset 39's table (11 fetches per side, the last step a guess).
//     Its thresholds are 0.125 / 0.0312 (not 3.11's defaults). Its luma is computed from
//     each tap's rgb (no alpha pass). Its maths equals FXAA 3.11's, but five expressions
//     round differently; Order::kSeed003Glsl reproduces them:
//       edgeHorz = (|H3| + 2|H1|) + |H2|              (3.11: |H3| + (2|H1| + |H2|)), same Vert
//       lowpass  = (1/12)·((2(NS+WE) + NWSW) + NESE)  (3.11: (2(NS+WE) + (NWSW+NESE))·(1/12))
//       subpixC  = |lowpass - M| / range              (3.11: |.|·(1/range))
//       smooth   = ((-2c+3)·c)·c                      (3.11: (-2c+3)·(c·c))
//       offset   = -dst / spanLength + 0.5            (3.11: dst·(-(1/spanLength)) + 0.5)
//     Its "lumaCenter < lumaLocalAverage" equals 3.11's "lumaM - lumaNN·0.5 < 0" exactly.
//     Orientation: its Down/Up/Left/Right are texel offsets (0,-1)/(0,1)/(-1,0)/(1,0), i.e.
//     3.11's N/S/W/E, so its ">=" tie-breaks pick the same texels as 3.11.
#include "methods/fxaa311.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <type_traits>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "methods/families.h"

namespace aalab {

namespace {

using Luma = Fxaa311Params::Luma;
using Order = Fxaa311Params::Order;

const std::map<int, std::vector<float>>& PresetTable() {
  // Fxaa3_11.h "FXAA QUALITY - MEDIUM DITHER PRESETS" (10–15), "LOW DITHER PRESETS"
  // (20–29) and "EXTREME QUALITY" (39): FXAA_QUALITY__P0 .. P(PS-1).
  static const std::map<int, std::vector<float>> table = {
      {10, {1.5f, 3.0f, 12.0f}},
      {11, {1.0f, 1.5f, 3.0f, 12.0f}},
      {12, {1.0f, 1.5f, 2.0f, 4.0f, 12.0f}},
      {13, {1.0f, 1.5f, 2.0f, 2.0f, 4.0f, 12.0f}},
      {14, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
      {15, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
      {20, {1.5f, 2.0f, 8.0f}},
      {21, {1.0f, 1.5f, 2.0f, 8.0f}},
      {22, {1.0f, 1.5f, 2.0f, 2.0f, 8.0f}},
      {23, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 8.0f}},
      {24, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 3.0f, 8.0f}},
      {25, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {26, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {27, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {28, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {29, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
      {39, {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
  };
  return table;
}

// Writes the input pixel's rgb (alpha 255): the shader's "return rgbyM".
void CopyPixel(const Image8& src, int x, int y, uint8_t* out) {
  const uint8_t* p = src.Pixel(x, y);
  out[0] = p[0];
  out[1] = p[1];
  out[2] = p[2];
  out[3] = 255;
}

// One invocation of FxaaPixelShader for pixel (x, y). Variable names are the shader's.
void ShadePixel(BilinearSampler& tex, const Image8& src, int x, int y, const Fxaa311Params& prm, float rcpX, float rcpY,
                uint8_t* out) {
  const Luma lm = prm.luma;
  const bool glsl = prm.order == Order::kSeed003Glsl;
  const std::vector<float>& P = prm.steps;
  auto L = [lm](const Float4& t) { return Fxaa311TapLuma(t, lm); };

  float posMx = (static_cast<float>(x) + 0.5f) / static_cast<float>(src.Width());
  float posMy = (static_cast<float>(y) + 0.5f) / static_cast<float>(src.Height());
  // The 3x3 taps as the shader writes them (see "Taps" above).
  auto tap = [&](int dx, int dy) {
    if (glsl) return tex.SampleNormalizedOffset(posMx, posMy, dx, dy);   // textureLodOffset
    return tex.SampleNormalized(posMx + static_cast<float>(dx) * rcpX,   // texture2D(tex,
                                posMy + static_cast<float>(dy) * rcpY);  //   posM + off·rcp)
  };
  const Float4 rgbyM = tap(0, 0);  // FxaaTexTop(tex, posM)
  const float lumaM = L(rgbyM);
  float lumaS = L(tap(0, 1));   // FxaaTexOff(tex, posM, ( 0, 1), rcp)
  float lumaE = L(tap(1, 0));   // ( 1, 0)
  float lumaN = L(tap(0, -1));  // ( 0,-1)
  float lumaW = L(tap(-1, 0));  // (-1, 0)

  const float maxSM = std::max(lumaS, lumaM);
  const float minSM = std::min(lumaS, lumaM);
  const float maxESM = std::max(lumaE, maxSM);
  const float minESM = std::min(lumaE, minSM);
  const float maxWN = std::max(lumaN, lumaW);
  const float minWN = std::min(lumaN, lumaW);
  const float rangeMax = std::max(maxWN, maxESM);
  const float rangeMin = std::min(minWN, minESM);
  const float rangeMaxScaled = rangeMax * prm.edge_threshold;
  const float range = rangeMax - rangeMin;
  const float rangeMaxClamped = std::max(prm.edge_threshold_min, rangeMaxScaled);
  const bool earlyExit = range < rangeMaxClamped;
  if (earlyExit) {  // return rgbyM
    out[0] = StoreUnorm8(rgbyM.r);
    out[1] = StoreUnorm8(rgbyM.g);
    out[2] = StoreUnorm8(rgbyM.b);
    out[3] = 255;
    return;
  }
  // Deviation (documented above): the shader would go on with subpixRcpRange = 1/0.
  if (range == 0.0f) {
    CopyPixel(src, x, y, out);
    return;
  }

  const float lumaNW = L(tap(-1, -1));
  const float lumaSE = L(tap(1, 1));
  const float lumaNE = L(tap(1, -1));
  const float lumaSW = L(tap(-1, 1));

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
    // seed 003: abs(-2*Left + LeftCorners) + abs(-2*Center + DownUp)*2 + abs(-2*Right + ...)
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
    // seed 003: (1.0/12.0) * (2.0*(lumaDownUp + lumaLeftRight) + lumaLeftCorners + lumaRightCorners)
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
  const float subpixC = std::min(std::max(subpixCIn, 0.0f), 1.0f);  // clamp(x, 0, 1)

  float posBx = posMx;
  float posBy = posMy;
  const float offNPx = (!horzSpan) ? 0.0f : rcpX;
  const float offNPy = (horzSpan) ? 0.0f : rcpY;
  if (!horzSpan) posBx += lengthSign * 0.5f;
  if (horzSpan) posBy += lengthSign * 0.5f;

  float posNx = posBx - offNPx * P[0];
  float posNy = posBy - offNPy * P[0];
  float posPx = posBx + offNPx * P[0];
  float posPy = posBy + offNPy * P[0];
  const float subpixD = ((-2.0f) * subpixC) + 3.0f;
  float lumaEndN = L(tex.SampleNormalized(posNx, posNy));
  const float subpixE = subpixC * subpixC;
  float lumaEndP = L(tex.SampleNormalized(posPx, posPy));

  if (!pairN) lumaNN = lumaSS;
  const float gradientScaled = gradient * 1.0f / 4.0f;
  const float lumaMM = lumaM - lumaNN * 0.5f;
  const float subpixF = glsl ? (subpixD * subpixC) * subpixC : subpixD * subpixE;
  const bool lumaMLTZero = lumaMM < 0.0f;

  lumaEndN -= lumaNN * 0.5f;
  lumaEndP -= lumaNN * 0.5f;
  bool doneN = std::fabs(lumaEndN) >= gradientScaled;
  bool doneP = std::fabs(lumaEndP) >= gradientScaled;
  if (!doneN) posNx -= offNPx * P[1];
  if (!doneN) posNy -= offNPy * P[1];
  bool doneNP = (!doneN) || (!doneP);
  if (!doneP) posPx += offNPx * P[1];
  if (!doneP) posPy += offNPy * P[1];

  // The shader's nested "if(doneNP) { ... }" blocks, one per step P2 .. P(n-1).
  for (size_t k = 2; k < P.size() && doneNP; ++k) {
    if (!doneN) lumaEndN = L(tex.SampleNormalized(posNx, posNy));
    if (!doneP) lumaEndP = L(tex.SampleNormalized(posPx, posPy));
    if (!doneN) lumaEndN = lumaEndN - lumaNN * 0.5f;
    if (!doneP) lumaEndP = lumaEndP - lumaNN * 0.5f;
    doneN = std::fabs(lumaEndN) >= gradientScaled;
    doneP = std::fabs(lumaEndP) >= gradientScaled;
    if (!doneN) posNx -= offNPx * P[k];
    if (!doneN) posNy -= offNPy * P[k];
    doneNP = (!doneN) || (!doneP);
    if (!doneP) posPx += offNPx * P[k];
    if (!doneP) posPy += offNPy * P[k];
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
  const Float4 c = tex.SampleNormalized(posMx, posMy);
  out[0] = StoreUnorm8(c.r);  // the RGBA8 render target's float-to-UNORM conversion
  out[1] = StoreUnorm8(c.g);
  out[2] = StoreUnorm8(c.b);
  out[3] = 255;
}

}  // namespace

const std::vector<std::string>& Fxaa311LumaNames() {
  static const std::vector<std::string> names = {"rec601", "rec601-rgb", "green", "sqrt-luminance"};
  return names;
}

Fxaa311Params::Luma ParseFxaa311Luma(const std::string& name) {
  if (name == "rec601") return Luma::kRec601;
  if (name == "rec601-rgb") return Luma::kRec601Rgb;
  if (name == "green") return Luma::kGreen;
  if (name == "sqrt-luminance") return Luma::kSqrtLuminance;
  throw UserError("unknown FXAA luma '" + name + "' (allowed: " + JoinNames(Fxaa311LumaNames()) + ")");
}

float Fxaa311TapLuma(const Float4& t, Fxaa311Params::Luma luma) {
  switch (luma) {
    case Luma::kRec601:
    case Luma::kSqrtLuminance: return t.a;
    case Luma::kGreen: return t.g;
    case Luma::kRec601Rgb: return t.r * 0.299f + (t.g * 0.587f + t.b * 0.114f);
  }
  return t.a;
}

Image8 Fxaa311LumaFrame(const Image8& in, Fxaa311Params::Luma luma, SamplerArithmetic sampler) {
  AALAB_CHECK(in.Channels() == 4, "FXAA needs an RGBA8 frame");
  Image8 out = in;
  if (luma != Luma::kRec601 && luma != Luma::kSqrtLuminance) return out;
  for (int y = 0; y < out.Height(); ++y) {
    uint8_t* row = out.Row(y);
    for (int x = 0; x < out.Width(); ++x) {
      uint8_t* p = row + 4 * x;
      float l = 0.0f;
      if (luma == Luma::kRec601) {
        // Fxaa3_11.h: "color.a = dot(color.rgb, FxaaFloat3(0.299, 0.587, 0.114))" on the
        // sRGB-encoded (perceptual) colour.
        const Float4 t{TexelValue(p[0], sampler), TexelValue(p[1], sampler), TexelValue(p[2], sampler), 0.0f};
        l = Fxaa311TapLuma(t, Luma::kRec601Rgb);
      } else {
        // Tutorial: color.a = sqrt(Luminance(color.rgb)) with linear rgb.
        const float r = SrgbDecode8(p[0]);
        const float g = SrgbDecode8(p[1]);
        const float b = SrgbDecode8(p[2]);
        l = std::sqrt((r * 0.2126729f + g * 0.7151522f) + b * 0.0721750f);
      }
      p[3] = StoreUnorm8(l);  // the pre-pass writes an RGBA8 target
    }
  }
  return out;
}

Image8 Fxaa311Reference(const Image8& in, const Fxaa311Params& params, PostStats* stats) {
  AALAB_CHECK(in.Channels() == 4, "FXAA needs an RGBA8 frame");
  AALAB_CHECK(params.steps.size() >= 2, "FXAA 3.11 needs at least two search steps");
  if (in.Empty()) return in;
  const bool prepass = params.luma == Luma::kRec601 || params.luma == Luma::kSqrtLuminance;
  Image8 prepared;
  if (prepass) prepared = Fxaa311LumaFrame(in, params.luma, params.sampler);
  const Image8& src = prepass ? prepared : in;

  const int w = src.Width();
  const int h = src.Height();
  const float rcpX = 1.0f / static_cast<float>(w);  // fxaaQualityRcpFrame.x
  const float rcpY = 1.0f / static_cast<float>(h);  // fxaaQualityRcpFrame.y
  Image8 out(w, h, 4);
  constexpr int kGrain = 8;
  std::vector<uint64_t> taps(static_cast<size_t>((h + kGrain - 1) / kGrain), 0);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    BilinearSampler tex(src, SubTexel::kExact, params.sampler);
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < w; ++x) ShadePixel(tex, src, x, y, params, rcpX, rcpY, out.Pixel(x, y));
    }
    taps[static_cast<size_t>(y0 / kGrain)] = tex.Taps();
  });
  if (stats) {
    for (uint64_t t : taps) stats->taps += t;
  }
  return out;
}

std::vector<int> Fxaa311PresetIds() {
  std::vector<int> ids;
  for (const auto& [id, steps] : PresetTable()) ids.push_back(id);
  return ids;
}

const std::vector<float>& Fxaa311PresetSteps(int preset) {
  const auto& t = PresetTable();
  auto it = t.find(preset);
  AALAB_CHECK(it != t.end(), "unknown FXAA 3.11 quality preset " + std::to_string(preset));
  return it->second;
}

const std::vector<float>& FxaaTutorialSteps(const std::string& level) {
  // seed 000, section 3.7: the first search step is 1 ("uvP = edgeUV + uvStep"), then
  // EDGE_STEP_SIZES, then LAST_EDGE_STEP_GUESS.
  static const std::vector<float> low = {1.0f, 1.5f, 2.0f, 2.0f, 8.0f};
  static const std::vector<float> medium = {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f};
  static const std::vector<float> high = {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f};
  if (level == "low") return low;
  if (level == "medium") return medium;
  if (level == "high") return high;
  throw InternalError("unknown FXAA tutorial level '" + level + "'");
}

Fxaa311Params FxaaTutorialHighParams() {
  Fxaa311Params p;
  p.steps = FxaaTutorialSteps("high");
  p.subpix = 0.75f;
  p.edge_threshold = 0.166f;
  p.edge_threshold_min = 0.0833f;
  p.luma = Luma::kSqrtLuminance;
  return p;
}

// ---------------------------------------------------------------------------------------
// Registry rows.

namespace {

std::vector<ParamDef> FxaaParamDefs(double thr, double thr_min, const std::string& luma) {
  return {
      FloatParam("subpix", 0.75, 0.0, 1.0,
                 "sub-pixel aliasing removal (fxaaQualitySubpix): 1 softer, 0.75 default, 0 off"),
      FloatParam("edge_threshold", thr, 0.0, 1.0,
                 "skip pixels whose luma range is below this fraction of the brightest luma "
                 "(fxaaQualityEdgeThreshold): 0.333 fast .. 0.063 overkill"),
      FloatParam("edge_threshold_min", thr_min, 0.0, 1.0,
                 "skip pixels whose luma range is below this absolute value, trims darks "
                 "(fxaaQualityEdgeThresholdMin): 0.0833 default .. 0.0312 visible limit"),
      ChoiceParam("luma", luma, Fxaa311LumaNames(),
                  "luma source: rec601 = dot(rgb,.299/.587/.114) in alpha at 8 bits; rec601-rgb "
                  "= same dot from each tap's rgb; green = green channel; sqrt-luminance = "
                  "sqrt(linear luminance) in alpha at 8 bits"),
  };
}

MethodPlan FxaaPlan(const std::string& name, const ParamValues& v, std::vector<float> steps, Order order) {
  Fxaa311Params fp;
  fp.steps = std::move(steps);
  fp.subpix = static_cast<float>(v.Number("subpix"));
  fp.edge_threshold = static_cast<float>(v.Number("edge_threshold"));
  fp.edge_threshold_min = static_cast<float>(v.Number("edge_threshold_min"));
  fp.luma = ParseFxaa311Luma(v.Choice("luma"));
  fp.order = order;
  MethodPlan plan;
  plan.name = name;
  plan.params = v;
  SetFxaa311Post(plan, fp);
  return plan;
}

std::string StepsText(const std::vector<float>& steps) {
  std::string s;
  float reach = 0.0f;
  for (float v : steps) {
    if (!s.empty()) s += " ";
    s += FormatNumber(v);
    reach += v;
  }
  return s + "; reach " + FormatNumber(reach) + " px";
}

MethodEntry FxaaEntry(const std::string& name, const std::string& help, std::vector<float> steps, double thr,
                      double thr_min, const std::string& luma, Order order) {
  return {name, help + " (steps " + StepsText(steps) + ")", FxaaParamDefs(thr, thr_min, luma),
          [name, steps, order](const ParamValues& v) { return FxaaPlan(name, v, steps, order); }};
}

}  // namespace

std::vector<MethodEntry> Fxaa311Methods() {
  std::vector<MethodEntry> out;
  for (int id : Fxaa311PresetIds()) {
    const char* kind = id < 20 ? "medium dither" : id < 30 ? "low dither" : "extreme quality";
    out.push_back(FxaaEntry("fxaa311-p" + std::to_string(id),
                            "FXAA 3.11 Quality preset " + std::to_string(id) + ", " + kind, Fxaa311PresetSteps(id),
                            0.166, 0.0833, "rec601", Order::kFxaa311));
  }
  out.push_back(FxaaEntry("fxaa-low", "FXAA 3.11, Catlike Coding tutorial low quality (= preset 22)",
                          FxaaTutorialSteps("low"), 0.166, 0.0833, "sqrt-luminance", Order::kFxaa311));
  out.push_back(FxaaEntry("fxaa-medium", "FXAA 3.11, Catlike Coding tutorial medium quality (= preset 27's table)",
                          FxaaTutorialSteps("medium"), 0.166, 0.0833, "sqrt-luminance", Order::kFxaa311));
  out.push_back(FxaaEntry("fxaa-high", "FXAA 3.11, Catlike Coding tutorial high quality (= preset 39)",
                          FxaaTutorialSteps("high"), 0.166, 0.0833, "sqrt-luminance", Order::kFxaa311));
  out.push_back(FxaaEntry("fxaa-iter12",
                          "widely copied GLSL FXAA with 12 iterations (seed 003): preset 39 steps, "
                          "thresholds 0.125/0.0312, luma from rgb per tap, that GLSL's float order",
                          Fxaa311PresetSteps(39), 0.125, 0.0312, "rec601-rgb", Order::kSeed003Glsl));
  // In `aalab run`'s default list: two presets, the tutorial's high quality and the GLSL copy.
  for (auto& e : out) {
    e.in_default_list =
        e.name == "fxaa311-p12" || e.name == "fxaa311-p39" || e.name == "fxaa-high" || e.name == "fxaa-iter12";
  }
  return out;
}

void SetFxaa311Post(MethodPlan& plan, const Fxaa311Params& fp) {
  // Both paths take the run's sampler arithmetic (PostOptions) and refuse debug views.
  auto make = [fp, name = plan.name](Image8 (*filter)(const Image8&, const Fxaa311Params&, PostStats*)) {
    return [fp, name, filter](const Image8& in, const PostOptions& options, PostStats* stats) {
      if (!options.debug_view.empty()) {
        throw UserError("method '" + name + "' has no debug view '" + options.debug_view + "'");
      }
      Fxaa311Params p = fp;
      p.sampler = options.sampler;
      return filter(in, p, stats);
    };
  };
  plan.post = make(&Fxaa311);
  plan.post_reference = make(&Fxaa311Reference);
  plan.config = fp;
}

}  // namespace aalab
