// Analytical anti-aliasing renderer (scenes/analytic.h).
//
// Per pixel centre: the ordinary camera ray (the `none` sample) and, for every analytic shape
// whose screen bounds (plus the ramp's reach) contain the pixel, the signed distance d from
// the ray to the shape's outline in the shape's own (world) units, with its exact derivatives
// with respect to the pixel position computed by forward-mode differentiation (dual numbers)
// through the camera ray — the quantities a fragment shader gets from dFdx / dFdy, without the
// 2×2-quad finite difference:
//   sphere   d = |(c − o) − dir((c − o)·dir)| − r      (ray-to-centre distance − r)
//   disk     d = |o + dir·t − c| − r, t = ((c − o)·n)/(dir·n)   (distance in the disk's plane)
//   capsule  d = distance(ray line, segment p0 p1) − r
// The per-object pixel size is the world size of a pixel at the shape's centre depth. When
// every shape's alpha at the pixel agrees with the point sample (1 where the ray is inside
// the outline, 0 outside) the `none` sample stands; otherwise the shapes with alpha > 0 are
// sorted by depth along the ray and composited front to back over the first non-analytic
// surface behind them, found by tracing a copy of the scene without the analytic shapes.
#include "scenes/analytic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "scenes/render.h"

namespace aalab {

namespace {

constexpr int kTile = 8;
constexpr int kBin = 16;

/// A value and its derivatives with respect to the pixel position (x, y).
struct Dual {
  double v = 0, dx = 0, dy = 0;
};
Dual operator+(Dual a, Dual b) { return {a.v + b.v, a.dx + b.dx, a.dy + b.dy}; }
Dual operator-(Dual a, Dual b) { return {a.v - b.v, a.dx - b.dx, a.dy - b.dy}; }
Dual operator*(Dual a, Dual b) { return {a.v * b.v, a.dx * b.v + a.v * b.dx, a.dy * b.v + a.v * b.dy}; }
Dual operator/(Dual a, Dual b) {
  const double inv = 1.0 / b.v;
  return {a.v * inv, (a.dx * b.v - a.v * b.dx) * inv * inv, (a.dy * b.v - a.v * b.dy) * inv * inv};
}
Dual Sqrt(Dual a) {
  const double s = std::sqrt(std::max(a.v, 0.0));
  const double k = s > 0.0 ? 0.5 / s : 0.0;
  return {s, a.dx * k, a.dy * k};
}
Dual Const(double v) { return {v, 0, 0}; }

struct DVec {
  Dual x, y, z;
};
DVec operator+(const DVec& a, const DVec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
DVec operator-(const DVec& a, const DVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
DVec operator*(const DVec& a, Dual s) { return {a.x * s, a.y * s, a.z * s}; }
Dual Dot(const DVec& a, const DVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
DVec ConstVec(glm::dvec3 v) { return {Const(v.x), Const(v.y), Const(v.z)}; }

/// The tracer's camera (tracer.cpp's ray setup) in double with derivatives.
struct CameraRays {
  bool persp = true;
  glm::dvec3 origin, fwd, right, up;
  double half_h = 1, aspect = 1, w = 1, h = 1;
  CameraRays(const Camera& cam, int width, int height) {
    const CameraBasis b = CameraBasisOf(cam);
    origin = cam.position;
    fwd = b.forward;
    right = b.right;
    up = b.up;
    persp = cam.type == CameraType::kPerspective;
    half_h = persp ? std::tan(glm::radians(static_cast<double>(cam.fov_y_deg)) * 0.5) : 0.5 * cam.height;
    w = width;
    h = height;
    aspect = w / h;
  }
  /// Ray through the continuous pixel position (x, y), with derivatives.
  void Ray(double x, double y, DVec* o, DVec* d) const {
    const Dual nx{2.0 * x / w - 1.0, 2.0 / w, 0.0};
    const Dual ny{1.0 - 2.0 * y / h, 0.0, -2.0 / h};
    const Dual a = nx * Const(half_h * aspect), b = ny * Const(half_h);
    const DVec off = ConstVec(right) * a + ConstVec(up) * b;
    if (persp) {
      const DVec v = ConstVec(fwd) + off;
      *o = ConstVec(origin);
      *d = v * (Const(1.0) / Sqrt(Dot(v, v)));
    } else {
      *o = ConstVec(origin) + off;
      *d = ConstVec(fwd);
    }
  }
  /// World size of one pixel at depth z along the view direction.
  double PixelWorld(double z) const { return (persp ? 2.0 * half_h * z : 2.0 * half_h) / h; }
  /// Pixel position of a world point in front of the camera (z > 0 for perspective).
  bool Project(glm::dvec3 p, double* px, double* py) const {
    const glm::dvec3 q = p - origin;
    const double z = glm::dot(q, fwd);
    double a = glm::dot(q, right), b = glm::dot(q, up);
    if (persp) {
      if (z <= 1e-9) return false;
      a /= z;
      b /= z;
    }
    *px = (a / (half_h * aspect) + 1.0) * 0.5 * w;
    *py = (1.0 - b / half_h) * 0.5 * h;
    return true;
  }
};

struct AnalyticShape {
  int shape = 0;
  std::array<float, 3> colour{};  // display-linear
  double p_object = 0;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // screen bounds incl. the ramp's reach
};

/// Signed distance (world units) from the ray to the shape's outline, and the depth along
/// the ray of the shape's point nearest the ray. False when undefined (disk seen edge-on,
/// shape behind the ray's origin).
bool Distance(const Shape& s, const DVec& o, const DVec& dir, Dual* d, double* depth) {
  switch (s.kind) {
    case ShapeKind::kSphere: {
      const DVec w = ConstVec(s.center) - o;
      const Dual tc = Dot(w, dir);
      const DVec q = w - dir * tc;
      const Dual dist = Sqrt(Dot(q, q));
      *d = dist - Const(s.radius);
      *depth = tc.v - std::sqrt(std::max(0.0, static_cast<double>(s.radius) * s.radius - dist.v * dist.v));
      return tc.v > 0.0;
    }
    case ShapeKind::kDisk: {
      const DVec n = ConstVec(s.normal);
      const Dual denom = Dot(dir, n);
      if (std::fabs(denom.v) < 1e-9) return false;
      const Dual t = Dot(ConstVec(s.center) - o, n) / denom;
      const DVec q = o + dir * t - ConstVec(s.center);
      *d = Sqrt(Dot(q, q)) - Const(s.radius);
      *depth = t.v;
      return t.v > 0.0;
    }
    case ShapeKind::kCapsule: {
      const glm::dvec3 u = glm::dvec3(s.p1) - glm::dvec3(s.p0);
      const DVec U = ConstVec(u);
      const DVec w0 = ConstVec(s.p0) - o;
      const double a = glm::dot(u, u);
      const Dual b = Dot(U, dir), e = Dot(dir, w0), dd = Dot(U, w0), c = Dot(dir, dir);
      const Dual denom = Const(a) * c - b * b;
      Dual sp = Const(0.0);
      if (a > 0.0 && denom.v > 1e-12 * a) {
        sp = (b * e - c * dd) / denom;
        if (sp.v < 0.0) sp = Const(0.0);
        if (sp.v > 1.0) sp = Const(1.0);
      }
      const DVec q = w0 + U * sp;  // segment point relative to the ray origin
      const Dual tq = Dot(q, dir);
      const DVec perp = q - dir * tq;
      const Dual dist = Sqrt(Dot(perp, perp));
      *d = dist - Const(s.radius);
      *depth = tq.v - std::sqrt(std::max(0.0, static_cast<double>(s.radius) * s.radius - dist.v * dist.v));
      return tq.v > 0.0;
    }
    default: return false;
  }
}

bool FlatColoured(const Scene& sc, const Shape& s) {
  const Material& m = sc.materials[static_cast<size_t>(s.material)];
  if (m.shading == Shading::kLambert && sc.Has(Effect::kLambert)) return false;
  if (m.texture && sc.Has(Effect::kTextures)) return false;
  if (m.alpha && sc.Has(Effect::kAlphaTest)) return false;
  return s.kind == ShapeKind::kSphere || s.kind == ShapeKind::kDisk || s.kind == ShapeKind::kCapsule;
}

/// Conservative screen bounds of a shape's bounding sphere (centre, radius) grown by
/// `margin` px; the whole screen when any part is near or behind a perspective camera.
void ScreenBounds(const CameraRays& cam, glm::dvec3 c, double r, double margin, AnalyticShape* a) {
  a->x0 = -1e30;
  a->y0 = -1e30;
  a->x1 = 1e30;
  a->y1 = 1e30;
  double lx = 1e300, ly = 1e300, hx = -1e300, hy = -1e300;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 corner =
        c + cam.right * ((k & 1) ? r : -r) + cam.up * ((k & 2) ? r : -r) + cam.fwd * ((k & 4) ? r : -r);
    double x, y;
    if (!cam.Project(corner, &x, &y)) return;
    lx = std::min(lx, x);
    hx = std::max(hx, x);
    ly = std::min(ly, y);
    hy = std::max(hy, y);
  }
  a->x0 = lx - margin;
  a->x1 = hx + margin;
  a->y0 = ly - margin;
  a->y1 = hy + margin;
}

struct Layer {
  double depth;
  double alpha;
  int shape;
};

}  // namespace

double AaaPixelSizeOf(AaaPixelSize method, double p_object, double gx, double gy) {
  switch (method) {
    case AaaPixelSize::kObject: return p_object;
    case AaaPixelSize::kLength: return std::sqrt(gx * gx + gy * gy);
    case AaaPixelSize::kFwidth: return std::fabs(gx) + std::fabs(gy);
  }
  return p_object;
}

double AaaAlpha(const AnalyticSpec& spec, double d, double p, double p_object) {
  const double t = std::clamp((p_object - d - p * spec.shrink) / (p * spec.smoothing), 0.0, 1.0);
  return spec.blend == AaaBlend::kSmoothstep ? t * t * (3.0 - 2.0 * t) : t;
}

Image8 RenderAnalyticFrame(const Tracer& tracer, int width, int height, const AnalyticSpec& spec,
                           TraceCounters* counters, AnalyticCounters* analytic) {
  AALAB_CHECK(width > 0 && height > 0, "render size must be positive");
  const Scene& sc = tracer.GetScene();
  const CameraRays cam(sc.camera, width, height);
  // The analytic shapes, and the scene behind them (everything else).
  std::vector<AnalyticShape> shapes;
  std::vector<int> analytic_of(sc.shapes.size(), -1);
  Scene behind_scene = sc;
  behind_scene.shapes.clear();
  std::vector<int> behind_to_full;
  const double margin = 2.0 + 2.0 * std::fabs(spec.shrink) + 2.0 * spec.smoothing;
  for (size_t i = 0; i < sc.shapes.size(); ++i) {
    const Shape& s = sc.shapes[i];
    if (!FlatColoured(sc, s)) {
      behind_scene.shapes.push_back(s);
      behind_to_full.push_back(static_cast<int>(i));
      continue;
    }
    AnalyticShape a;
    a.shape = static_cast<int>(i);
    const glm::vec3 col = sc.materials[static_cast<size_t>(s.material)].color;
    a.colour = DisplayLinear(sc.display, {col.x, col.y, col.z});
    glm::dvec3 c = s.center;
    double r = s.radius;
    if (s.kind == ShapeKind::kCapsule) {
      c = 0.5 * (glm::dvec3(s.p0) + glm::dvec3(s.p1));
      r = 0.5 * glm::length(glm::dvec3(s.p1) - glm::dvec3(s.p0)) + s.radius;
    }
    a.p_object = cam.PixelWorld(glm::dot(c - cam.origin, cam.fwd));
    ScreenBounds(cam, c, r, margin, &a);
    analytic_of[i] = static_cast<int>(shapes.size());
    shapes.push_back(a);
  }
  // Built only when something can be composited (a scene without analytic shapes renders as
  // `none` and never traces behind).
  const std::unique_ptr<Tracer> behind = shapes.empty() ? nullptr : std::make_unique<Tracer>(behind_scene);
  // Screen bins of analytic shapes (in shape order).
  const int bx = (width + kBin - 1) / kBin, by = (height + kBin - 1) / kBin;
  std::vector<std::vector<int>> bins(static_cast<size_t>(bx) * by);
  for (size_t k = 0; k < shapes.size(); ++k) {
    const AnalyticShape& a = shapes[k];
    if (a.x1 < 0 || a.y1 < 0 || a.x0 > width || a.y0 > height) continue;
    const int ix0 = std::clamp(static_cast<int>(std::floor(a.x0)) / kBin, 0, bx - 1);
    const int iy0 = std::clamp(static_cast<int>(std::floor(a.y0)) / kBin, 0, by - 1);
    const int ix1 = std::clamp(static_cast<int>(std::floor(std::min(a.x1, 1e9))) / kBin, 0, bx - 1);
    const int iy1 = std::clamp(static_cast<int>(std::floor(std::min(a.y1, 1e9))) / kBin, 0, by - 1);
    for (int y = iy0; y <= iy1; ++y) {
      for (int x = ix0; x <= ix1; ++x) bins[static_cast<size_t>(y) * bx + x].push_back(static_cast<int>(k));
    }
  }

  Image8 out(width, height, 4, 255);
  std::vector<int32_t> surface(static_cast<size_t>(width) * height, -1);
  std::vector<uint8_t> fractional(static_cast<size_t>(width) * height, 0);
  std::vector<uint8_t> near_outline(static_cast<size_t>(width) * height, 0);
  const int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
  const int tiles = tiles_x * tiles_y;
  std::vector<TraceCounters> per_tile(static_cast<size_t>(tiles));
  std::vector<uint64_t> evals(static_cast<size_t>(tiles), 0);
  ParallelForChunks(tiles, 1, [&](int begin, int end) {
    std::vector<SamplePos> pos, slow_pos;
    std::vector<SampleResult> res, slow_res;
    std::vector<int> slow_px;
    std::vector<std::vector<Layer>> slow_layers;
    std::vector<Layer> layers;
    for (int t = begin; t < end; ++t) {
      const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
      const int x1 = std::min(x0 + kTile, width), y1 = std::min(y0 + kTile, height);
      pos.clear();
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) pos.push_back({static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f});
      }
      res.assign(pos.size(), SampleResult{});
      tracer.Trace(pos.data(), static_cast<int>(pos.size()), width, height, res.data(),
                   &per_tile[static_cast<size_t>(t)]);
      slow_pos.clear();
      slow_px.clear();
      slow_layers.clear();
      size_t k = 0;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x, ++k) {
          const size_t pix = static_cast<size_t>(y) * width + x;
          surface[pix] = res[k].surface;
          const std::vector<int>& cand = bins[static_cast<size_t>(y / kBin) * bx + x / kBin];
          layers.clear();
          bool agree = true, frac = false, near = false;
          if (!cand.empty()) {
            DVec o, dir;
            cam.Ray(x + 0.5, y + 0.5, &o, &dir);
            for (int ci : cand) {
              const AnalyticShape& a = shapes[static_cast<size_t>(ci)];
              if (x + 0.5 < a.x0 || x + 0.5 > a.x1 || y + 0.5 < a.y0 || y + 0.5 > a.y1) continue;
              Dual d;
              double depth;
              ++evals[static_cast<size_t>(t)];
              if (!Distance(sc.shapes[static_cast<size_t>(a.shape)], o, dir, &d, &depth)) continue;
              const double p = AaaPixelSizeOf(spec.pixel_size, a.p_object, d.dx, d.dy);
              double alpha;
              if (p > 0.0 && std::isfinite(p)) {
                alpha = AaaAlpha(spec, d.v, p, a.p_object);
                if (std::fabs(d.v) < p) near = true;
              } else {
                alpha = d.v <= 0.0 ? 1.0 : 0.0;  // no gradient (ray through the centre line): point sample
              }
              if (alpha != (d.v <= 0.0 ? 1.0 : 0.0)) agree = false;
              if (alpha > 0.0 && alpha < 1.0) frac = true;
              if (alpha > 0.0) layers.push_back({depth, alpha, a.shape});
            }
          }
          fractional[pix] = frac ? 1 : 0;
          near_outline[pix] = near ? 1 : 0;
          if (agree) {
            ResolveBoxPixel(sc.display, &res[k], 1, out.Pixel(x, y));  // the `none` pixel, same bits
            continue;
          }
          std::stable_sort(layers.begin(), layers.end(), [](const Layer& l, const Layer& m) {
            return l.depth < m.depth || (l.depth == m.depth && l.shape < m.shape);
          });
          slow_pos.push_back(pos[k]);
          slow_px.push_back(static_cast<int>(pix));
          slow_layers.push_back(layers);
        }
      }
      if (slow_pos.empty()) continue;
      slow_res.assign(slow_pos.size(), SampleResult{});
      behind->Trace(slow_pos.data(), static_cast<int>(slow_pos.size()), width, height, slow_res.data(),
                    &per_tile[static_cast<size_t>(t)]);
      for (size_t s = 0; s < slow_pos.size(); ++s) {
        const SampleResult& b = slow_res[s];
        const std::array<float, 3> bl = DisplayLinear(sc.display, {b.rgb[0], b.rgb[1], b.rgb[2]});
        double acc[3] = {0, 0, 0}, transmit = 1.0;
        for (const Layer& l : slow_layers[s]) {
          if (l.depth >= b.t) break;  // behind the first opaque surface
          const auto& col = shapes[static_cast<size_t>(analytic_of[static_cast<size_t>(l.shape)])].colour;
          for (int c = 0; c < 3; ++c) acc[c] += transmit * l.alpha * col[static_cast<size_t>(c)];
          transmit *= 1.0 - l.alpha;
        }
        for (int c = 0; c < 3; ++c) acc[c] += transmit * bl[static_cast<size_t>(c)];
        const int pix = slow_px[s];
        uint8_t* p = out.Pixel(pix % width, pix / width);
        for (int c = 0; c < 3; ++c) p[c] = QuantizeUnorm8(SrgbEncode(static_cast<float>(acc[c])));
      }
    }
  });
  AnalyticCounters ac;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t i = static_cast<size_t>(y) * width + x;
      const int32_t s = surface[i];
      const bool edge = (x > 0 && surface[i - 1] != s) || (x + 1 < width && surface[i + 1] != s) ||
                        (y > 0 && surface[i - static_cast<size_t>(width)] != s) ||
                        (y + 1 < height && surface[i + static_cast<size_t>(width)] != s);
      ac.edge_pixels += edge ? 1 : 0;
      ac.analytic_edge_pixels += (edge && near_outline[i]) ? 1 : 0;
      ac.analytic_pixels += fractional[i];
    }
  }
  for (uint64_t e : evals) ac.distance_evals += e;
  if (analytic) *analytic = ac;
  if (counters) {
    for (const auto& c : per_tile) *counters += c;
  }
  return out;
}

}  // namespace aalab
