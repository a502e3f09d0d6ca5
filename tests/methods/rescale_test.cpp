// Tests for frame rescaling (methods/rescale.cpp) and the render-scale methods
// (methods/render_scale.cpp). Expected values are worked out by hand in the comments.
#include "methods/rescale.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "methods/fxaa311.h"
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

// 8 × 2 ramp 0, 32, ..., 224 in every channel, both rows equal.
Image8 Ramp() {
  Image8 img(8, 2, 4, 255);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 8; ++x) {
      for (int c = 0; c < 3; ++c) img.At(x, y, c) = static_cast<uint8_t>(32 * x);
    }
  }
  return img;
}

TEST(Rescale, ConstantStaysConstant) {
  const Image8 in = Solid(48, 36, 37, 141, 222);
  for (Rescale k : {Rescale::kBilinear, Rescale::kBicubic}) {
    for (auto [w, h] : {std::pair{96, 72}, {24, 18}, {64, 48}, {36, 27}, {17, 5}, {48, 36}}) {
      const Image8 out = RescaleFrame(in, w, h, k, nullptr);
      ASSERT_EQ(out.Width(), w);
      ASSERT_EQ(out.Height(), h);
      EXPECT_TRUE(out == Solid(w, h, 37, 141, 222)) << static_cast<int>(k) << " " << w << "x" << h;
    }
  }
}

TEST(Rescale, BsplineWeights) {
  // t = 0: w = (1/6, 4/6, 1/6, 0); g0 = 5/6, g1 = 1/6, h0 = (4/6)/(5/6) = 0.8, h1 = 0.
  const BsplineTaps a = BsplineCubicTaps(0.0f);
  EXPECT_NEAR(a.w[0], 1.0 / 6, 1e-7);
  EXPECT_NEAR(a.w[1], 4.0 / 6, 1e-7);
  EXPECT_NEAR(a.w[2], 1.0 / 6, 1e-7);
  EXPECT_EQ(a.w[3], 0.0f);
  EXPECT_NEAR(a.h0, 0.8, 1e-7);
  EXPECT_EQ(a.h1, 0.0f);
  // t = 0.5: w0 = 0.125/6 = 1/48; w1 = (3/8 − 6/4 + 4)/6 = 23/48; w2 = 23/48; w3 = 1/48;
  // g0 = g1 = 1/2; h0 = 23/24, h1 = 1/24 (symmetric about the midpoint).
  const BsplineTaps b = BsplineCubicTaps(0.5f);
  EXPECT_NEAR(b.w[0], 1.0 / 48, 1e-7);
  EXPECT_NEAR(b.w[1], 23.0 / 48, 1e-7);
  EXPECT_NEAR(b.w[2], 23.0 / 48, 1e-7);
  EXPECT_NEAR(b.w[3], 1.0 / 48, 1e-7);
  EXPECT_NEAR(b.g0, 0.5, 1e-7);
  EXPECT_NEAR(b.h0, 23.0 / 24, 1e-7);
  EXPECT_NEAR(b.h1, 1.0 / 24, 1e-7);
  // Partition of unity, positivity, and the two taps' weights.
  for (int i = 0; i <= 64; ++i) {
    const float t = static_cast<float>(i) / 64.0f * 0.999999f;
    const BsplineTaps w = BsplineCubicTaps(t);
    EXPECT_NEAR(w.w[0] + w.w[1] + w.w[2] + w.w[3], 1.0, 1e-6) << t;
    EXPECT_NEAR(w.g0 + w.g1, 1.0, 1e-6) << t;
    for (float v : w.w) EXPECT_GE(v, 0.0f);
    EXPECT_GE(w.h0, 0.0f);
    EXPECT_LE(w.h0, 1.0f);
    EXPECT_GE(w.h1, 0.0f);
    EXPECT_LE(w.h1, 1.0f);
    // The B-spline reproduces linear functions: sum w_j·(j − 1) = t for texels i−1..i+2.
    EXPECT_NEAR(-w.w[0] + w.w[2] + 2 * w.w[3], t, 1e-6) << t;
  }
}

TEST(Rescale, DownscaleRampByHand) {
  // 8 → 4 wide: output X samples input x-coordinate u = (X + 0.5)/4·8 = 2X + 1, halfway
  // between texels 2X and 2X+1 (texel-centre space 2X + 0.5).
  // Bilinear: (32·2X + 32·(2X+1))/2 = 16, 80, 144, 208.
  // Bicubic: t = 0.5, weights (1, 23, 23, 1)/48 over texels 2X−1 .. 2X+2 (clamped):
  //   X=0: (0 + 23·0 + 23·32 + 64)/48 = 800/48 = 16.67 → 17
  //   X=1: (32 + 23·64 + 23·96 + 128)/48 = 3840/48 = 80
  //   X=2: (96 + 23·128 + 23·160 + 192)/48 = 6912/48 = 144
  //   X=3: (160 + 23·192 + 23·224 + 224)/48 = 9952/48 = 207.33 → 207 (texel 8 clamps to 7)
  // Rows: 2 → 1, v = 1.0 sits between the two equal rows.
  const Image8 in = Ramp();
  PostStats sb, sc;
  const Image8 bl = RescaleFrame(in, 4, 1, Rescale::kBilinear, &sb);
  const Image8 bc = RescaleFrame(in, 4, 1, Rescale::kBicubic, &sc);
  const int want_bl[4] = {16, 80, 144, 208};
  const int want_bc[4] = {17, 80, 144, 207};
  for (int X = 0; X < 4; ++X) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(bl.At(X, 0, c), want_bl[X]) << X;
      EXPECT_EQ(bc.At(X, 0, c), want_bc[X]) << X;
    }
    EXPECT_EQ(bl.At(X, 0, 3), 255);
  }
  EXPECT_EQ(sb.taps, 4u);      // one bilinear tap per output pixel
  EXPECT_EQ(sc.taps, 4u * 4);  // four per output pixel
}

TEST(Rescale, UpscaleByHand) {
  // [0, 255] → 4 wide, bilinear: u = (X + 0.5)/4·2 = 0.25, 0.75, 1.25, 1.75, i.e. texel-
  // centre positions −0.25, 0.25, 0.75, 1.25: clamp → 0; 0.25·255 = 63.75 → 64;
  // 0.75·255 = 191.25 → 191; clamp → 255.
  Image8 in(2, 1, 4, 255);
  for (int c = 0; c < 3; ++c) {
    in.At(0, 0, c) = 0;
    in.At(1, 0, c) = 255;
  }
  const Image8 out = RescaleFrame(in, 4, 1, Rescale::kBilinear, nullptr);
  const int want[4] = {0, 64, 191, 255};
  for (int X = 0; X < 4; ++X) EXPECT_EQ(out.At(X, 0, 0), want[X]) << X;
  // Bicubic of a step never overshoots (all B-spline weights are positive) and is monotone.
  const Image8 bc = RescaleFrame(in, 8, 1, Rescale::kBicubic, nullptr);
  for (int X = 1; X < 8; ++X) EXPECT_GE(bc.At(X, 0, 0), bc.At(X - 1, 0, 0));
}

TEST(Rescale, NoneIsIdentityAndChecksSize) {
  const Image8 in = Ramp();
  EXPECT_TRUE(RescaleFrame(in, 8, 2, Rescale::kNone, nullptr) == in);
  EXPECT_THROW(RescaleFrame(in, 4, 1, Rescale::kNone, nullptr), InternalError);
}

TEST(Rescale, SameBitsAtAnyThreadCount) {
  Image8 in(91, 67, 4, 255);
  uint32_t s = 3;
  for (int y = 0; y < 67; ++y) {
    for (int x = 0; x < 91; ++x) {
      for (int c = 0; c < 3; ++c) {
        s = s * 1664525u + 1013904223u;
        in.At(x, y, c) = static_cast<uint8_t>(s >> 24);
      }
    }
  }
  for (Rescale k : {Rescale::kBilinear, Rescale::kBicubic}) {
    SetThreadCount(1);
    const Image8 a = RescaleFrame(in, 68, 50, k, nullptr);
    SetThreadCount(2);
    const Image8 b = RescaleFrame(in, 68, 50, k, nullptr);
    SetThreadCount(0);
    EXPECT_TRUE(a == b);
  }
}

TEST(RenderScale, Plans) {
  const MethodPlan a = MakeMethod("scale43");
  EXPECT_DOUBLE_EQ(a.render.scale, 4.0 / 3.0);
  EXPECT_EQ(a.render.pattern, SamplePattern::kCenter);
  EXPECT_EQ(a.rescale, Rescale::kBilinear);
  EXPECT_FALSE(a.post);
  EXPECT_FALSE(a.IsPostOnly());
  const MethodPlan b = MakeMethod("scale43-fxaa-high:rescale=bicubic");
  EXPECT_DOUBLE_EQ(b.render.scale, 4.0 / 3.0);
  EXPECT_EQ(b.rescale, Rescale::kBicubic);
  ASSERT_TRUE(b.post);
  EXPECT_EQ(MakeMethod("scale43:scale=2").render.scale, 2.0);
  EXPECT_EQ(MakeMethod("scale43:scale=0.5").render.scale, 0.5);
  EXPECT_THROW(MakeMethod("scale43:scale=5"), UserError);
  EXPECT_THROW(MakeMethod("scale43:rescale=lanczos"), UserError);
  EXPECT_THROW(MakeMethod("scale43:subpix=0.5"), UserError);

  // The post filter is fxaa-high at the render size.
  Image8 img = Solid(64, 48, 10, 20, 30);
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      if (2 * x + 5 * y < 150) {
        img.At(x, y, 0) = 250;
        img.At(x, y, 1) = 240;
        img.At(x, y, 2) = 200;
      }
    }
  }
  EXPECT_TRUE(b.post(img, {}, nullptr) == MakeMethod("fxaa-high").post(img, {}, nullptr));

  // The runner's sequence at 4/3, 2 and 0.5 for a 48 × 36 output: render round(s·W) ×
  // round(s·H), post, RescaleFrame back to 48 × 36.
  for (double sc : {4.0 / 3.0, 2.0, 0.5}) {
    const MethodPlan p = MakeMethod("scale43-fxaa-high:scale=" + FormatNumber(sc));
    const int rw = static_cast<int>(std::lround(sc * 48)), rh = static_cast<int>(std::lround(sc * 36));
    const Image8 frame = RescaleFrame(img, rw, rh, Rescale::kBilinear, nullptr);  // stand-in render
    PostStats st;
    const Image8 post = p.post(frame, {}, &st);
    const Image8 out = RescaleFrame(post, 48, 36, p.rescale, &st);
    EXPECT_EQ(out.Width(), 48);
    EXPECT_EQ(out.Height(), 36);
    EXPECT_GT(st.taps, static_cast<uint64_t>(5 * rw * rh));
  }
}

}  // namespace
}  // namespace aalab
