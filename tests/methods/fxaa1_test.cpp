// Tests for FXAA 1.0 (methods/fxaa1.cpp). Expected values are worked out by hand from the
// whitepaper's equations (arithmetic in the comments); none is copied from the program.
//
// Notation: a grey value k has FxaaLuma = k/255 · (1 + 0.587/0.299) = k/255 · Lw, with
// Lw ≈ 2.963 the luma of white. Black/white images therefore have lumas 0 and Lw.
#include "methods/fxaa1.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "methods/registry.h"

namespace aalab {
namespace {

Image8 Solid(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
  Image8 img(w, h, 4, 255);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      img.At(x, y, 0) = r;
      img.At(x, y, 1) = g;
      img.At(x, y, 2) = b;
    }
  }
  return img;
}
Image8 Grey(int w, int h, uint8_t v) { return Solid(w, h, v, v, v); }
void SetGrey(Image8& img, int x, int y, uint8_t v) {
  for (int c = 0; c < 3; ++c) img.At(x, y, c) = v;
}
uint8_t G(const Image8& img, int x, int y) { return img.At(x, y, 0); }

Image8 Apply(const Image8& in, const Fxaa1Params& p, const std::string& view = "", PostStats* stats = nullptr) {
  return Fxaa1(in, p, view, stats);
}

Fxaa1Trace Trace(const Image8& in, int x, int y, const Fxaa1Params& p, uint64_t* taps = nullptr) {
  BilinearSampler tex(in);
  Fxaa1Trace t = Fxaa1TracePixel(tex, x, y, p);
  if (taps != nullptr) *taps = tex.Taps();
  return t;
}

// The staircase used by several tests: white above, black below, the boundary row
// b(x) = 3 + floor(x / 16) steps down one row every 16 columns (a slope of 1/16).
Image8 Staircase(int w = 64, int h = 12) {
  Image8 img = Grey(w, h, 0);
  for (int x = 0; x < w; ++x) {
    const int b = 3 + x / 16;
    for (int y = 0; y < b && y < h; ++y) SetGrey(img, x, y, 255);
  }
  return img;
}

// ---------------------------------------------------------------------------------------
// Flat input.

TEST(Fxaa1, FlatImageIsUnchangedByEveryPreset) {
  // range = 0 < max(EDGE_THRESHOLD_MIN > 0, ...) ⇒ early exit everywhere: 5 taps a pixel.
  const Image8 in = Solid(23, 17, 90, 140, 200);
  for (int preset = 0; preset <= 5; ++preset) {
    PostStats stats;
    EXPECT_EQ(Apply(in, Fxaa1Preset(preset), "", &stats), in) << "preset " << preset;
    EXPECT_EQ(stats.taps, 5u * 23u * 17u) << "preset " << preset;
  }
}

TEST(Fxaa1, ZeroThresholdsOnFlatImageAreSafe) {
  // Both edge thresholds 0: range = 0 is not < max(0, 0), so every pixel runs the whole
  // algorithm and the shader would compute rangeL/range = 0/0. Guard ⇒ blendL = 0.
  // gradient = 0 ⇒ |lumaEnd − lumaPair| >= 0 ends both searches at the first fetch:
  // dstN = dstP = 1, directionN = (1 < 1) = false, lumaEnd = lumaPair ⇒ (0<0) == (0<0) ⇒ no
  // shift; spanLength = 2 ⇒ offset = 0 ⇒ rgbF = rgbM and out = rgbF + 0·(rgbL − rgbF) = rgbM.
  // Taps: 9 neighbourhood + 1 + 1 search + 1 final = 12 a pixel (search_acceleration 1),
  // 9 + 4 + 4 + 1 = 18 with search_acceleration 4 (each fetch = 4 bilinear probes).
  const Image8 in = Solid(11, 7, 90, 140, 200);
  Fxaa1Params p = Fxaa1Preset(3);
  p.edge_threshold = 0.0f;
  p.edge_threshold_min = 0.0f;
  PostStats stats;
  EXPECT_EQ(Apply(in, p, "", &stats), in);
  EXPECT_EQ(stats.taps, 12u * 11u * 7u);
  const Fxaa1Trace t = Trace(in, 5, 3, p);
  EXPECT_FALSE(t.early_exit);
  EXPECT_EQ(t.blend_l, 0.0f);
  EXPECT_EQ(t.offset, 0.0f);
  EXPECT_FALSE(std::isnan(t.rgb_out[0]));

  p.search_acceleration = 4;
  p.subpix_trim = 0.0f;
  PostStats stats4;
  EXPECT_EQ(Apply(in, p, "", &stats4), in);
  EXPECT_EQ(stats4.taps, 18u * 11u * 7u);
}

// ---------------------------------------------------------------------------------------
// Sub-pixel aliasing: an isolated dot.

TEST(Fxaa1, IsolatedDotGetsLowpassBlendCappedAtCap) {
  // White dot M at (4,4) on black. N = W = E = S = 0, so lumaL = 0, rangeL = Lw, range = Lw:
  //   ratio = 1, blendL = max(0, 1 − 1/4)·(1/(1 − 1/4)) = 1, then min(CAP, 1) = CAP.
  // Orientation: edgeVert = |0.5·0 − Lw + 0.5·0| = Lw = edgeHorz ⇒ horzSpan (ties horizontal);
  // gradientN = gradientS = Lw ⇒ pairN (ties N); lumaPair = Lw/2, limit Lw/4. The first
  // fetches on either side read two black texels: |0 − Lw/2| >= Lw/4 ⇒ both done;
  // dstN = dstP = start ⇒ offset = 0.5 − start/(2·start) = 0 ⇒ rgbF = white.
  // Presets 1-5 (CAP 3/4, 3x3 box rgbL = 1/9):
  //   out = rgbF + 3/4·(1/9 − 1) = 1/4 + 1/12 = 1/3 ⇒ 255/3 = 85.0 ⇒ 85.
  // Preset 0 (CAP 2/3, cross rgbL = 1/5): out = 1/3 + 2/3·1/5 = 7/15 ⇒ 119.0 ⇒ 119.
  // The dot's 4-neighbours: lumaL = Lw/4, ratio 1/4, blendL = max(0, 0) = 0; their pair
  // gradients are both 0 so the limit is 0 and both searches end at once with
  // dstN = dstP, lumaEnd on the P side = 0 = lumaPair ⇒ no shift ⇒ unchanged (0).
  // Diagonal neighbours: N, W, M, E, S all black ⇒ early exit. So only the dot changes.
  Image8 in = Grey(9, 9, 0);
  SetGrey(in, 4, 4, 255);
  for (int preset = 0; preset <= 5; ++preset) {
    Image8 expected = in;
    SetGrey(expected, 4, 4, preset == 0 ? 119 : 85);
    EXPECT_EQ(Apply(in, Fxaa1Preset(preset)), expected) << "preset " << preset;
  }
  const Fxaa1Trace t = Trace(in, 4, 4, Fxaa1Preset(3));
  EXPECT_FLOAT_EQ(t.blend_l, 0.75f);
  EXPECT_TRUE(t.horz_span);
  EXPECT_TRUE(t.pair_n);
  EXPECT_EQ(t.offset, 0.0f);
  EXPECT_NEAR(t.rgb_l[0], 1.0 / 9.0, 1e-7);
}

// ---------------------------------------------------------------------------------------
// End-of-edge search and the sub-pixel shift on a long staircase.

TEST(Fxaa1, StaircaseOffsetsFallLinearlyFromStepEndsToMiddle) {
  // Segment k = 1 covers columns 16..31 with white rows < 4 and black rows >= 4; segment 0
  // has the boundary one row higher (rows 3 and 4 both black), segment 2 one row lower
  // (rows 3 and 4 both white). Take column x = 16 + j.
  // Black pixel (x, 4): pairs with N (white), lumaPair = Lw/2, limit Lw/4. Searching along
  // v = 4 (halfway between rows 3 and 4): pairs inside the segment read Lw/2 (go on); the
  // N search stops at column 15 (pair 0,0 ⇒ |0 − Lw/2| >= Lw/4), the P search at column 32
  // (pair Lw,Lw). dstN = (x + 0.5) − 15.5 = j + 1, dstP = 32.5 − (x + 0.5) = 16 − j,
  // spanLength = 17. Needs at most 16 fetches: preset 3 reaches.
  //   j <= 7: directionN; lumaEnd = 0: (lumaM − Lw/2 < 0) == (0 − Lw/2 < 0) ⇒ no shift.
  //   j >= 8: the P end, lumaEnd = Lw: (true) != (false) ⇒ shift towards the pair (−y) by
  //           0.5 − (16 − j)/17, rising linearly from 1/34 (j = 8) to 15/34 (j = 15).
  // White pixel (x, 3): pairs with S, same pair line and ends. lumaM − Lw/2 > 0.
  //   j <= 7: N end, lumaEnd = 0 ⇒ shift towards +y by 0.5 − (j + 1)/17: 15/34 at j = 0
  //           falling to 1/34 at j = 7.   j >= 8: P end, lumaEnd = Lw ⇒ no shift.
  const Image8 in = Staircase();
  const Fxaa1Params p = Fxaa1Preset(3);
  for (int j = 0; j < 16; ++j) {
    const int x = 16 + j;
    const Fxaa1Trace black = Trace(in, x, 4, p);
    ASSERT_FALSE(black.early_exit) << j;
    EXPECT_TRUE(black.horz_span) << j;
    EXPECT_TRUE(black.pair_n) << j;
    EXPECT_TRUE(black.done_n && black.done_p) << j;
    EXPECT_FLOAT_EQ(black.dst_n, static_cast<float>(j + 1)) << j;
    EXPECT_FLOAT_EQ(black.dst_p, static_cast<float>(16 - j)) << j;
    const double black_expected = j <= 7 ? 0.0 : -(0.5 - (16.0 - j) / 17.0);
    EXPECT_NEAR(black.offset, black_expected, 1e-6) << "black j=" << j;

    const Fxaa1Trace white = Trace(in, x, 3, p);
    ASSERT_FALSE(white.early_exit) << j;
    EXPECT_TRUE(white.horz_span) << j;
    EXPECT_FALSE(white.pair_n) << j;
    const double white_expected = j <= 7 ? 0.5 - (j + 1.0) / 17.0 : 0.0;
    EXPECT_NEAR(white.offset, white_expected, 1e-6) << "white j=" << j;
  }
  // The shifted fetch is a bilinear blend of the pixel and its pair: black j = 14 is shifted
  // up by 0.5 − 2/17 = 13/34 ⇒ weight 13/34 on the white texel above.
  EXPECT_NEAR(Trace(in, 30, 4, p).rgb_f[0], 13.0 / 34.0, 1e-6);

  // Offset view: white j = 0 is shifted +y by 15/34 ⇒ skyblue (0.2, 0.6, 1) mixed with the
  // grey lumaO = Lw/Lw = 1 by |2·offset| = 15/17: r = 0.2·15/17 + 2/17 = 5/17 ⇒ 75,
  // g = 0.6·15/17 + 2/17 = 11/17 ⇒ 165, b = 1 ⇒ 255. Unshifted edge pixels are grey.
  const Image8 view = Apply(in, p, "offset");
  EXPECT_EQ(view.At(16, 3, 0), 75);
  EXPECT_EQ(view.At(16, 3, 1), 165);
  EXPECT_EQ(view.At(16, 3, 2), 255);
  EXPECT_EQ(view.At(24, 3, 0), 255);  // j = 8, white, no shift: grey 1
  EXPECT_EQ(view.At(24, 3, 2), 255);
  EXPECT_EQ(view.At(20, 4, 0), 0);  // j = 4, black, no shift: grey 0
}

TEST(Fxaa1, SearchStepsLimitTheReach) {
  // Black staircase pixel j = 15 (x = 31, y = 4): the P end is 1 texel away, the N end 16.
  // Preset 3: offset −(0.5 − 1/17). With search_steps = 4 the N search fetches at 1..4
  // texels, never finds the end and has advanced once more: dstN = 5, done_n = false;
  // dstP = 1 ⇒ offset −(0.5 − 1/6) = −1/3.
  const Image8 in = Staircase();
  Fxaa1Params p = Fxaa1Preset(3);
  EXPECT_NEAR(Trace(in, 31, 4, p).offset, -(0.5 - 1.0 / 17.0), 1e-6);
  p.search_steps = 4;
  const Fxaa1Trace t = Trace(in, 31, 4, p);
  EXPECT_FALSE(t.done_n);
  EXPECT_EQ(t.fetches_n, 4);
  EXPECT_FLOAT_EQ(t.dst_n, 5.0f);
  EXPECT_FLOAT_EQ(t.dst_p, 1.0f);
  EXPECT_NEAR(t.offset, -1.0 / 3.0, 1e-6);
}

TEST(Fxaa1, SearchThresholdZeroEndsEverySearchAtOnce) {
  // SEARCH_THRESHOLD = 0 ⇒ limit 0 ⇒ |lumaEnd − lumaPair| >= 0 at the first fetch:
  // dstN = dstP = 1 ⇒ offset = ±(0.5 − 1/2) = 0 for every pixel of the staircase.
  const Image8 in = Staircase();
  Fxaa1Params p = Fxaa1Preset(3);
  p.search_threshold = 0.0f;
  int edges = 0;
  for (int y = 0; y < in.Height(); ++y) {
    for (int x = 0; x < in.Width(); ++x) {
      const Fxaa1Trace t = Trace(in, x, y, p);
      if (t.early_exit) continue;
      ++edges;
      EXPECT_EQ(t.offset, 0.0f) << x << "," << y;
      EXPECT_EQ(t.fetches_n + t.fetches_p, 2) << x << "," << y;
    }
  }
  EXPECT_GE(edges, 2 * 64);
}

// ---------------------------------------------------------------------------------------
// Search acceleration: the anisotropic fetch as a box over N texel pairs.

// White rows 0..3 over black rows 4..7; pixel M = (12, 4) pairs with N (white) and searches
// along v = 4. A "gap" column c has (c, 3) black, so its pair averages 0 instead of Lw/2.
Image8 EdgeWithGaps(std::initializer_list<int> gaps) {
  Image8 img = Grey(48, 8, 0);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 48; ++x) SetGrey(img, x, y, 255);
  }
  for (int c : gaps) SetGrey(img, c, 3, 0);
  return img;
}

TEST(Fxaa1, AccelerationThreeAveragesThreePairs) {
  // Gaps at columns 16 and 18 (4 and 6 texels right of M). lumaPair = Lw/2, limit Lw/4.
  // N = 3: start 2, step 3. P fetch 1 centred at u = 14.5: probes at 13.5, 14.5, 15.5 =
  // columns 13..15, mean Lw/2 ⇒ go on. Fetch 2 at 17.5: columns 16, 17, 18, mean
  // (0 + Lw/2 + 0)/3 = Lw/6, |Lw/6 − Lw/2| = Lw/3 >= Lw/4 ⇒ done: dstP = 17.5 − 12.5 = 5.
  // (A single bilinear fetch at the box centre would read column 17 only and miss both
  // gaps.) N side: 4 fetches at 10.5, 7.5, 4.5, 1.5 find nothing, then advance to −1.5:
  // dstN = 14. Taps: 9 + (4 + 2)·3 probes + 1 = 28.
  const Image8 in = EdgeWithGaps({16, 18});
  Fxaa1Params p = Fxaa1Preset(3);
  p.search_acceleration = 3;
  p.search_steps = 4;
  uint64_t taps = 0;
  const Fxaa1Trace t = Trace(in, 12, 4, p, &taps);
  EXPECT_TRUE(t.horz_span);
  EXPECT_TRUE(t.pair_n);
  EXPECT_TRUE(t.done_p);
  EXPECT_EQ(t.fetches_p, 2);
  EXPECT_FLOAT_EQ(t.dst_p, 5.0f);
  EXPECT_NEAR(t.luma_end_p, t.luma_pair / 3.0f, 1e-6);
  EXPECT_FALSE(t.done_n);
  EXPECT_EQ(t.fetches_n, 4);
  EXPECT_FLOAT_EQ(t.dst_n, 14.0f);
  EXPECT_EQ(taps, 28u);

  // Single-texel fetches (acceleration 1, same reach of 12) stop at the first gap: dstP = 4.
  p.search_acceleration = 1;
  p.search_steps = 12;
  const Fxaa1Trace t1 = Trace(in, 12, 4, p);
  EXPECT_TRUE(t1.done_p);
  EXPECT_FLOAT_EQ(t1.dst_p, 4.0f);
}

TEST(Fxaa1, AccelerationFourSkipsANarrowGap) {
  // One gap at column 15 (3 texels right). N = 4: start 2.5, step 4. Fetch 1 centred at
  // 15.0 averages columns 13..16: (3·Lw/2 + 0)/4 = 3Lw/8, |3Lw/8 − Lw/2| = Lw/8 < Lw/4 ⇒ go
  // on (with search_steps = 1 the search ends here, lumaEndP = 3Lw/8, advanced to 19.0:
  // dstP = 6.5); fetch 2 at 19.0 (columns 17..20) reads Lw/2 ⇒ go on; out of steps,
  // advanced to 23: dstP = 23 − 12.5 = 10.5, not done. Single-texel fetches stop at the
  // gap: dstP = 3.
  const Image8 in = EdgeWithGaps({15});
  Fxaa1Params p = Fxaa1Preset(0);  // steps 2, acceleration 4
  Fxaa1Params one = p;
  one.search_steps = 1;
  const Fxaa1Trace t0 = Trace(in, 12, 4, one);
  EXPECT_FALSE(t0.done_p);
  EXPECT_NEAR(t0.luma_end_p, t0.luma_pair * 0.75f, 1e-6);
  EXPECT_FLOAT_EQ(t0.dst_p, 6.5f);
  const Fxaa1Trace t = Trace(in, 12, 4, p);
  EXPECT_FALSE(t.done_p);
  EXPECT_NEAR(t.luma_end_p, t.luma_pair, 1e-6);
  EXPECT_FLOAT_EQ(t.dst_p, 10.5f);
  p.search_acceleration = 1;
  p.search_steps = 8;
  const Fxaa1Trace t1 = Trace(in, 12, 4, p);
  EXPECT_TRUE(t1.done_p);
  EXPECT_FLOAT_EQ(t1.dst_p, 3.0f);
}

TEST(Fxaa1, AccelerationTwoStartsAtOneAndAHalf) {
  // Gaps at columns 15 and 16. N = 2: start 1.5, step 2. Fetch 1 at 14.0 = columns 13, 14:
  // Lw/2 ⇒ go on; fetch 2 at 16.0 = columns 15, 16: 0 ⇒ done, dstP = 16 − 12.5 = 3.5.
  const Image8 in = EdgeWithGaps({15, 16});
  const Fxaa1Trace t = Trace(in, 12, 4, Fxaa1Preset(2));
  EXPECT_TRUE(t.done_p);
  EXPECT_EQ(t.fetches_p, 2);
  EXPECT_FLOAT_EQ(t.dst_p, 3.5f);
}

// ---------------------------------------------------------------------------------------
// Borders: clamp-to-edge everywhere.

TEST(Fxaa1, CornerDotReadsClampedNeighbours) {
  // White (0,0) on black, preset 3. Clamped reads: N = W = NW = (0,0) white, NE = (1,0),
  // SW = (0,1), E, S, SE black. lumaL = (Lw + Lw + 0 + 0)/4 = Lw/2 ⇒ ratio 1/2 ⇒
  // blendL = (1/2 − 1/4)·4/3 = 1/3. rgbL = 4 whites / 9 = 4/9.
  // edgeVert = |Lw/4 − Lw/2| + |Lw/2 − Lw| + 0 = 3Lw/4 = edgeHorz (same by symmetry) ⇒ horz.
  // gradientN = 0 < gradientS = Lw ⇒ pair S, lumaPair = Lw/2, limit Lw/4, search along v = 1.
  // N side: column −1 clamps to column 0 (white over black = Lw/2) forever: 16 fetches, then
  // one more advance ⇒ dstN = 17. P side: column 1 is black/black ⇒ done, dstP = 1.
  // P nearer, lumaEnd = 0: (Lw − Lw/2 < 0) = false != (0 − Lw/2 < 0) = true ⇒ shift +y by
  // 0.5 − 1/18 = 4/9. rgbF at v = 0.5 + 4/9: 5/9 of row 0 (white) ⇒ 5/9.
  // out = 5/9 + 1/3·(4/9 − 5/9) = 5/9 − 1/27 = 14/27 = 0.5185 ⇒ 132.2 ⇒ 132.
  Image8 in = Grey(6, 5, 0);
  SetGrey(in, 0, 0, 255);
  const Fxaa1Trace t = Trace(in, 0, 0, Fxaa1Preset(3));
  EXPECT_NEAR(t.blend_l, 1.0 / 3.0, 1e-6);
  EXPECT_NEAR(t.rgb_l[0], 4.0 / 9.0, 1e-6);
  EXPECT_TRUE(t.horz_span);
  EXPECT_FALSE(t.pair_n);
  EXPECT_FLOAT_EQ(t.dst_n, 17.0f);
  EXPECT_FLOAT_EQ(t.dst_p, 1.0f);
  EXPECT_NEAR(t.offset, 4.0 / 9.0, 1e-6);
  EXPECT_EQ(G(Apply(in, Fxaa1Preset(3)), 0, 0), 132);
}

// Replicates the border columns `pad` times on the left and right (axis 0) or the border
// rows on the top and bottom (axis 1): the image a clamp-to-edge sampler sees.
Image8 ClampExtend(const Image8& in, int pad, int axis) {
  const int w = in.Width() + (axis == 0 ? 2 * pad : 0);
  const int h = in.Height() + (axis == 1 ? 2 * pad : 0);
  Image8 out(w, h, 4, 255);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int sx = std::clamp(axis == 0 ? x - pad : x, 0, in.Width() - 1);
      const int sy = std::clamp(axis == 1 ? y - pad : y, 0, in.Height() - 1);
      for (int c = 0; c < 4; ++c) out.At(x, y, c) = in.At(sx, sy, c);
    }
  }
  return out;
}

int MaxDiffInCrop(const Image8& small, const Image8& big, int ox, int oy) {
  int worst = 0;
  for (int y = 0; y < small.Height(); ++y) {
    for (int x = 0; x < small.Width(); ++x) {
      for (int c = 0; c < 4; ++c) {
        worst = std::max(worst, std::abs(small.At(x, y, c) - big.At(x + ox, y + oy, c)));
      }
    }
  }
  return worst;
}

TEST(Fxaa1, EdgesTouchingTheBorderMatchTheClampExtendedImage) {
  // A staircase crossing the left and right borders (searches run into the clamp) and one
  // along the top and bottom rows (neighbourhoods read clamped rows): FXAA on the image must
  // equal FXAA on the image extended by replicated borders, cropped. Padding 40 > the
  // longest reach (32 steps + 1). Along-edge padding changes no float position the result
  // depends on (shifts are perpendicular), so the match is exact; padding across an edge
  // moves the shifted fetch's coordinate by 40 texels, and float rounding of
  // v + offset may then move a result by at most one code (it does, once, in preset 3).
  Image8 stairs = Grey(21, 9, 0);
  for (int x = 0; x < 21; ++x) {
    for (int y = 0; y < 2 + x / 7; ++y) SetGrey(stairs, x, y, 230);
  }
  Image8 rows = Grey(19, 6, 30);  // bright row 0, row 1 too from x = 9; a dot on row 5
  for (int x = 0; x < 19; ++x) {
    SetGrey(rows, x, 0, 200);
    if (x >= 9) SetGrey(rows, x, 1, 200);
  }
  SetGrey(rows, 7, 5, 250);
  for (int preset = 0; preset <= 5; ++preset) {
    const Fxaa1Params p = Fxaa1Preset(preset);
    EXPECT_EQ(MaxDiffInCrop(Apply(stairs, p), Apply(ClampExtend(stairs, 40, 0), p), 40, 0), 0) << "preset " << preset;
    EXPECT_LE(MaxDiffInCrop(Apply(rows, p), Apply(ClampExtend(rows, 40, 1), p), 0, 40), 1) << "preset " << preset;
    // Sanity: the border pixels really were processed.
    EXPECT_NE(Apply(stairs, p), stairs) << "preset " << preset;
  }
}

// ---------------------------------------------------------------------------------------
// Parameter overrides.

TEST(Fxaa1, EdgeThresholdAboveContrastLeavesEdgeUntouched) {
  // Grey dot 140 on 100. range = 40/255·Lw ≈ 0.4648, rangeMax = 140/255·Lw ≈ 1.6268.
  // Preset 3: threshold max(1/24, 1.6268/8 = 0.2034) < 0.4648 ⇒ processed:
  //   ratio 1 ⇒ blendL = 3/4; rgbL = (8·100 + 140)/9 = 104.44; rgbF = 140;
  //   out = 140 + 3/4·(104.44 − 140) = 113.33 ⇒ 113.
  // edge_threshold = 0.5: threshold 0.813 > 0.4648 ⇒ early exit, dot stays 140.
  Image8 in = Grey(7, 7, 100);
  SetGrey(in, 3, 3, 140);
  Fxaa1Params p = Fxaa1Preset(3);
  EXPECT_EQ(G(Apply(in, p), 3, 3), 113);
  p.edge_threshold = 0.5f;
  EXPECT_EQ(Apply(in, p), in);
}

TEST(Fxaa1, EdgeThresholdMinSkipsDarks) {
  // Dot 20 on 0: range = rangeMax = 20/255·Lw ≈ 0.2324 > max(1/24, 0.029) ⇒ processed:
  //   out = 20 + 3/4·(20/9 − 20) = 6.67 ⇒ 7. edge_threshold_min = 0.25 > 0.2324 ⇒ untouched.
  Image8 in = Grey(7, 7, 0);
  SetGrey(in, 3, 3, 20);
  Fxaa1Params p = Fxaa1Preset(3);
  EXPECT_EQ(G(Apply(in, p), 3, 3), 7);
  p.edge_threshold_min = 0.25f;
  EXPECT_EQ(Apply(in, p), in);
}

TEST(Fxaa1, SubpixCapAndTrimControlTheLowpassBlend) {
  Image8 in = Grey(9, 9, 0);
  SetGrey(in, 4, 4, 255);
  Fxaa1Params p = Fxaa1Preset(3);
  // CAP = 0: blendL = 0 ⇒ out = rgbF = white (offset 0): the dot is untouched.
  Fxaa1Params cap0 = p;
  cap0.subpix_cap = 0.0f;
  EXPECT_EQ(Apply(in, cap0), in);
  // TRIM = 0: the dot's 4-neighbours have ratio 1/4 ⇒ blendL = min(3/4, 1/4) = 1/4 (with
  // TRIM 1/4 it was 0); their rgbL = 1/9 (the dot in the 3x3 box), rgbF = 0 (no shift) ⇒
  // out = 1/4·1/9 = 0.0278 ⇒ 7.08 ⇒ 7. The dot itself: ratio 1 ⇒ still min(3/4, 1) ⇒ 85.
  Fxaa1Params trim0 = p;
  trim0.subpix_trim = 0.0f;
  Image8 expected = in;
  SetGrey(expected, 4, 4, 85);
  SetGrey(expected, 3, 4, 7);
  SetGrey(expected, 5, 4, 7);
  SetGrey(expected, 4, 3, 7);
  SetGrey(expected, 4, 5, 7);
  EXPECT_EQ(Apply(in, trim0), expected);
  // SUBPIX_FASTER in preset 0 (cross lowpass 1/5 ⇒ 119, see the dot test); with the 3x3 box
  // instead: out = 1/3 + 2/3·1/9 = 11/27 = 0.4074 ⇒ 103.9 ⇒ 104.
  Fxaa1Params box0 = Fxaa1Preset(0);
  box0.subpix_faster = false;
  EXPECT_EQ(G(Apply(in, box0), 4, 4), 104);
}

TEST(Fxaa1, RejectsOutOfRangeParametersAndUnknownViews) {
  const Image8 in = Grey(4, 4, 10);
  Fxaa1Params p = Fxaa1Preset(3);
  p.search_acceleration = 5;
  EXPECT_THROW(Apply(in, p), UserError);
  p = Fxaa1Preset(3);
  p.subpix_trim = 1.0f;
  EXPECT_THROW(Apply(in, p), UserError);
  p = Fxaa1Preset(3);
  p.search_steps = 0;
  EXPECT_THROW(Apply(in, p), UserError);
  EXPECT_THROW(Apply(in, Fxaa1Preset(3), "edges"), UserError);
  EXPECT_THROW(Fxaa1Preset(6), UserError);
  try {
    Apply(in, Fxaa1Preset(3), "offst");
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("negpos"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------
// Debug views.

TEST(Fxaa1, DebugViewsUseTheWhitepaperColours) {
  const Image8 in = Staircase();
  const Fxaa1Params p = Fxaa1Preset(3);
  auto px = [](const Image8& img, int x, int y) {
    return std::array<int, 3>{img.At(x, y, 0), img.At(x, y, 1), img.At(x, y, 2)};
  };
  using C = std::array<int, 3>;
  // Non-edge pixels: grey lumaO = lumaM/(1 + 0.587/0.299): white ⇒ 255, black ⇒ 0.
  for (const std::string& v : Fxaa1DebugViews()) {
    const Image8 img = Apply(in, p, v);
    EXPECT_EQ(px(img, 20, 0), (C{255, 255, 255})) << v;
    EXPECT_EQ(px(img, 20, 10), (C{0, 0, 0})) << v;
  }
  // passthrough: edges red → yellow by blendL/CAP. Interior staircase pixel: blendL 0 ⇒ red.
  // Corner pixel (16,3) (W, S black): blendL = 1/3, 1/3 / (3/4) = 4/9 ⇒ 113.3 ⇒ 113.
  const Image8 pass = Apply(in, p, "passthrough");
  EXPECT_EQ(px(pass, 20, 4), (C{255, 0, 0}));
  EXPECT_EQ(px(pass, 16, 3), (C{255, 113, 0}));
  // horzvert: horizontal spans gold (1, 0.75, 0) ⇒ (255, 191, 0) (191.25).
  const Image8 hv = Apply(in, p, "horzvert");
  EXPECT_EQ(px(hv, 20, 4), (C{255, 191, 0}));
  // A vertical edge: blue (0, 0.5, 1) ⇒ (0, 128, 255) (127.5 rounds to nearest even?
  // no: lround(127.5) = 128, away from zero).
  Image8 vert = Grey(8, 6, 0);
  for (int y = 0; y < 6; ++y) {
    for (int x = 4; x < 8; ++x) SetGrey(vert, x, y, 255);
  }
  EXPECT_EQ(px(Apply(vert, p, "horzvert"), 3, 2), (C{0, 128, 255}));
  // pair: black row pairs with N ⇒ blue; white row pairs with S ⇒ green.
  const Image8 pair = Apply(in, p, "pair");
  EXPECT_EQ(px(pair, 20, 4), (C{0, 0, 255}));
  EXPECT_EQ(px(pair, 20, 3), (C{0, 255, 0}));
  // negpos: j <= 7 has the negative end nearer ⇒ red, j >= 8 ⇒ blue.
  const Image8 np = Apply(in, p, "negpos");
  EXPECT_EQ(px(np, 18, 4), (C{255, 0, 0}));
  EXPECT_EQ(px(np, 28, 4), (C{0, 0, 255}));
  // A tie dstN = dstP (the dot: both ends 1 texel away) is not dstN < dstP ⇒ blue; the
  // dot's passthrough colour is (1, blendL/CAP = 1, 0) = yellow.
  Image8 dot = Grey(9, 9, 0);
  SetGrey(dot, 4, 4, 255);
  EXPECT_EQ(px(Apply(dot, p, "negpos"), 4, 4), (C{0, 0, 255}));
  EXPECT_EQ(px(Apply(dot, p, "passthrough"), 4, 4), (C{255, 255, 0}));
}

// ---------------------------------------------------------------------------------------
// Determinism.

TEST(Fxaa1, IdenticalAtOneAndTwoThreads) {
  Image8 in(97, 61, 4, 255);
  for (int y = 0; y < 61; ++y) {
    for (int x = 0; x < 97; ++x) {
      const bool disk = (x - 40) * (x - 40) + (y - 30) * (y - 30) < 400;
      const bool stripe = ((x * 3 + y) / 7) % 2 == 0;
      in.At(x, y, 0) = static_cast<uint8_t>(disk ? 220 : stripe ? 40 : 120);
      in.At(x, y, 1) = static_cast<uint8_t>(disk ? 180 : (x * 37 + y * 11) % 256);
      in.At(x, y, 2) = static_cast<uint8_t>((x * y) % 256);
    }
  }
  for (int preset = 0; preset <= 5; ++preset) {
    PostStats s1, s2;
    SetThreadCount(1);
    const Image8 a = Apply(in, Fxaa1Preset(preset), "", &s1);
    SetThreadCount(2);
    const Image8 b = Apply(in, Fxaa1Preset(preset), "", &s2);
    SetThreadCount(0);
    EXPECT_EQ(a, b) << "preset " << preset;
    EXPECT_EQ(s1.taps, s2.taps) << "preset " << preset;
    EXPECT_NE(a, in) << "preset " << preset;
  }
}

// ---------------------------------------------------------------------------------------
// Error against analytic anti-aliasing.

using InsideFn = std::function<bool(double, double)>;

// Point-sampled (pixel centres) 8-bit frame of a shape: colour `fg` inside, `bg` outside.
Image8 PointSampled(int w, int h, const InsideFn& inside, std::array<uint8_t, 3> fg, std::array<uint8_t, 3> bg) {
  Image8 img(w, h, 4, 255);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto& c = inside(x + 0.5, y + 0.5) ? fg : bg;
      for (int k = 0; k < 3; ++k) img.At(x, y, k) = c[k];
    }
  }
  return img;
}

// Reference: coverage from a 32x32 grid per pixel, blended in linear light and sRGB-encoded
// (the harness's reference resolve), as floats in [0, 1].
std::vector<float> AnalyticReference(int w, int h, const InsideFn& inside, std::array<uint8_t, 3> fg,
                                     std::array<uint8_t, 3> bg) {
  constexpr int kN = 32;
  std::vector<float> ref(static_cast<size_t>(w) * h * 3);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      int hits = 0;
      for (int j = 0; j < kN; ++j) {
        for (int i = 0; i < kN; ++i) hits += inside(x + (i + 0.5) / kN, y + (j + 0.5) / kN);
      }
      const double cov = static_cast<double>(hits) / (kN * kN);
      for (int k = 0; k < 3; ++k) {
        const double lin = cov * SrgbDecode8(fg[k]) + (1.0 - cov) * SrgbDecode8(bg[k]);
        ref[(static_cast<size_t>(y) * w + x) * 3 + k] = SrgbEncode(static_cast<float>(lin));
      }
    }
  }
  return ref;
}

double Rmse(const Image8& img, const std::vector<float>& ref) {
  double sum = 0.0;
  for (int y = 0; y < img.Height(); ++y) {
    for (int x = 0; x < img.Width(); ++x) {
      for (int k = 0; k < 3; ++k) {
        const double d = img.At(x, y, k) / 255.0 - ref[(static_cast<size_t>(y) * img.Width() + x) * 3 + k];
        sum += d * d;
      }
    }
  }
  return std::sqrt(sum / (static_cast<double>(img.PixelCount()) * 3.0));
}

TEST(Fxaa1, EveryPresetLowersErrorOnARasterizedPolygon) {
  // A triangle (convex: inside all three edge half-planes), with three different slopes.
  const double ax = 6.3, ay = 9.1, bx = 58.2, by = 20.7, cx = 17.9, cy = 57.4;
  auto edge = [](double x0, double y0, double x1, double y1, double x, double y) {
    return (x1 - x0) * (y - y0) - (y1 - y0) * (x - x0);
  };
  const InsideFn tri = [&](double x, double y) {
    return edge(ax, ay, bx, by, x, y) >= 0 && edge(bx, by, cx, cy, x, y) >= 0 && edge(cx, cy, ax, ay, x, y) >= 0;
  };
  const std::array<uint8_t, 3> fg{235, 220, 190}, bg{25, 40, 70};
  const Image8 aliased = PointSampled(64, 64, tri, fg, bg);
  const std::vector<float> ref = AnalyticReference(64, 64, tri, fg, bg);
  const double base = Rmse(aliased, ref);
  for (int preset = 0; preset <= 5; ++preset) {
    const double e = Rmse(Apply(aliased, Fxaa1Preset(preset)), ref);
    std::printf("[ fxaa1    ] triangle rmse none %.5f  p%d %.5f  (%.1f%% lower)\n", base, preset, e,
                100.0 * (base - e) / base);
    EXPECT_LT(e, base) << "preset " << preset;
  }
}

TEST(Fxaa1, LongSearchPresetsWinOnANearHorizontalEdge) {
  // Half-plane below y = 20.3 + x/40 (a step every 40 columns): the ends of each run are up
  // to 20 texels from its middle, beyond presets 0-1's reach (10.5 and 14 texels).
  const InsideFn below = [](double x, double y) { return y > 20.3 + x / 40.0; };
  const std::array<uint8_t, 3> fg{230, 230, 230}, bg{30, 30, 30};
  const Image8 aliased = PointSampled(200, 40, below, fg, bg);
  const std::vector<float> ref = AnalyticReference(200, 40, below, fg, bg);
  double e[6];
  const double base = Rmse(aliased, ref);
  for (int preset = 0; preset <= 5; ++preset) {
    e[preset] = Rmse(Apply(aliased, Fxaa1Preset(preset)), ref);
    std::printf("[ fxaa1    ] slope 1/40 rmse none %.5f  p%d %.5f  (%.1f%% lower)\n", base, preset, e[preset],
                100.0 * (base - e[preset]) / base);
    EXPECT_LT(e[preset], base) << "preset " << preset;
  }
  for (int hi : {3, 4}) {
    for (int lo : {0, 1}) EXPECT_LT(e[hi], e[lo]) << "p" << hi << " vs p" << lo;
  }
}

// ---------------------------------------------------------------------------------------
// Registry.

TEST(Fxaa1, RegistryPresetsMatchTheWhitepaperTable) {
  struct Row {
    double thr, thr_min;
    int steps, accel;
    double search_thr, cap, trim;
    int faster;
  };
  const Row rows[6] = {
      {1.0 / 4, 1.0 / 12, 2, 4, 1.0 / 4, 2.0 / 3, 1.0 / 4, 1},
      {1.0 / 8, 1.0 / 16, 4, 3, 1.0 / 4, 3.0 / 4, 1.0 / 4, 0},
      {1.0 / 8, 1.0 / 24, 8, 2, 1.0 / 4, 3.0 / 4, 1.0 / 4, 0},
      {1.0 / 8, 1.0 / 24, 16, 1, 1.0 / 4, 3.0 / 4, 1.0 / 4, 0},
      {1.0 / 8, 1.0 / 24, 24, 1, 1.0 / 4, 3.0 / 4, 1.0 / 4, 0},
      {1.0 / 8, 1.0 / 24, 32, 1, 1.0 / 4, 3.0 / 4, 1.0 / 4, 0},
  };
  Image8 in = Grey(9, 9, 0);
  SetGrey(in, 4, 4, 255);
  const Image8 stairs = Staircase();
  for (int k = 0; k < 6; ++k) {
    const std::string name = "fxaa1-p" + std::to_string(k);
    const MethodPlan plan = MakeMethod(name);
    EXPECT_TRUE(plan.IsPostOnly()) << name;
    EXPECT_EQ(plan.render.SamplesPerPixel(), 1);
    EXPECT_EQ(plan.debug_views, Fxaa1DebugViews());
    EXPECT_DOUBLE_EQ(plan.params.Number("edge_threshold"), rows[k].thr) << name;
    EXPECT_DOUBLE_EQ(plan.params.Number("edge_threshold_min"), rows[k].thr_min) << name;
    EXPECT_EQ(plan.params.Int("search_steps"), rows[k].steps) << name;
    EXPECT_EQ(plan.params.Int("search_acceleration"), rows[k].accel) << name;
    EXPECT_DOUBLE_EQ(plan.params.Number("search_threshold"), rows[k].search_thr) << name;
    EXPECT_DOUBLE_EQ(plan.params.Number("subpix_cap"), rows[k].cap) << name;
    EXPECT_DOUBLE_EQ(plan.params.Number("subpix_trim"), rows[k].trim) << name;
    EXPECT_EQ(plan.params.Int("subpix_faster"), rows[k].faster) << name;
    // The plan's filter is Fxaa1 with Fxaa1Preset(k), taps included.
    PostStats a, b;
    EXPECT_EQ(plan.post(stairs, PostOptions{}, &a), Apply(stairs, Fxaa1Preset(k), "", &b)) << name;
    EXPECT_EQ(a.taps, b.taps) << name;
    EXPECT_THROW(plan.post(stairs, PostOptions{"bogus"}, nullptr), UserError) << name;
  }
  // Overrides: canonical spec (definition order), value, and effect (CAP = 0 leaves the
  // dot untouched, see SubpixCapAndTrimControlTheLowpassBlend).
  const MethodPlan tuned = MakeMethod("fxaa1-p2:search_steps=12,edge_threshold=0.1");
  EXPECT_EQ(tuned.spec, "fxaa1-p2:edge_threshold=0.1,search_steps=12");
  EXPECT_EQ(tuned.params.Int("search_steps"), 12);
  const MethodPlan cap0 = MakeMethod("fxaa1-p3:subpix_cap=0");
  EXPECT_EQ(cap0.post(in, PostOptions{}, nullptr), in);
  EXPECT_THROW(MakeMethod("fxaa1-p3:search_acceleration=5"), UserError);
  EXPECT_THROW(MakeMethod("fxaa1-p3:subpix_trim=1"), UserError);
  EXPECT_THROW(MakeMethod("fxaa1-p3:search_steps=65"), UserError);
  EXPECT_THROW(MakeMethod("fxaa1-p3:subpix=2"), UserError);
}

}  // namespace
}  // namespace aalab
