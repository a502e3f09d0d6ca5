// A glTF model as a scene (scenes/model_scene.h).
#include "scenes/model_scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "core/error.h"
#include "scenes/gltf_load.h"

namespace aalab {
namespace fs = std::filesystem;
using Json = nlohmann::json;

bool IsModelPath(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".glb" || ext == ".gltf";
}

namespace {

/// The file's stem as a scene name (lowercase-kebab): "DamagedHelmet" → "damaged-helmet",
/// "2CylinderEngine" → "2-cylinder-engine"; "model" if nothing is left.
std::string KebabName(const std::string& stem) {
  std::string out;
  for (size_t i = 0; i < stem.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(stem[i]);
    const bool upper = std::isupper(c) != 0;
    const bool boundary =
        i > 0 && (upper || std::isdigit(static_cast<unsigned char>(stem[i - 1])) != std::isdigit(c)) &&
        std::isalnum(static_cast<unsigned char>(stem[i - 1])) && !std::isupper(static_cast<unsigned char>(stem[i - 1]));
    if (std::isalnum(c)) {
      if (boundary && !out.empty() && out.back() != '-') out += '-';
      out += static_cast<char>(std::tolower(c));
    } else if (!out.empty() && out.back() != '-') {
      out += '-';
    }
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.empty() ? "model" : out;
}

}  // namespace

Json ModelSceneJson(const std::string& path) {
  GltfLoadOptions opt;
  opt.decode_images = false;
  const GltfContent g = LoadGltf(path, opt);
  // Effects: what the materials need (the same rules the scene parser enforces).
  bool unlit = false, lit = false, tex = false, normal = false, mask = false, blend = false;
  for (const Material& m : g.materials) {
    const GltfMaterial& x = *m.gltf;
    const bool l = m.shading != Shading::kUnlit;
    unlit |= !l;
    lit |= l;
    tex |= x.base_tex.Has() || (l && (x.mr_tex.Has() || x.emissive_tex.Has() || x.occlusion_tex.Has()));
    normal |= l && x.normal_tex.Has();
    mask |= x.alpha_mode == AlphaMode::kMask;
    blend |= x.alpha_mode == AlphaMode::kBlend;
  }
  Json effects = Json::array();
  if (unlit) effects.push_back("unlit");
  if (lit) effects.insert(effects.end(), {"lambert", "shadows", "specular"});
  if (tex) effects.push_back("textures");
  if (mask) effects.push_back("alpha_test");
  if (blend) effects.push_back("alpha_blend");
  if (normal) effects.push_back("normal_map");
  Json camera;
  if (!g.cameras.empty()) {
    camera = {{"type", "gltf"}, {"index", 0}};
  } else {
    // Framing the bounds: a 40° camera looking at the centre from the front-right, above
    // (glTF's +Z is the model's front, +Y up), far enough that the bounding sphere fits
    // the height with 10% to spare.
    const glm::dvec3 lo(g.bounds_min), hi(g.bounds_max);
    const glm::dvec3 c = (lo + hi) * 0.5;
    const double r = std::max(glm::length(hi - lo) * 0.5, 1e-6);
    const double dist = 1.1 * r / std::sin(glm::radians(20.0));
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.5, 0.35, 1.0));
    const glm::dvec3 p = c + dir * dist;
    camera = {{"type", "perspective"}, {"position", {p.x, p.y, p.z}}, {"look_at", {c.x, c.y, c.z}}, {"fov_y", 40}};
  }
  return Json{{"name", KebabName(fs::path(path).stem().string())},
              {"description", "the glTF model " + fs::path(path).filename().string() +
                                  " with aalab's default sun and studio environment"},
              {"effects", effects},
              {"camera", camera},
              {"display", {{"exposure", 1.0}, {"tonemap", "aces"}}},
              {"background", {0.55, 0.6, 0.7}},
              {"materials", Json::object()},
              // The default studio environment (image-based lighting, docs/lighting.md) in place
              // of a flat ambient term, and a sun of 1.2π lux (glTF units).
              {"environment", {{"map", "studio"}, {"intensity", 1.0}}},
              {"light_units", "gltf"},
              {"lights",
               {{{"type", "directional"},
                 {"direction", {0.4, -1.0, -0.6}},
                 {"color", {1.0, 0.95, 0.85}},
                 {"intensity", 3.7699112},
                 {"shadows", lit}}}},
              {"objects", {{{"shape", "gltf"}, {"file", fs::absolute(path).lexically_normal().string()}}}}};
}

Scene LoadModelScene(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw UserError("glTF file '" + path + "' not found");
  const Json j = ModelSceneJson(path);
  std::string effects;
  for (const Json& e : j["effects"]) effects += (effects.empty() ? "" : ", ") + e.get<std::string>();
  std::cerr << "aalab: scene from model '" << path << "': camera "
            << (j["camera"]["type"] == "gltf" ? "the file's first" : "framing the model's bounds") << "; effects "
            << effects << " (aalab scene " << path << " writes this scene file)\n";
  Scene s = ParseScene(j.dump(), path, fs::path(path).parent_path().string());
  s.path = path;
  return s;
}

}  // namespace aalab
