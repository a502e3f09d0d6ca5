/// Exact 2-D area primitives in double precision for the exact reference and the analytic-AA
/// tests: convex polygon clipping (Sutherland–Hodgman), the shoelace area, the area of a disk
/// or a capsule (stadium) intersected with a convex polygon, and the closed-form area of a disk
/// intersected with an axis-aligned rectangle. All closed form: no sampling, no quadrature.
#pragma once
#include <array>

namespace aalab {

struct Vec2d {
  double x = 0, y = 0;
};

/// A convex polygon with at most kMaxVertices vertices (either winding).
struct ConvexPoly {
  static constexpr int kMaxVertices = 32;
  std::array<Vec2d, kMaxVertices> v{};
  int n = 0;
  void Push(Vec2d p);
};

/// The axis-aligned rectangle [x0, x1] × [y0, y1] as a counter-clockwise (in x-right, y-up
/// terms) convex polygon.
ConvexPoly RectPoly(double x0, double y0, double x1, double y1);

/// Signed shoelace area (positive for counter-clockwise vertices in x-right, y-up axes).
double SignedArea(const ConvexPoly& p);

/// Keeps the part of `p` where nx·x + ny·y <= c (Sutherland–Hodgman, one plane). Exact up to
/// rounding of the intersection points; convex in, convex out.
ConvexPoly ClipHalfPlane(const ConvexPoly& p, double nx, double ny, double c);

/// p ∩ q for convex q (q clipped by each of p's edges; p must have non-zero area, either
/// winding).
ConvexPoly ClipConvex(const ConvexPoly& q, const ConvexPoly& p);

/// Area of the disk (centre c, radius r ≥ 0) intersected with the convex polygon p: the sum
/// over p's edges of the signed area of disk ∩ triangle(c, a, b), each split where the edge
/// crosses the circle into triangle pieces (inside) and circular sectors (outside).
double DiskPolyArea(Vec2d c, double r, const ConvexPoly& p);

/// Area of the capsule (stadium: every point within r of the segment a–b) intersected with
/// the convex polygon p: the rectangle part by clipping, the two half-disk caps by
/// DiskPolyArea on p clipped to each cap's half-plane. The three parts do not overlap.
double CapsulePolyArea(Vec2d a, Vec2d b, double r, const ConvexPoly& p);

/// Area of the disk (centre (cx, cy), radius r) ∩ [x0, x1] × [y0, y1] from the odd-odd
/// primitive G(x, y) = sgn x · sgn y · A(|x|, |y|) (../shared/notes/msaa-and-analytic-aa.md §4),
/// independent of DiskPolyArea (the tests compare the two).
double DiskRectArea(double cx, double cy, double r, double x0, double y0, double x1, double y1);

/// Distance from point p to the segment a–b.
double PointSegmentDistance(Vec2d p, Vec2d a, Vec2d b);

/// Distance between the segments a–b and c–d (0 when they cross).
double SegmentSegmentDistance(Vec2d a, Vec2d b, Vec2d c, Vec2d d);

}  // namespace aalab
