// Tests for FXAA 3.11 Quality (methods/fxaa311.cpp). Expected pixels are worked out by hand
// from the shader's equations (FXAA-interactive.fs in seeds/004); the arithmetic is in the
// comments. Image sizes are powers of two so that positions (k + 0.5)/W and the steps
// P·(1/W) are exact in float and the hand arithmetic carries over bit for bit.
#include "methods/fxaa311.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "methods/registry.h"

namespace aalab {
namespace {

using Luma = Fxaa311Params::Luma;

Image8 Solid(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
  Image8 img(w, h, 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.Pixel(x, y);
      p[0] = r;
      p[1] = g;
      p[2] = b;
      p[3] = 255;
    }
  }
  return img;
}

void Set(Image8& img, int x, int y, uint8_t r, uint8_t g, uint8_t b) {
  uint8_t* p = img.Pixel(x, y);
  p[0] = r;
  p[1] = g;
  p[2] = b;
  p[3] = 255;
}

Fxaa311Params Preset(int id, Luma luma = Luma::kRec601) {
  Fxaa311Params p;
  p.steps = Fxaa311PresetSteps(id);
  p.luma = luma;
  return p;
}

// FXAA 3.11 methods: the registry rows of the family "fxaa311" (presets, tutorial levels, iter12).
bool IsFxaaMethod(const MethodEntry& e) { return e.family == "fxaa311"; }

// ---------------------------------------------------------------------------------------
// Step tables.

TEST(Fxaa311, StepTablesEqualDesignDoc) {
  // docs/design.md "Reference facts", FXAA 3.11 quality presets, written out by hand (and checked against the
  // FXAA_QUALITY__P* #defines of seeds/004: they agree row for row).
  const std::vector<std::pair<int, std::vector<float>>> design = {
      {10, {1.5, 3, 12}},
      {11, {1, 1.5, 3, 12}},
      {12, {1, 1.5, 2, 4, 12}},
      {13, {1, 1.5, 2, 2, 4, 12}},
      {14, {1, 1.5, 2, 2, 2, 4, 12}},
      {15, {1, 1.5, 2, 2, 2, 2, 4, 12}},
      {20, {1.5, 2, 8}},
      {21, {1, 1.5, 2, 8}},
      {22, {1, 1.5, 2, 2, 8}},
      {23, {1, 1.5, 2, 2, 2, 8}},
      {24, {1, 1.5, 2, 2, 2, 3, 8}},
      {25, {1, 1.5, 2, 2, 2, 2, 4, 8}},
      {26, {1, 1.5, 2, 2, 2, 2, 2, 4, 8}},
      {27, {1, 1.5, 2, 2, 2, 2, 2, 2, 4, 8}},
      {28, {1, 1.5, 2, 2, 2, 2, 2, 2, 2, 4, 8}},
      {29, {1, 1.5, 2, 2, 2, 2, 2, 2, 2, 2, 4, 8}},
      {39, {1, 1, 1, 1, 1, 1.5, 2, 2, 2, 2, 4, 8}},
  };
  std::vector<int> ids;
  for (const auto& [id, steps] : design) {
    ids.push_back(id);
    EXPECT_EQ(Fxaa311PresetSteps(id), steps) << "preset " << id;
  }
  EXPECT_EQ(Fxaa311PresetIds(), ids);
  EXPECT_THROW(Fxaa311PresetSteps(16), InternalError);

  // The tutorial (seeds/000, 3.7): first step 1, EDGE_STEP_SIZES, LAST_EDGE_STEP_GUESS.
  // low = 1.5 2 2 | 8; medium = 1.5 2 2 2 2 2 2 4 | 8; high = 1 1 1 1 1.5 2 2 2 2 4 | 8.
  EXPECT_EQ(FxaaTutorialSteps("low"), (std::vector<float>{1, 1.5, 2, 2, 8}));
  EXPECT_EQ(FxaaTutorialSteps("medium"), (std::vector<float>{1, 1.5, 2, 2, 2, 2, 2, 2, 4, 8}));
  EXPECT_EQ(FxaaTutorialSteps("high"), (std::vector<float>{1, 1, 1, 1, 1, 1.5, 2, 2, 2, 2, 4, 8}));
  // low is preset 22, high is preset 39, and medium is preset 27's table (the tutorial's
  // text calls it 26, whose table has one 2 fewer).
  EXPECT_EQ(FxaaTutorialSteps("low"), Fxaa311PresetSteps(22));
  EXPECT_EQ(FxaaTutorialSteps("medium"), Fxaa311PresetSteps(27));
  EXPECT_EQ(FxaaTutorialSteps("high"), Fxaa311PresetSteps(39));
}

TEST(Fxaa311, RegistryHasEveryMethodWithItsDefaults) {
  std::vector<std::string> want;
  for (int id : {10, 11, 12, 13, 14, 15, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 39}) {
    want.push_back("fxaa311-p" + std::to_string(id));
  }
  for (const char* n : {"fxaa-low", "fxaa-medium", "fxaa-high", "fxaa-iter12"}) want.push_back(n);
  std::vector<std::string> have;
  for (const auto& e : MethodRegistry()) {
    if (!IsFxaaMethod(e)) continue;
    have.push_back(e.name);
    EXPECT_FALSE(e.help.empty());
    ASSERT_EQ(e.params.size(), 4u) << e.name;
    for (const auto& d : e.params) EXPECT_FALSE(d.help.empty()) << e.name << " " << d.name;
  }
  EXPECT_EQ(have, want);

  const MethodPlan p39 = MakeMethod("fxaa311-p39");
  EXPECT_TRUE(p39.IsPostOnly());
  EXPECT_EQ(p39.params.Number("subpix"), 0.75);
  EXPECT_EQ(p39.params.Number("edge_threshold"), 0.166);
  EXPECT_EQ(p39.params.Number("edge_threshold_min"), 0.0833);
  EXPECT_EQ(p39.params.Choice("luma"), "rec601");
  EXPECT_EQ(MakeMethod("fxaa-high").params.Choice("luma"), "sqrt-luminance");
  const MethodPlan it12 = MakeMethod("fxaa-iter12");
  EXPECT_EQ(it12.params.Number("edge_threshold"), 0.125);
  EXPECT_EQ(it12.params.Number("edge_threshold_min"), 0.0312);
  EXPECT_EQ(it12.params.Choice("luma"), "rec601-rgb");
  EXPECT_EQ(MakeMethod("fxaa311-p39:subpix=0.5,luma=green").spec, "fxaa311-p39:subpix=0.5,luma=green");
  EXPECT_THROW(MakeMethod("fxaa311-p39:luma=blue"), UserError);
  EXPECT_THROW(MakeMethod("fxaa311-p39:subpix=1.5"), UserError);
  EXPECT_THROW(MakeMethod("fxaa311-p39:steps=3"), UserError);
  EXPECT_THROW(ParseFxaa311Luma("luma"), UserError);
}

// fxaa-high and preset 39 share a table, fxaa-low / -medium and presets 22 / 27 too: with
// the same luma the filters are the same function.
TEST(Fxaa311, TutorialLevelsEqualTheirPresets) {
  Image8 img = Solid(32, 32, 20, 30, 40);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      if (3 * x + 7 * y < 150) Set(img, x, y, 230, 220, 200);
    }
  }
  const std::vector<std::pair<std::string, std::string>> pairs = {{"fxaa-low", "fxaa311-p22:luma=sqrt-luminance"},
                                                                  {"fxaa-medium", "fxaa311-p27:luma=sqrt-luminance"},
                                                                  {"fxaa-high", "fxaa311-p39:luma=sqrt-luminance"}};
  for (const auto& [a, b] : pairs) {
    const Image8 oa = MakeMethod(a).post(img, {}, nullptr);
    const Image8 ob = MakeMethod(b).post(img, {}, nullptr);
    EXPECT_TRUE(oa == ob) << a << " vs " << b;
  }
}

// ---------------------------------------------------------------------------------------
// Flat images and the zero-range division.

TEST(Fxaa311, FlatImageUnchangedByEveryPreset) {
  const Image8 flat = Solid(24, 16, 90, 160, 200);
  int n = 0;
  for (const auto& e : MethodRegistry()) {
    if (!IsFxaaMethod(e)) continue;
    PostStats st;
    EXPECT_TRUE(MakeMethod(e.name).post(flat, {}, &st) == flat) << e.name;
    // Every pixel exits early after rgbyM and its 4 neighbours: 5 fetches.
    EXPECT_EQ(st.taps, 5u * 24 * 16) << e.name;
    ++n;
  }
  EXPECT_EQ(n, 21);
}

TEST(Fxaa311, ZeroRangeReturnsInputInsteadOfNaN) {
  // range = 0 passes the early exit only if 0 < max(min, rangeMax*threshold) fails, i.e.
  // edge_threshold_min = 0 and rangeMax*edge_threshold = 0. The shader then computes
  // subpixRcpRange = 1/0 = inf and subpixC = clamp(|subpixB|*inf): NaN when subpixB = 0.
  // We return the input pixel there.
  Fxaa311Params p = Preset(39);
  p.edge_threshold_min = 0.0f;
  p.edge_threshold = 0.0f;
  const Image8 grey = Solid(8, 8, 120, 130, 140);
  EXPECT_TRUE(Fxaa311(grey, p, nullptr) == grey);
  for (Luma l : {Luma::kRec601, Luma::kRec601Rgb, Luma::kGreen, Luma::kSqrtLuminance}) {
    p.luma = l;
    EXPECT_TRUE(Fxaa311(grey, p, nullptr) == grey);
  }
  // Flat black with the default relative threshold: rangeMax = 0, so 0.166*0 = 0 as well.
  Fxaa311Params q = Preset(12);
  q.edge_threshold_min = 0.0f;
  const Image8 black = Solid(8, 8, 0, 0, 0);
  EXPECT_TRUE(Fxaa311(black, q, nullptr) == black);
  // A black cross with white corners: range over the cross is 0 but subpixB = (0·2 + 4)/12
  // is not, so the shader would get inf (subpixC = 1) rather than NaN; we still return M.
  Image8 cross = Solid(3, 3, 255, 255, 255);
  for (auto [x, y] : {std::pair{1, 1}, {0, 1}, {2, 1}, {1, 0}, {1, 2}}) Set(cross, x, y, 0, 0, 0);
  const Image8 out = Fxaa311(cross, q, nullptr);
  EXPECT_EQ(out.At(1, 1, 0), 0);
  EXPECT_EQ(out.At(1, 1, 1), 0);
  EXPECT_EQ(out.At(1, 1, 2), 0);
  // Zero-range pixels stop after the 5 fetches of the cross, like an early exit; the
  // shader would fetch the 4 corners, search (2) and fetch once more.
  PostStats st;
  EXPECT_TRUE(Fxaa311(black, q, &st) == black);
  EXPECT_EQ(st.taps, 5u * 8 * 8);
}

TEST(Fxaa311, ZeroRangeKeepsColourWhereIeeeWouldBlend) {
  // Green luma, edge_threshold_min = 0. M = red (255,0,0), N = blue (0,0,255), S = E = W =
  // black: the cross has luma 0 everywhere → rangeMax = 0, range = 0 → no early exit
  // (0 < max(0, 0) is false). Corners are white (luma 1), so subpixB = (0·2 + 4)/12 = 1/3.
  // IEEE would give subpixC = clamp(1/3 · inf) = 1, subpixH = 0.75, horzSpan (4 >= 4),
  // pairN (0 >= 0) → 0.75 towards N → (0.25·255, 0, 0.75·255) = (64, 0, 191).
  // We return the input pixel instead: (255, 0, 0).
  Image8 img = Solid(3, 3, 255, 255, 255);
  Set(img, 1, 1, 255, 0, 0);
  Set(img, 1, 0, 0, 0, 255);
  Set(img, 0, 1, 0, 0, 0);
  Set(img, 2, 1, 0, 0, 0);
  Set(img, 1, 2, 0, 0, 0);
  Fxaa311Params p = Preset(39, Luma::kGreen);
  p.edge_threshold_min = 0.0f;
  const Image8 out = Fxaa311(img, p, nullptr);
  EXPECT_EQ(out.At(1, 1, 0), 255);
  EXPECT_EQ(out.At(1, 1, 1), 0);
  EXPECT_EQ(out.At(1, 1, 2), 0);
}

// ---------------------------------------------------------------------------------------
// A 1-pixel dot, by hand.

TEST(Fxaa311, DotByHand) {
  // 16×16 black, one white pixel M at (8, 8); rec601 luma in alpha: white 255 → 1, black 0.
  //
  // Centre (8, 8): lumaM = 1, N = S = E = W = 0, corners 0.
  //   rangeMax 1, rangeMin 0, range 1 ≥ max(0.0833, 0.166) → no early exit.
  //   subpixA = (N+S + W+E)·2 + (NW+SW + NE+SE) = 0; subpixB = 0/12 − 1 = −1;
  //   subpixC = clamp(1 · 1/1) = 1; smoothstep: subpixD = −2·1 + 3 = 1, subpixE = 1,
  //   subpixF = 1; subpixG = 1² = 1; subpixH = 1 · 0.75 = 0.75.
  //   edgeHorz = |−2W + NW+SW| + 2|−2M + N+S| + |−2E + NE+SE| = 0 + 4 + 0 = 4; edgeVert = 4;
  //   horzSpan = 4 >= 4 → true. gradientN = gradientS = −1 → pairN = (1 >= 1) → north,
  //   lengthSign = −1/16. lumaNN = N + M = 1; gradientScaled = 0.25.
  //   First search taps at (8.5 ∓ P0, 8.0) in texels: rows 7/8 of columns 7 / 9 → 0;
  //   lumaEnd = 0 − 0.5 = −0.5, |−0.5| ≥ 0.25 → both done. dstN = dstP = P0/16 →
  //   pixelOffset = 0.5 − 0.5 = 0. pixelOffsetSubpix = max(0, 0.75) = 0.75.
  //   Final tap at v = 8.5 − 0.75 = 7.75 → 0.75·row 7 + 0.25·row 8 = 0.25 → 63.75 → 64.
  // North neighbour (8, 7): M = 0, S = 1, rest 0. range 1.
  //   subpixA = (0+1 + 0+0)·2 + 0 = 2; subpixB = 2/12 = 1/6; subpixC = 1/6;
  //   subpixF = (3 − 1/3)·(1/36) = 2/27; subpixH = 0.75·(2/27)² = 3/729 = 0.0041152.
  //   edgeHorz = 0 + 2·1 + 0 = 2; edgeVert = |−2S + SW+SE| + 2·0 + 0 = 2 → horzSpan (tie).
  //   gradientN = 0, gradientS = 1 → pairN false → towards S (+1/16). Search: both ends
  //   done at once (columns 7 and 9 read 0, lumaEnd −0.5); lumaMM = 0 − 0.5 < 0 and
  //   lumaEndP < 0 → goodSpan false → offset = subpixH. 0.0041152·255 = 1.049 → 1.
  //   South neighbour: the mirror image → 1.
  // East neighbour (9, 8): M = 0, W = 1. edgeHorz = |−2W + NW+SW| = 2; edgeVert =
  //   2|−2M + W+E| = 2 → horzSpan = (2 >= 2) true: blends vertically with black N or S →
  //   0 (unchanged). With "edgeHorz > edgeVert" it would blend with the dot and give 1.
  // Diagonal (7, 7): its cross is all black → range 0 < 0.0833 → early exit.
  Image8 img = Solid(16, 16, 0, 0, 0);
  Set(img, 8, 8, 255, 255, 255);
  for (int id : Fxaa311PresetIds()) {
    PostStats st;
    const Image8 out = Fxaa311(img, Preset(id), &st);
    for (int y = 0; y < 16; ++y) {
      for (int x = 0; x < 16; ++x) {
        int want = 0;
        if (x == 8 && y == 8) want = 64;
        if (x == 8 && (y == 7 || y == 9)) want = 1;
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(out.At(x, y, c), want) << "preset " << id << " at " << x << "," << y;
        }
        ASSERT_EQ(out.At(x, y, 3), 255);
      }
    }
    // Taps: 251 pixels exit after 5; the dot and its 4 neighbours take 9 + 2 search + 1 final.
    EXPECT_EQ(st.taps, 251u * 5 + 5u * 12) << "preset " << id;
  }
}

// ---------------------------------------------------------------------------------------
// A staircase with 256-px treads: who finds the end of the edge.

TEST(Fxaa311, LongEdgeReachPerPreset) {
  // 512×16: rows 0..7 black; rows ≥ 9 white; row 8 white for x < 256, black for x ≥ 256.
  // The boundary steps down by 1 px at x = 256. Pixel (256+k, 8), k ≥ 1: M = 0, N = 0,
  // S = 1, E = W = 0, SW = SE = 1 → horzSpan, pairN false (towards S), lumaNN = 1,
  // gradientScaled = 0.25, lumaMM = −0.5 < 0. Search on the row 8/9 boundary: to the right
  // the pair (black, white) reads 0.5 → lumaEnd 0 forever (clamp-to-edge continues the
  // edge) → dstP = S, the sum of all steps. To the left, a tap at texel x-coordinate u
  // reads 0.5 + 0.5·w(255) where w(255) = clamp(256.5 − u, 0, 1), so |lumaEnd| ≥ 0.25 iff
  // u ≤ 256 (equality is the ">=" tie: 0.75 − 0.5 = 0.25 exactly). u = 256.5 + k − d for a
  // tap at distance d, so the end is found iff some fetch distance d = P0+…+Pj (j ≤ n−2)
  // reaches k + 0.5: reach k_max = floor(P0 + … + P(n−2) − 0.5).
  //   found:     lumaEndN = +0.25..0.5 → goodSpanN = (false != true) = true, dstN = d <
  //              dstP → pixelOffset = 0.5 − d/(d + S); out = round(255·pixelOffset).
  //   not found: dstN = dstP = S → pixelOffset 0 → subpix only: subpixA = (0+1+0+0)·2 +
  //              (0+1) + (0+1) = 4 → subpixC = 1/3 → subpixF = (3 − 2/3)/9 = 7/27 →
  //              0.75·(7/27)² = 0.0504115 → 12.85 → 13.
  // k_max by hand: p10 1.5+3 = 4.5 → 4; p11 5.5 → 5; p12 8.5 → 8; p13 10.5 → 10;
  // p14 12.5 → 12; p15 14.5 → 14; p20 3.5 → 3; p21 4.5 → 4; p22 6.5 → 6; p23 8.5 → 8;
  // p24 11.5 → 11; p25 14.5 → 14; p26 16.5 → 16; p27 18.5 → 18; p28 20.5 → 20;
  // p29 22.5 → 22; p39 18.5 → 18.
  const std::vector<std::pair<int, int>> kmax = {{10, 4},  {11, 5},  {12, 8},  {13, 10}, {14, 12}, {15, 14},
                                                 {20, 3},  {21, 4},  {22, 6},  {23, 8},  {24, 11}, {25, 14},
                                                 {26, 16}, {27, 18}, {28, 20}, {29, 22}, {39, 18}};
  Image8 img = Solid(512, 16, 0, 0, 0);
  for (int y = 8; y < 16; ++y) {
    for (int x = 0; x < 512; ++x) {
      if (y >= 9 || x < 256) Set(img, x, y, 255, 255, 255);
    }
  }
  for (const auto& [id, reach] : kmax) {
    const std::vector<float>& P = Fxaa311PresetSteps(id);
    double S = 0;
    for (float v : P) S += v;
    const Image8 out = Fxaa311(img, Preset(id), nullptr);
    for (int k = 1; k <= reach + 4; ++k) {
      int want = 13;
      if (k <= reach) {
        double d = 0;
        for (size_t j = 0; j + 1 < P.size(); ++j) {
          d += P[j];
          if (d >= k + 0.5) break;
        }
        const double v = 255.0 * (0.5 - d / (d + S));
        ASSERT_GT(std::fabs(v - std::floor(v) - 0.5), 1e-3);  // not a rounding tie
        want = static_cast<int>(std::lround(v));
      }
      EXPECT_EQ(out.At(256 + k, 8, 0), want) << "preset " << id << " k " << k;
    }
  }
  // Spot values: p10 finds the end at k = 4 (d = 4.5: 0.5 − 4.5/21 → 72.86 → 73) and
  // misses it at k = 10 (13); p39 finds it at k = 10 (d = 10.5, S = 26.5:
  // 0.5 − 10.5/37 = 0.2162 → 55.14 → 55) and at k = 18 (d = 18.5: 0.5 − 18.5/45 → 22.67 → 23).
  const Image8 o10 = Fxaa311(img, Preset(10), nullptr);
  const Image8 o39 = Fxaa311(img, Preset(39), nullptr);
  EXPECT_EQ(o10.At(260, 8, 0), 73);
  EXPECT_EQ(o10.At(266, 8, 0), 13);
  EXPECT_EQ(o39.At(266, 8, 0), 55);
  EXPECT_EQ(o39.At(274, 8, 0), 23);
  EXPECT_EQ(o39.At(275, 8, 0), 13);
}

// ---------------------------------------------------------------------------------------
// Tie-breaks.

TEST(Fxaa311, EarlyExitIsStrict) {
  // Green luma; a dot of green 51 on black: lumaM = 51/255 = 0.2f, range = 0.2f.
  // edge_threshold = 0, edge_threshold_min = 0.2 → rangeMaxClamped = 0.2f = range:
  // "range < rangeMaxClamped" is false → the pixel is filtered. subpixC = 0.2f·(1/0.2f) = 1
  // → offset 0.75 towards a black neighbour → g = 0.25·51 = 12.75 → 13.
  // With min = 0.21 the pixel exits early and keeps 51.
  Image8 img = Solid(8, 8, 0, 0, 0);
  Set(img, 4, 4, 0, 51, 0);
  Fxaa311Params p = Preset(39, Luma::kGreen);
  p.edge_threshold = 0.0f;
  p.edge_threshold_min = 0.2f;
  EXPECT_EQ(Fxaa311(img, p, nullptr).At(4, 4, 1), 13);
  p.edge_threshold_min = 0.21f;
  EXPECT_EQ(Fxaa311(img, p, nullptr).At(4, 4, 1), 51);
}

TEST(Fxaa311, PairTieTakesNorth) {
  // Green luma. Row 7 = (255, 200, 0), row 9 = (0, 200, 255), everything else black: the
  // black row 8 has N and S of equal luma 200/255 and different colours.
  // M = 0, N = S = 0.7843, E = W = 0, corners 0.7843: edgeHorz = 2·1.5686 + 1.5686 + 1.5686
  // = 6.27, edgeVert = 0 → horizontal. gradientN = gradientS → pairN = (|gN| >= |gS|) →
  // north. The search never ends (the rows are uniform): dstN = dstP → pixelOffset 0.
  // subpixA = 1.5686·2 + 3.1373 = 6.2745; /12 = 0.52288; subpixC = 0.52288/0.78431 = 2/3;
  // subpixF = (3 − 4/3)·4/9 = 20/27; subpixH = 0.75·(20/27)² = 0.411523.
  // Final tap 0.411523 towards row 7: r = 0.411523·255 = 104.94 → 105,
  // g = 0.411523·200 = 82.30 → 82, b = 0. ("pairN = |gN| > |gS|" would pick S: (0, 82, 105).)
  Image8 img = Solid(16, 16, 0, 0, 0);
  for (int x = 0; x < 16; ++x) {
    Set(img, x, 7, 255, 200, 0);
    Set(img, x, 9, 0, 200, 255);
  }
  const Image8 out = Fxaa311(img, Preset(39, Luma::kGreen), nullptr);
  EXPECT_EQ(out.At(5, 8, 0), 105);
  EXPECT_EQ(out.At(5, 8, 1), 82);
  EXPECT_EQ(out.At(5, 8, 2), 0);
}

TEST(Fxaa311, EndTestIsGreaterOrEqual) {
  // Green luma, 16×16: rows 0..7 = 0; rows 8..15 = 204 (0.8f), except (3, 8) = 102 (0.4f).
  // M = (4, 8) = 0.8: N = 0, S = E = 0.8, W = 0.4, NW = NE = 0, SW = SE = 0.8.
  // edgeHorz = 2·|−1.6 + 0.8| + |−1.6 + 0.8| + |−0.8 + 0.8| = 2.4, edgeVert = 2·|−1.6 + 1.2|
  // + 0 + 0 = 0.8 → horizontal; gradientN = −0.8, gradientS = 0 → north, lengthSign = −1/16.
  // lumaNN = 0.8, gradientScaled = 0.8/4 = 0.2f, lumaMM = 0.4 (not < 0).
  // First N tap at texel (3.5, 8.0): 0.5·(3,7) + 0.5·(3,8) = 0.2f; lumaEndN = 0.2f − 0.4f =
  // −0.2f: |lumaEndN| == gradientScaled exactly → done by ">=", dstN = 1 texel.
  // The P side reads 0.5·0 + 0.5·0.8 = 0.4 → lumaEnd 0 forever → dstP = 26.5 (p39).
  // goodSpanN = (−0.2 < 0) != false = true; pixelOffset = 0.5 − 1/27.5 = 0.463636.
  // subpixA = (0.8 + 1.2)·2 + 1.6 = 5.6; subpixC = |5.6/12 − 0.8|/0.8 = 0.416667;
  // subpixH = 0.75·((3 − 0.8333)·0.17361)² = 0.106121 < 0.4636.
  // Final tap at v = 8.5 − 0.463636: (1 − 0.463636)·0.8 = 0.429091 → 109.42 → 109.
  // (With ">" the left end is never found: offset = subpixH → (1 − 0.106121)·204 → 182.)
  Image8 img = Solid(16, 16, 0, 0, 0);
  for (int y = 8; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) Set(img, x, y, 0, 204, 0);
  }
  Set(img, 3, 8, 0, 102, 0);
  const Image8 out = Fxaa311(img, Preset(39, Luma::kGreen), nullptr);
  EXPECT_EQ(out.At(4, 8, 1), 109);
}

TEST(Fxaa311, NearerEndTieGivesNoEdgeOffset) {
  // directionN = dstN < dstP takes P on a tie, but a tie also makes
  // pixelOffset = 0.5 − dst/(2·dst) = 0, so only the sub-pixel offset remains whichever
  // end is taken. Row 8 black between white rows 7 and 9 (uniform, no end found, and
  // dstN = dstP exactly): M = 0, N = S = 1, E = W = 0, corners 1 → subpixA = 2·2 + 4 = 8 →
  // subpixC = 8/12 = 2/3 → subpixF = (3 − 4/3)·4/9 = 20/27 → subpixH = 0.75·(20/27)² =
  // 0.411523 → towards row 7 (pairN tie): 0.411523·255 = 104.94 → 105.
  Image8 img = Solid(16, 16, 0, 0, 0);
  for (int x = 0; x < 16; ++x) {
    Set(img, x, 7, 255, 255, 255);
    Set(img, x, 9, 255, 255, 255);
  }
  for (int id : Fxaa311PresetIds()) {
    EXPECT_EQ(Fxaa311(img, Preset(id), nullptr).At(6, 8, 0), 105) << "preset " << id;
  }
}

// ---------------------------------------------------------------------------------------
// Luma modes.

TEST(Fxaa311, LumaModesForKnownColours) {
  Image8 img(6, 1, 4);
  const uint8_t colours[6][3] = {{255, 0, 0},     {0, 255, 0},     {0, 0, 255},
                                 {255, 255, 255}, {128, 128, 128}, {188, 188, 188}};
  for (int i = 0; i < 6; ++i) Set(img, i, 0, colours[i][0], colours[i][1], colours[i][2]);
  // rec601: dot(rgb, (0.299, 0.587, 0.114))·255 → 76.245, 149.685, 29.07, 255, 128, 188.
  const Image8 r601 = Fxaa311LumaFrame(img, Luma::kRec601);
  const int want601[6] = {76, 150, 29, 255, 128, 188};
  // sqrt-luminance: sqrt(0.2126729·R + 0.7151522·G + 0.0721750·B) of the decoded colour:
  // red sqrt(0.2126729) = 0.461165 → 117.60 → 118; green sqrt(0.7151522) = 0.845667 →
  // 215.65 → 216; blue sqrt(0.072175) = 0.268654 → 68.51 → 69; white 255; sRGB 128 decodes
  // to 0.215861 → sqrt 0.464609 → 118.48 → 118; sRGB 188: ((188/255 + 0.055)/1.055)^2.4 =
  // 0.502886 → sqrt 0.709145 → 180.83 → 181.
  const Image8 sq = Fxaa311LumaFrame(img, Luma::kSqrtLuminance);
  const int wantsq[6] = {118, 216, 69, 255, 118, 181};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(r601.At(i, 0, 3), want601[i]) << i;
    EXPECT_EQ(sq.At(i, 0, 3), wantsq[i]) << i;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(sq.At(i, 0, c), img.At(i, 0, c));  // rgb kept
  }
  // green and rec601-rgb store nothing.
  EXPECT_TRUE(Fxaa311LumaFrame(img, Luma::kGreen) == img);
  EXPECT_TRUE(Fxaa311LumaFrame(img, Luma::kRec601Rgb) == img);
  // What a tap reads.
  const Float4 t{0.5f, 0.25f, 1.0f, 0.75f};
  EXPECT_EQ(Fxaa311TapLuma(t, Luma::kRec601), 0.75f);
  EXPECT_EQ(Fxaa311TapLuma(t, Luma::kSqrtLuminance), 0.75f);
  EXPECT_EQ(Fxaa311TapLuma(t, Luma::kGreen), 0.25f);
  // 0.5·0.299 + 0.25·0.587 + 1·0.114 = 0.1495 + 0.14675 + 0.114 = 0.41025
  EXPECT_NEAR(Fxaa311TapLuma(t, Luma::kRec601Rgb), 0.41025f, 1e-6f);
}

TEST(Fxaa311, LumaModeChangesWhatIsAnEdge) {
  // Pure red (255,0,0) next to pure blue: green luma sees 0 vs 0 (no edge); rec601 sees
  // 76/255 vs 29/255: range 0.184 ≥ max(0.0833, 0.166·0.298) → filtered.
  Image8 img = Solid(8, 8, 255, 0, 0);
  for (int y = 0; y < 8; ++y) {
    for (int x = 4; x < 8; ++x) Set(img, x, y, 0, 0, 255);
  }
  EXPECT_TRUE(Fxaa311(img, Preset(39, Luma::kGreen), nullptr) == img);
  EXPECT_FALSE(Fxaa311(img, Preset(39, Luma::kRec601), nullptr) == img);
  EXPECT_FALSE(Fxaa311(img, Preset(39, Luma::kRec601Rgb), nullptr) == img);
}

// ---------------------------------------------------------------------------------------
// Determinism.

Image8 Noise(int w, int h, uint32_t seed) {
  Image8 img(w, h, 4);
  uint32_t s = seed;
  for (auto& v : img.Data()) {
    s = s * 1664525u + 1013904223u;
    v = static_cast<uint8_t>(s >> 24);
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) img.At(x, y, 3) = 255;
  }
  return img;
}

TEST(Fxaa311, SameBitsAtAnyThreadCount) {
  const Image8 img = Noise(97, 83, 7);
  for (const char* m : {"fxaa311-p39", "fxaa311-p10", "fxaa-low", "fxaa-iter12"}) {
    const MethodPlan plan = MakeMethod(m);
    SetThreadCount(1);
    PostStats s1;
    const Image8 a = plan.post(img, {}, &s1);
    SetThreadCount(2);
    PostStats s2;
    const Image8 b = plan.post(img, {}, &s2);
    SetThreadCount(0);
    EXPECT_TRUE(a == b) << m;
    EXPECT_EQ(s1.taps, s2.taps) << m;
  }
}

TEST(Fxaa311, Seed003OrderOnlyChangesRounding) {
  // seed 003's GLSL and FXAA 3.11 are the same equations with five expressions associated
  // differently. On noise (every pixel processed, many near-ties) count where that shows.
  const Image8 img = Noise(128, 128, 11);
  Fxaa311Params a = Preset(39, Luma::kRec601Rgb);
  a.edge_threshold = 0.125f;
  a.edge_threshold_min = 0.0312f;
  Fxaa311Params b = a;
  b.order = Fxaa311Params::Order::kSeed003Glsl;
  const Image8 oa = Fxaa311(img, a, nullptr);
  const Image8 ob = Fxaa311(img, b, nullptr);
  int differ = 0, big = 0, maxdiff = 0;
  for (int y = 0; y < 128; ++y) {
    for (int x = 0; x < 128; ++x) {
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(oa.At(x, y, c) - ob.At(x, y, c)));
      differ += d > 0;
      big += d > 1;
      maxdiff = std::max(maxdiff, d);
    }
  }
  std::printf(
      "  noise 128x128: seed-003 order vs 3.11 order: %d pixels differ, %d by more "
      "than 1/255, max %d/255\n",
      differ, big, maxdiff);
  EXPECT_LE(differ, 128 * 128 / 50);
}

TEST(Fxaa311, Seed003EdgeSumOrderDecidesExactTies) {
  // Almost all of the differences above come from horzSpan at neighbourhoods where
  // edgeHorz == edgeVert in exact arithmetic: the float sums then round differently.
  //   FXAA 3.11: edgeHorz = |H3| + (2|H1| + |H2|)   seed 003: (|H3| + |H1|·2) + |H2|
  // Find (deterministically) a 3×3 of grey levels k/255 with an exact tie (checked in
  // integers: 255·H = −2k_W + k_NW + k_SW etc.) whose two float orders decide differently,
  // and check that the filter follows each order's decision: the outputs differ.
  uint32_t s = 12345;
  auto next = [&s] {
    s = s * 1664525u + 1013904223u;
    return static_cast<int>((s >> 24) % 6) * 51;  // 0, 51, ..., 255
  };
  for (int tries = 0; tries < 2000000; ++tries) {
    int k[3][3];
    for (auto& row : k) {
      for (int& v : row) v = next();
    }
    const int M = k[1][1], N = k[0][1], S = k[2][1], W = k[1][0], E = k[1][2];
    const int NW = k[0][0], NE = k[0][2], SW = k[2][0], SE = k[2][2];
    const int iH = std::abs(-2 * W + NW + SW) + 2 * std::abs(-2 * M + N + S) + std::abs(-2 * E + NE + SE);
    const int iV = std::abs(-2 * S + SW + SE) + 2 * std::abs(-2 * M + W + E) + std::abs(-2 * N + NW + NE);
    const int irange = std::max({M, N, S, W, E}) - std::min({M, N, S, W, E});
    if (iH != iV || iH == 0 || irange < 60) continue;
    auto l = [](int v) { return static_cast<float>(v) / 255.0f; };
    const float h1 = std::fabs(-2.0f * l(M) + (l(N) + l(S)));
    const float h2 = std::fabs(-2.0f * l(E) + (l(NE) + l(SE)));
    const float h3 = std::fabs(-2.0f * l(W) + (l(NW) + l(SW)));
    const float v1 = std::fabs(-2.0f * l(M) + (l(W) + l(E)));
    const float v2 = std::fabs(-2.0f * l(N) + (l(NW) + l(NE)));
    const float v3 = std::fabs(-2.0f * l(S) + (l(SW) + l(SE)));
    const bool horz311 = h3 + (h1 * 2.0f + h2) >= v3 + (v1 * 2.0f + v2);
    const bool horzGlsl = (h3 + h1 * 2.0f) + h2 >= (v3 + v1 * 2.0f) + v2;
    if (horz311 == horzGlsl) continue;
    Image8 img(3, 3, 4, 255);
    for (int y = 0; y < 3; ++y) {
      for (int x = 0; x < 3; ++x) Set(img, x, y, 0, static_cast<uint8_t>(k[y][x]), 0);
    }
    Fxaa311Params a = Preset(39, Luma::kGreen);
    a.edge_threshold_min = 0.0312f;
    Fxaa311Params b = a;
    b.order = Fxaa311Params::Order::kSeed003Glsl;
    const int ga = Fxaa311(img, a, nullptr).At(1, 1, 1);
    const int gb = Fxaa311(img, b, nullptr).At(1, 1, 1);
    std::printf("  exact tie H = V = %d/255 after %d tries: 3.11 order %s -> %d, seed-003 order %s -> %d\n", iH, tries,
                horz311 ? "horizontal" : "vertical", ga, horzGlsl ? "horizontal" : "vertical", gb);
    EXPECT_NE(ga, gb);
    return;
  }
  FAIL() << "no exact tie that the two orders round differently was found";
}

// ---------------------------------------------------------------------------------------
// A hard-edged polygon against its analytic coverage.

struct Tri {
  double x[3], y[3];
  bool Inside(double px, double py) const {
    bool neg = false, pos = false;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      const double e = (x[j] - x[i]) * (py - y[i]) - (y[j] - y[i]) * (px - x[i]);
      neg = neg || e < 0;
      pos = pos || e > 0;
    }
    return !(neg && pos);
  }
};

TEST(Fxaa311, EveryPresetLowersPolygonError) {
  const int n = 64;
  const Tri tri{{5.3, 59.2, 17.8}, {9.7, 21.4, 57.1}};
  const float fg[3] = {0.9f, 0.75f, 0.3f};    // linear
  const float bg[3] = {0.03f, 0.04f, 0.08f};  // linear
  Image8 aliased(n, n, 4);
  std::vector<double> ref(static_cast<size_t>(n) * n * 3);
  const int ss = 16;  // 256 stratified samples per pixel for the coverage
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const bool in = tri.Inside(x + 0.5, y + 0.5);
      int hits = 0;
      for (int j = 0; j < ss; ++j) {
        for (int i = 0; i < ss; ++i) hits += tri.Inside(x + (i + 0.5) / ss, y + (j + 0.5) / ss);
      }
      const double cov = static_cast<double>(hits) / (ss * ss);
      for (int c = 0; c < 3; ++c) {
        aliased.At(x, y, c) = QuantizeUnorm8(SrgbEncode(in ? fg[c] : bg[c]));
        const double lin = cov * fg[c] + (1.0 - cov) * bg[c];
        ref[(static_cast<size_t>(y) * n + x) * 3 + c] = SrgbEncode(static_cast<float>(lin));
      }
      aliased.At(x, y, 3) = 255;
    }
  }
  auto mse = [&](const Image8& img) {
    double sum = 0;
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        for (int c = 0; c < 3; ++c) {
          const double d = img.At(x, y, c) / 255.0 - ref[(static_cast<size_t>(y) * n + x) * 3 + c];
          sum += d * d;
        }
      }
    }
    return sum / (n * n * 3.0);
  };
  const double base = mse(aliased);
  for (const auto& e : MethodRegistry()) {
    if (!IsFxaaMethod(e)) continue;
    const double after = mse(MakeMethod(e.name).post(aliased, {}, nullptr));
    std::printf("  polygon MSE %-14s %.6e -> %.6e (%.1f%%)\n", e.name.c_str(), base, after, 100.0 * after / base);
    EXPECT_LT(after, base) << e.name;
  }
  // fxaa-iter12 differs from preset 39 with the same thresholds and luma only in float
  // order: count the pixels where that shows.
  Fxaa311Params a = Preset(39, Luma::kRec601Rgb);
  a.edge_threshold = 0.125f;
  a.edge_threshold_min = 0.0312f;
  Fxaa311Params b = a;
  b.order = Fxaa311Params::Order::kSeed003Glsl;
  const Image8 oa = Fxaa311(aliased, a, nullptr);
  const Image8 ob = Fxaa311(aliased, b, nullptr);
  int differ = 0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      differ +=
          oa.At(x, y, 0) != ob.At(x, y, 0) || oa.At(x, y, 1) != ob.At(x, y, 1) || oa.At(x, y, 2) != ob.At(x, y, 2);
    }
  }
  std::printf("  iter12 GLSL order vs FXAA 3.11 order: %d of %d pixels differ\n", differ, n * n);
  EXPECT_LE(differ, n * n / 100);
  EXPECT_TRUE(ob == MakeMethod("fxaa-iter12").post(aliased, {}, nullptr));
}

}  // namespace
}  // namespace aalab
