#include <gtest/gtest.h>

#include "scene_test_util.h"
#include "scenes/library.h"

namespace aalab {
namespace {
using testing::MakeScene;
using testing::ParseError;
using testing::ParseText;

const std::string kWhite = R"({"w": {"shading": "unlit", "color": [1,1,1]}})";
const std::string kQuad = R"([{"shape": "quad", "size": [2,2], "material": "w"}])";

void ExpectError(const std::string& json, const std::vector<std::string>& parts) {
  const std::string e = ParseError(json);
  ASSERT_FALSE(e.empty()) << "expected a validation error";
  for (const auto& p : parts) EXPECT_NE(e.find(p), std::string::npos) << "message: " << e << "\nmissing: " << p;
}

TEST(SceneParse, MinimalSceneParses) {
  const Scene s = ParseText(MakeScene(R"(["unlit"])", kWhite, kQuad));
  EXPECT_EQ(s.name, "t");
  EXPECT_TRUE(s.Has(Effect::kUnlit));
  EXPECT_FALSE(s.Has(Effect::kShadows));
  ASSERT_EQ(s.shapes.size(), 1u);
  EXPECT_EQ(s.shapes[0].triangles.size(), 2u);
}

TEST(SceneParse, EveryLibrarySceneParsesAndDescribesItself) {
  const auto names = LibrarySceneNames();
  for (const char* want : {"wedges", "circle", "thin-wires", "checker-plane", "specular-spheres", "detail-texture",
                           "shadow-stipple", "hdr-edges", "mesh"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  }
  for (const auto& n : names) {
    const Scene s = LoadScene(n);
    EXPECT_EQ(s.name, n);
    EXPECT_FALSE(s.description.empty()) << n;
  }
  EXPECT_EQ(SuiteScenes("default").size() + SuiteScenes("hard").size(), names.size());
  EXPECT_FALSE(SuiteScenes("quick").empty());
}

TEST(SceneParse, SyntaxAndTypeErrorsNameThePath) {
  ExpectError("{\"name\": ", {"test.json", "not valid JSON"});
  ExpectError(MakeScene(R"(["unlit"])", kWhite, R"([{"shape": "quad", "size": "big", "material": "w"}])"),
              {"/objects/0/size", "expected an array of 2 numbers", "\"big\""});
  ExpectError(MakeScene(R"(["unlit"])", kWhite, R"([{"shape": "sphere", "radius": -1, "material": "w"}])"),
              {"/objects/0/radius", "-1", "out of range"});
  ExpectError(MakeScene(R"(["unlit"])", kWhite, R"([{"shape": "sphere", "material": "w"}])"),
              {"/objects/0", "missing required field 'radius'"});
  ExpectError(MakeScene(R"(["unlit"])", kWhite, R"([{"shape": "cone", "material": "w"}])"),
              {"/objects/0/shape", "'cone'", "quad, plane, polygon"});
  ExpectError(MakeScene(R"(["unlit"])", kWhite, R"([{"shape": "quad", "size": [1,1], "material": "w", "colour": 1}])"),
              {"unknown field 'colour'"});
  ExpectError(MakeScene(R"(["unlit"])", kWhite, R"([{"shape": "quad", "size": [1,1], "material": "x"}])"),
              {"/objects/0/material", "unknown material 'x'", "defined: w"});
  ExpectError(MakeScene(R"(["unlit"])", kWhite, R"([{"shape": "quad", "size": [0,1], "material": "w"}])"),
              {"/objects/0/size", "> 0"});
  ExpectError(MakeScene(R"(["unlit"])", kWhite, R"([{"shape": "mesh", "file": "nope.obj", "material": "w"}])"),
              {"/objects/0/file", "nope.obj", "not found"});
  ExpectError(MakeScene(R"(["unlit"])", kWhite,
                        R"([{"shape": "polygon", "points": [[0,0,0],[2,0,0],[0.5,0.5,0],[0,2,0]], "material": "w"}])"),
              {"/objects/0/points", "not convex"});
  ExpectError(MakeScene(R"(["unlit"])", kWhite,
                        R"([{"shape": "sphere", "radius": 1, "material": "w", "transform": {"scale": [1,2,1]}}])"),
              {"/objects/0/transform", "uniform scale"});
}

TEST(SceneParse, CameraErrors) {
  ExpectError(R"({"name": "t", "effects": ["unlit"], "camera": {"type": "fisheye", "position": [0,0,1], "look_at": [0,0,0]},
                 "materials": {"w": {"shading": "unlit"}}, "objects": [{"shape": "quad", "size": [1,1], "material": "w"}]})",
              {"/camera/type", "perspective, orthographic"});
  ExpectError(R"({"name": "t", "effects": ["unlit"], "camera": {"type": "perspective", "position": [0,0,1], "look_at": [0,0,1], "fov_y": 40},
                 "materials": {"w": {"shading": "unlit"}}, "objects": [{"shape": "quad", "size": [1,1], "material": "w"}]})",
              {"/camera/look_at", "equals position"});
  ExpectError(R"({"name": "t", "effects": ["unlit"], "camera": {"type": "perspective", "position": [0,0,1], "look_at": [0,0,0], "fov_y": 180},
                 "materials": {"w": {"shading": "unlit"}}, "objects": [{"shape": "quad", "size": [1,1], "material": "w"}]})",
              {"/camera/fov_y", "180", "out of range"});
}

TEST(SceneParse, UndeclaredEffectsAreErrorsNotDowngrades) {
  const std::string textured = R"({"w": {"shading": "unlit", "texture": {"pattern": "checker"}}})";
  ExpectError(MakeScene(R"(["unlit"])", textured, kQuad), {"/materials/w/texture", "needs effect 'textures'"});
  const std::string lit = R"({"w": {"shading": "lambert"}})";
  const std::string shadow_light = R"(, "lights": [{"type": "directional", "direction": [0,0,-1], "shadows": true}])";
  ExpectError(MakeScene(R"(["lambert"])", lit, kQuad, shadow_light), {"/lights/0/shadows", "needs effect 'shadows'"});
  ExpectError(MakeScene(R"(["unlit"])", lit, kQuad, shadow_light), {"needs effect 'lambert'"});
  const std::string spec = R"({"w": {"shading": "lambert", "specular": [1,1,1], "shininess": 50}})";
  const std::string light = R"(, "lights": [{"type": "directional", "direction": [0,0,-1]}])";
  ExpectError(MakeScene(R"(["lambert"])", spec, kQuad, light), {"needs effect 'specular'"});
  const std::string cut = R"({"w": {"shading": "unlit", "alpha": {"pattern": "stripes"}}})";
  ExpectError(MakeScene(R"(["unlit"])", cut, kQuad), {"needs effect 'alpha_test'"});
}

TEST(SceneParse, DeclaredButUnusedEffectIsAnError) {
  ExpectError(MakeScene(R"(["unlit", "textures"])", kWhite, kQuad), {"/effects", "'textures' is declared but nothing"});
  ExpectError(MakeScene(R"(["unlit", "unlit"])", kWhite, kQuad), {"declared twice"});
  ExpectError(MakeScene(R"(["unlit", "raytraced-gi"])", kWhite, kQuad), {"'raytraced-gi' is not allowed", "alpha_test"});
}

TEST(SceneParse, TransformsApply) {
  const Scene s = ParseText(MakeScene(
      R"(["unlit"])", kWhite,
      R"([{"shape": "quad", "size": [2,2], "material": "w", "transform": {"translate": [1,2,3], "rotate": [0,0,90], "scale": 2}},
          {"shape": "sphere", "radius": 0.5, "material": "w", "transform": {"translate": [0,0,-1], "scale": 3}}])"));
  // Quad corner (-1,-1,0) → scale 2 → (-2,-2,0) → rotate 90° about Z → (2,-2,0) → translate → (3,0,3).
  EXPECT_NEAR(s.shapes[0].positions[0].x, 3.0f, 1e-5);
  EXPECT_NEAR(s.shapes[0].positions[0].y, 0.0f, 1e-5);
  EXPECT_NEAR(s.shapes[0].positions[0].z, 3.0f, 1e-5);
  EXPECT_NEAR(s.shapes[1].radius, 1.5f, 1e-6);
  EXPECT_NEAR(s.shapes[1].center.z, -1.0f, 1e-6);
}

TEST(SceneParse, LoadSceneErrorsListLibrary) {
  try {
    LoadScene("no-such-scene");
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("wedges"), std::string::npos);
  }
  EXPECT_THROW(LoadScene("/nonexistent/scene.json"), UserError);
  EXPECT_THROW(SuiteScenes("nope"), UserError);
}

}  // namespace
}  // namespace aalab
