// The raster path's scene file: writer and reader of the format core/raster_geometry.h states.
#include "core/raster_geometry.h"

#include <cmath>
#include <cstring>

#include "core/error.h"

namespace aalab {

namespace {

constexpr char kMagic[8] = {'A', 'A', 'L', 'A', 'B', 'R', 'G', '2'};

class Writer {
 public:
  void U32(uint32_t v) { Raw(&v, 4); }
  void I32(int32_t v) { Raw(&v, 4); }
  void F32(float v) { Raw(&v, 4); }
  void F3(const std::array<float, 3>& v) {
    for (float f : v) F32(f);
  }
  void F2(const std::array<float, 2>& v) {
    for (float f : v) F32(f);
  }
  void Raw(const void* p, size_t n) {
    // The build targets are little-endian (x86-64, aarch64): the bytes are written as held.
    out_.append(static_cast<const char*>(p), n);
  }
  std::string Take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  Reader(const std::string& b, const std::string& origin) : b_(b), origin_(origin) {}
  void Need(size_t n, const char* what) {
    if (b_.size() - pos_ < n) {
      throw UserError("raster scene file '" + origin_ + "' ends at byte " + std::to_string(b_.size()) + " inside " +
                      what + " (truncated; write it again with aalab export-geometry)");
    }
  }
  uint32_t U32(const char* what) {
    Need(4, what);
    uint32_t v;
    std::memcpy(&v, b_.data() + pos_, 4);
    pos_ += 4;
    return v;
  }
  int32_t I32(const char* what) { return static_cast<int32_t>(U32(what)); }
  float F32(const char* what) {
    Need(4, what);
    float v;
    std::memcpy(&v, b_.data() + pos_, 4);
    pos_ += 4;
    if (!std::isfinite(v)) Fail(std::string(what) + " is not a finite number");
    return v;
  }
  std::array<float, 3> F3(const char* what) { return {F32(what), F32(what), F32(what)}; }
  std::array<float, 2> F2(const char* what) { return {F32(what), F32(what)}; }
  int Choice(const char* what, int lo, int hi) {
    const int32_t v = I32(what);
    if (v < lo || v > hi) {
      Fail(std::string(what) + " is " + std::to_string(v) + " (allowed: " + std::to_string(lo) + ".." +
           std::to_string(hi) + ")");
    }
    return v;
  }
  uint32_t Count(const char* what, size_t bytes_each) {
    const uint32_t n = U32(what);
    if (bytes_each > 0 && n > (b_.size() - pos_) / bytes_each) {
      Fail(std::string(what) + " is " + std::to_string(n) + ", more than the file's remaining " +
           std::to_string(b_.size() - pos_) + " bytes hold (truncated; write it again with aalab export-geometry)");
    }
    return n;
  }
  std::string Str(uint32_t n, const char* what) {
    Need(n, what);
    std::string s = b_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  [[noreturn]] void Fail(const std::string& msg) const {
    throw UserError("raster scene file '" + origin_ + "' at byte " + std::to_string(pos_) + ": " + msg);
  }
  size_t Pos() const { return pos_; }
  size_t Size() const { return b_.size(); }

 private:
  const std::string& b_;
  const std::string& origin_;
  size_t pos_ = 0;
};

}  // namespace

std::string RasterSceneBytes(const RasterScene& s) {
  Writer w;
  w.Raw(kMagic, 8);
  w.U32(static_cast<uint32_t>(s.name.size()));
  w.Raw(s.name.data(), s.name.size());
  w.I32(s.orthographic ? 1 : 0);
  w.F3(s.position);
  w.F3(s.look_at);
  w.F3(s.up);
  w.F32(s.fov_y_deg);
  w.F32(s.height);
  w.F32(s.exposure);
  w.I32(s.tonemap);
  w.F3(s.background);
  w.F3(s.ambient);
  w.I32(s.lambert ? 1 : 0);
  w.I32(s.shadows ? 1 : 0);
  w.U32(static_cast<uint32_t>(s.lights.size()));
  for (const auto& l : s.lights) {
    w.I32(l.type);
    w.F3(l.direction);
    w.F3(l.color);
    w.F32(l.intensity);
    w.F3(l.position);
    w.F32(l.range);
    w.F32(l.cos_inner);
    w.F32(l.cos_outer);
    w.I32(l.shadows ? 1 : 0);
  }
  w.U32(static_cast<uint32_t>(s.materials.size()));
  for (const auto& m : s.materials) {
    w.I32(m.lit ? 1 : 0);
    w.F3(m.color);
    const RasterTexture& t = m.texture;
    w.I32(t.pattern);
    w.F32(t.scale);
    w.F32(t.cos_angle);
    w.F32(t.sin_angle);
    w.F32(t.duty);
    w.U32(t.seed);
    w.F3(t.color_a);
    w.F3(t.color_b);
  }
  w.U32(static_cast<uint32_t>(s.triangles.size()));
  for (const auto& t : s.triangles) {
    w.I32(t.shape);
    w.I32(t.material);
    w.I32(t.smooth ? 1 : 0);
    w.I32(t.disk ? 1 : 0);
    w.F3(t.center);
    w.F32(t.radius);
    for (const auto& c : t.corners) {
      w.F3(c.position);
      w.F3(c.normal);
      w.F2(c.uv);
    }
  }
  return w.Take();
}

RasterScene ParseRasterScene(const std::string& bytes, const std::string& origin) {
  Reader r(bytes, origin);
  r.Need(8, "the magic");
  if (std::memcmp(bytes.data(), kMagic, 8) != 0) {
    throw UserError("'" + origin +
                    "' is not a raster scene file (it does not start with AALABRG2; write one with "
                    "aalab export-geometry)");
  }
  r.Str(8, "the magic");
  RasterScene s;
  s.name = r.Str(r.Count("the name length", 1), "the name");
  s.orthographic = r.Choice("the camera type", 0, 1) == 1;
  s.position = r.F3("the camera position");
  s.look_at = r.F3("the camera look_at");
  s.up = r.F3("the camera up");
  s.fov_y_deg = r.F32("the camera fov_y");
  s.height = r.F32("the camera height");
  s.exposure = r.F32("the exposure");
  s.tonemap = r.Choice("the tonemap", 0, 2);
  s.background = r.F3("the background");
  s.ambient = r.F3("the ambient");
  s.lambert = r.Choice("the lambert flag", 0, 1) == 1;
  s.shadows = r.Choice("the shadows flag", 0, 1) == 1;
  s.lights.resize(r.Count("the light count", 60));
  for (auto& l : s.lights) {
    l.type = r.Choice("a light type", 0, 2);
    l.direction = r.F3("a light direction");
    l.color = r.F3("a light colour");
    l.intensity = r.F32("a light intensity");
    l.position = r.F3("a light position");
    l.range = r.F32("a light range");
    l.cos_inner = r.F32("a light's cos_inner");
    l.cos_outer = r.F32("a light's cos_outer");
    l.shadows = r.Choice("a light's shadows flag", 0, 1) == 1;
  }
  s.materials.resize(r.Count("the material count", 64));
  for (auto& m : s.materials) {
    m.lit = r.Choice("a material's lit flag", 0, 1) == 1;
    m.color = r.F3("a material colour");
    RasterTexture& t = m.texture;
    t.pattern = r.Choice("a material's texture pattern", -1, 2);
    t.scale = r.F32("a texture scale");
    t.cos_angle = r.F32("a texture's stripe cosine");
    t.sin_angle = r.F32("a texture's stripe sine");
    t.duty = r.F32("a texture's stripe duty");
    t.seed = r.U32("a texture seed");
    t.color_a = r.F3("a texture's color_a");
    t.color_b = r.F3("a texture's color_b");
  }
  s.triangles.resize(r.Count("the triangle count", 128));
  const int n_mat = static_cast<int>(s.materials.size());
  for (auto& t : s.triangles) {
    t.shape = r.Choice("a triangle's shape", 0, 0x7fffffff);
    t.material = r.Choice("a triangle's material", 0, n_mat - 1);
    t.smooth = r.Choice("a triangle's smooth flag", 0, 1) == 1;
    t.disk = r.Choice("a triangle's disk flag", 0, 1) == 1;
    t.center = r.F3("a disk centre");
    t.radius = r.F32("a disk radius");
    for (auto& c : t.corners) {
      c.position = r.F3("a corner position");
      c.normal = r.F3("a corner normal");
      c.uv = r.F2("a corner uv");
    }
  }
  if (r.Pos() != r.Size())
    r.Fail("the file goes on past its last triangle (" + std::to_string(r.Size() - r.Pos()) + " bytes)");
  return s;
}

}  // namespace aalab
