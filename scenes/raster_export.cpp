// Scene → RasterScene (scenes/raster_export.h): what the raster tool needs, and the one list
// of what it cannot draw yet.
#include "scenes/raster_export.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace aalab {

namespace {

std::array<float, 3> A3(glm::vec3 v) { return {v.x, v.y, v.z}; }

const char* ShapeKindName(ShapeKind k) {
  switch (k) {
    case ShapeKind::kTriangles: return "triangles";
    case ShapeKind::kSphere: return "sphere";
    case ShapeKind::kDisk: return "disk";
    case ShapeKind::kCapsule: return "capsule";
    case ShapeKind::kCylinder: return "cylinder";
  }
  return "?";
}

/// The pattern's parameters; stripes carry the cosine and sine of their angle as
/// EvaluatePattern (scenes/tracer.cpp) computes them, so the GPU needs no trigonometry.
RasterTexture RasterTextureOf(const Texture& t) {
  RasterTexture r;
  r.pattern = static_cast<int32_t>(t.pattern);
  r.scale = t.scale;
  const float ang = glm::radians(t.angle_deg);
  r.cos_angle = std::cos(ang);
  r.sin_angle = std::sin(ang);
  r.duty = t.duty;
  r.seed = t.seed;
  r.color_a = A3(t.color_a);
  r.color_b = A3(t.color_b);
  return r;
}

/// A disk as the two triangles of its bounding square in its own plane, 1/16 larger than
/// the disk (so that vertex snapping cannot cut a covered sample off), each corner with
/// the disk's normal and the uv the tracer gives a disk's points (d·tangent, d·bitangent).
void AddDiskImpostor(const Shape& s, int32_t index, std::vector<RasterTriangle>& out) {
  const glm::vec3 b = glm::cross(s.normal, s.tangent);
  const float e = s.radius * 1.0625f;
  const float su[4] = {-e, e, e, -e}, sv[4] = {-e, -e, e, e};
  RasterCorner c[4];
  for (int k = 0; k < 4; ++k) {
    c[k].position = A3(s.center + s.tangent * su[k] + b * sv[k]);
    c[k].normal = A3(s.normal);
    c[k].uv = {su[k], sv[k]};
  }
  for (const auto& idx : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
    RasterTriangle t;
    t.shape = index;
    t.material = s.material;
    t.disk = true;
    t.center = A3(s.center);
    t.radius = s.radius;
    for (int k = 0; k < 3; ++k) t.corners[k] = c[idx[k]];
    out.push_back(t);
  }
}

bool AllGltf(const Scene& sc) {
  if (sc.materials.empty()) return false;
  for (const auto& m : sc.materials)
    if (!m.gltf) return false;
  return true;
}

/// Why a glTF material cannot be drawn yet ("" when it can): the raster path shades what the
/// default suite's glTF scenes use (glTF 2.0 metallic-roughness with base colour,
/// metallic-roughness and normal textures, OPAQUE or MASK, single- or double-sided).
std::string GltfUnsupported(const Scene& sc, const Material& m) {
  const GltfMaterial& g = *m.gltf;
  const std::string who = "glTF material '" + m.name + "' ";
  if (g.alpha_mode == AlphaMode::kBlend) return who + "is alphaMode BLEND";
  if (g.emissive != glm::vec3(0.0f) || g.emissive_tex.Has()) return who + "is emissive";
  if (g.occlusion_tex.Has()) return who + "has an occlusion texture";
  if (m.alpha) return who + "has a procedural alpha";
  for (const TextureRef* t : {&g.base_tex, &g.mr_tex, &g.normal_tex}) {
    if (!t->Has()) continue;
    if (t->texcoord != 0) return who + "reads TEXCOORD_1";
    if (t->transformed) return who + "uses KHR_texture_transform";
    if (!(t->filter == SamplerFilter{})) return who + "has a sampler other than LINEAR / LINEAR_MIPMAP_LINEAR";
    const TexelFormat f = sc.images[static_cast<size_t>(t->image)]->levels[0].format;
    if (f != TexelFormat::kSrgb8 && f != TexelFormat::kUnorm8) return who + "has a texture that is not 8-bit";
  }
  return "";
}

/// The image's mip chain as the file holds it (8-bit levels, as aalab stores them).
RasterImage RasterImageOf(const MipChain& c) {
  RasterImage r;
  r.format = c.levels[0].format == TexelFormat::kSrgb8 ? 0 : 1;
  for (const MipLevel& l : c.levels) r.levels.push_back({l.width, l.height, l.bytes});
  return r;
}

}  // namespace

std::string RasterUnsupported(const Scene& sc) {
  // A scene of glTF materials only may declare specular, alpha_test and normal_map: its
  // shading is ShadeGltf's, which the raster path draws (docs/gpu.md "The default suite's
  // glTF scenes").
  const bool gltf = AllGltf(sc);
  for (Effect e : {Effect::kSpecular, Effect::kAlphaTest, Effect::kAlphaBlend, Effect::kNormalMap}) {
    if (gltf && e != Effect::kAlphaBlend) continue;
    if (sc.Has(e)) return std::string("it declares the effect '") + EffectName(e) + "'";
  }
  if (sc.environment) return "it has an environment (image-based lighting)";
  if (sc.animation.Moves()) return "it moves (animation)";
  for (const auto& s : sc.shapes) {
    if (s.kind != ShapeKind::kTriangles && s.kind != ShapeKind::kDisk) {
      return "it has an analytic shape ('" + s.source + "': " + ShapeKindName(s.kind) + ")";
    }
  }
  for (const auto& m : sc.materials) {
    if (m.gltf) {
      if (!gltf) return "it mixes glTF and scene-file materials ('" + m.name + "')";
      if (std::string why = GltfUnsupported(sc, m); !why.empty()) return why;
      continue;
    }
    if (m.shading == Shading::kPbr) return "material '" + m.name + "' uses PBR shading";
  }
  if (gltf && sc.Has(Effect::kNormalMap)) {
    for (const auto& s : sc.shapes) {
      const Material& m = sc.materials[static_cast<size_t>(s.material)];
      if (m.gltf->normal_tex.Has() && s.tangents.empty()) {
        return "glTF mesh '" + s.source + "' is normal-mapped without a TANGENT attribute";
      }
    }
  }
  return "";
}

RasterScene RasterSceneOf(const Scene& sc) {
  if (const std::string why = RasterUnsupported(sc); !why.empty()) {
    throw UserError("the raster path cannot draw scene '" + sc.name + "' yet: " + why +
                    " (it draws still triangle scenes, unlit or lambert, solid colours or procedural "
                    "textures, disks, lights and shadows, and glTF metallic-roughness materials with base colour, "
                    "metallic-roughness and normal textures, OPAQUE or MASK; of the synthetic suite: wedges, mesh, "
                    "checker-plane, detail-texture, circle, hdr-edges, sdf-circles, shadow-stipple; of the default "
                    "suite: all four)");
  }
  RasterScene r;
  r.name = sc.name;
  r.orthographic = sc.camera.type == CameraType::kOrthographic;
  r.position = A3(sc.camera.position);
  r.look_at = A3(sc.camera.look_at);
  r.up = A3(sc.camera.up);
  r.fov_y_deg = sc.camera.fov_y_deg;
  r.height = sc.camera.height;
  r.exposure = sc.display.exposure;
  r.tonemap = static_cast<int>(sc.display.tonemap);
  r.background = A3(sc.background);
  r.ambient = A3(sc.ambient);
  r.lambert = sc.Has(Effect::kLambert);
  r.shadows = sc.Has(Effect::kShadows);
  r.textures = sc.Has(Effect::kTextures);
  r.normal_map = sc.Has(Effect::kNormalMap);
  r.alpha_test = sc.Has(Effect::kAlphaTest);
  for (int k = 0; k < 256; ++k) {
    r.srgb_table[static_cast<size_t>(k)] = Srgb8Table()[k];
    r.unorm_table[static_cast<size_t>(k)] = Unorm8Table()[k];
  }
  for (const auto& l : sc.lights) {
    r.lights.push_back({static_cast<int32_t>(l.type), A3(l.direction), A3(l.color), l.intensity, A3(l.position),
                        l.range, l.cos_inner, l.cos_outer, l.shadows});
  }
  const bool textures = sc.Has(Effect::kTextures);
  std::vector<int> used;  // Scene::images indices, in the file's order
  for (const auto& m : sc.materials) {
    RasterMaterial rm;
    rm.lit = m.shading == Shading::kLambert;
    rm.color = A3(m.color);
    // The tracer reads a material's texture only when the scene declares `textures`.
    if (textures && m.texture) rm.texture = RasterTextureOf(*m.texture);
    if (m.gltf) {
      const GltfMaterial& g = *m.gltf;
      rm.gltf = true;
      RasterGltf& p = rm.pbr;
      p.unlit = m.shading == Shading::kUnlit;
      p.base_factor = {g.base_factor.x, g.base_factor.y, g.base_factor.z, g.base_factor.w};
      p.metallic = g.metallic;
      p.roughness = g.roughness;
      p.normal_scale = g.normal_scale;
      p.alpha_cutoff = m.alpha_cutoff;
      p.alpha_mode = g.alpha_mode == AlphaMode::kMask ? 1 : 0;
      p.double_sided = g.double_sided;
      // Images are numbered in the order the materials first use them (only those used).
      auto ref = [&](const TextureRef& t) {
        RasterTextureRef out;
        if (!t.Has()) return out;
        const auto it = std::find(used.begin(), used.end(), t.image);
        out.image = static_cast<int32_t>(it - used.begin());
        if (it == used.end()) {
          used.push_back(t.image);
          r.images.push_back(RasterImageOf(*sc.images[static_cast<size_t>(t.image)]));
        }
        out.wrap_s = static_cast<int32_t>(t.wrap_s);
        out.wrap_t = static_cast<int32_t>(t.wrap_t);
        return out;
      };
      p.base = ref(g.base_tex);
      p.mr = ref(g.mr_tex);
      p.normal = ref(g.normal_tex);
    }
    r.materials.push_back(rm);
  }
  for (size_t si = 0; si < sc.shapes.size(); ++si) {
    const Shape& s = sc.shapes[si];
    if (s.kind == ShapeKind::kDisk) {
      AddDiskImpostor(s, static_cast<int32_t>(si), r.triangles);
      continue;
    }
    const bool smooth = !s.normals.empty();
    for (const glm::uvec3& t : s.triangles) {
      RasterTriangle tri;
      tri.shape = static_cast<int32_t>(si);
      tri.material = s.material;
      tri.smooth = smooth;
      const glm::vec3 p[3] = {s.positions[t.x], s.positions[t.y], s.positions[t.z]};
      const glm::vec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
      const unsigned idx[3] = {t.x, t.y, t.z};
      for (int k = 0; k < 3; ++k) {
        tri.corners[k].position = A3(p[k]);
        tri.corners[k].normal = A3(smooth ? s.normals[idx[k]] : face);
        if (idx[k] < s.uvs.size()) tri.corners[k].uv = {s.uvs[idx[k]].x, s.uvs[idx[k]].y};
        if (idx[k] < s.tangents.size()) {
          const glm::vec4 tg = s.tangents[idx[k]];
          tri.corners[k].tangent = {tg.x, tg.y, tg.z, tg.w};
        }
      }
      r.triangles.push_back(tri);
    }
  }
  return r;
}

}  // namespace aalab
