// The geometric edge mask of `wedges` against the scene's analytic polygon edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "core/edge_mask.h"
#include "core/image.h"
#include "core/parallel.h"
#include "scenes/library.h"
#include "scenes/render.h"

namespace aalab {
namespace {

struct Seg {
  double ax, ay, bx, by;
};

double DistToSeg(double px, double py, const Seg& s) {
  const double dx = s.bx - s.ax, dy = s.by - s.ay;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((px - s.ax) * dx + (py - s.ay) * dy) / len2 : 0.0;
  t = std::max(0.0, std::min(1.0, t));
  const double qx = s.ax + t * dx - px, qy = s.ay + t * dy - py;
  return std::sqrt(qx * qx + qy * qy);
}

TEST(EdgeMask, WedgesMaskHoldsEveryPolygonEdgeAndNoInterior) {
  const Scene scene = LoadScene("wedges");
  ASSERT_EQ(scene.camera.type, CameraType::kOrthographic);
  const int W = 192, H = 108;
  Tracer tracer(scene);
  const Reference ref = RenderReference(tracer, W, H, 8, 1, nullptr);
  // Orthographic camera looking down −Z at the origin with up +Y: world (x, y) → pixel
  // ((x − cx) / s + W/2, H/2 − (y − cy) / s) with s = height / H world units per pixel.
  const double s = scene.camera.height / H;
  const double cx = scene.camera.position.x, cy = scene.camera.position.y;
  std::vector<Seg> segs;
  for (const Shape& shape : scene.shapes) {
    ASSERT_EQ(shape.positions.size(), 4u);  // quads
    for (int k = 0; k < 4; ++k) {
      const auto& a = shape.positions[k];
      const auto& b = shape.positions[(k + 1) % 4];
      segs.push_back(
          {(a.x - cx) / s + W / 2.0, H / 2.0 - (a.y - cy) / s, (b.x - cx) / s + W / 2.0, H / 2.0 - (b.y - cy) / s});
    }
  }
  // 1. Every point of every edge inside the frame lies in a mask pixel.
  int checked = 0;
  for (const Seg& g : segs) {
    for (int i = 0; i <= 400; ++i) {
      const double t = i / 400.0;
      const double x = g.ax + t * (g.bx - g.ax), y = g.ay + t * (g.by - g.ay);
      if (x < 0 || y < 0 || x >= W || y >= H) continue;
      EXPECT_GT(ref.edge_mask.At(static_cast<int>(x), static_cast<int>(y), 0), 0.5f) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 3000);
  // 2. No pixel whose centre is farther than 1.5·√2 ≈ 2.121 px from every edge is in the
  //    mask: a raw mask pixel holds a piece of an edge, and the farthest point of a diagonal
  //    neighbour's area from this pixel's centre is 1.5 px along both axes. Flat interiors
  //    and background stay out.
  int interior = 0;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      double d = 1e9;
      for (const Seg& g : segs) d = std::min(d, DistToSeg(x + 0.5, y + 0.5, g));
      if (d > 1.5 * std::sqrt(2.0) + 1e-9) {
        EXPECT_EQ(ref.edge_mask.At(x, y, 0), 0.0f) << x << "," << y;
        ++interior;
      }
    }
  }
  EXPECT_GT(interior, W * H / 2);
}

/// Resets the poison when a test ends, even on failure.
struct PoisonGuard {
  ~PoisonGuard() { SetUninitializedPoison(-1); }
};

bool SameBytes(const ImageF& a, const ImageF& b) {
  return a.Width() == b.Width() && a.Height() == b.Height() && a.Channels() == b.Channels() &&
         std::memcmp(a.Data().data(), b.Data().data(), a.Data().size() * sizeof(float)) == 0;
}

// DilateMask runs its rows in parallel chunks of 16 into an image made with kUninitialized:
// under the poisons 0x00 and 0xA5 and at 1, 2 and 3 threads it equals the 3×3 dilation
// computed here pixel by pixel (a 53x47 mask: 3 chunks and a short one; random pixels set,
// and the corners, so that the clamped border is reached).
TEST(EdgeMask, DilationByRowChunksEqualsThePlainDilation) {
  PoisonGuard guard;
  const int w = 53, h = 47;
  ImageF raw(w, h, 1);
  uint64_t s = 99;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      s = s * 6364136223846793005ULL + 1442695040888963407ULL;
      raw.At(x, y, 0) = (s >> 60) == 0 ? 1.0f : 0.0f;
    }
  }
  raw.At(0, 0, 0) = raw.At(w - 1, h - 1, 0) = 1.0f;
  ImageF want(w, h, 1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      bool any = false;
      for (int yy = std::max(y - 1, 0); yy <= std::min(y + 1, h - 1); ++yy) {
        for (int xx = std::max(x - 1, 0); xx <= std::min(x + 1, w - 1); ++xx) any = any || raw.At(xx, yy, 0) > 0.5f;
      }
      want.At(x, y, 0) = any ? 1.0f : 0.0f;
    }
  }
  for (int poison : {0x00, 0xA5}) {
    SetUninitializedPoison(poison);
    for (int threads : {1, 2, 3}) {
      SetThreadCount(threads);
      EXPECT_TRUE(SameBytes(DilateMask(raw), want)) << "poison " << poison << ", " << threads << " threads";
    }
  }
  SetThreadCount(0);
}

// RenderReference makes its four images with kUninitialized and writes them tile by tile:
// under the poisons 0x00 and 0xA5 and at 1, 2 and 3 threads the images and the dilated mask
// are the same bytes (wedges at 37x29, a size of clipped tiles, 4 samples per pixel).
TEST(EdgeMask, ReferenceImagesAreWrittenWholeAtAnyThreadCount) {
  PoisonGuard guard;
  const Scene scene = LoadScene("wedges");
  const Tracer tracer(scene);
  SetUninitializedPoison(0);
  SetThreadCount(1);
  const Reference base = RenderReference(tracer, 37, 29, 2, 1, nullptr);
  for (int poison : {0x00, 0xA5}) {
    SetUninitializedPoison(poison);
    for (int threads : {1, 2, 3}) {
      SetThreadCount(threads);
      const Reference r = RenderReference(tracer, 37, 29, 2, 1, nullptr);
      const std::string what = "poison " + std::to_string(poison) + ", " + std::to_string(threads) + " threads";
      EXPECT_TRUE(SameBytes(r.image, base.image)) << what;
      EXPECT_TRUE(SameBytes(r.half_a, base.half_a)) << what;
      EXPECT_TRUE(SameBytes(r.half_b, base.half_b)) << what;
      EXPECT_TRUE(SameBytes(r.edge_mask_raw, base.edge_mask_raw)) << what;
      EXPECT_TRUE(SameBytes(r.edge_mask, base.edge_mask)) << what;
    }
  }
  SetThreadCount(0);
}

}  // namespace
}  // namespace aalab
