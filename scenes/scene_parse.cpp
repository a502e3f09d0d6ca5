// Scene files: JSON → Scene, with validation. Every field is documented in scenes/README.md.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <filesystem>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/input_files.h"
#include "core/params.h"
#include "scenes/gltf_load.h"
#include "scenes/lighting_parse.h"
#include "scenes/json_fields.h"
#include "scenes/motion_parse.h"
#include "scenes/scene.h"
#include "scenes/shapes.h"

namespace aalab {
namespace fs = std::filesystem;

const char* EffectName(Effect e) {
  switch (e) {
    case Effect::kUnlit: return "unlit";
    case Effect::kLambert: return "lambert";
    case Effect::kShadows: return "shadows";
    case Effect::kSpecular: return "specular";
    case Effect::kTextures: return "textures";
    case Effect::kAlphaTest: return "alpha_test";
    case Effect::kAlphaBlend: return "alpha_blend";
    case Effect::kNormalMap: return "normal_map";
  }
  return "?";
}

CameraBasis CameraBasisOf(const Camera& cam) {
  CameraBasis b;
  b.forward = glm::normalize(cam.look_at - cam.position);
  b.right = glm::normalize(glm::cross(b.forward, cam.up));
  b.up = glm::cross(b.right, b.forward);
  return b;
}

std::vector<std::string> Scene::EffectNames() const {
  std::vector<std::string> out;
  for (int i = 0; i < kEffectCount; ++i) {
    if (effects[i]) out.push_back(EffectName(static_cast<Effect>(i)));
  }
  return out;
}

namespace {

constexpr double kMaxCoord = 1e8;  // beyond this float32 positions lose all sub-unit precision

Texture ParseTexture(const JsonField& f) {
  f.RequireObject({"pattern", "scale", "angle", "duty", "seed", "color_a", "color_b"});
  Texture t;
  const std::string p = f.Child("pattern").Choice({"checker", "stripes", "noise"});
  t.pattern = p == "checker"   ? TexturePattern::kChecker
              : p == "stripes" ? TexturePattern::kStripes
                               : TexturePattern::kNoise;
  t.scale = static_cast<float>(f.NumberOr("scale", 1.0, 0.0, 1e6, true));
  t.angle_deg = static_cast<float>(f.NumberOr("angle", 0.0, -360.0, 360.0));
  t.duty = static_cast<float>(f.NumberOr("duty", 0.5, 0.0, 1.0));
  t.seed = f.Has("seed") ? static_cast<uint32_t>(f.Child("seed").Integer(0, 1 << 30)) : 0u;
  t.color_a = f.Vec3Or("color_a", glm::vec3(0.0f), 0.0, 1e7);
  t.color_b = f.Vec3Or("color_b", glm::vec3(1.0f), 0.0, 1e7);
  return t;
}

Material ParseMaterial(const JsonField& f, const std::string& name) {
  f.RequireObject({"shading", "color", "texture", "specular", "shininess", "alpha", "alpha_cutoff"});
  Material m;
  m.name = name;
  m.shading = f.Child("shading").Choice({"unlit", "lambert"}) == "unlit" ? Shading::kUnlit : Shading::kLambert;
  m.color = f.Vec3Or("color", glm::vec3(1.0f), 0.0, 1e7);
  if (f.Has("texture")) m.texture = ParseTexture(f.Child("texture"));
  if (f.Has("specular")) {
    m.specular = f.Child("specular").Vec3(0.0, 1e7);
    m.shininess = static_cast<float>(f.Child("shininess").Number(1.0, 1e6));
    if (m.shading != Shading::kLambert)
      f.Child("specular").Fail("specular needs shading 'lambert' (it is lit by the scene's lights)");
  } else if (f.Has("shininess")) {
    f.Child("shininess").Fail("shininess without 'specular'");
  }
  if (f.Has("alpha")) m.alpha = ParseTexture(f.Child("alpha"));
  m.alpha_cutoff = static_cast<float>(f.NumberOr("alpha_cutoff", 0.5, 0.0, 1.0));
  if (f.Has("alpha_cutoff") && !m.alpha) f.Child("alpha_cutoff").Fail("alpha_cutoff without 'alpha'");
  return m;
}

Light ParseLight(const JsonField& f, LightUnits units) {
  f.RequireObject(
      {"type", "direction", "position", "color", "intensity", "shadows", "inner_cone_deg", "outer_cone_deg", "range"});
  Light l;
  const std::string type = f.Child("type").Choice({"directional", "point", "spot"});
  if (type == "directional" || type == "spot") {
    l.type = type == "directional" ? LightType::kDirectional : LightType::kSpot;
    // Normalised in double: in float the squared length of (1e30, 1e30, 1e30) overflows and
    // normalize() silently returns the zero vector.
    const glm::dvec3 d(f.Child("direction").Vec3());
    const double len = glm::length(d);
    if (!(len > 0.0)) f.Child("direction").Fail("direction must not be zero");
    l.direction = glm::vec3(d / len);
    if (glm::length(l.direction) < 0.5f) f.Child("direction").Fail("direction is too small to normalise");
  }
  if (type == "directional") {
    if (f.Has("position")) f.Child("position").Fail("a directional light has no position");
    if (f.Has("range")) f.Child("range").Fail("a directional light has no range");
  } else {
    if (type == "point") l.type = LightType::kPoint;
    l.position = f.Child("position").Vec3(-kMaxCoord, kMaxCoord);
    if (type == "point" && f.Has("direction")) f.Child("direction").Fail("a point light has no direction");
    if (f.Has("range")) l.range = static_cast<float>(f.Child("range").Number(0.0, 1e12, true));
  }
  if (type == "spot") {
    const double inner = f.NumberOr("inner_cone_deg", 0.0, 0.0, 90.0);
    const double outer = f.NumberOr("outer_cone_deg", 45.0, 0.0, 90.0, true);
    if (!(inner < outer))
      f.Fail("a spot light needs inner_cone_deg < outer_cone_deg (KHR_lights_punctual: 0 <= inner < outer <= 90)");
    l.cos_inner = static_cast<float>(std::cos(inner * 3.14159265358979323846 / 180.0));
    l.cos_outer = static_cast<float>(std::cos(outer * 3.14159265358979323846 / 180.0));
  } else {
    for (const char* k : {"inner_cone_deg", "outer_cone_deg"}) {
      if (f.Has(k)) f.Child(k).Fail("only a spot light has cone angles");
    }
  }
  l.color = f.Vec3Or("color", glm::vec3(1.0f), 0.0, 1e7);
  l.intensity = InternalIntensity(f.NumberOr("intensity", 1.0, 0.0, 1e12), units);
  l.shadows = f.BoolOr("shadows", false);
  return l;
}

Camera ParseCamera(const JsonField& f) {
  f.RequireObject({"type", "position", "look_at", "up", "fov_y", "height"});
  Camera c;
  const std::string type = f.Child("type").Choice({"perspective", "orthographic"});
  c.type = type == "perspective" ? CameraType::kPerspective : CameraType::kOrthographic;
  c.position = f.Child("position").Vec3(-kMaxCoord, kMaxCoord);
  c.look_at = f.Child("look_at").Vec3(-kMaxCoord, kMaxCoord);
  c.up = f.Vec3Or("up", glm::vec3(0, 1, 0));
  // In double: with float, cross products of large vectors overflow (up = [1e30, 0, 0] was
  // reported as "parallel") and tiny ones underflow.
  const glm::dvec3 fwd = glm::dvec3(c.look_at) - glm::dvec3(c.position);
  const glm::dvec3 up(c.up);
  if (glm::length(fwd) == 0.0) f.Child("look_at").Fail("look_at equals position");
  if (!(glm::length(glm::cross(fwd / glm::length(fwd), up)) > 1e-6 * glm::length(up))) {
    f.Has("up") ? f.Child("up").Fail("up is zero or parallel to the view direction")
                : f.Fail("the default up (0,1,0) is parallel to the view direction; give 'up'");
  }
  c.up = glm::vec3(glm::normalize(up));  // only its direction matters
  if (c.type == CameraType::kPerspective) {
    c.fov_y_deg = static_cast<float>(f.Child("fov_y").Number(0.0, 179.0, true));
    if (f.Has("height")) f.Child("height").Fail("'height' is for orthographic cameras (perspective uses fov_y)");
  } else {
    c.height = static_cast<float>(f.Child("height").Number(0.0, 1e9, true));
    if (f.Has("fov_y")) f.Child("fov_y").Fail("'fov_y' is for perspective cameras (orthographic uses height)");
  }
  return c;
}

glm::mat4 ParseTransform(const JsonField& f) {
  f.RequireObject({"translate", "rotate", "scale"});
  const glm::vec3 t = f.Vec3Or("translate", glm::vec3(0.0f), -kMaxCoord, kMaxCoord);
  const glm::vec3 r = f.Vec3Or("rotate", glm::vec3(0.0f), -3600.0, 3600.0);
  glm::vec3 s(1.0f);
  if (f.Has("scale")) {
    const JsonField sf = f.Child("scale");
    if (sf.Value().is_number()) {
      s = glm::vec3(static_cast<float>(sf.Number(0.0, 1e9, true)));
    } else {
      s = sf.Vec3(0.0, 1e9);
      if (s.x <= 0 || s.y <= 0 || s.z <= 0) sf.Fail("scale components must be > 0");
    }
  }
  return MakeTransform(t, r, s);
}

Shape ParseShape(const JsonField& f, const std::string& base_dir) {
  const std::string kind = f.Child("shape").Choice(
      {"quad", "plane", "polygon", "box", "disk", "sphere", "capsule", "cylinder", "mesh", "triangles"});
  const std::set<std::string> common = {"shape", "material", "transform", "name", "motion"};
  auto allow = [&](std::set<std::string> extra) {
    extra.insert(common.begin(), common.end());
    f.RequireObject(extra);
  };
  if (kind == "quad" || kind == "plane") {
    allow({"size"});
    const glm::vec2 size = f.Child("size").Vec2(0.0, 1e9);
    if (size.x <= 0 || size.y <= 0) f.Child("size").Fail("size components must be > 0");
    return kind == "quad" ? MakeQuad(size) : MakePlane(size);
  }
  if (kind == "polygon") {
    allow({"points"});
    const JsonField pts = f.Child("points");
    const size_t n = pts.ArraySize();
    if (n < 3 || n > 4096) pts.Fail("a polygon needs 3 to 4096 points, got " + std::to_string(n));
    std::vector<glm::vec3> points;
    for (size_t i = 0; i < n; ++i) points.push_back(pts.At(i).Vec3(-kMaxCoord, kMaxCoord));
    // Convex and planar: every consecutive cross product points the same way as the first
    // non-zero one (fan triangulation is only correct for convex polygons).
    glm::vec3 ref(0.0f);
    for (size_t i = 0; i < n; ++i) {
      const glm::vec3 c = glm::cross(points[(i + 1) % n] - points[i], points[(i + 2) % n] - points[(i + 1) % n]);
      if (glm::length(c) == 0.0f) continue;
      if (glm::length(ref) == 0.0f) {
        ref = c;
      } else if (glm::dot(glm::normalize(c), glm::normalize(ref)) < 0.999f) {
        pts.Fail(
            "polygon is not convex and planar (fan triangulation needs a convex planar polygon; use 'triangles' or a "
            "mesh)");
      }
    }
    if (glm::length(ref) == 0.0f) pts.Fail("polygon has zero area (all points collinear)");
    return MakePolygon(points);
  }
  if (kind == "box") {
    allow({"size"});
    const glm::vec3 size = f.Child("size").Vec3(0.0, 1e9);
    if (size.x <= 0 || size.y <= 0 || size.z <= 0) f.Child("size").Fail("size components must be > 0");
    return MakeBox(size);
  }
  if (kind == "disk" || kind == "sphere") {
    allow({"radius"});
    const float r = static_cast<float>(f.Child("radius").Number(0.0, 1e9, true));
    return kind == "disk" ? MakeDisk(r) : MakeSphere(r);
  }
  if (kind == "capsule" || kind == "cylinder") {
    allow({"from", "to", "radius"});
    const glm::vec3 a = f.Child("from").Vec3(-kMaxCoord, kMaxCoord);
    const glm::vec3 b = f.Child("to").Vec3(-kMaxCoord, kMaxCoord);
    if (glm::length(b - a) == 0.0f) f.Child("to").Fail("'to' equals 'from' (zero-length " + kind + ")");
    const float r = static_cast<float>(f.Child("radius").Number(0.0, 1e9, true));
    return MakeSegment(kind == "capsule" ? ShapeKind::kCapsule : ShapeKind::kCylinder, a, b, r);
  }
  if (kind == "mesh") {
    allow({"file"});
    const JsonField file = f.Child("file");
    const fs::path p = fs::path(base_dir) / file.String();
    if (const std::string what = WhatIsAt(p.string()); !what.empty()) {
      file.Fail("mesh file '" + p.string() + "' " + what + " (an .obj file is expected)");
    }
    NoteInputFile(p.string());  // an input: --out may not hold it (core/input_files.h)
    try {
      return LoadObjMesh(p.string());
    } catch (const UserError& e) {
      file.Fail(e.what());
    }
  }
  // triangles
  allow({"vertices", "indices"});
  const JsonField vf = f.Child("vertices");
  const JsonField inf = f.Child("indices");
  std::vector<glm::vec3> verts;
  for (size_t i = 0; i < vf.ArraySize(); ++i) verts.push_back(vf.At(i).Vec3(-kMaxCoord, kMaxCoord));
  if (verts.empty()) vf.Fail("no vertices");
  std::vector<glm::uvec3> tris;
  for (size_t i = 0; i < inf.ArraySize(); ++i) {
    const JsonField t = inf.At(i);
    if (t.ArraySize() != 3) t.Fail("a triangle needs 3 indices");
    glm::uvec3 tri;
    for (int k = 0; k < 3; ++k) tri[k] = static_cast<unsigned>(t.At(k).Integer(0, static_cast<int>(verts.size()) - 1));
    tris.push_back(tri);
  }
  if (tris.empty()) inf.Fail("no triangles");
  return MakeTriangles(verts, tris);
}

void RequireEffect(const Scene& s, Effect e, const JsonField& where, const std::string& why) {
  if (!s.Has(e)) {
    where.Fail(why + " needs effect '" + EffectName(e) + "', which the scene does not declare in 'effects' " +
               "(declared: " + JoinNames(s.EffectNames()) + ")");
  }
}

/// A {"shape": "gltf", "file": ..., "transform": ...} object: every primitive of the file,
/// placed by its nodes and then by the object's transform; its materials and images join the
/// scene's. The first glTF object's cameras are kept for "camera": {"type": "gltf"}.
void AddGltfObject(Scene& s, const JsonField& o, const std::string& base_dir, std::vector<Camera>& cameras,
                   std::map<int, size_t>& object_of_material) {
  o.RequireObject({"shape", "file", "transform", "name", "motion"});
  const JsonField file = o.Child("file");
  const fs::path p = fs::path(base_dir) / file.String();
  if (const std::string what = WhatIsAt(p.string()); !what.empty()) {
    file.Fail("glTF file '" + p.string() + "' " + what + " (a .gltf or .glb file is expected)");
  }
  NoteInputFile(p.string());  // an input: --out may not hold it (core/input_files.h)
  GltfContent g;
  try {
    g = LoadGltf(p.string());
  } catch (const UserError& e) {
    file.Fail(e.what());
  }
  if (o.Has("motion")) o.Child("motion").Fail("glTF objects do not move yet (animate the camera instead)");
  // One warning per file for what is loaded but not drawn as written (scenes/gltf_load.h).
  for (const std::string& note : g.notes) {
    std::cerr << "aalab: warning: glTF file '" << p.string() << "': " << note << "\n";
    s.notes.push_back(p.filename().string() + ": " + note);
  }
  {
    char line[256];
    std::snprintf(line, sizeof line,
                  "loaded in %.3f s: %zu triangles, %zu textures (%.1f MB as stored, %.1f MB as RGBA8)", g.load_seconds,
                  g.triangles, g.images.size(), g.texture_bytes / 1e6, g.texture_bytes8 / 1e6);
    std::cerr << "aalab: glTF file '" << p.string() << "' " << line << "\n";
  }
  s.files_read.push_back(p.string());
  s.files_read.insert(s.files_read.end(), g.files_read.begin(), g.files_read.end());
  for (const std::string& f : g.files_read) NoteInputFile(f);  // buffers and images: inputs too
  s.load.push_back({p.filename().string(), g.load_seconds, g.texture_bytes, g.texture_bytes8, g.triangles});
  const glm::mat4 m = o.Has("transform") ? ParseTransform(o.Child("transform")) : glm::mat4(1.0f);
  const int mat_base = static_cast<int>(s.materials.size());
  const int img_base = static_cast<int>(s.images.size());
  const size_t index = std::stoul(o.Path().substr(o.Path().rfind('/') + 1));
  for (Material& mat : g.materials) {
    for (TextureRef* t : {&mat.gltf->base_tex, &mat.gltf->mr_tex, &mat.gltf->normal_tex, &mat.gltf->emissive_tex,
                          &mat.gltf->occlusion_tex}) {
      if (t->Has()) t->image += img_base;
    }
    object_of_material[static_cast<int>(s.materials.size())] = index;
    s.materials.push_back(std::move(mat));
  }
  for (auto& img : g.images) s.images.push_back(std::move(img));
  for (Shape& sh : g.shapes) {
    sh.material += mat_base;
    TransformShape(sh, m);
    for (const glm::vec3& q : sh.positions) {
      if (!(std::fabs(q.x) <= kMaxCoord && std::fabs(q.y) <= kMaxCoord && std::fabs(q.z) <= kMaxCoord)) {
        o.Child("transform").Fail("moves a vertex of '" + p.string() + "' beyond +-1e8");
      }
    }
    s.shapes.push_back(std::move(sh));
  }
  // The file's KHR_lights_punctual lights (read by LoadGltf from its parsed document, in the
  // extension's own units: scenes/gltf_lights.h), placed by the object's transform.
  for (Light l : g.lights) {
    l.position = glm::vec3(m * glm::vec4(l.position, 1.0f));
    const glm::vec3 d = glm::mat3(m) * l.direction;
    if (glm::length(d) > 0.0f) l.direction = glm::normalize(d);
    s.lights.push_back(l);
  }
  if (cameras.empty()) {
    for (Camera c : g.cameras) {
      c.position = glm::vec3(m * glm::vec4(c.position, 1.0f));
      c.look_at = glm::vec3(m * glm::vec4(c.look_at, 1.0f));
      c.up = glm::normalize(glm::mat3(m) * c.up);
      cameras.push_back(c);
    }
  }
}

/// The effects a glTF material needs: its shading (unlit, or lambert + specular for the
/// metallic-roughness BRDF), textures, normal_map, alpha_test (MASK), alpha_blend (BLEND).
void GltfMaterialEffects(const Scene& s, const Material& mat, const JsonField& obj,
                         std::array<bool, kEffectCount>& used) {
  const GltfMaterial& g = *mat.gltf;
  const std::string who = "glTF material '" + mat.name + "'";
  auto need = [&](Effect e, const std::string& why) {
    RequireEffect(s, e, obj.Child("file"), who + " (" + why + ")");
    used[static_cast<int>(e)] = true;
  };
  if (mat.shading == Shading::kUnlit) {
    need(Effect::kUnlit, "KHR_materials_unlit");
  } else {
    need(Effect::kLambert, "its diffuse lobe");
    need(Effect::kSpecular, "its GGX specular lobe");
  }
  const bool lit = mat.shading != Shading::kUnlit;
  if (g.base_tex.Has() || (lit && (g.mr_tex.Has() || g.emissive_tex.Has() || g.occlusion_tex.Has()))) {
    need(Effect::kTextures, "an image texture");
  }
  if (lit && g.normal_tex.Has()) need(Effect::kNormalMap, "a normal texture");
  if (g.alpha_mode == AlphaMode::kMask) need(Effect::kAlphaTest, "alphaMode MASK");
  if (g.alpha_mode == AlphaMode::kBlend) need(Effect::kAlphaBlend, "alphaMode BLEND");
}

}  // namespace

Scene ParseScene(const std::string& text, const std::string& origin, const std::string& base_dir) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw UserError(origin + ": not valid JSON: " + e.what());
  } catch (const nlohmann::json::exception& e) {
    // Not a parse_error: a number too large for a double (out_of_range.406, "1e999").
    throw UserError(origin + ": not valid JSON: " + e.what() +
                    " (numbers must be finite doubles; JSON has no NaN or Infinity)");
  }
  const JsonField root(doc, origin, "");
  root.RequireObject({"name", "description", "effects", "camera", "display", "background", "ambient", "materials",
                      "lights", "light_units", "environment", "objects", "animation"});
  Scene s;
  s.name = root.Child("name").String();
  for (char c : s.name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) {
      root.Child("name").Fail("scene names are lowercase-kebab ('" + s.name + "')");
    }
  }
  if (s.name.empty()) root.Child("name").Fail("empty name");
  s.description = root.StringOr("description", "");

  const JsonField effects = root.Child("effects");
  std::vector<std::string> all;
  for (int i = 0; i < kEffectCount; ++i) all.push_back(EffectName(static_cast<Effect>(i)));
  if (effects.ArraySize() == 0) effects.Fail("declare at least one effect (allowed: " + JoinNames(all) + ")");
  for (size_t i = 0; i < effects.ArraySize(); ++i) {
    const std::string e = effects.At(i).Choice(all);
    for (int k = 0; k < kEffectCount; ++k) {
      if (all[k] == e) {
        if (s.effects[k]) effects.At(i).Fail("effect '" + e + "' declared twice");
        s.effects[k] = true;
      }
    }
  }

  // "camera": {"type": "gltf", "index": k}: camera k of the first glTF object (set below).
  int gltf_camera = -1;
  const JsonField camf = root.Child("camera");
  if (camf.Value().is_object() && camf.Value().contains("type") && camf.Value()["type"] == "gltf") {
    camf.RequireObject({"type", "index"});
    gltf_camera = camf.Has("index") ? camf.Child("index").Integer(0, 1 << 20) : 0;
  } else {
    s.camera = ParseCamera(camf);
  }
  if (root.Has("display")) {
    const JsonField d = root.Child("display");
    d.RequireObject({"exposure", "tonemap"});
    s.display.exposure = static_cast<float>(d.NumberOr("exposure", 1.0, 0.0, 1e9, true));
    if (d.Has("tonemap")) s.display.tonemap = ParseTonemap(d.Child("tonemap").Choice({"none", "reinhard", "aces"}));
  }
  s.background = root.Vec3Or("background", glm::vec3(0.0f), 0.0, 1e7);
  s.ambient = root.Vec3Or("ambient", glm::vec3(0.0f), 0.0, 1e7);

  const JsonField mats = root.Child("materials");
  bool any_gltf = false;  // a scene of glTF objects only brings its materials from the files
  if (root.Has("objects") && root.Child("objects").Value().is_array()) {
    for (const auto& o : root.Child("objects").Value())
      any_gltf |= o.is_object() && o.contains("shape") && o["shape"] == "gltf";
  }
  if (!mats.Value().is_object() || (mats.Value().empty() && !any_gltf))
    mats.Fail("expected an object of named materials");
  std::map<std::string, int> mat_index;
  for (auto it = mats.Value().begin(); it != mats.Value().end(); ++it) {
    mat_index[it.key()] = static_cast<int>(s.materials.size());
    s.materials.push_back(ParseMaterial(mats.Child(it.key()), it.key()));
  }

  const LightUnits units = ParseLightUnits(root, root.Has("lights") && root.Child("lights").ArraySize() > 0);
  if (root.Has("lights")) {
    const JsonField lights = root.Child("lights");
    for (size_t i = 0; i < lights.ArraySize(); ++i) s.lights.push_back(ParseLight(lights.At(i), units));
  }
  if (root.Has("environment")) {
    s.environment = ParseEnvironment(root.Child("environment"), base_dir, &s.files_read);
    for (const std::string& f : s.files_read) NoteInputFile(f);  // an environment map is an input too
  }

  if (root.Has("animation")) s.animation = ParseAnimation(root.Child("animation"));

  const JsonField objs = root.Child("objects");
  if (objs.ArraySize() == 0) objs.Fail("a scene needs at least one object");
  std::vector<Camera> gltf_cameras;               // the cameras of the first glTF object
  std::map<int, size_t> gltf_object_of_material;  // material index -> the glTF object it came from
  std::vector<bool> mat_used(s.materials.size(), false);
  for (size_t i = 0; i < objs.ArraySize(); ++i) {
    const JsonField o = objs.At(i);
    if (o.Has("shape") && o.Child("shape").Value() == "gltf") {
      AddGltfObject(s, o, base_dir, gltf_cameras, gltf_object_of_material);
      mat_used.resize(s.materials.size(), true);
      continue;
    }
    Shape shape = ParseShape(o, base_dir);
    const JsonField mf = o.Child("material");
    const std::string mname = mf.String();
    auto it = mat_index.find(mname);
    if (it == mat_index.end()) {
      std::vector<std::string> names;
      for (const auto& kv : mat_index) names.push_back(kv.first);
      mf.Fail("unknown material '" + mname + "' (defined: " + JoinNames(names) + ")");
    }
    shape.material = it->second;
    mat_used[it->second] = true;
    if (o.Has("transform") && !TransformShape(shape, ParseTransform(o.Child("transform")))) {
      o.Child("transform").Fail("a " + shape.source + " needs a uniform scale (it stays an exact analytic shape)");
    }
    if (shape.kind != ShapeKind::kTriangles && !(shape.radius >= FLT_MIN && std::isfinite(shape.radius))) {
      o.Fail("the " + shape.source + "'s radius times the transform's scale is " + FormatNumber(shape.radius) +
             ", outside single precision (radius x scale must lie in [1.2e-38, 3.4e38])");
    }
    if (o.Has("motion")) {
      const ObjectMotion motion = ParseObjectMotion(o.Child("motion"), s.animation.frames);
      float smin = 1.0f;
      for (const MotionKey& k : motion.keys) smin = std::min(smin, k.scale);
      if (shape.kind != ShapeKind::kTriangles && !(shape.radius * smin >= FLT_MIN)) {
        o.Child("motion").Fail("the " + shape.source +
                               "'s radius times the smallest motion scale underflows single precision");
      }
      shape.motion = static_cast<int>(s.animation.objects.size());
      s.animation.objects.push_back(motion);
    }
    s.shapes.push_back(std::move(shape));
  }
  if (gltf_camera >= 0) {
    if (gltf_camera >= static_cast<int>(gltf_cameras.size())) {
      camf.Fail("camera index " + std::to_string(gltf_camera) + " but the first glTF object's file has " +
                std::to_string(gltf_cameras.size()) + " camera(s)");
    }
    s.camera = gltf_cameras[static_cast<size_t>(gltf_camera)];
  }
  if (root.Has("animation") && s.animation.camera.empty() && s.animation.objects.empty()) {
    root.Child("animation").Fail("an animation that moves nothing: give camera keys or an object 'motion'");
  }

  // Effects: content needs its effects declared, and every declared effect must be used —
  // a scene simulates exactly what it calls for.
  std::array<bool, kEffectCount> used{};
  for (size_t m = 0; m < s.materials.size(); ++m) {
    const Material& mat = s.materials[m];
    if (mat.gltf) {
      GltfMaterialEffects(s, mat, objs.At(gltf_object_of_material.at(static_cast<int>(m))), used);
      continue;
    }
    const JsonField mf = mats.Child(mat.name);
    if (!mat_used[m]) mf.Fail("material '" + mat.name + "' is not used by any object");
    const Effect shade = mat.shading == Shading::kUnlit ? Effect::kUnlit : Effect::kLambert;
    RequireEffect(s, shade, mf.Child("shading"), "shading '" + std::string(EffectName(shade)) + "'");
    used[static_cast<int>(shade)] = true;
    if (mat.texture) {
      RequireEffect(s, Effect::kTextures, mf.Child("texture"), "a texture");
      used[static_cast<int>(Effect::kTextures)] = true;
    }
    if (mat.specular != glm::vec3(0.0f)) {
      RequireEffect(s, Effect::kSpecular, mf.Child("specular"), "a specular highlight");
      used[static_cast<int>(Effect::kSpecular)] = true;
    }
    if (mat.alpha) {
      RequireEffect(s, Effect::kAlphaTest, mf.Child("alpha"), "an alpha cut-out");
      used[static_cast<int>(Effect::kAlphaTest)] = true;
    }
  }
  bool lit = used[static_cast<int>(Effect::kLambert)];
  for (size_t i = 0; i < s.lights.size(); ++i) {
    if (s.lights[i].shadows) {
      RequireEffect(s, Effect::kShadows, root.Child("lights").At(i).Child("shadows"), "a shadow-casting light");
      used[static_cast<int>(Effect::kShadows)] = true;
    }
  }
  if (lit && s.lights.empty() && s.ambient == glm::vec3(0.0f) && !s.environment) {
    root.Fail("lambert materials need lights, an ambient term or an environment (the scene would be black)");
  }
  if (!lit && !s.lights.empty() && root.Has("lights"))
    root.Child("lights").Fail("lights without any lambert material light nothing");
  if (!lit && s.environment)
    root.Child("environment").Fail("an environment without any lambert or glTF PBR material lights nothing");
  for (int e = 0; e < kEffectCount; ++e) {
    if (s.effects[e] && !used[e]) {
      effects.Fail("effect '" + std::string(EffectName(static_cast<Effect>(e))) +
                   "' is declared but nothing in the scene uses it (declare exactly the effects the content needs)");
    }
  }
  return s;
}

Scene LoadSceneFile(const std::string& path) {
  if (!fs::exists(path)) throw UserError("scene file '" + path + "' does not exist");
  if (fs::is_directory(path)) throw UserError("scene file '" + path + "' is a folder, not a scene file");
  // A FIFO or device would block or never end: scene files are regular files.
  if (!fs::is_regular_file(path)) throw UserError("scene file '" + path + "' is not a regular file");
  std::ifstream f(path, std::ios::binary);
  if (!f) throw UserError("scene file '" + path + "' cannot be read: " + std::strerror(errno));
  std::stringstream ss;
  ss << f.rdbuf();
  Scene s = ParseScene(ss.str(), "scene '" + path + "'", fs::path(path).parent_path().string());
  s.path = path;
  return s;
}

}  // namespace aalab
