/// A glTF model (.glb / .gltf) as a scene of its own, so that `aalab run --scenes model.glb`
/// works with no scene file: the file's first camera, else one framing the model's bounds;
/// the default studio environment (image-based lighting) and a sun; the effects inferred from the file's materials.
/// `aalab scene model.glb` writes the same scene file, to edit.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "scenes/scene.h"

namespace aalab {

/// True for a path ending in .glb or .gltf (any case).
bool IsModelPath(const std::string& path);

/// The scene file (JSON) that draws the model at `path` as described above. The model is
/// read without decoding textures (geometry, materials, cameras). Throws UserError as
/// LoadGltf.
nlohmann::json ModelSceneJson(const std::string& path);

/// The scene of ModelSceneJson, parsed; prints one line naming the camera and effects
/// chosen (to stderr).
Scene LoadModelScene(const std::string& path);

}  // namespace aalab
