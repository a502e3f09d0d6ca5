// The raster path's scene file: writer and reader of the format core/raster_geometry.h states.
#include "core/raster_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"

namespace aalab {

namespace {

constexpr char kMagic[8] = {'A', 'A', 'L', 'A', 'B', 'R', 'G', '3'};
constexpr int kVersion = 3;
constexpr int kOldestVersion = 2;
/// Largest image edge the file holds (scenes/texture_image.h kMaxTextureSize).
constexpr uint32_t kMaxImageEdge = 16384;

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
  void F4(const std::array<float, 4>& v) {
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
  std::array<float, 4> F4(const char* what) { return {F32(what), F32(what), F32(what), F32(what)}; }
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
  w.I32((s.textures ? 1 : 0) | (s.normal_map ? 2 : 0) | (s.alpha_test ? 4 : 0));
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
    w.I32(m.gltf ? 1 : 0);
    if (!m.gltf) continue;
    const RasterGltf& g = m.pbr;
    w.I32(g.unlit ? 1 : 0);
    w.F4(g.base_factor);
    w.F32(g.metallic);
    w.F32(g.roughness);
    w.F32(g.normal_scale);
    w.F32(g.alpha_cutoff);
    w.I32(g.alpha_mode);
    w.I32(g.double_sided ? 1 : 0);
    for (const RasterTextureRef* r : {&g.base, &g.mr, &g.normal}) {
      w.I32(r->image);
      w.I32(r->wrap_s);
      w.I32(r->wrap_t);
    }
  }
  for (float f : s.srgb_table) w.F32(f);
  for (float f : s.unorm_table) w.F32(f);
  w.U32(static_cast<uint32_t>(s.images.size()));
  for (const auto& im : s.images) {
    w.I32(im.format);
    w.U32(static_cast<uint32_t>(im.levels.size()));
    for (const auto& l : im.levels) {
      w.U32(static_cast<uint32_t>(l.width));
      w.U32(static_cast<uint32_t>(l.height));
      w.Raw(l.rgba.data(), l.rgba.size());
    }
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
      w.F4(c.tangent);
    }
  }
  return w.Take();
}

RasterScene ParseRasterScene(const std::string& bytes, const std::string& origin) {
  Reader r(bytes, origin);
  r.Need(8, "the magic");
  if (std::memcmp(bytes.data(), kMagic, 7) != 0) {
    throw UserError("'" + origin +
                    "' is not a raster scene file (it does not start with AALABRG; write one with "
                    "aalab export-geometry)");
  }
  const int version = bytes[7] - '0';
  if (version < kOldestVersion || version > kVersion) {
    throw UserError("raster scene file '" + origin + "' is version '" + std::string(1, bytes[7]) + "' (AALABRG" +
                    std::string(1, bytes[7]) + "); this build reads versions " + std::to_string(kOldestVersion) + ".." +
                    std::to_string(kVersion) + " (write it again with this build's aalab export-geometry)");
  }
  const bool v3 = version >= 3;
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
  if (v3) {
    const int f = r.Choice("the glTF effect flags", 0, 7);
    s.textures = (f & 1) != 0;
    s.normal_map = (f & 2) != 0;
    s.alpha_test = (f & 4) != 0;
  }
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
    if (v3) m.gltf = r.Choice("a material's glTF flag", 0, 1) == 1;
    if (!m.gltf) continue;
    RasterGltf& g = m.pbr;
    g.unlit = r.Choice("a glTF material's unlit flag", 0, 1) == 1;
    g.base_factor = r.F4("a glTF baseColorFactor");
    g.metallic = r.F32("a glTF metallicFactor");
    g.roughness = r.F32("a glTF roughnessFactor");
    g.normal_scale = r.F32("a glTF normal scale");
    g.alpha_cutoff = r.F32("a glTF alphaCutoff");
    g.alpha_mode = r.Choice("a glTF alpha mode (0 OPAQUE, 1 MASK)", 0, 1);
    g.double_sided = r.Choice("a glTF doubleSided flag", 0, 1) == 1;
    for (RasterTextureRef* t : {&g.base, &g.mr, &g.normal}) {
      t->image = r.Choice("a glTF texture's image", -1, 0x7fffffff);
      t->wrap_s = r.Choice("a glTF texture's wrap_s", 0, 2);
      t->wrap_t = r.Choice("a glTF texture's wrap_t", 0, 2);
    }
  }
  if (v3) {
    for (float& f : s.srgb_table) f = r.F32("the sRGB decode table");
    for (float& f : s.unorm_table) f = r.F32("the unorm decode table");
    s.images.resize(r.Count("the image count", 8));
    for (auto& im : s.images) {
      im.format = r.Choice("an image format (0 sRGB, 1 linear)", 0, 1);
      im.levels.resize(r.Choice("an image's level count", 1, 15));
      for (size_t k = 0; k < im.levels.size(); ++k) {
        RasterMipLevel& l = im.levels[k];
        l.width = r.Choice("a mip level's width", 1, static_cast<int>(kMaxImageEdge));
        l.height = r.Choice("a mip level's height", 1, static_cast<int>(kMaxImageEdge));
        // Each level is the one above halved, rounded down, at least 1 (BuildMipChain).
        if (k > 0 && (l.width != std::max(1, im.levels[k - 1].width / 2) ||
                      l.height != std::max(1, im.levels[k - 1].height / 2))) {
          r.Fail("mip level " + std::to_string(k) + " is " + std::to_string(l.width) + "x" + std::to_string(l.height) +
                 ", not half of the level above (rounded down, at least 1)");
        }
        const size_t n = static_cast<size_t>(l.width) * static_cast<size_t>(l.height) * 4;
        const std::string px = r.Str(static_cast<uint32_t>(n), "a mip level's texels");
        l.rgba.assign(px.begin(), px.end());
      }
    }
  }
  const int n_img = static_cast<int>(s.images.size());
  for (const auto& m : s.materials) {
    for (const RasterTextureRef* t : {&m.pbr.base, &m.pbr.mr, &m.pbr.normal}) {
      if (t->image >= n_img) {
        r.Fail("a glTF texture names image " + std::to_string(t->image) + " of " + std::to_string(n_img));
      }
    }
  }
  s.triangles.resize(r.Count("the triangle count", v3 ? 144 : 128));
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
      if (v3) c.tangent = r.F4("a corner tangent");
    }
  }
  if (r.Pos() != r.Size())
    r.Fail("the file goes on past its last triangle (" + std::to_string(r.Size() - r.Pos()) + " bytes)");
  return s;
}

}  // namespace aalab
