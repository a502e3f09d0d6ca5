// The raster path's tolerance rule (docs/gpu.md "Correctness on Mesa"), worked out from the
// scene alone, independently of the raster tool: where a GPU frame may differ from aalab's by
// more than the 1-code rounding. Triangle edges within the rasteriser's vertex snapping
// distance (Edges, SnapDistance); procedural-texture cell boundaries, disk outlines and
// shadow boundaries within the float slack of interpolated attributes (SurfaceCells).
// Shared by raster_test.cpp.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <utility>
#include <vector>

#include "core/image.h"
#include "core/raster_geometry.h"
#include "core/render_spec.h"
#include "gpu/raster/raster_renderer.h"

namespace aalab {

using raster::RasterRenderer;

/// The scene's projected triangle edges in image pixel coordinates (y down), as the
/// tracer's camera rays define them: nx = 2x/W − 1, ny = 1 − 2y/H (scenes/tracer.cpp).
/// Worked out here from the camera alone, independently of the raster tool's matrix.
struct Edges {
  std::vector<std::array<double, 4>> seg;  // x0, y0, x1, y1
  /// Distance from (x, y) to the nearest edge, px.
  double Nearest(double x, double y) const {
    double best = 1e30;
    for (const auto& s : seg) {
      const double dx = s[2] - s[0], dy = s[3] - s[1];
      const double len2 = dx * dx + dy * dy;
      double t = len2 > 0 ? ((x - s[0]) * dx + (y - s[1]) * dy) / len2 : 0.0;
      t = std::clamp(t, 0.0, 1.0);
      best = std::min(best, std::hypot(x - (s[0] + t * dx), y - (s[1] + t * dy)));
    }
    return best;
  }
};

/// The tracer's camera in double (scenes/tracer.cpp): nx = 2x/W − 1, ny = 1 − 2y/H.
struct Cam {
  glm::dvec3 pos, fwd, right, up;
  double half_h, aspect;
  bool ortho;
  int w, h;
  Cam(const RasterScene& s, int width, int height) : w(width), h(height) {
    pos = {s.position[0], s.position[1], s.position[2]};
    fwd = glm::normalize(glm::dvec3(s.look_at[0], s.look_at[1], s.look_at[2]) - pos);
    right = glm::normalize(glm::cross(fwd, glm::dvec3(s.up[0], s.up[1], s.up[2])));
    up = glm::cross(right, fwd);
    aspect = static_cast<double>(w) / h;
    ortho = s.orthographic;
    half_h = ortho ? s.height * 0.5 : std::tan(s.fov_y_deg * M_PI / 180.0 * 0.5);
  }
  /// A camera-space point (x along right, y along up, z along forward) to image pixels.
  glm::dvec2 Project(glm::dvec3 c) const {
    const double z = ortho ? 1.0 : c.z;
    const double nx = c.x / (z * half_h * aspect), ny = c.y / (z * half_h);
    return {(nx + 1.0) * 0.5 * w, (1.0 - ny) * 0.5 * h};
  }
  glm::dvec3 ToCamera(const std::array<float, 3>& p) const {
    const glm::dvec3 v = glm::dvec3(p[0], p[1], p[2]) - pos;
    return {glm::dot(v, right), glm::dot(v, up), glm::dot(v, fwd)};
  }
  /// The ray through image point (x, y): origin and direction.
  std::pair<glm::dvec3, glm::dvec3> Ray(double x, double y) const {
    const double a = (2.0 * x / w - 1.0) * half_h * aspect, b = (1.0 - 2.0 * y / h) * half_h;
    if (ortho) return {pos + right * a + up * b, fwd};
    return {pos, fwd + right * a + up * b};
  }
};

inline Edges ProjectEdges(const RasterScene& s, int w, int h) {
  const Cam cam(s, w, h);
  // Edges reaching behind the camera are clipped to just in front of it (a large ground
  // plane's far edge is then the horizon line the image shows).
  const double z_min = 1e-6;
  Edges e;
  for (const auto& t : s.triangles) {
    if (t.disk) continue;  // an impostor's square is no edge of the image (SurfaceCells handles disks)
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 a = cam.ToCamera(t.corners[static_cast<size_t>(k)].position);
      glm::dvec3 b = cam.ToCamera(t.corners[static_cast<size_t>((k + 1) % 3)].position);
      if (!cam.ortho) {
        if (a.z < z_min && b.z < z_min) continue;
        if (a.z < z_min) a = a + (b - a) * ((z_min - a.z) / (b.z - a.z));
        if (b.z < z_min) b = b + (a - b) * ((z_min - b.z) / (a.z - b.z));
      }
      const glm::dvec2 pa = cam.Project(a), pb = cam.Project(b);
      e.seg.push_back({pa.x, pa.y, pb.x, pb.y});
    }
  }
  return e;
}

/// The tracer's shadow ray from `p` on a surface of geometric normal `ng` (any length), as
/// scenes/tracer_shade.cpp ShadowRays builds it: `ng` turned to face the camera ray `d`, the
/// direction `*L` to the light (directional: the negated direction; point and spot: towards
/// the position, `*tfar` just short of it), the origin `*o` offset by 1e-4 + max|p|*1e-6
/// along `ng`. False when the light is behind the surface (no ray).
inline bool ShadowRayFrom(glm::dvec3 p, glm::dvec3 ng, glm::dvec3 d, const RasterLight& light, glm::dvec3* o,
                          glm::dvec3* L, double* tfar) {
  ng = glm::normalize(ng);
  if (glm::dot(ng, d) > 0) ng = -ng;
  *tfar = 1e300;
  if (light.type == 0) {
    *L = -glm::dvec3(light.direction[0], light.direction[1], light.direction[2]);
  } else {
    *L = glm::dvec3(light.position[0], light.position[1], light.position[2]) - p;
    *tfar = glm::length(*L) * (1 - 1e-5);
    *L = glm::normalize(*L);
  }
  if (glm::dot(ng, *L) <= 0) return false;
  const double eps = 1e-4 + std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}) * 1e-6;
  *o = p + ng * eps;
  return true;
}

/// Where a pixel may legitimately come out differently away from triangle edges: near a
/// procedural texture's cell boundary or a disk's outline. The exact surface point (double
/// rays against the scene's triangles and disks; barycentric interpolation of the corners'
/// uv) is taken at the pixel centre and at the corners of the square of half-width `snap`
/// px around it (the rasteriser's vertex snapping moves the interpolated attributes, world
/// position and uv, as it moves the edges), and with a slack of 16·2^−24·M in uv and in
/// world units, where M is the largest corner |uv| or |coordinate| of the triangle (or disk
/// square) hit: both sides interpolate in float from terms ≤ M (the tracer with Embree's float
/// barycentrics or its disk test, 2 multiplies + 2 adds per component; the GPU with its plane
/// equations and the clipper's lerps for triangles reaching behind the camera), each within
/// 8·2^−24·M of the exact value (4 roundings of terms ≤ M in the interpolation, 4 more for
/// the barycentrics), so 16·2^−24·M apart. A pixel whose shape and texture cell (the
/// pattern's floor(u·scale), floor(v·scale)) are the same at all those points, and whose
/// centre is not within the slack of a disk's outline, differs by the 1-code rounding at most.
struct SurfaceCells {
  const RasterScene& s;
  Cam cam;
  /// Closest hit of the ray through (x, y): triangle index (−1: none; a disk: the first of
  /// its two impostor triangles) and the exact uv and world point.
  int Hit(double x, double y, glm::dvec2* uv, glm::dvec3* at = nullptr) const {
    const auto [o, d] = cam.Ray(x, y);
    int best = -1;
    double best_t = 1e300;
    for (size_t i = 0; i < s.triangles.size(); ++i) {
      const RasterTriangle& tri = s.triangles[i];
      const auto& c = tri.corners;
      const glm::dvec3 p0(c[0].position[0], c[0].position[1], c[0].position[2]);
      if (tri.disk) {
        // The disk: its plane (normal in the corners), points within the radius of the centre.
        const glm::dvec3 n(c[0].normal[0], c[0].normal[1], c[0].normal[2]);
        const glm::dvec3 ctr(tri.center[0], tri.center[1], tri.center[2]);
        const double dn = glm::dot(d, n);
        if (dn == 0.0) continue;
        const double t = glm::dot(ctr - o, n) / dn;
        const glm::dvec3 p = o + d * t;
        if (t <= 0 || t >= best_t || glm::length(p - ctr) > tri.radius) continue;
        best_t = t;
        best = static_cast<int>(i);
        // The disk's uv is the square's (affine in the plane): interpolate from the corners.
      }
      const glm::dvec3 e1 = glm::dvec3(c[1].position[0], c[1].position[1], c[1].position[2]) - p0;
      const glm::dvec3 e2 = glm::dvec3(c[2].position[0], c[2].position[1], c[2].position[2]) - p0;
      const glm::dvec3 pv = glm::cross(d, e2);
      const double det = glm::dot(e1, pv);
      if (det == 0.0) continue;
      const glm::dvec3 tv = o - p0;
      const double u = glm::dot(tv, pv) / det;
      const glm::dvec3 qv = glm::cross(tv, e1);
      const double v = glm::dot(d, qv) / det;
      const double t = glm::dot(e2, qv) / det;
      if (!tri.disk) {
        if (u < 0 || v < 0 || u + v > 1 || t <= 0 || t >= best_t) continue;
        best_t = t;
        best = static_cast<int>(i);
      } else if (best != static_cast<int>(i)) {
        continue;
      }
      *uv = glm::dvec2(c[0].uv[0], c[0].uv[1]) * (1 - u - v) + glm::dvec2(c[1].uv[0], c[1].uv[1]) * u +
            glm::dvec2(c[2].uv[0], c[2].uv[1]) * v;
      if (at) *at = o + d * t;
    }
    // Both impostor triangles of a disk name the same surface: report the first.
    if (best > 0 && s.triangles[static_cast<size_t>(best)].disk && s.triangles[static_cast<size_t>(best - 1)].disk &&
        s.triangles[static_cast<size_t>(best - 1)].shape == s.triangles[static_cast<size_t>(best)].shape) {
      --best;
    }
    return best;
  }
  static std::pair<double, double> Cell(const RasterTexture& t, glm::dvec2 uv) {
    if (t.pattern < 0) return {0.0, 0.0};
    if (t.pattern == 1) return {std::floor((uv.x * t.cos_angle + uv.y * t.sin_angle) * t.scale), 0.0};
    return {std::floor(uv.x * t.scale), std::floor(uv.y * t.scale)};
  }
  static double Largest(const RasterTriangle& t) {
    double big = 0;
    for (const auto& c : t.corners) {
      for (float f : {c.uv[0], c.uv[1], c.position[0], c.position[1], c.position[2]})
        big = std::max(big, std::fabs(double(f)));
    }
    return big;
  }
  /// Whether a shadow ray from `p` on triangle `tri` to light `l` is blocked, in double, as
  /// the tracer builds it (scenes/tracer_shade.cpp ShadowRays): the geometric normal facing
  /// the camera ray `d`, the origin offset by 1e−4 + max|p|·10^−6 to the light's side.
  bool Blocked(glm::dvec3 p, int tri, glm::dvec3 d, const RasterLight& light) const {
    const auto& c = s.triangles[static_cast<size_t>(tri)].corners;
    auto P = [&](int k) {
      return glm::dvec3(c[static_cast<size_t>(k)].position[0], c[static_cast<size_t>(k)].position[1],
                        c[static_cast<size_t>(k)].position[2]);
    };
    glm::dvec3 ng = s.triangles[static_cast<size_t>(tri)].disk
                        ? glm::dvec3(c[0].normal[0], c[0].normal[1], c[0].normal[2])
                        : glm::cross(P(1) - P(0), P(2) - P(0));
    glm::dvec3 o, L;
    double tfar = 0;
    if (!ShadowRayFrom(p, ng, d, light, &o, &L, &tfar)) return false;
    for (const auto& t : s.triangles) {
      const auto& k = t.corners;
      const glm::dvec3 p0(k[0].position[0], k[0].position[1], k[0].position[2]);
      if (t.disk) {
        const glm::dvec3 n(k[0].normal[0], k[0].normal[1], k[0].normal[2]);
        const glm::dvec3 ctr(t.center[0], t.center[1], t.center[2]);
        const double dn = glm::dot(L, n);
        if (dn == 0) continue;
        const double tt = glm::dot(ctr - o, n) / dn;
        if (tt > 0 && tt < tfar && glm::length(o + L * tt - ctr) <= t.radius) return true;
        continue;
      }
      const glm::dvec3 e1 = glm::dvec3(k[1].position[0], k[1].position[1], k[1].position[2]) - p0;
      const glm::dvec3 e2 = glm::dvec3(k[2].position[0], k[2].position[1], k[2].position[2]) - p0;
      const glm::dvec3 pv = glm::cross(L, e2);
      const double det = glm::dot(e1, pv);
      if (det == 0) continue;
      const glm::dvec3 tv = o - p0;
      const double u = glm::dot(tv, pv) / det;
      const glm::dvec3 qv = glm::cross(tv, e1);
      const double v = glm::dot(L, qv) / det;
      const double tt = glm::dot(e2, qv) / det;
      if (u >= 0 && v >= 0 && u + v <= 1 && tt > 0 && tt < tfar) return true;
    }
    return false;
  }
  /// Shadows: whether the light's visibility at the pixel centre's surface point could come
  /// out otherwise: it changes at a corner of the ±snap square, or with the point moved by
  /// the world slack along any axis (the GPU's interpolated position and the tracer's hit
  /// each within 8·2^−24·M of the exact point).
  bool NearShadowEdge(double x, double y, double snap, int tri, glm::dvec3 at) const {
    if (!s.shadows || !s.materials[static_cast<size_t>(s.triangles[static_cast<size_t>(tri)].material)].lit)
      return false;
    const glm::dvec3 d = cam.Ray(x, y).second;
    const double slack = 16.0 * std::ldexp(Largest(s.triangles[static_cast<size_t>(tri)]), -24);
    for (const RasterLight& light : s.lights) {
      if (!light.shadows) continue;
      const bool here = Blocked(at, tri, d, light);
      for (int k = 0; k < 6; ++k) {
        glm::dvec3 q = at;
        q[k % 3] += k < 3 ? slack : -slack;
        if (Blocked(q, tri, d, light) != here) return true;
      }
      for (int k = 0; k < 4; ++k) {
        glm::dvec2 uv;
        glm::dvec3 p2;
        const double xx = x + ((k & 1) ? snap : -snap), yy = y + ((k & 2) ? snap : -snap);
        const int t2 = Hit(xx, yy, &uv, &p2);
        if (t2 < 0 || Blocked(p2, t2, cam.Ray(xx, yy).second, light) != here) return true;
      }
    }
    return false;
  }
  /// True when the pixel centre (x, y) may see another shape, texture cell or shadow than
  /// the exact one.
  bool NearBoundary(double x, double y, double snap) const {
    // A disk's outline within the slack of the ray's point in the disk's plane.
    const auto [o, d] = cam.Ray(x, y);
    for (const auto& t : s.triangles) {
      if (!t.disk) continue;
      const glm::dvec3 n(t.corners[0].normal[0], t.corners[0].normal[1], t.corners[0].normal[2]);
      const glm::dvec3 ctr(t.center[0], t.center[1], t.center[2]);
      const double dn = glm::dot(d, n);
      if (dn == 0.0) continue;
      const glm::dvec3 p = o + d * (glm::dot(ctr - o, n) / dn);
      if (std::fabs(glm::length(p - ctr) - t.radius) <= 16.0 * std::ldexp(Largest(t), -24)) return true;
    }
    glm::dvec2 uv;
    glm::dvec3 at;
    const int tri = Hit(x, y, &uv, &at);
    if (tri < 0) return false;
    if (NearShadowEdge(x, y, snap, tri, at)) return true;
    const RasterTriangle& hit = s.triangles[static_cast<size_t>(tri)];
    const RasterTexture& tex = s.materials[static_cast<size_t>(hit.material)].texture;
    const auto cell = Cell(tex, uv);
    const double slack = 16.0 * std::ldexp(Largest(hit), -24);
    for (int k = 0; k < 4; ++k) {
      const double sx = (k & 1) ? 1 : -1, sy = (k & 2) ? 1 : -1;
      if (Cell(tex, uv + glm::dvec2(sx, sy) * slack) != cell) return true;
      glm::dvec2 uv2;
      const int other = Hit(x + sx * snap, y + sy * snap, &uv2);
      if (other < 0 || s.triangles[static_cast<size_t>(other)].shape != hit.shape || Cell(tex, uv2) != cell)
        return true;
    }
    return false;
  }
};

/// How far coverage may legitimately move: the rasteriser snaps each vertex to
/// 2^−bits px, i.e. by at most 2^−(bits+1) per axis, √2·2^−(bits+1) in distance, and an edge
/// between two snapped vertices moves no further; 1e−4 px more for float rounding of the
/// projection (a few ulps of coordinates below 10^3 px).
inline double SnapDistance(const RasterRenderer& r) {
  return std::sqrt(2.0) * std::ldexp(1.0, -(r.SubpixelBits() + 1)) + 1e-4;
}

/// Whether any of pixel (x, y)'s shading or coverage points (the centre; SSAA's grid × grid
/// sub-pixel centres; for grid = −n, MSAA's centre and n standard sample positions; plus
/// TAA's jitter) may see another shape or texture cell than the exact one.
template <typename Cells>
bool AnyNearBoundary(const Cells& cells, int x, int y, int grid, double jx, double jy, double snap) {
  if (grid < 0) {
    if (cells.NearBoundary(x + 0.5 + jx, y + 0.5 + jy, snap)) return true;
    for (const auto& o : StandardSamplePositions(-grid)) {
      if (cells.NearBoundary(x + (8 + o.x) / 16.0 + jx, y + (8 + o.y) / 16.0 + jy, snap)) return true;
    }
    return false;
  }
  for (int j = 0; j < grid; ++j) {
    for (int i = 0; i < grid; ++i) {
      if (cells.NearBoundary(x + (i + 0.5) / grid + jx, y + (j + 0.5) / grid + jy, snap / grid)) return true;
    }
  }
  return false;
}

struct FrameDiff {
  int max_off_edge = 0;     ///< largest channel difference at pixels away from every edge
  int near_edge_flips = 0;  ///< pixels over 1 code apart whose centre lies within the snap distance
  int texture_flips = 0;    ///< pixels over 1 code apart that may see another texture cell
  int unexplained = 0;      ///< pixels over 1 code apart whose centre does not
  double worst_distance = 0;
  int one_code = 0;  ///< pixels exactly 1 code apart (rounding of the last bit)
  int max_any = 0;   ///< largest channel difference anywhere
};

template <typename Cells = SurfaceCells>
FrameDiff Compare(const Image8& aalab, const std::vector<uint8_t>& gl, const Edges& edges, double snap, int w, int h,
                  const Cells* cells = nullptr, int grid = 1, double jx = 0, double jy = 0) {
  FrameDiff d;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      int m = 0;
      for (int c = 0; c < 3; ++c) {
        m = std::max(m, std::abs(int(aalab.At(x, y, c)) - int(gl[(static_cast<size_t>(y) * w + x) * 3 + c])));
      }
      d.max_any = std::max(d.max_any, m);
      d.one_code += m == 1;
      if (m <= 1) continue;
      const double dist = edges.Nearest(x + 0.5, y + 0.5);
      if (dist <= snap) {
        ++d.near_edge_flips;
        d.worst_distance = std::max(d.worst_distance, dist);
      } else if (cells && AnyNearBoundary(*cells, x, y, grid, jx, jy, snap)) {
        ++d.texture_flips;
      } else {
        ++d.unexplained;
        d.max_off_edge = std::max(d.max_off_edge, m);
        if (d.unexplained <= 5) std::printf("  pixel (%d, %d): %d codes apart, %.5f px from an edge\n", x, y, m, dist);
      }
    }
  }
  return d;
}

}  // namespace aalab
