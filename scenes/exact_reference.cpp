// The exact reference for flat scenes: closed-form pixel coverage with exact occlusion.
//
// Every qualifying shape (exact_reference.h lists the rules) is projected to the image plane
// in double: a disk (disk facing the camera, sphere), a stadium (capsule) or a triangle.
// Shapes are sorted front to back (the depth ranges of overlapping shapes are disjoint, so
// the order is that of the nearest depth). Each pixel keeps its still-visible region as a
// list of convex polygons, each minus a set of curved shapes already drawn in front of it:
//  - a curved shape C covers Σ_pieces area(C ∩ piece) (curved shapes never overlap, so the
//    curved shapes subtracted from a piece do not intersect C), then joins each piece's set;
//  - a triangle T covers Σ_pieces [area(T ∩ piece) − Σ_{D in the set} area(D ∩ T ∩ piece)]
//    (T ∩ piece is convex; the D are disjoint), then each piece is replaced by piece \ T,
//    split into at most three convex pieces along T's edges.
// All areas are closed form (analytic_geometry.h). The background takes what is left.
#include "scenes/exact_reference.h"

#include <algorithm>
#include <cmath>

#include "core/color.h"
#include "core/edge_mask.h"
#include "core/error.h"
#include "core/parallel.h"
#include "scenes/analytic_geometry.h"

namespace aalab {

namespace {

constexpr int kBin = 16;  // screen bins of 16 × 16 px for candidate lists
constexpr int kMaxCurvedPerPiece = 24;

enum class FlatKind { kDisk, kCapsule, kTriangle };

struct FlatShape {
  FlatKind kind = FlatKind::kDisk;
  int shape = 0;  // index into Scene::shapes (= /objects index)
  Vec2d a, b, c;  // disk: a = centre; capsule: a–b; triangle: a, b, c
  double r = 0;   // disk / capsule radius in px
  double zmin = 0, zmax = 0;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // image bounding box
  ConvexPoly tri;                         // triangle as a polygon
};

bool Curved(const FlatShape& s) { return s.kind != FlatKind::kTriangle; }

/// Orthographic projection of the tracer's camera in double: pixel = (a·W/(2·hw) + W/2,
/// H/2 − b·H/(2·hh)) with a, b the offsets along right / up (tracer.cpp's ray setup inverted).
struct OrthoProjection {
  glm::dvec3 origin, fwd, right, up;
  double sx = 0, sy = 0, w = 0, h = 0;  // px per world unit; frame size
  OrthoProjection(const Camera& cam, int width, int height) {
    // Same float basis as the tracer, then widened.
    const CameraBasis b = CameraBasisOf(cam);
    origin = cam.position;
    fwd = b.forward;
    right = b.right;
    up = b.up;
    w = width;
    h = height;
    const double half_h = 0.5 * static_cast<double>(cam.height);
    const double half_w = half_h * w / h;
    sx = w / (2.0 * half_w);
    sy = h / (2.0 * half_h);
  }
  Vec2d Pixel(glm::vec3 p) const {
    const glm::dvec3 d = glm::dvec3(p) - origin;
    return {0.5 * w + glm::dot(d, right) * sx, 0.5 * h - glm::dot(d, up) * sy};
  }
  double Depth(glm::vec3 p) const { return glm::dot(glm::dvec3(p) - origin, fwd); }
};

std::string ObjectPath(int i) { return "/objects/" + std::to_string(i); }

double CurvedArea(const FlatShape& s, const ConvexPoly& p) {
  return s.kind == FlatKind::kDisk ? DiskPolyArea(s.a, s.r, p) : CapsulePolyArea(s.a, s.b, s.r, p);
}

/// Area of the overlap of two shapes in the image (0 when they only touch).
double OverlapArea(const FlatShape& s, const FlatShape& t) {
  if (Curved(s) && Curved(t)) {
    double gap;
    if (s.kind == FlatKind::kDisk && t.kind == FlatKind::kDisk) {
      gap = std::hypot(s.a.x - t.a.x, s.a.y - t.a.y);
    } else if (s.kind == FlatKind::kDisk) {
      gap = PointSegmentDistance(s.a, t.a, t.b);
    } else if (t.kind == FlatKind::kDisk) {
      gap = PointSegmentDistance(t.a, s.a, s.b);
    } else {
      gap = SegmentSegmentDistance(s.a, s.b, t.a, t.b);
    }
    return gap < s.r + t.r ? 1.0 : 0.0;  // only "overlaps or not" matters for curved pairs
  }
  if (Curved(s)) return CurvedArea(s, t.tri);
  if (Curved(t)) return CurvedArea(t, s.tri);
  return std::fabs(SignedArea(ClipConvex(s.tri, t.tri)));
}

double ShapeArea(const FlatShape& s) {
  if (s.kind == FlatKind::kDisk) return M_PI * s.r * s.r;
  if (s.kind == FlatKind::kCapsule) return M_PI * s.r * s.r + 2.0 * s.r * std::hypot(s.b.x - s.a.x, s.b.y - s.a.y);
  return std::fabs(SignedArea(s.tri));
}

struct FlatScene {
  std::vector<FlatShape> shapes;  // front to back
  std::string refusal;
};

FlatScene Flatten(const Scene& scene, int width, int height) {
  FlatScene fs;
  if (scene.camera.type != CameraType::kOrthographic) {
    fs.refusal = "/camera/type is 'perspective': the exact reference needs an orthographic camera";
    return fs;
  }
  for (int e = 0; e < kEffectCount; ++e) {
    if (scene.effects[e] && static_cast<Effect>(e) != Effect::kUnlit) {
      fs.refusal = "/effects declares '" + std::string(EffectName(static_cast<Effect>(e))) +
                   "': the exact reference needs effects [\"unlit\"] only (one constant colour per shape)";
      return fs;
    }
  }
  const OrthoProjection proj(scene.camera, width, height);
  const double scale = proj.sx;  // world → px (square pixels: sx == sy)
  for (size_t i = 0; i < scene.shapes.size(); ++i) {
    const Shape& sh = scene.shapes[i];
    const int idx = static_cast<int>(i);
    FlatShape f;
    f.shape = idx;
    switch (sh.kind) {
      case ShapeKind::kCylinder:
        fs.refusal = ObjectPath(idx) +
                     " is a cylinder: the exact reference takes disks facing the camera, spheres, "
                     "capsules and triangle shapes (a cylinder's outline has elliptic caps)";
        return fs;
      case ShapeKind::kDisk: {
        const double facing = std::fabs(glm::dot(glm::dvec3(glm::normalize(sh.normal)), proj.fwd));
        if (facing < 1.0 - 1e-6) {
          fs.refusal = ObjectPath(idx) +
                       " is a disk whose normal is not parallel to the view direction: the exact "
                       "reference takes disks facing the camera only (others image as ellipses)";
          return fs;
        }
        f.kind = FlatKind::kDisk;
        f.a = proj.Pixel(sh.center);
        f.r = sh.radius * scale;
        f.zmin = f.zmax = proj.Depth(sh.center);
        break;
      }
      case ShapeKind::kSphere:
        f.kind = FlatKind::kDisk;
        f.a = proj.Pixel(sh.center);
        f.r = sh.radius * scale;
        f.zmin = proj.Depth(sh.center) - sh.radius;
        f.zmax = proj.Depth(sh.center) + sh.radius;
        break;
      case ShapeKind::kCapsule: {
        f.kind = FlatKind::kCapsule;
        f.a = proj.Pixel(sh.p0);
        f.b = proj.Pixel(sh.p1);
        f.r = sh.radius * scale;
        const double z0 = proj.Depth(sh.p0), z1 = proj.Depth(sh.p1);
        f.zmin = std::min(z0, z1) - sh.radius;
        f.zmax = std::max(z0, z1) + sh.radius;
        break;
      }
      case ShapeKind::kTriangles: break;
    }
    if (sh.kind == ShapeKind::kTriangles) {
      for (const glm::uvec3& t : sh.triangles) {
        FlatShape tf;
        tf.kind = FlatKind::kTriangle;
        tf.shape = idx;
        tf.a = proj.Pixel(sh.positions[t.x]);
        tf.b = proj.Pixel(sh.positions[t.y]);
        tf.c = proj.Pixel(sh.positions[t.z]);
        tf.tri.Push(tf.a);
        tf.tri.Push(tf.b);
        tf.tri.Push(tf.c);
        const double za = proj.Depth(sh.positions[t.x]), zb = proj.Depth(sh.positions[t.y]),
                     zc = proj.Depth(sh.positions[t.z]);
        tf.zmin = std::min({za, zb, zc});
        tf.zmax = std::max({za, zb, zc});
        tf.x0 = std::min({tf.a.x, tf.b.x, tf.c.x});
        tf.x1 = std::max({tf.a.x, tf.b.x, tf.c.x});
        tf.y0 = std::min({tf.a.y, tf.b.y, tf.c.y});
        tf.y1 = std::max({tf.a.y, tf.b.y, tf.c.y});
        if (SignedArea(tf.tri) == 0.0) continue;  // edge-on: covers no area
        fs.shapes.push_back(tf);
      }
    } else {
      const Vec2d lo{std::min(f.a.x, f.kind == FlatKind::kCapsule ? f.b.x : f.a.x),
                     std::min(f.a.y, f.kind == FlatKind::kCapsule ? f.b.y : f.a.y)};
      const Vec2d hi{std::max(f.a.x, f.kind == FlatKind::kCapsule ? f.b.x : f.a.x),
                     std::max(f.a.y, f.kind == FlatKind::kCapsule ? f.b.y : f.a.y)};
      f.x0 = lo.x - f.r;
      f.y0 = lo.y - f.r;
      f.x1 = hi.x + f.r;
      f.y1 = hi.y + f.r;
      fs.shapes.push_back(f);
    }
    if (!fs.shapes.empty() && fs.shapes.back().shape == idx && fs.shapes.back().zmin < 0.0) {
      fs.refusal = ObjectPath(idx) + " reaches behind the orthographic camera's image plane (depth " +
                   std::to_string(fs.shapes.back().zmin) + " < 0): the exact reference cannot clip it";
      return fs;
    }
    if (static_cast<int>(fs.shapes.size()) > kMaxExactPrimitives) {
      fs.refusal = "/objects has more than " + std::to_string(kMaxExactPrimitives) +
                   " shapes after splitting meshes into triangles: too many for the exact reference";
      return fs;
    }
  }
  std::stable_sort(fs.shapes.begin(), fs.shapes.end(),
                   [](const FlatShape& p, const FlatShape& q) { return p.zmin < q.zmin; });
  // Pairwise: curved shapes must not overlap; overlapping shapes need disjoint depth ranges.
  const size_t n = fs.shapes.size();
  for (size_t i = 0; i < n; ++i) {
    const FlatShape& s = fs.shapes[i];
    for (size_t j = i + 1; j < n; ++j) {
      const FlatShape& t = fs.shapes[j];
      if (s.shape == t.shape) continue;  // triangles of one mesh: depth-tested like any pair below
      if (s.x1 <= t.x0 || t.x1 <= s.x0 || s.y1 <= t.y0 || t.y1 <= s.y0) continue;
      const double ov = OverlapArea(s, t);
      if (Curved(s) && Curved(t) && ov > 0.0) {
        fs.refusal = ObjectPath(s.shape) + " and " + ObjectPath(t.shape) +
                     " are curved shapes that overlap in the image: the exact reference needs curved shapes "
                     "(disks, spheres, capsules) to be disjoint";
        return fs;
      }
      const double tol = 1e-9 * std::min(ShapeArea(s), ShapeArea(t));
      if (ov > tol && !(s.zmax < t.zmin || t.zmax < s.zmin)) {
        fs.refusal = ObjectPath(s.shape) + " and " + ObjectPath(t.shape) +
                     " overlap in the image and their depth ranges overlap: the exact reference needs one of two "
                     "overlapping shapes wholly in front of the other";
        return fs;
      }
    }
  }
  // Triangles of one mesh that overlap each other in the image: the same depth rule.
  for (size_t i = 0; i < n; ++i) {
    const FlatShape& s = fs.shapes[i];
    if (Curved(s)) continue;
    for (size_t j = i + 1; j < n; ++j) {
      const FlatShape& t = fs.shapes[j];
      if (t.shape != s.shape || Curved(t)) continue;
      if (s.x1 <= t.x0 || t.x1 <= s.x0 || s.y1 <= t.y0 || t.y1 <= s.y0) continue;
      const double ov = OverlapArea(s, t);
      if (ov > 1e-9 * std::min(ShapeArea(s), ShapeArea(t)) && !(s.zmax < t.zmin || t.zmax < s.zmin)) {
        fs.refusal = ObjectPath(s.shape) +
                     " has triangles that overlap in the image at overlapping depths: the "
                     "exact reference needs one of two overlapping triangles wholly in front of the other";
        return fs;
      }
    }
  }
  return fs;
}

struct Piece {
  ConvexPoly poly;
  std::array<int, kMaxCurvedPerPiece> sub{};
  int nsub = 0;
};

/// Coverage of pixel (px, py) by each candidate (indices into shapes, front to back).
/// Appends (flat index, coverage) pairs with coverage > 0 to `out`.
void CoverPixel(const std::vector<FlatShape>& shapes, const std::vector<int>& cand, int px, int py,
                std::vector<Piece>& pieces, std::vector<Piece>& next, std::vector<std::pair<int, double>>& out) {
  const double x0 = px, y0 = py, x1 = px + 1.0, y1 = py + 1.0;
  pieces.clear();
  pieces.push_back(Piece{RectPoly(x0, y0, x1, y1), {}, 0});
  for (int k : cand) {
    if (pieces.empty()) break;
    const FlatShape& s = shapes[static_cast<size_t>(k)];
    if (s.x1 <= x0 || s.x0 >= x1 || s.y1 <= y0 || s.y0 >= y1) continue;
    double cov = 0.0;
    if (Curved(s)) {
      // Quick reject / accept on the pixel's centre distance (half-diagonal √2/2).
      const Vec2d ctr{px + 0.5, py + 0.5};
      const double dist =
          s.kind == FlatKind::kDisk ? std::hypot(ctr.x - s.a.x, ctr.y - s.a.y) : PointSegmentDistance(ctr, s.a, s.b);
      if (dist >= s.r + 0.7072) continue;
      const bool full = dist <= s.r - 0.7072;
      for (Piece& p : pieces) {
        const double a = full ? std::fabs(SignedArea(p.poly)) : CurvedArea(s, p.poly);
        if (a <= 0.0) continue;
        cov += a;
        AALAB_CHECK(p.nsub < kMaxCurvedPerPiece, "too many curved shapes in one pixel for the exact reference");
        p.sub[static_cast<size_t>(p.nsub++)] = k;
      }
      if (full) pieces.clear();  // curved shapes never overlap: nothing else was subtracted
    } else {
      const double orient = SignedArea(s.tri) >= 0.0 ? 1.0 : -1.0;
      next.clear();
      for (const Piece& p : pieces) {
        const ConvexPoly in = ClipConvex(p.poly, s.tri);
        if (in.n == 0) {
          next.push_back(p);
          continue;
        }
        double a = std::fabs(SignedArea(in));
        for (int d = 0; d < p.nsub; ++d)
          a -= CurvedArea(shapes[static_cast<size_t>(p.sub[static_cast<size_t>(d)])], in);
        cov += std::max(0.0, a);
        // piece \ T: the part outside edge 0, then inside 0 and outside 1, then inside 0, 1
        // and outside 2.
        ConvexPoly rest = p.poly;
        for (int e = 0; e < 3 && rest.n > 0; ++e) {
          const Vec2d ea = s.tri.v[static_cast<size_t>(e)], eb = s.tri.v[static_cast<size_t>((e + 1) % 3)];
          const double nx = orient * (eb.y - ea.y), ny = -orient * (eb.x - ea.x);
          const double c = nx * ea.x + ny * ea.y;
          Piece outside{ClipHalfPlane(rest, -nx, -ny, -c), p.sub, p.nsub};
          if (outside.poly.n > 0) next.push_back(outside);
          rest = ClipHalfPlane(rest, nx, ny, c);
        }
      }
      pieces.swap(next);
    }
    if (cov > 0.0) out.emplace_back(k, cov);
  }
}

/// Runs CoverPixel over the frame in parallel rows; `sink(x, y, coverages)` per pixel.
template <typename Sink>
void CoverFrame(const FlatScene& fs, int width, int height, const Sink& sink) {
  const int bx = (width + kBin - 1) / kBin, by = (height + kBin - 1) / kBin;
  std::vector<std::vector<int>> bins(static_cast<size_t>(bx) * by);
  for (size_t k = 0; k < fs.shapes.size(); ++k) {  // front-to-back order within each bin
    const FlatShape& s = fs.shapes[k];
    const int ix0 = std::max(0, static_cast<int>(std::floor(s.x0)) / kBin);
    const int iy0 = std::max(0, static_cast<int>(std::floor(s.y0)) / kBin);
    const int ix1 = std::min(bx - 1, static_cast<int>(std::floor(std::min(s.x1, 1e9))) / kBin);
    const int iy1 = std::min(by - 1, static_cast<int>(std::floor(std::min(s.y1, 1e9))) / kBin);
    if (s.x1 < 0 || s.y1 < 0) continue;
    for (int y = iy0; y <= iy1; ++y) {
      for (int x = ix0; x <= ix1; ++x) bins[static_cast<size_t>(y) * bx + x].push_back(static_cast<int>(k));
    }
  }
  ParallelForChunks(height, 1, [&](int begin, int end) {
    std::vector<Piece> pieces, next;
    std::vector<std::pair<int, double>> cov;
    for (int y = begin; y < end; ++y) {
      for (int x = 0; x < width; ++x) {
        cov.clear();
        CoverPixel(fs.shapes, bins[static_cast<size_t>(y / kBin) * bx + x / kBin], x, y, pieces, next, cov);
        sink(x, y, cov);
      }
    }
  });
}

FlatScene FlattenOrThrow(const Scene& scene, int width, int height) {
  FlatScene fs = Flatten(scene, width, height);
  if (!fs.refusal.empty()) throw UserError("scene '" + scene.name + "': --reference exact: " + fs.refusal);
  return fs;
}

}  // namespace

std::string ExactReferenceRefusal(const Scene& scene) { return Flatten(scene, 960, 540).refusal; }

Reference RenderExactReference(const Scene& scene, int width, int height) {
  AALAB_CHECK(width > 0 && height > 0, "exact reference size must be positive");
  const FlatScene fs = FlattenOrThrow(scene, width, height);
  std::vector<std::array<float, 3>> colour(scene.shapes.size());
  for (size_t i = 0; i < scene.shapes.size(); ++i) {
    const glm::vec3 c = scene.materials[static_cast<size_t>(scene.shapes[i].material)].color;
    colour[i] = DisplayLinear(scene.display, {c.x, c.y, c.z});
  }
  const std::array<float, 3> bg =
      DisplayLinear(scene.display, {scene.background.x, scene.background.y, scene.background.z});
  Reference ref;
  ref.grid = 0;
  ref.image = ImageF(width, height, 3);
  ref.edge_mask_raw = ImageF(width, height, 1);
  CoverFrame(fs, width, height, [&](int x, int y, const std::vector<std::pair<int, double>>& cov) {
    double sum[3] = {0, 0, 0}, total = 0.0;
    int first = -2;
    bool edge = false;
    for (const auto& [k, a] : cov) {
      const int shape = fs.shapes[static_cast<size_t>(k)].shape;
      for (int c = 0; c < 3; ++c) sum[c] += a * colour[static_cast<size_t>(shape)][static_cast<size_t>(c)];
      total += a;
      if (first == -2) first = shape;
      if (shape != first) edge = true;
    }
    const double rest = std::max(0.0, 1.0 - total);
    if (rest > 1e-12 && first != -2) edge = true;
    for (int c = 0; c < 3; ++c) {
      ref.image.At(x, y, c) = SrgbEncode(static_cast<float>(sum[c] + rest * bg[static_cast<size_t>(c)]));
    }
    ref.edge_mask_raw.At(x, y, 0) = edge ? 1.0f : 0.0f;
  });
  ref.half_a = ref.image;
  ref.half_b = ref.image;
  ref.edge_mask = DilateMask(ref.edge_mask_raw);
  return ref;
}

std::vector<DiskProbe> DiskProbes(const Scene& scene, int width, int height, const ImageF& ref) {
  std::vector<DiskProbe> out;
  const FlatScene fs = Flatten(scene, width, height);
  if (!fs.refusal.empty()) return out;
  for (const FlatShape& s : fs.shapes) {
    if (s.kind != FlatKind::kDisk) continue;
    DiskProbe p;
    p.x0 = static_cast<int>(std::floor(s.a.x - s.r - 2.0));
    p.y0 = static_cast<int>(std::floor(s.a.y - s.r - 2.0));
    p.x1 = static_cast<int>(std::ceil(s.a.x + s.r + 2.0));
    p.y1 = static_cast<int>(std::ceil(s.a.y + s.r + 2.0));
    if (p.x0 < 0 || p.y0 < 0 || p.x1 > width || p.y1 > height) continue;
    bool isolated = true;
    for (const FlatShape& t : fs.shapes) {
      if (&t == &s || t.x1 <= p.x0 || t.x0 >= p.x1 || t.y1 <= p.y0 || t.y0 >= p.y1) continue;
      if (Curved(t) || t.zmin <= s.zmax) isolated = false;  // another outline, or something in front
    }
    if (!isolated) continue;
    const float* o = &ref.At(p.x0, p.y0, 0);
    for (int y = p.y0; y < p.y1 && isolated; ++y) {
      for (int x = p.x0; x < p.x1; ++x) {
        if (std::hypot(x + 0.5 - s.a.x, y + 0.5 - s.a.y) <= s.r + 1.5) continue;
        for (int c = 0; c < 3; ++c) isolated = isolated && ref.At(x, y, c) == o[c];
      }
    }
    if (!isolated) continue;
    p.radius_px = s.r;
    p.area_px = M_PI * s.r * s.r;
    const glm::vec3 col =
        scene.materials[static_cast<size_t>(scene.shapes[static_cast<size_t>(s.shape)].material)].color;
    p.inside = DisplayLinear(scene.display, {col.x, col.y, col.z});
    for (int c = 0; c < 3; ++c) p.outside[static_cast<size_t>(c)] = SrgbDecode(o[c]);
    out.push_back(p);
  }
  return out;
}

std::vector<double> ExactVisibleAreas(const Scene& scene, int width, int height) {
  const FlatScene fs = FlattenOrThrow(scene, width, height);
  // Per-row sums (rows run in parallel), merged in row order: deterministic.
  std::vector<std::vector<double>> rows(static_cast<size_t>(height), std::vector<double>(scene.shapes.size() + 1, 0.0));
  CoverFrame(fs, width, height, [&](int, int y, const std::vector<std::pair<int, double>>& cov) {
    double total = 0.0;
    for (const auto& [k, a] : cov) {
      rows[static_cast<size_t>(y)][static_cast<size_t>(fs.shapes[static_cast<size_t>(k)].shape)] += a;
      total += a;
    }
    rows[static_cast<size_t>(y)].back() += std::max(0.0, 1.0 - total);
  });
  std::vector<double> out(scene.shapes.size() + 1, 0.0);
  for (const auto& r : rows) {
    for (size_t i = 0; i < r.size(); ++i) out[i] += r[i];
  }
  return out;
}

}  // namespace aalab
