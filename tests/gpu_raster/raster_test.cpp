// The raster path (gpu/raster, docs/gpu.md "The raster path") against aalab's own renderer,
// on whatever OpenGL 4.5 EGL gives here (Mesa's llvmpipe in CI):
//  - the 1× frame (and TAA's jittered frame) equals aalab's 8-bit frame within 1 code per
//    channel, except at pixels whose centre lies within the rasteriser's vertex snapping
//    distance of a projected triangle edge, where coverage may legitimately flip;
//  - MSAA 2/4/8×: glGetMultisamplefv's positions equal the standard D3D11 / Vulkan table
//    (../shared/notes/msaa-and-analytic-aa.md §1, core/render_spec.h) and the shape seen by
//    every sample equals the one aalab's MSAA simulation (Tracer::TraceMsaa) sees, again
//    except within the snapping distance of an edge;
//  - MSAA 4× and SSAA 2×2 resolved frames equal aalab's within 1 code away from edges.
// Without a context the tests skip, and fail under CI (tests/skip_or_fail.h).
#include <gtest/gtest.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "core/raster_geometry.h"
#include "core/render_spec.h"
#include "gpu/raster/egl_context.h"
#include "gpu/raster/raster_renderer.h"
#include "methods/registry.h"
#include "scenes/library.h"
#include "scenes/motion_render.h"
#include "scenes/raster_export.h"
#include "scenes/render.h"
#include "scenes/tracer.h"
#include "tests/skip_or_fail.h"

namespace aalab {
namespace {

using raster::RasterMethod;
using raster::RasterRenderer;

/// One context for the whole test program ("" when made, else why not).
const std::string& ContextError() {
  static const std::string why = [] {
    raster::GlDeviceInfo info;
    const std::string r = raster::MakeHeadlessGlContext(raster::EglPlatform::kAuto, &info);
    if (r.empty())
      std::printf("raster tests on %s (%s) via %s\n", info.renderer.c_str(), info.version.c_str(),
                  info.platform.c_str());
    return r;
  }();
  return why;
}

#define REQUIRE_GL()                                                                                                  \
  do {                                                                                                                \
    if (!ContextError().empty()) AALAB_SKIP_OR_FAIL_UNDER_CI("no OpenGL 4.5 context through EGL: " + ContextError()); \
  } while (0)

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

Edges ProjectEdges(const RasterScene& s, int w, int h) {
  const Cam cam(s, w, h);
  // Edges reaching behind the camera are clipped to just in front of it (a large ground
  // plane's far edge is then the horizon line the image shows).
  const double z_min = 1e-6;
  Edges e;
  for (const auto& t : s.triangles) {
    if (t.disk) continue;  // an impostor's square is no edge of the image (TextureCells handles disks)
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
struct TextureCells {
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
  /// True when the pixel centre (x, y) may see another shape or texture cell than the exact one.
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
    const int tri = Hit(x, y, &uv);
    if (tri < 0) return false;
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
double SnapDistance(const RasterRenderer& r) {
  return std::sqrt(2.0) * std::ldexp(1.0, -(r.SubpixelBits() + 1)) + 1e-4;
}

/// Whether any of pixel (x, y)'s shading or coverage points (the centre; SSAA's grid × grid
/// sub-pixel centres; for grid = −n, MSAA's centre and n standard sample positions; plus
/// TAA's jitter) may see another shape or texture cell than the exact one.
bool AnyNearBoundary(const TextureCells& cells, int x, int y, int grid, double jx, double jy, double snap) {
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

FrameDiff Compare(const Image8& aalab, const std::vector<uint8_t>& gl, const Edges& edges, double snap, int w, int h,
                  const TextureCells* cells = nullptr, int grid = 1, double jx = 0, double jy = 0) {
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

struct Loaded {
  Scene scene;
  RasterScene raster;
  std::unique_ptr<Tracer> tracer;
};

std::unique_ptr<Loaded> Load(const std::string& name) {
  auto l = std::make_unique<Loaded>();
  l->scene = LoadScene(name);
  l->raster = RasterSceneOf(l->scene);
  l->tracer = std::make_unique<Tracer>(l->scene);
  return l;
}

/// GL_MAX_SAMPLES of the context (Mesa 22's llvmpipe: 4).
int MaxSamples() {
  GLint n = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &n);
  return n;
}

RasterMethod Method(const std::string& spec) {
  RasterMethod m;
  std::string why;
  EXPECT_TRUE(raster::ParseRasterMethod(spec, &m, &why)) << why;
  return m;
}

// The 1× frame: one sample at each pixel centre, the same shading and display transform.
// wedges (orthographic, unlit, 9 rotated quads) and mesh (perspective, lambert, 3200 flat
// triangles, a directional light) at 320×180, both target formats.
TEST(RasterPath, OneXFrameMatchesAalab) {
  REQUIRE_GL();
  for (const std::string name : {"wedges", "mesh"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    const Image8 ref = RenderFrame(*l->tracer, w, h, RenderSpec{}, 1, nullptr);
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    for (auto fmt : {raster::TargetFormat::kRgba16f, raster::TargetFormat::kRgba32f}) {
      r.Configure(Method("none"), w, h, fmt, raster::ResolveKind::kShader);
      r.RenderFrame();
      const FrameDiff d = Compare(ref, r.ReadRgb8(), edges, SnapDistance(r), w, h);
      std::printf(
          "%s 1x %s: %d pixel(s) 1 code apart, %d >1 code apart (max %d), all within %.4f px of an edge (snap %.4f)\n",
          name.c_str(), fmt == raster::TargetFormat::kRgba16f ? "rgba16f" : "rgba32f", d.one_code, d.near_edge_flips,
          d.max_any, d.worst_distance, SnapDistance(r));
      EXPECT_EQ(d.unexplained, 0) << name << ": pixels away from every edge differ by up to " << d.max_off_edge;
      EXPECT_LE(d.near_edge_flips, 8) << name;
    }
  }
}

// TAA's jittered frame 1 (Halton(2,3) point 2: (0, −1/6) px) against aalab's render of the
// same jitter (FrameJitterAt of taa's own jitter spec; what `aalab export-frames
// --taa-frames` writes as taa-f1).
TEST(RasterPath, TaaJitteredFrameMatchesAalab) {
  REQUIRE_GL();
  auto l = Load("mesh");
  const int w = 320, h = 180;
  const FrameJitter j = FrameJitterAt(MakeMethod("taa").render.jitter, 1);
  const RasterMethod m = Method("taa");
  EXPECT_FLOAT_EQ(m.jx, j.x);
  EXPECT_FLOAT_EQ(m.jy, j.y);
  const SurfaceFrame sf = RenderSurfaceFrame(*l->tracer, w, h, j, nullptr);
  RasterRenderer r(l->raster);
  r.Configure(m, w, h, raster::TargetFormat::kRgba16f, raster::ResolveKind::kShader);
  r.RenderFrame();
  // The edges move with the jitter: the geometry is shifted by −jitter under the centre sample.
  Edges edges = ProjectEdges(l->raster, w, h);
  for (auto& s : edges.seg) {
    s[0] -= j.x, s[2] -= j.x;
    s[1] -= j.y, s[3] -= j.y;
  }
  const FrameDiff d = Compare(sf.image, r.ReadRgb8(), edges, SnapDistance(r), w, h);
  std::printf("mesh taa-f1: %d pixel(s) 1 code apart, %d >1 code apart (max %d), all within %.4f px of an edge\n",
              d.one_code, d.near_edge_flips, d.max_any, d.worst_distance);
  EXPECT_EQ(d.unexplained, 0);
  EXPECT_LE(d.near_edge_flips, 8);
}

// MSAA's sample positions as the GL reports them: the standard table, in the raster path's
// image-aligned window coordinates (x right, y down), i.e. (8 + o)/16 of the table's 1/16 px
// offsets from the centre.
TEST(RasterPath, MsaaSamplePositionsAreTheStandardOnes) {
  REQUIRE_GL();
  auto l = Load("wedges");
  RasterRenderer r(l->raster);
  for (int want : {2, 4, 8, 16}) {
    if (want > MaxSamples()) {
      std::printf("msaa-%dx: this GL allows %d samples (GL_MAX_SAMPLES); not checked here\n", want, MaxSamples());
      continue;
    }
    r.Configure(Method("msaa-" + std::to_string(want) + "x"), 64, 36, raster::TargetFormat::kRgba16f,
                raster::ResolveKind::kShader);
    // A GL may allocate more samples than asked; the positions are then the larger pattern's.
    const int n = r.Samples();
    if (n != want) std::printf("msaa-%dx: this GL allocates %d samples; checking the %d-sample pattern\n", want, n, n);
    ASSERT_GE(n, want);
    const std::vector<float> pos = r.SamplePositions();
    const auto& table = StandardSamplePositions(n);
    ASSERT_EQ(pos.size(), 2 * table.size());
    for (int s = 0; s < n; ++s) {
      EXPECT_FLOAT_EQ(pos[2 * s], (8 + table[s].x) / 16.0f) << n << "x sample " << s << " x";
      EXPECT_FLOAT_EQ(pos[2 * s + 1], (8 + table[s].y) / 16.0f) << n << "x sample " << s << " y";
    }
  }
}

// Coverage sample for sample on wedges (edges at 0.5° to 89.6°) and sdf-circles (85 disk
// impostors, their coverage per sample from gl_SampleMask): the shape each hardware
// sample sees (an ID pass into an R32UI multisample target) against the shape aalab's MSAA
// simulation traces at that sample (Tracer::TraceMsaa with the standard positions, as
// RenderFrame builds them). Differences only within the snapping distance of an edge.
TEST(RasterPath, MsaaCoverageMatchesAalabSampleForSample) {
  REQUIRE_GL();
  for (const std::string name : {"wedges", "sdf-circles"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    const TextureCells cells{l->raster, Cam(l->raster, w, h)};
    int disk_exempt = 0;
    for (int want : {2, 4, 8, 16}) {
      if (want > MaxSamples()) continue;
      r.Configure(Method("msaa-" + std::to_string(want) + "x"), w, h, raster::TargetFormat::kRgba16f,
                  raster::ResolveKind::kShader);
      const int n = r.Samples();  // what the GL allocated (≥ want), compared with aalab's n-sample MSAA
      const std::vector<int32_t> gl = r.SampleShapes();
      const auto& table = StandardSamplePositions(n);
      std::vector<SamplePos> pos, centres;
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          centres.push_back({x + 0.5f, y + 0.5f});
          for (const auto& o : table) {
            pos.push_back({static_cast<float>(x) + static_cast<float>(8 + o.x) / 16.0f,
                           static_cast<float>(y) + static_cast<float>(8 + o.y) / 16.0f});
          }
        }
      }
      MsaaSpec spec;
      spec.samples = n;
      std::vector<SampleResult> out(pos.size());
      TraceCounters counters;
      l->tracer->TraceMsaa(pos.data(), centres.data(), w * h, spec, w, h, out.data(), nullptr, &counters);
      ASSERT_EQ(gl.size(), out.size());
      int covered = 0, near_edge = 0, unexplained = 0;
      double worst = 0;
      for (size_t i = 0; i < out.size(); ++i) {
        covered += out[i].surface >= 0;
        if (gl[i] == out[i].surface) continue;
        const double dist = edges.Nearest(pos[i].x, pos[i].y);
        if (dist <= SnapDistance(r)) {
          ++near_edge;
          worst = std::max(worst, dist);
        } else if (cells.NearBoundary(pos[i].x, pos[i].y, SnapDistance(r))) {
          ++disk_exempt;  // within the float slack of a disk's outline (TextureCells)
        } else if (++unexplained <= 5) {
          ADD_FAILURE() << n << "x: sample " << i % n << " of pixel " << i / n << " at (" << pos[i].x << ", "
                        << pos[i].y << "): GL sees shape " << gl[i] << ", aalab " << out[i].surface << ", " << dist
                        << " px from the nearest edge";
        }
      }
      std::printf(
          "%s msaa-%dx (%d samples allocated): %zu samples (%d on a shape), %d differ within %.5f px of "
          "an edge (snap %.5f), %d at a disk's outline\n",
          name.c_str(), want, n, out.size(), covered, near_edge, worst, SnapDistance(r), disk_exempt);
      EXPECT_EQ(unexplained, 0) << name;
      EXPECT_GT(covered, static_cast<int>(out.size() / 10));  // the fixture has real coverage
      EXPECT_LE(near_edge + disk_exempt, static_cast<int>(out.size() / 2000)) << name;
    }
  }
}

// Resolved frames: MSAA 4× (both resolves) and SSAA 2×2 against aalab's msaa-4x and
// ssaa-2x2 frames (display transform per sample, box average in linear light).
TEST(RasterPath, ResolvedFramesMatchAalab) {
  REQUIRE_GL();
  for (const std::string name : {"wedges", "mesh"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    for (const std::string spec : {"msaa-4x", "ssaa-2x2"}) {
      const Image8 ref = RenderFrame(*l->tracer, w, h, MakeMethod(spec).render, 1, nullptr);
      for (auto res : {raster::ResolveKind::kShader, raster::ResolveKind::kBlit}) {
        if (spec == "ssaa-2x2" && res == raster::ResolveKind::kBlit) continue;
        r.Configure(Method(spec), w, h, raster::TargetFormat::kRgba32f, res);
        r.RenderFrame();
        // A resolved pixel on an edge averages samples near it: one flipped sample of n
        // moves it by up to 255/n codes, so the edge test asks for the pixel's whole
        // footprint (centre ± 0.5 px, the farthest sample ≤ 0.71 px away) near an edge.
        const FrameDiff d = Compare(ref, r.ReadRgb8(), edges, 0.7072 + SnapDistance(r), w, h);
        std::printf("%s %s (%s resolve): %d pixel(s) 1 code apart, %d edge pixel(s) >1 code apart (max %d)\n",
                    name.c_str(), spec.c_str(), res == raster::ResolveKind::kBlit ? "blit" : "shader", d.one_code,
                    d.near_edge_flips, d.max_any);
        EXPECT_EQ(d.unexplained, 0) << name << " " << spec;
        EXPECT_LE(d.near_edge_flips, 24) << name << " " << spec;
      }
    }
  }
}

// Procedural textures (checker-plane: a checker ground plane to the horizon, perspective,
// clipped by the near plane; detail-texture: hashed noise, one texel per pixel at 960×540,
// orthographic): the pattern functions ported to GLSL operation for operation, point-sampled
// at the perspective-correct uv. 1× (both formats), TAA's jittered frame 2 (frame 1's jitter
// (0, −1/6) px puts every sample of detail-texture at 320×180 exactly on a texel boundary,
// 3 texels to a pixel: a tie on every pixel, which the rule exempts and so checks nothing),
// MSAA 4× (one
// texture lookup per primitive and pixel, at the centre, on both sides) and SSAA 2×2 against
// aalab's frames; pixels over 1 code apart only near a geometric edge or where the exact uv
// lies within the stated slack of a cell boundary (TextureCells).
TEST(RasterPath, ProceduralTexturesMatchAalab) {
  REQUIRE_GL();
  for (const std::string name : {"checker-plane", "detail-texture"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    for (const std::string spec : {"none", "taa@2", "msaa-4x", "ssaa-2x2"}) {
      const RasterMethod m = Method(spec);
      Image8 ref;
      if (spec == "taa@2") {
        const FrameJitter j = FrameJitterAt(MakeMethod("taa").render.jitter, 2);
        EXPECT_FLOAT_EQ(m.jx, j.x);
        EXPECT_FLOAT_EQ(m.jy, j.y);
        ref = RenderSurfaceFrame(*l->tracer, w, h, j, nullptr).image;
      } else {
        ref = RenderFrame(*l->tracer, w, h, MakeMethod(spec).render, 1, nullptr);
      }
      const int grid = m.kind == RasterMethod::Kind::kSsaa ? m.grid : 1;
      for (auto fmt : {raster::TargetFormat::kRgba16f, raster::TargetFormat::kRgba32f}) {
        if (spec != "none" && fmt == raster::TargetFormat::kRgba32f) continue;
        r.Configure(m, w, h, fmt, raster::ResolveKind::kShader);
        r.RenderFrame();
        Edges moved = edges;
        for (auto& sg : moved.seg) {
          sg[0] -= m.jx, sg[2] -= m.jx;
          sg[1] -= m.jy, sg[3] -= m.jy;
        }
        const TextureCells cells{l->raster, Cam(l->raster, w, h)};
        // Resolved frames: a flipped sample anywhere in the pixel's footprint counts.
        const double reach = m.kind == RasterMethod::Kind::kMsaa || grid > 1 ? 0.7072 : 0.0;
        const FrameDiff d = Compare(ref, r.ReadRgb8(), moved, reach + SnapDistance(r), w, h, &cells, grid, m.jx, m.jy);
        std::printf(
            "%s %s %s: %d pixel(s) identical, %d 1 code apart, %d >1 code apart near an edge, %d near a texture "
            "cell boundary (max %d)\n",
            name.c_str(), spec.c_str(), fmt == raster::TargetFormat::kRgba16f ? "rgba16f" : "rgba32f",
            w * h - d.one_code - d.near_edge_flips - d.texture_flips - d.unexplained, d.one_code, d.near_edge_flips,
            d.texture_flips, d.max_any);
        EXPECT_EQ(d.unexplained, 0) << name << " " << spec << ": pixels differ by up to " << d.max_off_edge;
        // The fixture has structure: the checker reaches the horizon, the noise is non-constant.
        EXPECT_LE(d.near_edge_flips + d.texture_flips, w * h / 50) << name << " " << spec;
      }
    }
  }
}

// Disks as impostors (circle: one lambert disk under a point light; hdr-edges: quads and a
// disk through ACES; sdf-circles: 85 disks over two quads): 1×, TAA's frame 1, MSAA 4× and
// SSAA 2×2 against aalab's frames, under the same rule (triangle edges, disk outlines).
TEST(RasterPath, DiskScenesMatchAalab) {
  REQUIRE_GL();
  for (const std::string name : {"circle", "hdr-edges", "sdf-circles"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    for (const std::string spec : {"none", "taa", "msaa-4x", "ssaa-2x2"}) {
      const RasterMethod m = Method(spec);
      const Image8 ref =
          spec == "taa"
              ? RenderSurfaceFrame(*l->tracer, w, h, FrameJitterAt(MakeMethod("taa").render.jitter, 1), nullptr).image
              : RenderFrame(*l->tracer, w, h, MakeMethod(spec).render, 1, nullptr);
      const int grid = m.kind == RasterMethod::Kind::kSsaa ? m.grid : 1;
      r.Configure(m, w, h, raster::TargetFormat::kRgba16f, raster::ResolveKind::kShader);
      r.RenderFrame();
      Edges moved = edges;
      for (auto& sg : moved.seg) {
        sg[0] -= m.jx, sg[2] -= m.jx;
        sg[1] -= m.jy, sg[3] -= m.jy;
      }
      const TextureCells cells{l->raster, Cam(l->raster, w, h)};
      const double reach = m.kind == RasterMethod::Kind::kMsaa ? 0.7072 : 0.0;
      const FrameDiff d = Compare(ref, r.ReadRgb8(), moved, reach + SnapDistance(r), w, h, &cells,
                                  m.kind == RasterMethod::Kind::kMsaa ? -r.Samples() : grid, m.jx, m.jy);
      std::printf(
          "%s %s: %d pixel(s) identical, %d 1 code apart, %d >1 code apart near an edge, %d at a disk's outline "
          "(max %d)\n",
          name.c_str(), spec.c_str(), w * h - d.one_code - d.near_edge_flips - d.texture_flips - d.unexplained,
          d.one_code, d.near_edge_flips, d.texture_flips, d.max_any);
      EXPECT_EQ(d.unexplained, 0) << name << " " << spec << ": pixels differ by up to " << d.max_off_edge;
      EXPECT_LE(d.near_edge_flips + d.texture_flips, w * h / 200) << name << " " << spec;
    }
  }
}

}  // namespace
}  // namespace aalab
