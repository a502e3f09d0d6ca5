/// The scene format's lighting fields (scenes/README.md "Lighting"): "light_units" and
/// "environment". ParseScene calls these; each error names the file, the JSON path and what is
/// allowed.
#pragma once
#include <memory>
#include <string>

#include "scenes/ibl.h"
#include "scenes/json_fields.h"

namespace aalab {

/// How a scene file states light intensities.
enum class LightUnits {
  kGltf,     ///< "gltf": lux (directional), candela (point, spot); Lambert reflects ρE/π
  kLegacyPi  ///< "aalab-pi": aalab's convention before 2026-11: π × the glTF value
};

/// The message for a scene with lights and no "light_units" (the π migration).
std::string LightUnitsMissingMessage();

/// Reads root "light_units" (required when `has_lights`; refused without lights).
LightUnits ParseLightUnits(const JsonField& root, bool has_lights);

/// Converts an intensity stated in `units` to aalab's internal unit (Light::intensity): the
/// glTF value / π (in double, then rounded once to float), the legacy value as is.
float InternalIntensity(double value, LightUnits units);

/// Reads "environment": {"map": "studio" | "<file.hdr|.exr>" | [r, g, b], "intensity": 1,
/// "rotation_deg": 0}. A file is resolved against base_dir and appended to *files_read.
std::shared_ptr<const Environment> ParseEnvironment(const JsonField& f, const std::string& base_dir,
                                                    std::vector<std::string>* files_read);

}  // namespace aalab
