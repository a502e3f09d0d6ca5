// Scene content fingerprint (scenes/scene_hash.h): a visitor over every field in declaration
// order. A field added to a scene struct must be added here too (scene_hash_test checks that
// each existing field changes the hash).
#include "scenes/scene_hash.h"

#include <cstring>
#include <string>
#include <type_traits>

#include "core/hash.h"
#include "scenes/ibl.h"

namespace aalab {

namespace {

class Hasher {
 public:
  void Bytes(const void* data, size_t size) { h_ = Fnv1a64(data, size, h_); }
  template <typename T>
  void Pod(const T& v) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    Bytes(&v, sizeof v);
  }
  void F(float v) { Pod(v); }
  void D(double v) { Pod(v); }
  void I(int64_t v) { Pod(v); }
  void B(bool v) { I(v ? 1 : 0); }
  void S(const std::string& s) {
    I(static_cast<int64_t>(s.size()));  // length first: ("ab","c") differs from ("a","bc")
    Bytes(s.data(), s.size());
  }
  void V2(const glm::vec2& v) { F(v.x), F(v.y); }
  void V3(const glm::vec3& v) { F(v.x), F(v.y), F(v.z); }
  uint64_t Value() const { return h_; }

 private:
  uint64_t h_ = kFnv1aOffset;
};

void HashTexture(Hasher& h, const std::optional<Texture>& t) {
  h.B(t.has_value());
  if (!t) return;
  h.I(static_cast<int64_t>(t->pattern));
  h.F(t->scale);
  h.F(t->angle_deg);
  h.F(t->duty);
  h.I(t->seed);
  h.V3(t->color_a);
  h.V3(t->color_b);
}

}  // namespace

uint64_t SceneContentHash(const Scene& s) {
  Hasher h;
  h.S("aalab-scene-v1");
  h.S(s.name);
  h.I(kEffectCount);
  for (bool e : s.effects) h.B(e);
  h.I(static_cast<int64_t>(s.camera.type));
  h.V3(s.camera.position);
  h.V3(s.camera.look_at);
  h.V3(s.camera.up);
  h.F(s.camera.fov_y_deg);
  h.F(s.camera.height);
  h.F(s.display.exposure);
  h.I(static_cast<int64_t>(s.display.tonemap));
  h.V3(s.background);
  h.V3(s.ambient);
  h.I(static_cast<int64_t>(s.materials.size()));
  for (const Material& m : s.materials) {
    h.S(m.name);
    h.I(static_cast<int64_t>(m.shading));
    h.V3(m.color);
    HashTexture(h, m.texture);
    h.V3(m.specular);
    h.F(m.shininess);
    HashTexture(h, m.alpha);
    h.F(m.alpha_cutoff);
  }
  h.I(static_cast<int64_t>(s.lights.size()));
  for (const Light& l : s.lights) {
    h.I(static_cast<int64_t>(l.type));
    h.V3(l.direction);
    h.V3(l.position);
    h.V3(l.color);
    h.F(l.intensity);
    h.B(l.shadows);
  }
  h.I(static_cast<int64_t>(s.shapes.size()));
  for (const Shape& sh : s.shapes) {
    h.I(static_cast<int64_t>(sh.kind));
    h.S(sh.source);
    h.I(sh.material);
    h.I(static_cast<int64_t>(sh.positions.size()));
    for (const auto& p : sh.positions) h.V3(p);
    h.I(static_cast<int64_t>(sh.normals.size()));
    for (const auto& n : sh.normals) h.V3(n);
    h.I(static_cast<int64_t>(sh.uvs.size()));
    for (const auto& uv : sh.uvs) h.V2(uv);
    h.I(static_cast<int64_t>(sh.triangles.size()));
    for (const auto& t : sh.triangles) h.I(t.x), h.I(t.y), h.I(t.z);
    h.V3(sh.center);
    h.F(sh.radius);
    h.V3(sh.normal);
    h.V3(sh.tangent);
    h.V3(sh.p0);
    h.V3(sh.p1);
    h.I(sh.motion);
  }
  // glTF content (absent from every other scene, whose fingerprint this leaves unchanged).
  for (const Material& m : s.materials) {
    if (!m.gltf) continue;
    const GltfMaterial& g = *m.gltf;
    h.S("gltf-material");
    for (int c = 0; c < 4; ++c) h.F(g.base_factor[c]);
    h.F(g.metallic), h.F(g.roughness), h.F(g.normal_scale), h.F(g.occlusion_strength);
    h.V3(g.emissive);
    h.I(static_cast<int64_t>(g.alpha_mode));
    for (const TextureRef* t : {&g.base_tex, &g.mr_tex, &g.normal_tex, &g.emissive_tex, &g.occlusion_tex}) {
      h.I(t->image), h.I(static_cast<int64_t>(t->wrap_s)), h.I(static_cast<int64_t>(t->wrap_t));
      // Sampler filters, coordinate set and transform: only where they differ from the
      // defaults, so fingerprints of files without them stay as they were.
      if (!(t->filter == SamplerFilter{}) || t->texcoord != 0 || t->transformed) {
        h.S("texref");
        h.I(t->filter.mag_nearest), h.I(t->filter.min_nearest), h.I(static_cast<int64_t>(t->filter.mip)),
            h.I(t->texcoord);
        for (int c = 0; c < 3; ++c) h.V2(t->uv_transform[c]);
      }
    }
    if (g.alpha_mode == AlphaMode::kBlend) h.S("blend");
  }
  for (const auto& img : s.images) {
    h.S("image");
    const MipLevel& l0 = img->levels[0];
    h.I(l0.width), h.I(l0.height);
    for (size_t i = 0; i < static_cast<size_t>(l0.width) * l0.height; ++i) {
      const glm::vec4 t = l0.Fetch(i);
      h.V3(glm::vec3(t)), h.F(t.w);
    }
  }
  for (const Shape& sh : s.shapes) {
    if (sh.uvs1.empty()) continue;
    h.S("uvs1");
    for (const auto& uv : sh.uvs1) h.V2(uv);
  }
  for (const Shape& sh : s.shapes) {
    if (sh.tangents.empty()) continue;
    h.S("tangents");
    for (const glm::vec4& t : sh.tangents) h.V3(glm::vec3(t)), h.F(t.w);
  }
  // Spot lights, ranges and the environment (absent from scenes written before them, whose
  // fingerprint this leaves unchanged).
  for (const Light& l : s.lights) {
    if (l.type != LightType::kSpot && l.range == 0.0f) continue;
    h.S("light-cone-range");
    h.F(l.cos_inner), h.F(l.cos_outer), h.F(l.range);
  }
  if (s.environment) {
    const Environment& e = *s.environment;
    h.S("environment");
    h.S(e.name);
    h.F(e.intensity), h.F(e.rotation_deg);
    const EquirectMap& m = e.specular[0];
    h.I(m.width), h.I(m.height);
    for (const glm::vec3& t : m.texels) h.V3(t);
  }
  const Animation& a = s.animation;
  h.I(a.frames);
  h.I(static_cast<int64_t>(a.camera.size()));
  for (const CameraKey& k : a.camera) {
    h.D(k.frame);
    h.V3(k.offset);
    h.F(k.roll_deg);
    h.F(k.zoom);
  }
  h.I(static_cast<int64_t>(a.objects.size()));
  for (const ObjectMotion& o : a.objects) {
    h.V3(o.pivot);
    h.I(static_cast<int64_t>(o.keys.size()));
    for (const MotionKey& k : o.keys) {
      h.D(k.frame);
      h.V3(k.translate);
      h.V3(k.rotate_deg);
      h.F(k.scale);
    }
  }
  return h.Value();
}

}  // namespace aalab
