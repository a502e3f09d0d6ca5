// The geometric edge mask of `wedges` against the scene's analytic polygon edges.
#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace aalab
