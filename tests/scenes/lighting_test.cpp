// Lighting (docs/lighting.md) against values worked out by hand: the white furnace (a white
// Lambert sphere in a uniform environment shades to the environment's radiance; a white GGX
// surface with F0 = 1 approaches it as roughness falls), SH9 irradiance of environments whose
// irradiance has a closed form, a point light's inverse-square falloff and a spot light's cone
// (KHR_lights_punctual's reference formula), the π migration of light units, glTF node world
// matrices and punctual lights, and the Toksvig roughness of a known normal distribution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scene_test_util.h"
#include "scenes/gltf_lights.h"
#include "scenes/ibl.h"
#include "scenes/library.h"
#include "scenes/toksvig.h"
#include "scenes/tracer.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;
using testing::MakeScene;
using testing::ParseError;
using testing::ParseText;
constexpr double kPi = 3.14159265358979323846;

/// Radiance the tracer returns at continuous pixel position (x, y) of a 4 × 4 frame (the test
/// scenes' orthographic camera spans [-2, 2]² of the z = 0 plane: x_world = x − 2, y_world = 2 − y).
glm::vec3 RadianceAt(const Scene& s, float x, float y) {
  Tracer tracer(s);
  SamplePos p;
  p.x = x;
  p.y = y;
  SampleResult r;
  TraceCounters c;
  tracer.Trace(&p, 1, 4, 4, &r, &c);
  return {r.rgb[0], r.rgb[1], r.rgb[2]};
}

TEST(Lighting, WhiteFurnaceLambertSphereShadesToTheEnvironment) {
  // A white Lambert sphere in a uniform environment of radiance L reflects exactly L at every
  // normal: E(n) = πL, and ρE/π = L for ρ = 1.
  const Scene s = ParseText(MakeScene(R"(["lambert"])", R"({"w": {"shading": "lambert", "color": [1, 1, 1]}})",
                                      R"([{"shape": "sphere", "radius": 1.5, "material": "w"}])",
                                      R"(, "environment": {"map": [0.5, 0.25, 2.0]})"));
  for (const auto& xy : {std::pair<float, float>{2.0f, 2.0f}, {3.1f, 2.4f}, {1.0f, 1.2f}, {2.3f, 3.3f}}) {
    const glm::vec3 c = RadianceAt(s, xy.first, xy.second);
    EXPECT_NEAR(c.x, 0.5f, 1e-4f);
    EXPECT_NEAR(c.y, 0.25f, 1e-4f);
    EXPECT_NEAR(c.z, 2.0f, 4e-4f);
  }
  // intensity scales it; outside the sphere the background stays.
  const Scene s2 =
      ParseText(MakeScene(R"(["lambert"])", R"({"w": {"shading": "lambert", "color": [0.5, 0.5, 0.5]}})",
                          R"([{"shape": "sphere", "radius": 1.5, "material": "w"}])",
                          R"(, "background": [0.1, 0.2, 0.3], "environment": {"map": [1, 1, 1], "intensity": 3})"));
  EXPECT_NEAR(RadianceAt(s2, 2.0f, 2.0f).x, 1.5f, 2e-4f);
  EXPECT_FLOAT_EQ(RadianceAt(s2, 0.1f, 0.1f).z, 0.3f);
}

TEST(Lighting, WhiteFurnaceGgxApproachesTheEnvironment) {
  // F0 = 1: ∫ f cos = A + B, the GGX lobe's directional albedo, below 1 (single scattering)
  // and approaching 1 as roughness falls; at normal incidence it falls with roughness.
  float prev = 2.0f;
  for (float r : {0.02f, 0.1f, 0.3f, 0.6f, 1.0f}) {
    const glm::vec2 ab = IntegrateBrdf(1.0f, r, 4096);
    const float albedo = ab.x + ab.y;
    EXPECT_LE(albedo, 1.0005f) << r;
    EXPECT_LT(albedo, prev) << r;
    prev = albedo;
  }
  EXPECT_GT(IntegrateBrdf(1.0f, 0.02f, 4096).x + IntegrateBrdf(1.0f, 0.02f, 4096).y, 0.995f);
  // At roughness 1 (α = 1, D = 1/π) and normal incidence the albedo has a closed form:
  // ∫ G1(l)/(4π) dω = (1/(4π))·2π·∫₀¹ 2μ/(μ + 1) dμ = 1 − ln 2 (separable Smith-GGX).
  const glm::vec2 rough = IntegrateBrdf(1.0f, 1.0f, 4096);
  EXPECT_NEAR(rough.x + rough.y, 1.0 - std::log(2.0), 2e-3);
  // A uniform environment's prefilter is the environment at every roughness (weights are
  // normalised), so the specular IBL of a white F0 = 1 surface is L·(A + B).
  EquirectMap m;
  m.width = 64;
  m.height = 32;
  m.texels.assign(64 * 32, glm::vec3(0.7f));
  const auto env = MakeEnvironment(m, "uniform", 1.0f, 0.0f);
  for (float r : {0.0f, 0.25f, 0.5f, 0.9f}) {
    const glm::vec3 c = IblShadePbr(*env, {0, 0, 1}, {0, 0, 1}, 1.0f, glm::vec3(0.0f), glm::vec3(1.0f), r);
    const glm::vec2 ab = BrdfLut(1.0f, r);
    EXPECT_NEAR(c.x, 0.7f * (ab.x + ab.y), 1e-5f) << r;
    if (r <= 0.25f) {
      EXPECT_GT(c.x, 0.7f * 0.95f) << r;
    }
    EXPECT_LE(c.x, 0.7f * 1.0005f) << r;
  }
  // The diffuse part of a white dielectric-free surface (c_diff = 1) is L (the Lambert furnace).
  const glm::vec3 d = IblShadePbr(*env, {0, 1, 0}, {0, 1, 0}, 1.0f, glm::vec3(1.0f), glm::vec3(0.0f), 0.5f);
  EXPECT_NEAR(d.x, 0.7f, 1e-4f);
}

EquirectMap MapOf(int w, int h, const std::function<glm::vec3(glm::vec3)>& f) {
  EquirectMap m;
  m.width = w;
  m.height = h;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) m.texels.push_back(f(EquirectDirection((i + 0.5f) / w, (j + 0.5f) / h)));
  }
  return m;
}

TEST(Lighting, Sh9IrradianceMatchesClosedForms) {
  // L(d) = 1 + 0.5·d.y: E(n) = ∫ L (n·l)+ dl = π + (2π/3)·0.5·n.y (the constant's π and the
  // linear term's Â_1 = 2π/3, both exact in bands 0-1).
  const auto grad = ProjectSh9(MapOf(256, 128, [](glm::vec3 d) { return glm::vec3(1.0f + 0.5f * d.y); }));
  for (glm::vec3 n :
       {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::normalize(glm::vec3(1, 1, -2)), glm::vec3(1, 0, 0)}) {
    EXPECT_NEAR(Sh9Irradiance(grad, n).x, kPi + (2.0 * kPi / 3.0) * 0.5 * n.y, 2e-3) << n.x << " " << n.y;
  }
  // The upper hemisphere uniformly bright (a sky of radiance 1 above black ground): exact
  // irradiance π(1 + cos θ)/2; nine bands hold it exactly at the pole, the horizon and below
  // (the l = 2 coefficients of a step in y vanish).
  const auto sky = ProjectSh9(MapOf(256, 128, [](glm::vec3 d) { return glm::vec3(d.y > 0.0f ? 1.0f : 0.0f); }));
  EXPECT_NEAR(Sh9Irradiance(sky, {0, 1, 0}).x, kPi, 3e-3);
  EXPECT_NEAR(Sh9Irradiance(sky, {1, 0, 0}).x, kPi / 2.0, 3e-3);
  EXPECT_NEAR(Sh9Irradiance(sky, {0, -1, 0}).x, 0.0, 3e-3);
  // Rotation turns the map about +Y: a map bright toward +X, rotated by 90°, is bright toward −Z.
  const auto xmap = MapOf(64, 32, [](glm::vec3 d) { return glm::vec3(d.x > 0.0f ? 1.0f : 0.0f); });
  const auto env = MakeEnvironment(xmap, "x", 1.0f, 90.0f);
  EXPECT_GT(env->Diffuse({0, 0, -1}).x, 0.9f);
  EXPECT_LT(env->Diffuse({0, 0, 1}).x, 0.1f);
}

const std::string kQuad = R"([{"shape": "quad", "size": [100, 100], "material": "w"}])";
const std::string kLambert = R"({"w": {"shading": "lambert", "color": [0.5, 0.5, 0.5]}})";

TEST(Lighting, PointLightFallsOffWithTheInverseSquare) {
  // 100 cd at height 2 over a white (ρ = 0.5) plane: directly below E = 100/4 lux and L = ρE/π;
  // at x = 1.5, d² = 6.25 and cos θ = 2/2.5, so E = 100/6.25 · 0.8.
  const Scene s = ParseText(
      MakeScene(R"(["lambert"])", kLambert, kQuad,
                R"(, "light_units": "gltf", "lights": [{"type": "point", "position": [0, 0, 2], "intensity": 100}])"));
  EXPECT_NEAR(RadianceAt(s, 2.0f, 2.0f).x, 0.5 * 25.0 / kPi, 1e-4);
  EXPECT_NEAR(RadianceAt(s, 3.5f, 2.0f).x, 0.5 * (100.0 / 6.25 * 0.8) / kPi, 1e-4);
  // range 3: the specification's window clamp(1 − (d/range)⁴, 0, 1) on top of 1/d².
  const Scene r = ParseText(MakeScene(
      R"(["lambert"])", kLambert, kQuad,
      R"(, "light_units": "gltf", "lights": [{"type": "point", "position": [0, 0, 2], "intensity": 100, "range": 3}])"));
  const double win = 1.0 - std::pow(2.5 / 3.0, 4.0);
  EXPECT_NEAR(RadianceAt(r, 3.5f, 2.0f).x, 0.5 * (100.0 / 6.25 * 0.8) / kPi * win, 1e-4);
}

TEST(Lighting, SpotConeFollowsTheSpecificationsSmoothFalloff) {
  // A spot at height 1 pointing down, inner 10°, outer 30°. At horizontal offset x the angle
  // off-axis is atan(x): inside the inner cone full intensity, outside the outer cone none,
  // between them s = ((cos φ − cos 30°)/(cos 10° − cos 30°))².
  const Scene s = ParseText(MakeScene(
      R"(["lambert"])", kLambert, kQuad,
      R"(, "light_units": "gltf", "lights": [{"type": "spot", "position": [0, 0, 1], "direction": [0, 0, -1], "intensity": 10, "inner_cone_deg": 10, "outer_cone_deg": 30}])"));
  auto expected = [](double x) {
    const double d2 = 1.0 + x * x, cosphi = 1.0 / std::sqrt(d2);
    const double ci = std::cos(10.0 * kPi / 180.0), co = std::cos(30.0 * kPi / 180.0);
    double t = std::clamp((cosphi - co) / (ci - co), 0.0, 1.0);
    return 0.5 * (10.0 / d2 * cosphi) / kPi * t * t;
  };
  EXPECT_NEAR(RadianceAt(s, 2.0f, 2.0f).x, 0.5 * 10.0 / kPi, 1e-4);  // on the axis
  const double x20 = std::tan(20.0 * kPi / 180.0);                   // 20° off-axis
  EXPECT_NEAR(RadianceAt(s, 2.0f + static_cast<float>(x20), 2.0f).x, expected(x20), 1e-4);
  EXPECT_GT(expected(x20), 0.05);
  EXPECT_LT(expected(x20), 0.5 * 10.0 / kPi * 0.9);
  EXPECT_EQ(RadianceAt(s, 2.0f, 2.0f - 0.7f).x, 0.0f);  // 35° off-axis: outside the cone
}

TEST(Lighting, LightUnitsAreRequiredAndMigrateWithPi) {
  const std::string light = R"("lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": 2.5}])";
  const std::string msg = ParseError(MakeScene(R"(["lambert"])", kLambert, kQuad, ", " + light));
  EXPECT_NE(msg.find("light_units"), std::string::npos) << msg;
  EXPECT_NE(msg.find("multiply each light's intensity by pi"), std::string::npos) << msg;
  EXPECT_NE(msg.find("aalab-pi"), std::string::npos) << msg;
  // The old value under "aalab-pi" and π × it under "gltf" give the same light, bit for bit.
  const Scene old = ParseText(MakeScene(R"(["lambert"])", kLambert, kQuad, R"(, "light_units": "aalab-pi", )" + light));
  const Scene now = ParseText(MakeScene(
      R"(["lambert"])", kLambert, kQuad,
      R"(, "light_units": "gltf", "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": 7.853982}])"));
  EXPECT_EQ(old.lights[0].intensity, 2.5f);
  EXPECT_EQ(now.lights[0].intensity, 2.5f);
  // glTF units: a white Lambert plane under E = 1 lux reflects 1/π.
  const Scene lux = ParseText(MakeScene(
      R"(["lambert"])", R"({"w": {"shading": "lambert", "color": [1, 1, 1]}})", kQuad,
      R"(, "light_units": "gltf", "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": 1}])"));
  EXPECT_NEAR(RadianceAt(lux, 2.0f, 2.0f).x, 1.0 / kPi, 1e-6);
  EXPECT_NE(ParseError(MakeScene(R"(["lambert"])", kLambert, kQuad, R"(, "ambient": [1,1,1], "light_units": "gltf")"))
                .find("light_units without lights"),
            std::string::npos);
  EXPECT_NE(
      ParseError(MakeScene(R"(["lambert"])", kLambert, kQuad, R"(, "light_units": "watts", )" + light)).find("gltf"),
      std::string::npos);
  // The library's migrated scenes keep their pre-migration intensities exactly.
  const Scene glossy = LoadSceneFile(SceneLibraryDir() + "/real-glossy.json");
  EXPECT_EQ(glossy.lights[0].intensity, 6.0f);
  const Scene spheres = LoadSceneFile(SceneLibraryDir() + "/specular-spheres.json");
  EXPECT_EQ(spheres.lights[0].intensity, 2.5f);
  EXPECT_EQ(spheres.lights[1].intensity, 1.2f);
}

TEST(Lighting, EnvironmentFieldIsValidated) {
  auto err = [](const std::string& env) {
    return ParseError(MakeScene(R"(["lambert"])", kLambert, kQuad, R"(, "environment": )" + env));
  };
  EXPECT_NE(err(R"({"map": "nope.exr"})").find("not found"), std::string::npos);
  EXPECT_NE(err(R"({"intensity": 1})").find("needs a \"map\""), std::string::npos);
  EXPECT_NE(err(R"({"map": "studio", "rotation_deg": 400})").find("/environment/rotation_deg"), std::string::npos);
  EXPECT_NE(err(R"({"map": [1, -1, 1]})").find("/environment/map"), std::string::npos);
  EXPECT_NE(err(R"({"map": "studio", "blur": 1})").find("blur"), std::string::npos);
  EXPECT_EQ(err(R"({"map": "studio", "intensity": 0.5, "rotation_deg": -90})"), "");
}

/// Writes a w × h RGB float image (EXR or Radiance HDR by extension) holding `px`.
void WriteFloatImage(const std::string& path, int w, int h, const std::vector<float>& px) {
  auto out = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, px.data()) && out->close());
}

TEST(Lighting, EnvironmentMapsAreReadThroughIo) {
  // A 4 × 2 map, asymmetric in x and y, as EXR (float: exact) and Radiance HDR (RGBE: one
  // shared 8-bit exponent; these values, a mantissa of at most 8 bits under the largest
  // channel, are exact too: 2 = 128·2^-6, 0.5 = 32·2^-6).
  const std::vector<float> px = {1, 2, 0.5f, 0, 0, 0, 4, 4,    4,     0.25f, 0.5f, 1,
                                 8, 1, 0.5f, 2, 2, 0, 1, 0.5f, 0.25f, 16,    8,    4};
  const fs::path dir = testenv::ScratchDir("envmap");
  for (const char* ext : {".exr", ".hdr"}) {
    const std::string path = (dir / (std::string("env") + ext)).string();
    WriteFloatImage(path, 4, 2, px);
    const EquirectMap m = ReadEquirect(path);
    ASSERT_EQ(m.width, 4);
    ASSERT_EQ(m.height, 2);
    for (size_t t = 0; t < 8; ++t) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(m.texels[t][c], px[3 * t + c]) << ext << " texel " << t << " channel " << c;
    }
  }
  // Not twice as wide as high: refused from the header, naming the rule.
  const std::string square = (dir / "square.exr").string();
  WriteFloatImage(square, 2, 2, std::vector<float>(12, 1.0f));
  try {
    ReadEquirect(square);
    ADD_FAILURE() << "a 2 x 2 map was read";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("is 2 x 2: an equirectangular map is twice as wide as high"),
              std::string::npos)
        << e.what();
  }
  // A negative texel at (1, 0), and a file that is not an image (io's message, prefixed).
  std::vector<float> neg(24, 1.0f);
  neg[3 * 1 + 2] = -1.0f;
  const std::string bad = (dir / "neg.exr").string();
  WriteFloatImage(bad, 4, 2, neg);
  const std::string junk = (dir / "junk.hdr").string();
  std::ofstream(junk) << "not an image";
  for (const auto& [path, want] : {std::pair<std::string, std::string>{bad, "negative texel at (1, 0)"},
                                   {junk, "environment map '" + junk + "' could not be read: "}}) {
    try {
      ReadEquirect(path);
      ADD_FAILURE() << path << " was read";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    }
  }
}

TEST(Lighting, StudioEnvironmentIsDeterministicAndNeutral) {
  const EquirectMap a = StudioEnvironment(), b = StudioEnvironment();
  ASSERT_EQ(a.texels.size(), b.texels.size());
  EXPECT_EQ(std::memcmp(a.texels.data(), b.texels.data(), a.texels.size() * sizeof(glm::vec3)), 0);
  // Brighter above than below; the key light is the brightest spot.
  const auto sh = ProjectSh9(a);
  EXPECT_GT(Sh9Irradiance(sh, {0, 1, 0}).x, Sh9Irradiance(sh, {0, -1, 0}).x);
  EXPECT_GT(SampleEquirect(a, glm::normalize(glm::vec3(-0.55f, 0.65f, 0.55f))).x, 10.0f);
}

TEST(GltfLights, NodeWorldMatricesComposeParentsIteratively) {
  // Root 0 translates by (1, 2, 3) and turns 90° about +Y; child 1 translates by (0, 0, -2)
  // in its parent's frame: world position (1, 2, 3) + R_y(90°)·(0, 0, −2) = (1 − 2, 2, 3).
  const double h = std::sqrt(0.5);
  nlohmann::json g = {{"scenes", {{{"nodes", {0}}}}},
                      {"nodes",
                       {{{"translation", {1, 2, 3}}, {"rotation", {0, h, 0, h}}, {"children", {1}}},
                        {{"translation", {0, 0, -2}}},
                        {{"translation", {9, 9, 9}}}}}};
  const auto w = GltfNodeWorldMatrices(g);
  ASSERT_EQ(w.size(), 3u);
  ASSERT_TRUE(w[0] && w[1]);
  EXPECT_FALSE(w[2]);  // not in the displayed scene
  const glm::vec3 p = glm::vec3((*w[1])[3]);
  EXPECT_NEAR(p.x, -1.0f, 1e-5f);
  EXPECT_NEAR(p.y, 2.0f, 1e-5f);
  EXPECT_NEAR(p.z, 3.0f, 1e-5f);
  // A cycle is refused with the path where it closes.
  g["nodes"][1]["children"] = {0};
  try {
    GltfNodeWorldMatrices(g);
    FAIL() << "a cycle was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("/nodes/1/children/0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reached twice"), std::string::npos) << e.what();
  }
}

TEST(GltfLights, PunctualLightsArriveInTheSpecificationsUnits) {
  const double h = std::sqrt(0.5);
  // A spot on a node turned −90° about X (its −Z now points down, −Y), 5 m up.
  nlohmann::json g = nlohmann::json::parse(R"({
    "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"translation": [0, 5, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
              {"extensions": {"KHR_lights_punctual": {"light": 1}}}],
    "extensions": {"KHR_lights_punctual": {"lights": [
      {"type": "spot", "intensity": 314.159265, "color": [1, 0.5, 0.25], "range": 20,
       "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}},
      {"type": "directional", "intensity": 3.14159265}]}}})");
  g["nodes"][0]["rotation"] = {-h, 0, 0, h};
  const std::vector<Light> ls = GltfPunctualLights(g);
  ASSERT_EQ(ls.size(), 2u);
  EXPECT_EQ(ls[0].type, LightType::kSpot);
  EXPECT_NEAR(ls[0].intensity, 100.0f, 1e-4f);  // candela / π
  EXPECT_NEAR(ls[0].position.y, 5.0f, 1e-6f);
  EXPECT_NEAR(ls[0].direction.y, -1.0f, 1e-6f);
  EXPECT_NEAR(ls[0].cos_inner, std::cos(0.2), 1e-7);
  EXPECT_NEAR(ls[0].cos_outer, std::cos(0.6), 1e-7);
  EXPECT_EQ(ls[0].range, 20.0f);
  EXPECT_EQ(ls[0].color.y, 0.5f);
  EXPECT_EQ(ls[1].type, LightType::kDirectional);
  EXPECT_NEAR(ls[1].intensity, 1.0f, 1e-6f);  // lux / π
  EXPECT_NEAR(ls[1].direction.z, -1.0f, 1e-6f);
  // Malformed: cone angles out of order, an unknown type, a node naming a missing light.
  auto err = [](nlohmann::json j) {
    try {
      GltfPunctualLights(j);
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  nlohmann::json bad = g;
  bad["extensions"]["KHR_lights_punctual"]["lights"][0]["spot"]["innerConeAngle"] = 0.7;
  EXPECT_NE(err(bad).find("/extensions/KHR_lights_punctual/lights/0/spot"), std::string::npos);
  bad = g;
  bad["extensions"]["KHR_lights_punctual"]["lights"][1]["type"] = "area";
  EXPECT_NE(err(bad).find("'area' is not a light type"), std::string::npos);
  bad = g;
  bad["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 7;
  EXPECT_NE(err(bad).find("/nodes/1/extensions/KHR_lights_punctual/light"), std::string::npos);
}

TEST(Toksvig, RoughnessOfAKnownNormalDistribution) {
  // A 2 × 2 normal map whose columns tilt ±30° about Y: level 1 averages them to
  // (0, 0, cos 30°), r = 0.8660254; κ = (3r − r³)/(1 − r²) = 7.794229; α² = 1/(2κ) = 0.0641500.
  const float s30 = 0.5f, c30 = 0.8660254f;
  MipLevel l0;
  l0.width = l0.height = 2;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const glm::vec3 n(i == 0 ? s30 : -s30, 0.0f, c30);
      // 8-bit encoded, as a PNG normal map stores it: the unit chain normalises the error away.
      glm::vec3 t = glm::round((n * 0.5f + 0.5f) * 255.0f) / 255.0f;
      l0.texels.push_back(glm::vec4(t, 1.0f));
    }
  }
  const MipChain unit = UnitNormalChain(BuildMipChain(l0, "test"));
  ASSERT_EQ(unit.levels.size(), 2u);
  EXPECT_NEAR(glm::length(glm::vec3(unit.levels[0].texels[0])), 1.0f, 1e-6f);
  EXPECT_EQ(ToksvigAlpha2(glm::length(glm::vec3(unit.levels[0].texels[0]))), 0.0f);
  const float r = glm::length(glm::vec3(unit.levels[1].texels[0]));
  EXPECT_NEAR(r, 0.8660254f, 3e-3f);
  EXPECT_NEAR(ToksvigAlpha2(0.8660254f), 0.0641500f, 1e-6f);
  EXPECT_EQ(ToksvigAlpha2(1.0f), 0.0f);
  EXPECT_EQ(ToksvigAlpha2(0.0f), 1.0f);
}

}  // namespace
}  // namespace aalab
