/// glTF 2.0 files (.gltf with its buffers and images, or .glb), read as written (on the
/// project's nlohmann-json; docs/real-content.md "Why aalab reads glTF itself" says why not Assimp or tinygltf):
/// triangle meshes placed by the node hierarchy (the static pose: nodes' own transforms,
/// skins posed by their joints' nodes, morph targets at the default weights),
/// metallic-roughness materials with their textures and samplers, cameras. What is drawn,
/// warned about and refused: scenes/README.md "glTF objects".
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "scenes/gltf_doc.h"
#include "scenes/scene.h"

namespace aalab {

/// What a glTF file holds, in world space of the file (every node transform applied).
struct GltfContent {
  std::vector<Shape> shapes;        ///< one per mesh primitive and node instance; Shape::material
                                    ///< indexes `materials`
  std::vector<Material> materials;  ///< TextureRef::image indexes `images`
  std::vector<std::shared_ptr<const MipChain>> images;
  std::vector<Camera> cameras;  ///< the file's cameras, in node order, placed by their nodes
  std::vector<Light> lights;    ///< KHR_lights_punctual lights (scenes/gltf_lights.h), in world space of the file
  size_t triangles = 0;
  glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};  ///< of every vertex drawn
  /// Notes for the user: extensions used but not drawn (one line listing all), animations,
  /// skins and morph targets drawn at their static pose, primitives skipped (points, lines).
  std::vector<std::string> notes;
  /// Files read beyond the glTF itself (external buffers and images).
  std::vector<std::string> files_read;
  double load_seconds = 0.0;  ///< wall time of LoadGltf
  size_t texture_bytes = 0;   ///< bytes of the mip chains as stored
  size_t texture_bytes8 = 0;  ///< bytes of the same chains as RGBA8
};

struct GltfLoadOptions {
  bool decode_images = true;  ///< false: geometry, materials and cameras only (no texture decode)
};

/// Largest total of the RGBA8 mip chains of one file's textures (their headers are read
/// and summed before any texel is decoded).
inline constexpr size_t kMaxGltfTextureBytes8 = size_t{4} << 30;

/// Loads a glTF 2.0 file. Throws UserError naming the file, the JSON path and the rule for a
/// malformed file (scenes/gltf_doc.h; an index out of range, accessor bounds, recursive or
/// multiply-parented nodes, a node hierarchy deeper than kMaxGltfNodeDepth, a numeric
/// version, a wrong JSON type), required extensions aalab does not draw (all named), NaN/Inf
/// or |x| > 1e8 vertex positions, an image that does not decode or exceeds the texture
/// budget, and a file with no triangles.
GltfContent LoadGltf(const std::string& path, const GltfLoadOptions& options = {});

namespace gltf_detail {
/// The images `wanted` ((image index, sRGB) in content order) into out.images, files into
/// out.files_read: headers and budget first, then (with `decode`) the decodes; without
/// `decode`, a 1 × 1 white image each. Part of LoadGltf (scenes/gltf_images.cpp).
void ReadGltfImages(const GltfDoc& d, const std::vector<std::pair<long long, bool>>& wanted, bool decode,
                    GltfContent& out);
}  // namespace gltf_detail

}  // namespace aalab
