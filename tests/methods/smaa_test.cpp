// SMAA 1x: the generated area/search textures against entries worked out by hand from the
// published definitions (AreaTex.py, SearchTex.py), edge detection and a straight-edge
// blending case worked by hand from SMAA.hlsl, and the paths a user takes (presets through
// the registry, flat frames, odd sizes, bad parameters, debug views).
#include "methods/smaa.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "methods/registry.h"

namespace aalab {
namespace {

Image8 Gray(int w, int h, uint8_t v) {
  Image8 img(w, h, 4, 255);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) img.Pixel(x, y)[0] = img.Pixel(x, y)[1] = img.Pixel(x, y)[2] = v;
  }
  return img;
}

void SetGray(Image8& img, int x, int y, uint8_t v) {
  uint8_t* p = img.Pixel(x, y);
  p[0] = p[1] = p[2] = v;
}

SmaaParams NoDiagNoCorner() {
  SmaaParams p = SmaaPreset("high");
  p.diag = false;
  p.corner = false;
  return p;
}

// ---------------------------------------------------------------- area texture

TEST(SmaaAreaTexture, OrthogonalLShapeByHand) {
  // Pattern 1 (crossing edge at the left end going down), left = right = 0, offset 0: the
  // revectorised line runs from (0, -0.5) to (d/2, 0) = (0.5, 0); in pixel [0, 1] it
  // leaves a triangle of width 0.5 and height 0.5 below the edge: area 0.125 on the first
  // side, 0 on the other. Stored as int(255 · 0.125) = 31 at tile (3, 0), texel (0, 0).
  const auto a = SmaaAreaOrtho(1, 0, 0, 0.0);
  EXPECT_DOUBLE_EQ(a.first, 0.125);
  EXPECT_DOUBLE_EQ(a.second, 0.0);
  const Image8& t = SmaaAreaTexture();
  EXPECT_EQ(t.Pixel(48, 0)[0], 31);
  EXPECT_EQ(t.Pixel(48, 0)[1], 0);
  // left = 1, right = 4 (texel (1, 2): quadratic compression, distances 1² and 2²): d = 6,
  // line (0, -0.5) → (3, 0); over pixel [1, 2] it stays below the edge at heights -1/3 and
  // -1/6: a trapezoid of area 0.25 → int(63.75) = 63.
  const auto b = SmaaAreaOrtho(1, 1, 4, 0.0);
  EXPECT_NEAR(b.first, 0.25, 1e-15);
  EXPECT_EQ(b.second, 0.0);
  EXPECT_EQ(t.Pixel(48 + 1, 0 + 2)[0], 63);
  EXPECT_EQ(t.Pixel(48 + 1, 0 + 2)[1], 0);
  // The L pattern is only offset on the side of its crossing edge: left > right gives 0.
  EXPECT_EQ(SmaaAreaOrtho(1, 4, 1, 0.0), std::make_pair(0.0, 0.0));
}

TEST(SmaaAreaTexture, ZAndUShapesByHand) {
  // Pattern 9 (Z: down at the left end, up at the right end), left 0, right 1: d = 2, line
  // (0, -0.5) → (2, 0.5); pixel [0, 1] has heights -0.5 and 0: area 0.25 below → (63, 0)
  // at tile (3, 1), texel (0, 1). Its mirror pixel (left 1, right 0) gets (0, 63).
  const Image8& t = SmaaAreaTexture();
  EXPECT_EQ(SmaaAreaOrtho(9, 0, 1, 0.0), std::make_pair(0.25, 0.0));
  EXPECT_EQ(SmaaAreaOrtho(9, 1, 0, 0.0), std::make_pair(0.0, 0.25));
  EXPECT_EQ(t.Pixel(48 + 0, 16 + 1)[0], 63);
  EXPECT_EQ(t.Pixel(48 + 1, 16 + 0)[1], 63);
  // Pattern 3 (U: both crossing edges down), left = right = 0: each half-line gives 0.125
  // (as above), smoothed toward sqrt(2·0.125)/2 = 0.25 with p = d/32 = 1/32:
  // 0.25 + (0.125 − 0.25)/32 = 0.24609375, twice → 0.4921875 → int(125.5078) = 125.
  const auto u = SmaaAreaOrtho(3, 0, 0, 0.0);
  EXPECT_DOUBLE_EQ(u.first, 0.4921875);
  EXPECT_EQ(u.second, 0.0);
  EXPECT_EQ(t.Pixel(48, 48)[0], 125);
  // No crossing edges (pattern 0) and crossing edges on both sides of both ends (5, 10, 15)
  // are not revectorised.
  for (int p : {0, 5, 10, 15}) EXPECT_EQ(SmaaAreaOrtho(p, 3, 7, 0.0), std::make_pair(0.0, 0.0)) << p;
  EXPECT_EQ(t.Pixel(5, 9)[0], 0);
}

TEST(SmaaAreaTexture, DiagonalByHandAndLayout) {
  // Pattern 3 of the diagonal block (crossing edges at both ends): one line from (1, 0) to
  // (1 + d, d), i.e. y = x − 1. The opposite pixel at (1, 1) + (l, l) lies entirely on the
  // side y ≥ x − 1 except its corner sample, so its area is 0 or 1/900 → byte 0; the pixel
  // at (1, 0) + (l, l) has the 435 lattice samples with i > j strictly on the covered
  // side and 30 samples exactly on the line, so 1 − area is in [435, 465]/900 → byte in
  // [123, 131] (which side the on-line samples fall is decided by double rounding).
  const auto a = SmaaAreaDiag(3, 2, 5, 0.0, 0.0);
  EXPECT_GE(a.first, 435.0 / 900.0);
  EXPECT_LE(a.first, 465.0 / 900.0);
  EXPECT_LE(a.second, 1.0 / 900.0);
  const Image8& t = SmaaAreaTexture();
  const uint8_t* px = t.Pixel(80 + 20 * 1 + 2, 20 * 2 + 5);  // tile (1, 2) of pattern 3, texel (2, 5)
  EXPECT_GE(px[0], 123);
  EXPECT_LE(px[0], 131);
  EXPECT_EQ(px[1], 0);
  // Only the subsample-0 band (rows 0..79) is generated; SMAA 1x never reads the others.
  EXPECT_EQ(t.Width(), 160);
  EXPECT_EQ(t.Height(), 560);
  for (int y = 80; y < 560; y += 37) {
    for (int x = 0; x < 160; x += 13) EXPECT_EQ(t.Pixel(x, y)[0] | t.Pixel(x, y)[1], 0) << x << "," << y;
  }
}

// ---------------------------------------------------------------- search texture

TEST(SmaaSearchTexture, EntriesByHand) {
  // The pseudo-gather value of four edges (e0 e1 above, e2 e3 on the current row) sampled
  // at (-0.25, -0.125) is (e0·0.25 + e1·0.75)·0.125 + (e2·0.25 + e3·0.75)·0.875, in 32nds:
  // 4a + 28b. top = [0,0,1,1] → 28/32; top = [0,0,0,1] → 21/32; left = [0,1,0,0] → 3/32.
  // Left search, no crossing edges, both edges on: continue 2 → 254 at column 0,
  // row 32 − 28 = 4 (cropped at 17 and flipped).
  EXPECT_EQ(SmaaSearchDelta(false, 0.0, 28.0 / 32.0), 2);
  const Image8& t = SmaaSearchTexture();
  EXPECT_EQ(t.Width(), 64);
  EXPECT_EQ(t.Height(), 16);
  EXPECT_EQ(t.Pixel(0, 4)[0], 254);
  // A crossing edge (left[1]) stops the second step: 1 → 127 at column 3, row 4.
  EXPECT_EQ(SmaaSearchDelta(false, 3.0 / 32.0, 28.0 / 32.0), 1);
  EXPECT_EQ(t.Pixel(3, 4)[0], 127);
  // Right search, only the current pixel's edge on: 1 → 127 at column 33 + 0, row 11.
  EXPECT_EQ(SmaaSearchDelta(true, 0.0, 21.0 / 32.0), 1);
  EXPECT_EQ(t.Pixel(33, 11)[0], 127);
  // Right search with a crossing edge on the current pixel (left[3]): 0.
  EXPECT_EQ(SmaaSearchDelta(true, 21.0 / 32.0, 28.0 / 32.0), 0);
  EXPECT_EQ(t.Pixel(33 + 21, 4)[0], 0);
  // 2/32 is no gather value (4a + 28b ≠ 2): the table holds 0 there.
  EXPECT_EQ(SmaaSearchDelta(false, 2.0 / 32.0, 28.0 / 32.0), -1);
  EXPECT_EQ(t.Pixel(2, 4)[0], 0);
}

// ---------------------------------------------------------------- pass 1

TEST(SmaaEdges, LumaStepAndLocalContrastByHand) {
  // Row: 0 0 51 255 255 255 (gray codes). Luma = k/255 (the weights sum to 1).
  // x = 2: |0.2 − 0| = 0.2 ≥ 0.1 → left edge; but its right neighbour differs by 0.8 and
  //        2 · 0.2 < 0.8: local contrast adaptation drops it.
  // x = 3: |1 − 0.2| = 0.8 → left edge; max delta 0.8 (left-left: |0.2 − 0| = 0.2) kept.
  Image8 img = Gray(6, 3, 0);
  const uint8_t row[6] = {0, 0, 51, 255, 255, 255};
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 6; ++x) SetGray(img, x, y, row[x]);
  }
  const Image8 e = SmaaEdgeTexture(img, SmaaPreset("high"));
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 6; ++x) {
      EXPECT_EQ(e.Pixel(x, y)[0], x == 3 ? 255 : 0) << x << "," << y;
      EXPECT_EQ(e.Pixel(x, y)[1], 0) << x << "," << y;  // no top edges; row 0 reads itself (clamp)
    }
  }
  // With local_contrast = 5 the weak edge survives (5 · 0.2 ≥ 0.8).
  SmaaParams p = SmaaPreset("high");
  p.local_contrast_factor = 5.0f;
  EXPECT_EQ(SmaaEdgeTexture(img, p).Pixel(2, 1)[0], 255);
  // "Top" is the row above: a dark row 0 over a bright frame marks row 1's top edges.
  Image8 v = Gray(4, 4, 200);
  for (int x = 0; x < 4; ++x) SetGray(v, x, 0, 0);
  const Image8 ev = SmaaEdgeTexture(v, SmaaPreset("high"));
  for (int x = 0; x < 4; ++x) {
    EXPECT_EQ(ev.Pixel(x, 1)[1], 255);
    EXPECT_EQ(ev.Pixel(x, 0)[1], 0);
    EXPECT_EQ(ev.Pixel(x, 2)[1], 0);
  }
}

TEST(SmaaEdges, ColorCatchesChromaOnlyEdges) {
  // (255, 0, 0) beside (0, 76, 0): lumas 0.2126 and 76/255 · 0.7152 = 0.21316, |Δ| < 0.1:
  // no luma edge; the largest channel difference is 1: a colour edge.
  Image8 img = Gray(4, 2, 0);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 4; ++x) {
      uint8_t* p = img.Pixel(x, y);
      p[0] = x < 2 ? 255 : 0;
      p[1] = x < 2 ? 0 : 76;
      p[2] = 0;
    }
  }
  SmaaParams p = SmaaPreset("high");
  EXPECT_EQ(SmaaEdgeTexture(img, p).Pixel(2, 0)[0], 0);
  p.detection = SmaaParams::Detection::kColor;
  EXPECT_EQ(SmaaEdgeTexture(img, p).Pixel(2, 0)[0], 255);
}

// ---------------------------------------------------------------- passes 2 and 3 by hand

TEST(SmaaBlending, ZStepWeightsByHand) {
  // Edge texture of a Z step on a 16×16 frame: a top edge on pixels (8, 8) and (9, 8), a
  // crossing edge going down at its left end (left edge of (8, 8)) and one going up at its
  // right end (left edge of (10, 7)). Worked through SMAA.hlsl by hand (see docs/smaa.md):
  // pixel (8, 8): left search stops at once (crossing edge), search texture 127 → end at
  //   x = 8.5: distance 0; right search: 127 → distance 1; crossing codes round(4·0.75) = 3
  //   and round(4·0.25) = 1 → tile (3, 1) = pattern 9 (Z), texel (0, 1): area 0.25 → 63.
  // pixel (9, 8): left search reads 254 (two more pixels) → distance 1; right distance 0
  //   → texel (1, 0): (0, 63).
  Image8 edges(16, 16, 4, 0);
  edges.Pixel(8, 8)[1] = 255;
  edges.Pixel(9, 8)[1] = 255;
  edges.Pixel(8, 8)[0] = 255;
  edges.Pixel(10, 7)[0] = 255;
  const Image8 w = SmaaBlendTexture(edges, NoDiagNoCorner());
  EXPECT_EQ(w.Pixel(8, 8)[0], 63);
  EXPECT_EQ(w.Pixel(8, 8)[1], 0);
  EXPECT_EQ(w.Pixel(9, 8)[0], 0);
  EXPECT_EQ(w.Pixel(9, 8)[1], 63);
  // Pixels without a top edge get no horizontal weights.
  EXPECT_EQ(w.Pixel(10, 8)[0] | w.Pixel(10, 8)[1] | w.Pixel(7, 8)[0] | w.Pixel(7, 8)[1], 0);
}

TEST(SmaaBlending, CornerRoundingByHand) {
  // The Z step of ZStepWeightsByHand with corner detection on (diagonals off). The corner
  // test of SMAADetectHorizontalCornerPattern reads, at the left end L (texel centre of
  // (8, 8): the left search ended there, distance 0) and the right end R (centre of (9, 8),
  // distance 0 for pixel (9, 8)), the left edges one row below / two rows above:
  //   factor.x = 1 − rounding.x·E(L + (0, 1)).r − rounding.y·E(R + (1, 1)).r
  //   factor.y = 1 − rounding.x·E(L + (0, −2)).r − rounding.y·E(R + (1, −2)).r
  // with rounding = (1 − corner_rounding/100)·lr/(lr.x + lr.y), lr = step(d.xy, d.yx):
  // the nearer end (both when d.x = d.y). All reads are texel centres at this power-of-two
  // size: 0 or 1 exactly.
  // In ZStepWeightsByHand the crossing edges are one pixel long: the reads are 0, factor 1,
  // weights 63. Here they continue: the left one down to (8, 9), the right one up to (10, 6):
  // a real corner of the shape, which revectorisation would cut.
  // pixel (8, 8): d = (0, 1) → lr = (1, 0), rounding = (0.75, 0); E(8, 9).r = 1 →
  //   factor.x = 0.25: r = StoreUnorm8(0.25 · 63·fl(1/255)) = round(15.75) = 16.
  // pixel (9, 8): d = (1, 0) → lr = (0, 1), rounding = (0, 0.75); E(10, 6).r = 1 →
  //   factor.y = 0.25: g = 16.
  // corner_rounding = 100 keeps the full weight (63); 0 removes it (0).
  Image8 edges(16, 16, 4, 0);
  edges.Pixel(8, 8)[1] = 255;
  edges.Pixel(9, 8)[1] = 255;
  edges.Pixel(8, 8)[0] = 255;
  edges.Pixel(10, 7)[0] = 255;
  SmaaParams p = NoDiagNoCorner();
  p.corner = true;
  EXPECT_EQ(p.corner_rounding, 25);
  const Image8 short_crossings = SmaaBlendTexture(edges, p);
  EXPECT_EQ(short_crossings.Pixel(8, 8)[0], 63);
  EXPECT_EQ(short_crossings.Pixel(9, 8)[1], 63);
  edges.Pixel(8, 9)[0] = 255;
  edges.Pixel(10, 6)[0] = 255;
  const Image8 w = SmaaBlendTexture(edges, p);
  EXPECT_EQ(w.Pixel(8, 8)[0], 16);
  EXPECT_EQ(w.Pixel(8, 8)[1], 0);
  EXPECT_EQ(w.Pixel(9, 8)[0], 0);
  EXPECT_EQ(w.Pixel(9, 8)[1], 16);
  p.corner_rounding = 100;
  EXPECT_EQ(SmaaBlendTexture(edges, p).Pixel(8, 8)[0], 63);
  EXPECT_EQ(SmaaBlendTexture(edges, p).Pixel(9, 8)[1], 63);
  p.corner_rounding = 0;
  EXPECT_EQ(SmaaBlendTexture(edges, p).Pixel(8, 8)[0], 0);
  EXPECT_EQ(SmaaBlendTexture(edges, p).Pixel(9, 8)[1], 0);
  // The vertical twin (SMAADetectVerticalCornerPattern): the transposed edge texture (x ↔ y,
  // left ↔ top) gives the same weights in the left-edge slots (b, a) at the transposed pixels.
  Image8 t(16, 16, 4, 0);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      t.Pixel(y, x)[0] = edges.Pixel(x, y)[1];
      t.Pixel(y, x)[1] = edges.Pixel(x, y)[0];
    }
  }
  p.corner_rounding = 25;
  const Image8 wt = SmaaBlendTexture(t, p);
  EXPECT_EQ(wt.Pixel(8, 8)[2], 16);
  EXPECT_EQ(wt.Pixel(8, 8)[3], 0);
  EXPECT_EQ(wt.Pixel(8, 9)[2], 0);
  EXPECT_EQ(wt.Pixel(8, 9)[3], 16);
}

TEST(SmaaBlending, DiagonalSearchByHand) {
  // A 45° staircase on a 32×32 edge texture: both edges (left and top) on the 16 pixels
  // x + y = 31, 8 ≤ x ≤ 23 — what a bright region {x + y ≥ 31} gives. smaa-high: diagonals
  // on, max_search_steps_diag = 8 (corners off, so only the diagonal path shapes the weights).
  // Pixel P = (20, 11), traced through SMAACalculateDiagWeights:
  //   SearchDiag1 down-left (−1, +1): (19, 12) ... (12, 19) all have both edges (w = 1), so
  //     the loop runs to its limit, z = max_search_steps_diag − 1 = 7; the last fetch has a
  //     top edge: d.x = 7 + 1 = 8, and d.z = 1 ≥ 0.9: no crossing edge looked for (cc.x = 0).
  //   SearchDiag1 up-right (+1, −1): (21, 10), (22, 9), (23, 8), then (24, 7) without edges:
  //     d.y = 3, d.w = 0: the end's crossing edges are read at texel (23.5 + 1, 11.5 − 3.25)
  //     = (24.5, 8.25): 0.25·E(24, 7) + 0.75·E(24, 8), decoded (r·|5r − 3.75|, round g).
  //   d.x + d.y = 11 > 2: AreaDiag at texel (80 + 20·cc.x + 8, 20·cc.y + 3).
  //   SearchDiag2 (−1, −1) reads between (19, 10) and (20, 10): no edges, d.x = 0; (21, 11) has
  //     no left edge: d.y = 0; no second contribution.
  //   A diagonal was found (r ≠ −g): the orthogonal and vertical passes are skipped: b = a = 0.
  // Without a crossing edge: pattern 0 at texel (88, 3). AreaTex.py's pattern 0 averages the
  // lines (1, 1)→(1 + d, 1 + d) and (1, 0)→(1 + d, d) (d = l + r + 1 = 12), sampled on the
  // 30×30 lattice of pixel (1 + l, l) (weight 1 − area) and of (1 + l, 1 + l) (area); counted
  // by hand with the samples exactly on a line (which double rounding decides) either way:
  //   first line:  1 − [899, 900]/900, [435, 465]/900;  second: 1 − [435, 465]/900, [0, 1]/900
  //   average: both weights in [435, 466]/1800 → int(255·v) in [61, 66].
  // With a top edge on (24, 8): 0.75·1 → round → cz = 1, cc.y = 2·1 + 0 = 2: tile (0, 2),
  // pattern 2 (crossing code 2 at the far end), texel (88, 43). Its first line starts at the
  // near end's other corner, (0, 0)→(13, 12): on pixel (9, 8) the samples with
  // 116 + 12i > 13j (659, one on the line), on (9, 9) those with 12i − 13j > 261 (31, one on
  // the line); with the second line as above: weights [675, 706]/1800 → [95, 100] and
  // [31, 33]/1800 → 4.
  Image8 edges(32, 32, 4, 0);
  for (int x = 8; x <= 23; ++x) {
    edges.Pixel(x, 31 - x)[0] = 255;
    edges.Pixel(x, 31 - x)[1] = 255;
  }
  const SmaaParams p = SmaaPreset("high");
  ASSERT_TRUE(p.diag);
  ASSERT_EQ(p.max_search_steps_diag, 8);
  const Image8& area = SmaaAreaTexture();
  {
    const Image8 w = SmaaBlendTexture(edges, p);
    const uint8_t* px = w.Pixel(20, 11);
    EXPECT_GE(px[0], 61);
    EXPECT_LE(px[0], 66);
    EXPECT_GE(px[1], 61);
    EXPECT_LE(px[1], 66);
    EXPECT_EQ(px[2] | px[3], 0);
    EXPECT_EQ(px[0], area.Pixel(88, 3)[0]);  // the texel the hand-traced search lands on
    EXPECT_EQ(px[1], area.Pixel(88, 3)[1]);
  }
  edges.Pixel(24, 8)[1] = 255;
  {
    const Image8 w = SmaaBlendTexture(edges, p);
    const uint8_t* px = w.Pixel(20, 11);
    EXPECT_GE(px[0], 95);
    EXPECT_LE(px[0], 100);
    EXPECT_EQ(px[1], 4);
    EXPECT_EQ(px[2] | px[3], 0);
    EXPECT_EQ(px[0], area.Pixel(88, 43)[0]);
    EXPECT_EQ(px[1], area.Pixel(88, 43)[1]);
  }
}

TEST(SmaaBlending, NeighborhoodBlendByHand) {
  // Black rows 0..7 over white rows 8..15. Pixel (8, 8) carries weight r = 63/255 (blend
  // with the pixel above): it fetches at y − 0.24706 texel; the 8-bit fraction of 0.75294
  // is 193/256, so it gets 193/256 of its own white: 0.75390625 · 255 = 192.2 → 192.
  // Pixel (9, 8) carries g = 63/255, read by the pixel above it, (9, 7): it fetches at
  // y + 0.24706, fraction 63/256 of white → 62.75 → 63.
  Image8 in = Gray(16, 16, 0);
  for (int y = 8; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) SetGray(in, x, y, 255);
  }
  Image8 blend(16, 16, 4, 0);
  blend.Pixel(8, 8)[0] = 63;
  blend.Pixel(9, 8)[1] = 63;
  const Image8 out = SmaaNeighborhoodBlend(in, blend, SmaaPreset("high"));
  EXPECT_EQ(out.Pixel(8, 8)[0], 192);
  EXPECT_EQ(out.Pixel(9, 7)[0], 63);
  EXPECT_EQ(out.Pixel(9, 7)[3], 255);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      if ((x == 8 && y == 8) || (x == 9 && y == 7)) continue;
      EXPECT_EQ(out.Pixel(x, y)[0], in.Pixel(x, y)[0]) << x << "," << y;
    }
  }
}

TEST(SmaaBlending, StraightEdgeIsLeftAlone) {
  // A horizontal edge across the whole frame has no ends and no crossing edges: pattern 0,
  // area 0, no blending, at a power-of-two and at an odd size (8-bit sub-texel fetches).
  for (int w : {64, 301}) {
    Image8 in = Gray(w, 9, 30);
    for (int y = 5; y < 9; ++y) {
      for (int x = 0; x < w; ++x) SetGray(in, x, y, 220);
    }
    for (const char* preset : {"low", "medium", "high", "ultra"}) {
      const Image8 out = Smaa(in, SmaaPreset(preset), "", nullptr);
      for (int y = 0; y < 9; ++y) {
        for (int x = 0; x < w; ++x)
          ASSERT_EQ(out.Pixel(x, y)[0], in.Pixel(x, y)[0]) << preset << " w " << w << " " << x << "," << y;
      }
    }
  }
}

TEST(SmaaBlending, ExactSubTexelLeaksSpuriousWeights) {
  // The design point: at a non-power-of-two size the exact float fetch of the edge
  // texture at a pixel's own centre mixes in ~1e-7 of a neighbouring texel, which passes
  // `e.g > 0` / `e.r > 0`: pixels beside an edge run searches that the 8-bit mode (and a
  // GPU) never starts, and may get weights. Vertical stripes 7 px wide on a 301×23 frame.
  Image8 in = Gray(301, 23, 30);
  for (int y = 0; y < 23; ++y) {
    for (int x = 0; x < 301; ++x) SetGray(in, x, y, ((x / 7) % 2) ? 220 : 30);
  }
  SmaaParams p = SmaaPreset("high");
  PostStats fixed, exact;
  Smaa(in, p, "", &fixed);
  p.subtexel = SubTexel::kExact;
  Smaa(in, p, "", &exact);
  EXPECT_GT(exact.taps, fixed.taps);
  // At a power-of-two size the edge-texture coordinates are exact: on this frame (straight
  // full-height edges: no crossing edges, area 0 whatever the fraction) both modes agree,
  // taps included. (Elsewhere the modes can still differ at power-of-two sizes: the area
  // texture is 160×560 and its √d lookups interpolate with the fraction.)
  Image8 pow2 = Gray(256, 16, 30);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 256; ++x) SetGray(pow2, x, y, ((x / 7) % 2) ? 220 : 30);
  }
  PostStats a, b;
  const Image8 oa = Smaa(pow2, p, "", &a);
  p.subtexel = SubTexel::kFixed8;
  const Image8 ob = Smaa(pow2, p, "", &b);
  EXPECT_EQ(oa, ob);
  EXPECT_EQ(a.taps, b.taps);
}

// ---------------------------------------------------------------- symmetry

Image8 Transposed(const Image8& a) {
  Image8 b(a.Height(), a.Width(), 4);
  for (int y = 0; y < a.Height(); ++y) {
    for (int x = 0; x < a.Width(); ++x) {
      for (int c = 0; c < 4; ++c) b.Pixel(y, x)[c] = a.Pixel(x, y)[c];
    }
  }
  return b;
}

Image8 Flipped(const Image8& a) {
  Image8 b(a.Width(), a.Height(), 4);
  for (int y = 0; y < a.Height(); ++y) {
    for (int x = 0; x < a.Width(); ++x) {
      for (int c = 0; c < 4; ++c) b.Pixel(x, a.Height() - 1 - y)[c] = a.Pixel(x, y)[c];
    }
  }
  return b;
}

TEST(SmaaSymmetry, CommutesWithTransposeButNotWithAVerticalFlip) {
  // SMAA's orthogonal processing treats rows and columns alike (the pseudo-gather offsets,
  // searches, crossing edges and corner tests swap x and y), so with diagonals off, on
  // power-of-two frames (exact coordinates both ways), filtering the transposed image gives
  // the transposed result bit for bit: a typo in one orientation's code would break this.
  // Diagonal detection is not symmetric by design: the reference runs it only at pixels
  // with a top edge and stores its weights in the top-edge slots (r, g).
  // A vertical flip is not a symmetry either ("top" is the row above, as in Direct3D).
  Image8 img = Gray(64, 32, 20);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 64; ++x) {
      const bool in =
          (x - 30) * (x - 30) + (y - 17) * (y - 17) < 150 || (3 * x + 7 * y) % 97 < 20 || (x > 50 && y > 20);
      SetGray(img, x, y, in ? 230 : 20);
    }
  }
  int flip_differs = 0;
  for (const char* preset : {"low", "medium", "high", "ultra"}) {
    for (auto det : {SmaaParams::Detection::kLuma, SmaaParams::Detection::kColor}) {
      SmaaParams p = SmaaPreset(preset);
      p.detection = det;
      p.diag = false;
      const Image8 direct = Smaa(img, p, "", nullptr);
      EXPECT_NE(direct, img) << preset;
      EXPECT_EQ(Transposed(Smaa(Transposed(img), p, "", nullptr)), direct) << preset;
      flip_differs += Flipped(Smaa(Flipped(img), p, "", nullptr)) != direct;
    }
  }
  EXPECT_GT(flip_differs, 0);
}

// ---------------------------------------------------------------- user paths

TEST(Smaa, FlatFrameIsIdentityAndOddSizesWork) {
  for (auto [w, h] : std::vector<std::pair<int, int>>{{1, 1}, {1, 5}, {5, 1}, {2, 3}, {37, 23}}) {
    const Image8 flat = Gray(w, h, 123);
    for (const char* name : {"smaa-low", "smaa-medium", "smaa-high", "smaa-ultra"}) {
      const MethodPlan plan = MakeMethod(name);
      ASSERT_TRUE(plan.IsPostOnly());
      const Image8 out = plan.post(flat, PostOptions{}, nullptr);
      EXPECT_EQ(out, flat) << name << " " << w << "x" << h;
    }
    // A checker at odd sizes runs through every path without tripping a check.
    Image8 ch = Gray(w, h, 0);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) SetGray(ch, x, y, ((x + y) & 1) ? 255 : 0);
    }
    EXPECT_EQ(Smaa(ch, SmaaPreset("ultra"), "", nullptr).Width(), w);
  }
}

TEST(Smaa, PresetsMatchTheReference) {
  const SmaaParams low = SmaaPreset("low"), med = SmaaPreset("medium"), high = SmaaPreset("high"),
                   ultra = SmaaPreset("ultra");
  EXPECT_EQ(low.threshold, 0.15f);
  EXPECT_EQ(low.max_search_steps, 4);
  EXPECT_FALSE(low.diag || low.corner);
  EXPECT_EQ(med.threshold, 0.1f);
  EXPECT_EQ(med.max_search_steps, 8);
  EXPECT_FALSE(med.diag || med.corner);
  EXPECT_EQ(high.max_search_steps, 16);
  EXPECT_EQ(high.max_search_steps_diag, 8);
  EXPECT_EQ(high.corner_rounding, 25);
  EXPECT_TRUE(high.diag && high.corner);
  EXPECT_EQ(ultra.threshold, 0.05f);
  EXPECT_EQ(ultra.max_search_steps, 32);
  EXPECT_EQ(ultra.max_search_steps_diag, 16);
  const MethodPlan plan = MakeMethod("smaa-ultra:threshold=0.2,diag=off,subtexel=exact");
  EXPECT_EQ(plan.spec, "smaa-ultra:threshold=0.2,diag=off,subtexel=exact");
  EXPECT_EQ(plan.debug_views, SmaaDebugViews());
}

TEST(Smaa, BadParametersAreUserErrors) {
  for (const char* bad : {"smaa-high:threshold=0.6", "smaa-high:threshold=-0.1", "smaa-high:max_search_steps=113",
                          "smaa-high:max_search_steps=2.5", "smaa-high:max_search_steps_diag=21",
                          "smaa-high:corner_rounding=101", "smaa-high:diag=maybe", "smaa-high:detection=depth",
                          "smaa-high:subtexel=9bit", "smaa-high:predication=1", "smaa-extreme"}) {
    EXPECT_THROW(MakeMethod(bad), UserError) << bad;
  }
  const MethodPlan plan = MakeMethod("smaa-high");
  PostOptions opt;
  opt.debug_view = "luma";
  EXPECT_THROW(plan.post(Gray(4, 4, 0), opt, nullptr), UserError);
}

TEST(Smaa, DebugViews) {
  Image8 in = Gray(12, 12, 0);
  for (int y = 6; y < 12; ++y) {
    for (int x = 4; x < 12; ++x) SetGray(in, x, y, 255);
  }
  const MethodPlan plan = MakeMethod("smaa-high");
  PostOptions opt;
  opt.debug_view = "edges";
  const Image8 e = plan.post(in, opt, nullptr);
  EXPECT_EQ(e.Pixel(4, 8)[0], 255);  // left edge of the white block
  EXPECT_EQ(e.Pixel(8, 6)[1], 255);  // its top edge
  EXPECT_EQ(e.Pixel(8, 8)[0] | e.Pixel(8, 8)[1], 0);
  EXPECT_EQ(e.Pixel(0, 0)[3], 255);
  opt.debug_view = "weights";
  const Image8 w = plan.post(in, opt, nullptr);
  int nonzero = 0;
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 12; ++x) nonzero += (w.Pixel(x, y)[0] | w.Pixel(x, y)[1]) != 0;
  }
  EXPECT_GT(nonzero, 0);  // the block's corner is an L shape: some weights
}

}  // namespace
}  // namespace aalab
