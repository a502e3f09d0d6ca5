// Conformance: every glTF 2.0 file of Debian's assimp-testmodels (the Khronos sample models
// and the Assimp project's invalid-file fixtures) is either loaded or refused with the rule
// the Khronos validator names for it. Load only, no render (fast).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

#include "core/error.h"
#include "scenes/gltf_load.h"
#include "tests/skip_or_fail.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

const char* kModels = "/usr/share/assimp/models/glTF2";

/// What each file must give: "" loads; otherwise a substring of the refusal.
const std::map<std::string, std::string>& Expected() {
  static const std::map<std::string, std::string> k = {
      {"2CylinderEngine-glTF-Binary/2CylinderEngine.glb", ""},
      {"BoxBadNormals-glTF-Binary/BoxBadNormals.glb", ""},
      {"BoxTexcoords-glTF/boxTexcoords.gltf", ""},
      {"BoxTextured-glTF-Binary/BoxTextured.glb", ""},
      {"BoxTextured-glTF-Embedded/BoxTextured.gltf", ""},
      {"BoxTextured-glTF-pbrSpecularGlossiness/BoxTextured.gltf", ""},
      {"BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf", "KHR_technique_webgl"},
      {"BoxTextured-glTF/BoxTextured.gltf", ""},
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "NaN, infinite"},
      {"ClearCoat-glTF/ClearCoatTest.gltf", ""},
      {"IncorrectVertexArrays/Cube.gltf", "rule: buffer view bounds"},
      {"IndexOutOfRange/AllIndicesOutOfRange.gltf", "rule: index out of range"},
      {"IndexOutOfRange/IndexOutOfRange.gltf", "rule: index out of range"},
      {"MissingBin/BoxTextured.gltf", "not found"},
      {"RecursiveNodes/RecursiveNodes.gltf", "rule: recursive nodes"},
      {"SchemaFailures/sceneWrongType.gltf", "at /scene: must be an integer"},
      {"TestNoRootNode/NoScene.gltf", "at /scene: names scene 0, which does not exist"},
      {"TestNoRootNode/SceneWithoutNodes.gltf", "no triangles"},
      {"cameras/Cameras.gltf", ""},
      {"draco/2CylinderEngine.gltf", ""},
      {"glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf", ""},
      {"issue_3269/texcoord_crash.gltf", ""},
      {"simple_skin/simple_skin.gltf", ""},
      {"textureTransform/TextureTransformTest.gltf", ""},
      {"wrongTypes/badArray.gltf", "at /meshes/0/primitives: must be an array"},
      {"wrongTypes/badExtension.gltf", "KHR_texture_transform: must be an object"},
      {"wrongTypes/badNumber.gltf", "at /materials/0/normalTexture/index: is required"},
      {"wrongTypes/badObject.gltf", "at /materials/0/pbrMetallicRoughness: must be an object"},
      {"wrongTypes/badString.gltf", "/name: must be a string"},
      {"wrongTypes/badUint.gltf", "names textures -1, which does not exist (1 defined) (rule: index out of range)"},
  };
  return k;
}

TEST(GltfConformance, EveryTestModelLoadsOrIsRefusedWithItsRule) {
  if (!fs::is_directory(kModels))
    AALAB_SKIP_OR_FAIL_UNDER_CI("assimp-testmodels is not installed (apt-get install assimp-testmodels)");
  int seen = 0;
  for (const auto& e : fs::recursive_directory_iterator(kModels)) {
    const std::string ext = e.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    const std::string rel = fs::relative(e.path(), kModels).string();
    std::string message;
    const auto t0 = std::chrono::steady_clock::now();
    size_t tris = 0;
    try {
      tris = LoadGltf(e.path().string()).triangles;
    } catch (const UserError& err) {
      message = err.what();
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-70s %-8s %8zu tris %8.1f ms %s\n", rel.c_str(), message.empty() ? "loaded" : "refused", tris, ms,
                message.c_str());
    // The glTF-Asset-Generator primitive-mode files: triangles load, points and lines only
    // are refused as having nothing to draw.
    std::string want;
    if (rel.find("Mesh_PrimitiveMode") != std::string::npos) {
      want = message.empty() ? "" : "no triangles";
    } else {
      auto it = Expected().find(rel);
      ASSERT_NE(it, Expected().end()) << "no expectation for " << rel << " (" << message << ")";
      want = it->second;
    }
    ++seen;
    if (want.empty()) {
      EXPECT_TRUE(message.empty()) << rel << ": " << message;
    } else {
      EXPECT_NE(message.find(want), std::string::npos) << rel << ": expected '" << want << "', got '" << message << "'";
      EXPECT_NE(message.find(e.path().string()), std::string::npos) << "the message names the file: " << message;
    }
  }
  EXPECT_GE(seen, 46);
}

}  // namespace
}  // namespace aalab
