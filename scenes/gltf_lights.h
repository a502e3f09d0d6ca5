/// KHR_lights_punctual: the glTF file's own point, spot and directional lights, read from the
/// file's JSON as the extension's specification defines them (intensity in candela for point
/// and spot, lux for directional; a light shines down its node's −Z; node scale ignored).
/// Pure functions of the parsed JSON; LoadGltf calls GltfPunctualLights on the document it
/// parsed (GltfContent::lights) and scenes/scene_parse.cpp places them by the object's transform. docs/lighting.md
/// "Punctual lights".
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "scenes/scene.h"

namespace aalab {

/// The local matrix of node `node` ("matrix", else translation · rotation · scale).
glm::mat4 GltfNodeLocalMatrix(const nlohmann::json& node);

/// The world matrix of every node of the displayed scene (`scene`, else scenes[0]; a file
/// without scenes: every node that is nobody's child is a root), walked iteratively with an
/// explicit stack (no recursion). Nodes outside the displayed scene get nullopt. Throws
/// UserError naming the JSON path when a node is reached twice (a cycle or a second parent:
/// glTF nodes form strict trees) or a child / root index is out of range.
std::vector<std::optional<glm::mat4>> GltfNodeWorldMatrices(const nlohmann::json& gltf);

/// The file's KHR_lights_punctual lights instanced by the displayed scene's nodes, in node
/// order, in world space of the file, intensity in aalab's internal unit (the file's value
/// divided by π: Light). Empty when the file has none. Throws UserError naming the JSON path
/// for a malformed light (unknown type, negative intensity, range <= 0, cone angles outside
/// 0 <= inner < outer <= π/2, a node's light index out of range).
std::vector<Light> GltfPunctualLights(const nlohmann::json& gltf);

}  // namespace aalab
