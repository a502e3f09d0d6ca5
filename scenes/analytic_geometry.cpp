// Exact 2-D areas: convex clipping, shoelace, disk ∩ convex polygon, capsule ∩ convex polygon,
// disk ∩ rectangle. Sources: Sutherland & Hodgman 1974 (reentrant polygon clipping); the
// circle–triangle decomposition (signed triangle/sector pieces per edge) as in
// ../shared/notes/msaa-and-analytic-aa.md §4; the odd-odd primitive G for disk ∩ rectangle (same notes).
#include "scenes/analytic_geometry.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace aalab {

namespace {

double Cross(Vec2d a, Vec2d b) { return a.x * b.y - a.y * b.x; }
double Dot(Vec2d a, Vec2d b) { return a.x * b.x + a.y * b.y; }
Vec2d Sub(Vec2d a, Vec2d b) { return {a.x - b.x, a.y - b.y}; }
Vec2d Lerp(Vec2d a, Vec2d b, double t) { return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t}; }

/// Signed area of disk(0, r) ∩ triangle(0, a, b).
double DiskTriangleSigned(Vec2d a, Vec2d b, double r) {
  const double r2 = r * r;
  const Vec2d d = Sub(b, a);
  // |a + t d|² = r²  →  (d·d) t² + 2 (a·d) t + (a·a − r²) = 0
  const double A = Dot(d, d);
  double ts[4];
  int nt = 0;
  ts[nt++] = 0.0;
  if (A > 0.0) {
    const double B = Dot(a, d), C = Dot(a, a) - r2;
    const double disc = B * B - A * C;
    if (disc > 0.0) {
      const double s = std::sqrt(disc);
      const double t0 = (-B - s) / A, t1 = (-B + s) / A;
      if (t0 > 0.0 && t0 < 1.0) ts[nt++] = t0;
      if (t1 > 0.0 && t1 < 1.0) ts[nt++] = t1;
    }
  }
  ts[nt++] = 1.0;
  double area = 0.0;
  for (int i = 0; i + 1 < nt; ++i) {
    const Vec2d p = Lerp(a, b, ts[i]), q = Lerp(a, b, ts[i + 1]);
    const Vec2d m = Lerp(a, b, 0.5 * (ts[i] + ts[i + 1]));
    if (Dot(m, m) <= r2) {
      area += 0.5 * Cross(p, q);  // the piece lies inside the circle: a triangle
    } else {
      area += 0.5 * r2 * std::atan2(Cross(p, q), Dot(p, q));  // outside: a circular sector
    }
  }
  return area;
}

/// Area of disk(0, r) ∩ [0, a] × [0, b] for a, b ≥ 0.
double QuadrantArea(double a, double b, double r) {
  a = std::min(a, r);
  b = std::min(b, r);
  if (a <= 0.0 || b <= 0.0) return 0.0;
  if (a * a + b * b <= r * r) return a * b;
  auto S = [r](double u) {  // ∫0^u sqrt(r² − t²) dt
    const double s = std::clamp(u / r, -1.0, 1.0);
    return 0.5 * (u * std::sqrt(std::max(0.0, r * r - u * u)) + r * r * std::asin(s));
  };
  const double u_star = std::sqrt(std::max(0.0, r * r - b * b));
  return b * u_star + S(a) - S(u_star);
}

double G(double x, double y, double r) {
  const double sx = x < 0 ? -1.0 : 1.0, sy = y < 0 ? -1.0 : 1.0;
  return sx * sy * QuadrantArea(std::fabs(x), std::fabs(y), r);
}

}  // namespace

void ConvexPoly::Push(Vec2d p) {
  AALAB_CHECK(n < kMaxVertices, "convex polygon vertex capacity exceeded");
  v[static_cast<size_t>(n++)] = p;
}

ConvexPoly RectPoly(double x0, double y0, double x1, double y1) {
  ConvexPoly p;
  p.Push({x0, y0});
  p.Push({x1, y0});
  p.Push({x1, y1});
  p.Push({x0, y1});
  return p;
}

double SignedArea(const ConvexPoly& p) {
  double s = 0.0;
  for (int i = 0; i < p.n; ++i) s += Cross(p.v[static_cast<size_t>(i)], p.v[static_cast<size_t>((i + 1) % p.n)]);
  return 0.5 * s;
}

ConvexPoly ClipHalfPlane(const ConvexPoly& p, double nx, double ny, double c) {
  ConvexPoly out;
  if (p.n == 0) return out;
  for (int i = 0; i < p.n; ++i) {
    const Vec2d a = p.v[static_cast<size_t>(i)], b = p.v[static_cast<size_t>((i + 1) % p.n)];
    const double da = nx * a.x + ny * a.y - c, db = nx * b.x + ny * b.y - c;
    if (da <= 0.0) out.Push(a);
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) out.Push(Lerp(a, b, da / (da - db)));
  }
  if (out.n < 3) out.n = 0;
  return out;
}

ConvexPoly ClipConvex(const ConvexPoly& q, const ConvexPoly& p) {
  const double orient = SignedArea(p) >= 0.0 ? 1.0 : -1.0;
  ConvexPoly out = q;
  for (int i = 0; i < p.n && out.n > 0; ++i) {
    const Vec2d a = p.v[static_cast<size_t>(i)], b = p.v[static_cast<size_t>((i + 1) % p.n)];
    // Inside of a CCW edge a→b is to its left: cross(b − a, x − a) ≥ 0.
    const double nx = orient * (b.y - a.y), ny = -orient * (b.x - a.x);
    out = ClipHalfPlane(out, nx, ny, nx * a.x + ny * a.y);
  }
  return out;
}

double DiskPolyArea(Vec2d c, double r, const ConvexPoly& p) {
  if (p.n < 3 || r <= 0.0) return 0.0;
  double s = 0.0;
  for (int i = 0; i < p.n; ++i) {
    s += DiskTriangleSigned(Sub(p.v[static_cast<size_t>(i)], c), Sub(p.v[static_cast<size_t>((i + 1) % p.n)], c), r);
  }
  return std::fabs(s);
}

double CapsulePolyArea(Vec2d a, Vec2d b, double r, const ConvexPoly& p) {
  if (p.n < 3 || r <= 0.0) return 0.0;
  const Vec2d d = Sub(b, a);
  const double len = std::sqrt(Dot(d, d));
  if (len == 0.0) return DiskPolyArea(a, r, p);
  const Vec2d u{d.x / len, d.y / len};
  const double ua = Dot(u, a), ub = Dot(u, b);
  const Vec2d n{-u.y, u.x};
  const double na = Dot(n, a);
  // Rectangle: ua ≤ u·x ≤ ub and |n·x − na| ≤ r.
  ConvexPoly rect = ClipHalfPlane(p, -u.x, -u.y, -ua);
  rect = ClipHalfPlane(rect, u.x, u.y, ub);
  rect = ClipHalfPlane(rect, n.x, n.y, na + r);
  rect = ClipHalfPlane(rect, -n.x, -n.y, -(na - r));
  const double area_rect = std::fabs(SignedArea(rect));
  const ConvexPoly cap_a = ClipHalfPlane(p, u.x, u.y, ua);     // u·x ≤ ua
  const ConvexPoly cap_b = ClipHalfPlane(p, -u.x, -u.y, -ub);  // u·x ≥ ub
  return area_rect + DiskPolyArea(a, r, cap_a) + DiskPolyArea(b, r, cap_b);
}

double DiskRectArea(double cx, double cy, double r, double x0, double y0, double x1, double y1) {
  x0 -= cx;
  x1 -= cx;
  y0 -= cy;
  y1 -= cy;
  return G(x1, y1, r) - G(x0, y1, r) - G(x1, y0, r) + G(x0, y0, r);
}

double PointSegmentDistance(Vec2d p, Vec2d a, Vec2d b) {
  const Vec2d ab = Sub(b, a), ap = Sub(p, a);
  const double l2 = Dot(ab, ab);
  const double t = l2 > 0.0 ? std::clamp(Dot(ap, ab) / l2, 0.0, 1.0) : 0.0;
  const Vec2d q = Lerp(a, b, t);
  const Vec2d e = Sub(p, q);
  return std::sqrt(Dot(e, e));
}

double SegmentSegmentDistance(Vec2d a, Vec2d b, Vec2d c, Vec2d d) {
  const double d1 = Cross(Sub(b, a), Sub(c, a)), d2 = Cross(Sub(b, a), Sub(d, a));
  const double d3 = Cross(Sub(d, c), Sub(a, c)), d4 = Cross(Sub(d, c), Sub(b, c));
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0.0;
  return std::min(std::min(PointSegmentDistance(a, c, d), PointSegmentDistance(b, c, d)),
                  std::min(PointSegmentDistance(c, a, b), PointSegmentDistance(d, a, b)));
}

}  // namespace aalab
