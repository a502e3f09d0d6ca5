// The raster path's tolerance rule extended to glTF materials (docs/gpu.md "Correctness on
// Mesa"): where the GPU's frame of a glTF scene may differ from aalab's by more than the
// 1-code rounding away from triangle edges. The new source is the alpha test: a MASK
// material keeps a hit where baseColorFactor.a · α(uv) ≥ alphaCutoff, on camera rays (α
// trilinear at the tracer's footprint) and on shadow rays (α bilinear on level 0), and a
// pixel whose α lies that close to the cutoff may flip. "That close" is worked out, not
// fitted: α is a bilinear / trilinear blend of 8-bit texels, so it changes by at most 1
// per texel of level 0 (a coarser level's texel is wider), i.e. by at most max(W, H) per uv
// unit; both sides' uv differ from the exact one by the interpolation slack 16·2⁻²⁴·M
// (raster_rule.h) and, through vertex snapping, by the snap distance times the uv change
// per pixel J; λ's float rounding moves the trilinear weight by < 10⁻⁶. So a decision may
// flip where |α − cutoff| ≤ max(W, H)·(16·2⁻²⁴·M + snap·J) + 10⁻⁶. Shadow boundaries,
// through cut-outs or not, are found as raster_rule.h finds them (the decision changes
// within the world slack or the ±snap square). Everything here is the test's own double
// arithmetic on the scene file, except α itself, which is aalab's SampleTexture over the
// file's mip chains (the texels both sides filter).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "scenes/texture_image.h"
#include "tests/gpu_raster/raster_rule.h"

namespace aalab {

struct GltfCells {
  const RasterScene& s;
  Cam cam;
  double snap;
  std::vector<MipChain> chains;

  GltfCells(const RasterScene& scene, int w, int h, double snap_px) : s(scene), cam(scene, w, h), snap(snap_px) {
    for (const RasterImage& im : s.images) {
      MipChain c;
      for (const RasterMipLevel& l : im.levels) {
        MipLevel m;
        m.width = l.width;
        m.height = l.height;
        m.format = im.format == 0 ? TexelFormat::kSrgb8 : TexelFormat::kUnorm8;
        m.bytes = l.rgba;
        c.levels.push_back(std::move(m));
      }
      chains.push_back(std::move(c));
    }
  }

  glm::dvec3 P(int tri, int k) const {
    const auto& p = s.triangles[static_cast<size_t>(tri)].corners[static_cast<size_t>(k)].position;
    return {p[0], p[1], p[2]};
  }
  glm::dvec2 Uv(int tri, int k) const {
    const auto& u = s.triangles[static_cast<size_t>(tri)].corners[static_cast<size_t>(k)].uv;
    return {u[0], u[1]};
  }
  /// Möller–Trumbore in double; extrapolated (no bounds test) when `any`.
  bool Intersect(int tri, glm::dvec3 o, glm::dvec3 d, double* t, glm::dvec2* uv, bool any) const {
    const glm::dvec3 p0 = P(tri, 0), e1 = P(tri, 1) - p0, e2 = P(tri, 2) - p0;
    const glm::dvec3 pv = glm::cross(d, e2);
    const double det = glm::dot(e1, pv);
    if (det == 0.0) return false;
    const glm::dvec3 tv = o - p0;
    const double u = glm::dot(tv, pv) / det;
    const glm::dvec3 qv = glm::cross(tv, e1);
    const double v = glm::dot(d, qv) / det;
    *t = glm::dot(e2, qv) / det;
    if (!any && (u < 0 || v < 0 || u + v > 1 || *t <= 0)) return false;
    *uv = Uv(tri, 0) * (1 - u - v) + Uv(tri, 1) * u + Uv(tri, 2) * v;
    return true;
  }
  const RasterMaterial& Mat(int tri) const {
    return s.materials[static_cast<size_t>(s.triangles[static_cast<size_t>(tri)].material)];
  }
  int Shape(int tri) const { return s.triangles[static_cast<size_t>(tri)].shape; }
  bool Mask(int tri) const { return s.alpha_test && Mat(tri).gltf && Mat(tri).pbr.alpha_mode == 1; }
  double Slack(int tri) const {
    return 16.0 * std::ldexp(SurfaceCells::Largest(s.triangles[static_cast<size_t>(tri)]), -24);
  }
  /// α at uv with the footprint (dx, dy) (zero: level 0), and the largest level-0 edge.
  double Alpha(int tri, glm::dvec2 uv, glm::dvec2 dx, glm::dvec2 dy, double* edge) const {
    const RasterGltf& g = Mat(tri).pbr;
    *edge = 0;
    if (g.base.image < 0) return g.base_factor[3];
    const MipChain& c = chains[static_cast<size_t>(g.base.image)];
    *edge = std::max(c.levels[0].width, c.levels[0].height);
    UvDerivs d;
    d.dx = glm::vec2(dx);
    d.dy = glm::vec2(dy);
    const glm::vec4 t = SampleTexture(c, glm::vec2(uv), d, static_cast<WrapMode>(g.base.wrap_s),
                                      static_cast<WrapMode>(g.base.wrap_t), TextureFilter{});
    return static_cast<double>(g.base_factor[3] * t.w);
  }
  /// The camera ray through (x, y): the first hit that is not a culled back face and passes
  /// the alpha test; *near when a cut-out decision on the way lies within the slack.
  int Visible(double x, double y, glm::dvec3* at, bool* near) const {
    const auto [o, d] = cam.Ray(x, y);
    std::vector<std::pair<double, int>> hits;
    for (size_t i = 0; i < s.triangles.size(); ++i) {
      double t;
      glm::dvec2 uv;
      if (Intersect(static_cast<int>(i), o, d, &t, &uv, false)) hits.push_back({t, static_cast<int>(i)});
    }
    std::sort(hits.begin(), hits.end());
    for (const auto& [t, tri] : hits) {
      const glm::dvec3 n = glm::cross(P(tri, 1) - P(tri, 0), P(tri, 2) - P(tri, 0));
      if (Mat(tri).gltf && !Mat(tri).pbr.double_sided && glm::dot(n, d) > 0) continue;
      if (Mask(tri)) {
        double tt;
        glm::dvec2 uv, ux, uy;
        Intersect(tri, o, d, &tt, &uv, true);
        const auto rx = cam.Ray(x + 1, y), ry = cam.Ray(x, y + 1);  // the tracer's offset rays
        glm::dvec2 dx(1e30, 0), dy(1e30, 0);
        if (Intersect(tri, rx.first, rx.second, &tt, &ux, true) && tt > 0) dx = ux - uv;
        if (Intersect(tri, ry.first, ry.second, &tt, &uy, true) && tt > 0) dy = uy - uv;
        double edge;
        const double a = Alpha(tri, uv, dx, dy, &edge);
        const double j = std::max(glm::length(dx), glm::length(dy));
        const double delta = edge * (Slack(tri) + snap * j) + 1e-6;
        if (std::fabs(a - Mat(tri).pbr.alpha_cutoff) <= delta) *near = true;
        if (!(a >= Mat(tri).pbr.alpha_cutoff)) continue;
      }
      *at = o + d * t;
      return tri;
    }
    return -1;
  }
  /// The tracer's shadow ray from p on `tri` (raster_rule.h Blocked) with the cut-out test
  /// at each occluder (level 0 bilinear); *near when a cut-out decision lies within the slack.
  bool Blocked(glm::dvec3 p, int tri, glm::dvec3 d, const RasterLight& light, bool* near) const {
    glm::dvec3 o, L;
    double tfar = 0;
    if (!ShadowRayFrom(p, glm::cross(P(tri, 1) - P(tri, 0), P(tri, 2) - P(tri, 0)), d, light, &o, &L, &tfar))
      return false;
    bool blocked = false;
    for (size_t i = 0; i < s.triangles.size(); ++i) {
      const int k = static_cast<int>(i);
      double t;
      glm::dvec2 uv;
      if (!Intersect(k, o, L, &t, &uv, false) || !(t > 0 && t < tfar)) continue;
      if (!Mask(k)) return true;
      double edge;
      const double a = Alpha(k, uv, {0, 0}, {0, 0}, &edge);
      if (std::fabs(a - Mat(k).pbr.alpha_cutoff) <= edge * Slack(k) + 1e-6) *near = true;
      if (a >= Mat(k).pbr.alpha_cutoff) blocked = true;
    }
    return blocked;
  }
  /// True when the pixel centre (x, y) may see another surface, cut-out decision or shadow.
  bool NearBoundary(double x, double y, double snap_px) const {
    bool near = false;
    glm::dvec3 at;
    const int tri = Visible(x, y, &at, &near);
    if (near) return true;
    for (int k = 0; k < 4; ++k) {
      glm::dvec3 a2;
      const int t2 = Visible(x + ((k & 1) ? snap_px : -snap_px), y + ((k & 2) ? snap_px : -snap_px), &a2, &near);
      if (near || (t2 < 0) != (tri < 0) || (tri >= 0 && Shape(t2) != Shape(tri))) return true;
    }
    if (tri < 0 || !s.shadows || Mat(tri).pbr.unlit) return false;
    const glm::dvec3 d = cam.Ray(x, y).second;
    const double slack = Slack(tri);
    for (const RasterLight& light : s.lights) {
      if (!light.shadows) continue;
      const bool here = Blocked(at, tri, d, light, &near);
      if (near) return true;
      for (int k = 0; k < 6; ++k) {
        glm::dvec3 q = at;
        q[k % 3] += k < 3 ? slack : -slack;
        if (Blocked(q, tri, d, light, &near) != here || near) return true;
      }
      for (int k = 0; k < 4; ++k) {
        const double xx = x + ((k & 1) ? snap_px : -snap_px), yy = y + ((k & 2) ? snap_px : -snap_px);
        glm::dvec3 p2;
        const int t2 = Visible(xx, yy, &p2, &near);
        if (t2 < 0 || Blocked(p2, t2, cam.Ray(xx, yy).second, light, &near) != here || near) return true;
      }
    }
    return false;
  }
};

}  // namespace aalab
