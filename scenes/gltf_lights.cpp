// KHR_lights_punctual (Khronos, glTF 2.0 extension, ratified): lights defined in
// /extensions/KHR_lights_punctual/lights, instanced by nodes through
// node.extensions.KHR_lights_punctual.light. Units: point and spot intensity in candela
// (lm/sr), directional in lux (lm/m²); a spot's angular attenuation follows the
// specification's reference formula (scenes/light_eval.h), `range` its recommended window.
// aalab stores intensity / π (scenes/scene.h Light), so a Lambert surface of albedo ρ under
// irradiance E reflects ρE/π, as glTF and Blender define it.
#include "scenes/gltf_lights.h"

#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"

namespace aalab {

namespace {

constexpr double kPiD = 3.14159265358979323846;

[[noreturn]] void Fail(const std::string& path, const std::string& why) {
  throw UserError("KHR_lights_punctual: " + path + ": " + why);
}

double Number(const nlohmann::json& obj, const char* key, double fallback, const std::string& path) {
  if (!obj.contains(key)) return fallback;
  const nlohmann::json& v = obj[key];
  if (!v.is_number()) Fail(path + "/" + key, "expected a number");
  return v.get<double>();
}

}  // namespace

glm::mat4 GltfNodeLocalMatrix(const nlohmann::json& node) {
  if (node.contains("matrix") && node["matrix"].is_array() && node["matrix"].size() == 16) {
    float m[16];
    for (int i = 0; i < 16; ++i) m[i] = node["matrix"][i].get<float>();
    return glm::make_mat4(m);  // column-major, as glTF stores it
  }
  glm::vec3 t(0.0f), s(1.0f);
  glm::quat r(1.0f, 0.0f, 0.0f, 0.0f);
  if (node.contains("translation"))
    t = {node["translation"][0].get<float>(), node["translation"][1].get<float>(), node["translation"][2].get<float>()};
  if (node.contains("scale"))
    s = {node["scale"][0].get<float>(), node["scale"][1].get<float>(), node["scale"][2].get<float>()};
  if (node.contains("rotation")) {
    const auto& q = node["rotation"];  // glTF: x, y, z, w
    r = glm::quat(q[3].get<float>(), q[0].get<float>(), q[1].get<float>(), q[2].get<float>());
  }
  glm::mat4 m = glm::mat4_cast(r);
  m[0] *= s.x;
  m[1] *= s.y;
  m[2] *= s.z;
  m[3] = glm::vec4(t, 1.0f);
  return m;
}

std::vector<std::optional<glm::mat4>> GltfNodeWorldMatrices(const nlohmann::json& gltf) {
  const nlohmann::json empty = nlohmann::json::array();
  const nlohmann::json& nodes = gltf.contains("nodes") ? gltf["nodes"] : empty;
  const size_t n = nodes.size();
  std::vector<std::optional<glm::mat4>> world(n);
  // Roots: the displayed scene's nodes, else every node that is nobody's child.
  std::vector<std::pair<size_t, std::string>> roots;
  if (gltf.contains("scenes") && gltf["scenes"].is_array() && !gltf["scenes"].empty()) {
    const size_t si = gltf.contains("scene") ? gltf["scene"].get<size_t>() : 0;
    if (si >= gltf["scenes"].size()) Fail("/scene", "scene " + std::to_string(si) + " does not exist");
    const nlohmann::json& sc = gltf["scenes"][si];
    if (sc.contains("nodes")) {
      for (size_t k = 0; k < sc["nodes"].size(); ++k) {
        roots.emplace_back(sc["nodes"][k].get<size_t>(),
                           "/scenes/" + std::to_string(si) + "/nodes/" + std::to_string(k));
      }
    }
  } else {
    std::vector<bool> child(n, false);
    for (size_t i = 0; i < n; ++i) {
      if (!nodes[i].contains("children")) continue;
      for (const auto& c : nodes[i]["children"]) {
        const size_t ci = c.get<size_t>();
        if (ci < n) child[ci] = true;
      }
    }
    for (size_t i = 0; i < n; ++i) {
      if (!child[i]) roots.emplace_back(i, "/nodes/" + std::to_string(i));
    }
  }
  struct Item {
    size_t node;
    glm::mat4 parent;
    std::string path;
  };
  std::vector<Item> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({it->first, glm::mat4(1.0f), it->second});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    if (item.node >= n)
      Fail(item.path, "node " + std::to_string(item.node) + " does not exist (" + std::to_string(n) + " nodes)");
    if (world[item.node]) {
      Fail(item.path, "node " + std::to_string(item.node) +
                          " is reached twice (a cycle or a second parent; glTF nodes form strict trees)");
    }
    const nlohmann::json& node = nodes[item.node];
    const glm::mat4 w = item.parent * GltfNodeLocalMatrix(node);
    world[item.node] = w;
    if (!node.contains("children")) continue;
    const auto& ch = node["children"];
    for (size_t k = ch.size(); k-- > 0;) {
      stack.push_back(
          {ch[k].get<size_t>(), w, "/nodes/" + std::to_string(item.node) + "/children/" + std::to_string(k)});
    }
  }
  return world;
}

std::vector<Light> GltfPunctualLights(const nlohmann::json& gltf) {
  std::vector<Light> out;
  if (!gltf.contains("extensions") || !gltf["extensions"].contains("KHR_lights_punctual")) return out;
  const std::string base = "/extensions/KHR_lights_punctual/lights";
  const nlohmann::json& ext = gltf["extensions"]["KHR_lights_punctual"];
  if (!ext.contains("lights") || !ext["lights"].is_array()) Fail(base, "expected an array of lights");
  const nlohmann::json& defs = ext["lights"];
  std::vector<Light> proto;
  for (size_t i = 0; i < defs.size(); ++i) {
    const std::string p = base + "/" + std::to_string(i);
    const nlohmann::json& d = defs[i];
    if (!d.is_object() || !d.contains("type") || !d["type"].is_string())
      Fail(p + "/type", "missing (allowed: directional, point, spot)");
    const std::string type = d["type"].get<std::string>();
    Light l;
    if (type == "directional") {
      l.type = LightType::kDirectional;
    } else if (type == "point") {
      l.type = LightType::kPoint;
    } else if (type == "spot") {
      l.type = LightType::kSpot;
    } else {
      Fail(p + "/type", "'" + type + "' is not a light type (allowed: directional, point, spot)");
    }
    if (d.contains("color")) {
      const auto& c = d["color"];
      if (!c.is_array() || c.size() != 3) Fail(p + "/color", "expected [r, g, b]");
      for (int k = 0; k < 3; ++k) {
        if (!c[k].is_number() || !(c[k].get<double>() >= 0.0)) Fail(p + "/color", "components must be numbers >= 0");
        l.color[k] = c[k].get<float>();
      }
    }
    const double intensity = Number(d, "intensity", 1.0, p);
    if (!(intensity >= 0.0) || !std::isfinite(intensity)) Fail(p + "/intensity", "must be a finite number >= 0");
    l.intensity = static_cast<float>(intensity / kPiD);
    if (d.contains("range")) {
      if (l.type == LightType::kDirectional) Fail(p + "/range", "a directional light has no range");
      const double r = Number(d, "range", 0.0, p);
      if (!(r > 0.0) || !std::isfinite(r)) Fail(p + "/range", "must be > 0 (leave it out for an infinite range)");
      l.range = static_cast<float>(r);
    }
    if (l.type == LightType::kSpot) {
      const nlohmann::json spot = d.contains("spot") ? d["spot"] : nlohmann::json::object();
      const double inner = Number(spot, "innerConeAngle", 0.0, p + "/spot");
      const double outer = Number(spot, "outerConeAngle", kPiD / 4.0, p + "/spot");
      if (!(inner >= 0.0 && inner < outer && outer <= kPiD / 2.0)) {
        Fail(p + "/spot", "cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2 (got " +
                              std::to_string(inner) + ", " + std::to_string(outer) + ")");
      }
      l.cos_inner = static_cast<float>(std::cos(inner));
      l.cos_outer = static_cast<float>(std::cos(outer));
    }
    proto.push_back(l);
  }
  const std::vector<std::optional<glm::mat4>> world = GltfNodeWorldMatrices(gltf);
  for (size_t i = 0; i < world.size(); ++i) {
    if (!world[i]) continue;
    const nlohmann::json& node = gltf["nodes"][i];
    if (!node.contains("extensions") || !node["extensions"].contains("KHR_lights_punctual")) continue;
    const std::string p = "/nodes/" + std::to_string(i) + "/extensions/KHR_lights_punctual/light";
    const nlohmann::json& ref = node["extensions"]["KHR_lights_punctual"];
    if (!ref.contains("light") || !ref["light"].is_number_integer()) Fail(p, "expected a light index");
    const long long k = ref["light"].get<long long>();
    if (k < 0 || static_cast<size_t>(k) >= proto.size()) {
      Fail(p, "light " + std::to_string(k) + " does not exist (" + std::to_string(proto.size()) + " lights)");
    }
    Light l = proto[static_cast<size_t>(k)];
    const glm::mat4& w = *world[i];
    l.position = glm::vec3(w[3]);
    const glm::vec3 dir = glm::mat3(w) * glm::vec3(0.0f, 0.0f, -1.0f);
    const float len = glm::length(dir);
    if (!(len > 0.0f) || !std::isfinite(len))
      Fail("/nodes/" + std::to_string(i), "the node's matrix has no direction for its light (zero scale)");
    l.direction = dir / len;
    out.push_back(l);
  }
  return out;
}

}  // namespace aalab
