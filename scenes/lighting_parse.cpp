// The scene format's lighting fields: "light_units" (the π migration, docs/lighting.md
// "Units") and "environment" (image-based lighting, scenes/ibl.h).
#include "scenes/lighting_parse.h"

#include <filesystem>

#include "core/error.h"

namespace aalab {

namespace fs = std::filesystem;

namespace {
constexpr double kPiD = 3.14159265358979323846;
}  // namespace

std::string LightUnitsMissingMessage() {
  return "a scene with lights must state \"light_units\": \"gltf\" (intensities as glTF and Blender define "
         "them: directional in lux, point and spot in candela; a white Lambert surface under irradiance E "
         "reflects E/pi). Scene files written before this field existed used pi times those values: add "
         "\"light_units\": \"gltf\" and multiply each light's intensity by pi (3.14159265), or add "
         "\"light_units\": \"aalab-pi\" to keep the old values (docs/lighting.md \"Units\")";
}

LightUnits ParseLightUnits(const JsonField& root, bool has_lights) {
  if (!root.Has("light_units")) {
    if (has_lights) root.Fail(LightUnitsMissingMessage());
    return LightUnits::kGltf;
  }
  if (!has_lights) root.Child("light_units").Fail("light_units without lights (it states the lights' intensity units)");
  const std::string u = root.Child("light_units").Choice({"gltf", "aalab-pi"});
  return u == "gltf" ? LightUnits::kGltf : LightUnits::kLegacyPi;
}

float InternalIntensity(double value, LightUnits units) {
  return units == LightUnits::kGltf ? static_cast<float>(value / kPiD) : static_cast<float>(value);
}

std::shared_ptr<const Environment> ParseEnvironment(const JsonField& f, const std::string& base_dir,
                                                    std::vector<std::string>* files_read) {
  f.RequireObject({"map", "intensity", "rotation_deg"});
  const float intensity = static_cast<float>(f.NumberOr("intensity", 1.0, 0.0, 1e6));
  const float rotation = static_cast<float>(f.NumberOr("rotation_deg", 0.0, -360.0, 360.0));
  if (!f.Has("map"))
    f.Fail("an environment needs a \"map\": \"studio\", an equirectangular .hdr/.exr file, or [r, g, b]");
  const JsonField map = f.Child("map");
  if (map.Value().is_array()) {
    // A uniform environment of radiance [r, g, b] (the white furnace).
    const glm::vec3 c = map.Vec3(0.0, 1e7);
    EquirectMap m;
    m.width = 64;
    m.height = 32;
    m.texels.assign(static_cast<size_t>(m.width) * m.height, c);
    return MakeEnvironment(std::move(m), "uniform", intensity, rotation);
  }
  if (!map.Value().is_string()) map.Fail("expected \"studio\", a file name or [r, g, b]");
  const std::string name = map.String();
  if (name == "studio") return StudioEnvironmentShared(intensity, rotation);
  const fs::path p = fs::path(base_dir) / name;
  if (!fs::is_regular_file(p)) {
    map.Fail("environment map '" + p.string() +
             "' not found (allowed: \"studio\", an equirectangular .hdr or .exr "
             "file relative to the scene file, or [r, g, b])");
  }
  EquirectMap m;
  try {
    m = ReadEquirect(p.string());
  } catch (const UserError& e) {
    map.Fail(e.what());
  }
  if (files_read) files_read->push_back(p.string());
  return MakeEnvironment(std::move(m), p.string(), intensity, rotation);
}

}  // namespace aalab
