/// glTF 2.0 files (.gltf with its buffers and images, or .glb) through Assimp: triangle
/// meshes placed by the node hierarchy, metallic-roughness materials with their textures and
/// samplers, cameras. What is refused and why: scenes/README.md "glTF objects".
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace aalab {

/// What a glTF file holds, in world space of the file (every node transform applied).
struct GltfContent {
  std::vector<Shape> shapes;        ///< one per mesh primitive and node instance; Shape::material
                                    ///< indexes `materials`
  std::vector<Material> materials;  ///< TextureRef::image indexes `images`
  std::vector<std::shared_ptr<const MipChain>> images;
  std::vector<Camera> cameras;      ///< the file's cameras, in file order, placed by their nodes
  size_t triangles = 0;
};

/// Largest number of elements an accessor may declare (checked against the buffers before
/// Assimp reads them).
inline constexpr long long kMaxGltfAccessorCount = 1ll << 27;

/// Loads a glTF 2.0 file. Throws UserError naming the file and the part at fault for: a file
/// that is not glTF 2.0, a missing or short buffer, a buffer view or accessor beyond its
/// buffer, an accessor count above kMaxGltfAccessorCount, an index beyond its vertices,
/// NaN/Inf or |x| > 1e8 vertex positions, an image that does not decode, and every feature
/// aalab does not render (named: required or used extensions other than KHR_materials_unlit,
/// animations, skins, morph targets, vertex colours, points and lines, a second texture
/// coordinate set, nearest-neighbour sampler filters).
GltfContent LoadGltf(const std::string& path);

}  // namespace aalab
