// The raster path's scene file (core/raster_geometry.h) and its export (scenes/raster_export.h):
// what wedges.json says, worked out from the file (9 quads 2.6 × 0.9, rotated about z by the
// listed angles, orthographic camera of height 9), survives the bytes unchanged; refusals.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/raster_geometry.h"
#include "scenes/library.h"
#include "scenes/raster_export.h"

namespace aalab {
namespace {

TEST(RasterGeometry, WedgesFromTheSceneFileSurviveTheBytes) {
  const RasterScene s = ParseRasterScene(RasterSceneBytes(RasterSceneOf(LoadScene("wedges"))), "test");
  EXPECT_EQ(s.name, "wedges");
  EXPECT_TRUE(s.orthographic);
  EXPECT_FLOAT_EQ(s.height, 9.0f);
  EXPECT_FLOAT_EQ(s.position[2], 10.0f);
  EXPECT_FLOAT_EQ(s.background[2], 0.025f);
  EXPECT_FALSE(s.lambert);
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_FLOAT_EQ(s.materials[0].color[0], 0.35f);  // materials in name order: grey, white
  EXPECT_FLOAT_EQ(s.materials[1].color[0], 0.9f);
  ASSERT_EQ(s.triangles.size(), 18u);  // 9 quads, two triangles each
  // Each corner of quad k lies at (±1.3, ±0.45) in the quad's own frame: translate, rotate.
  const double tx[9] = {-5.33, 0, 5.33, -5.33, 0, 5.33, -5.33, 0, 5.33};
  const double ty[9] = {3, 3, 3, 0, 0, 0, -3, -3, -3};
  const double deg[9] = {0.5, 2.0, 7.0, 18.0, 45.0, 63.0, 80.0, 87.5, 89.6};
  for (const auto& t : s.triangles) {
    const int k = t.shape;
    ASSERT_GE(k, 0);
    ASSERT_LT(k, 9);
    EXPECT_EQ(t.material, k % 2 == 0 ? 1 : 0);  // white, grey, white, ...
    EXPECT_FALSE(t.smooth);
    const double a = deg[k] * M_PI / 180.0;
    for (const auto& c : t.corners) {
      const double x = c.position[0] - tx[k], y = c.position[1] - ty[k];
      EXPECT_NEAR(std::fabs(std::cos(a) * x + std::sin(a) * y), 1.3, 1e-5);
      EXPECT_NEAR(std::fabs(-std::sin(a) * x + std::cos(a) * y), 0.45, 1e-5);
      EXPECT_FLOAT_EQ(c.position[2], 0.0f);
      // Flat: the face normal, along z for a quad in the z = 0 plane.
      EXPECT_FLOAT_EQ(c.normal[0], 0.0f);
      EXPECT_FLOAT_EQ(c.normal[1], 0.0f);
      EXPECT_NE(c.normal[2], 0.0f);
    }
  }
}

TEST(RasterGeometry, MeshKeepsItsLightAndLambert) {
  const RasterScene s = RasterSceneOf(LoadScene("mesh"));
  EXPECT_FALSE(s.orthographic);
  EXPECT_FLOAT_EQ(s.fov_y_deg, 40.0f);
  EXPECT_TRUE(s.lambert);
  EXPECT_EQ(s.triangles.size(), 3200u);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_NEAR(s.lights[0].direction[2], -0.7 / std::sqrt(0.25 + 0.36 + 0.49), 1e-6);  // normalised on load
  EXPECT_NEAR(s.lights[0].intensity, 1.0f, 1e-6f);  // 3.1415927 in glTF units, / π inside aalab
  EXPECT_TRUE(s.materials[0].lit);
}

// The procedural textures as checker-plane.json and detail-texture.json state them: the
// plane's corners at (±2000, 0, ±2000) with uv = (x, z) (scenes/shapes.cpp MakePlane), the
// quad's at (±10, ±6, 0) with uv = (x, y); the patterns' parameters through the bytes.
TEST(RasterGeometry, ProceduralTexturesSurviveTheBytes) {
  const RasterScene c = ParseRasterScene(RasterSceneBytes(RasterSceneOf(LoadScene("checker-plane"))), "test");
  ASSERT_EQ(c.materials.size(), 1u);
  const RasterTexture& ct = c.materials[0].texture;
  EXPECT_EQ(ct.pattern, 0);  // checker
  EXPECT_FLOAT_EQ(ct.scale, 1.0f);
  EXPECT_FLOAT_EQ(ct.color_a[1], 0.05f);
  EXPECT_FLOAT_EQ(ct.color_b[2], 0.85f);
  EXPECT_FALSE(c.materials[0].lit);
  ASSERT_EQ(c.triangles.size(), 2u);
  for (const auto& t : c.triangles) {
    for (const auto& k : t.corners) {
      EXPECT_FLOAT_EQ(std::fabs(k.position[0]), 2000.0f);
      EXPECT_FLOAT_EQ(k.position[1], 0.0f);
      EXPECT_FLOAT_EQ(std::fabs(k.position[2]), 2000.0f);
      EXPECT_FLOAT_EQ(k.uv[0], k.position[0]);
      EXPECT_FLOAT_EQ(k.uv[1], k.position[2]);
    }
  }
  const RasterScene d = ParseRasterScene(RasterSceneBytes(RasterSceneOf(LoadScene("detail-texture"))), "test");
  ASSERT_EQ(d.materials.size(), 1u);
  const RasterTexture& dt = d.materials[0].texture;
  EXPECT_EQ(dt.pattern, 2);  // noise
  EXPECT_FLOAT_EQ(dt.scale, 60.0f);
  EXPECT_EQ(dt.seed, 7u);
  EXPECT_FLOAT_EQ(dt.color_a[0], 0.08f);
  EXPECT_FLOAT_EQ(dt.color_b[1], 0.75f);
  for (const auto& t : d.triangles) {
    for (const auto& k : t.corners) {
      EXPECT_FLOAT_EQ(std::fabs(k.uv[0]), 10.0f);
      EXPECT_FLOAT_EQ(std::fabs(k.uv[1]), 6.0f);
      EXPECT_FLOAT_EQ(k.uv[1], k.position[1]);
    }
  }
  // A scene without textures carries none; a bad pattern number is refused.
  EXPECT_EQ(RasterSceneOf(LoadScene("wedges")).materials[0].texture.pattern, -1);
  RasterScene bad;
  bad.materials.resize(1);
  bad.materials[0].texture.pattern = 3;
  try {
    ParseRasterScene(RasterSceneBytes(bad), "bad.geom");
    ADD_FAILURE() << "pattern 3 was not refused";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("texture pattern is 3 (allowed: -1..2)"), std::string::npos) << e.what();
  }
}

// circle.json: one disk of radius 3.6 at the origin facing +z, under a point light at
// (0, −5.5, 2) of intensity 125.66371 / π: the two triangles of its bounding square, 1/16
// larger, carry the disk; the light keeps its type and position.
TEST(RasterGeometry, DiskBecomesAnImpostorAndThePointLightSurvives) {
  const RasterScene s = ParseRasterScene(RasterSceneBytes(RasterSceneOf(LoadScene("circle"))), "test");
  ASSERT_EQ(s.triangles.size(), 2u);
  for (const auto& t : s.triangles) {
    EXPECT_TRUE(t.disk);
    EXPECT_FLOAT_EQ(t.radius, 3.6f);
    EXPECT_FLOAT_EQ(t.center[0], 0.0f);
    for (const auto& c : t.corners) {
      EXPECT_FLOAT_EQ(std::fabs(c.position[0]), 3.6f * 1.0625f);
      EXPECT_FLOAT_EQ(std::fabs(c.position[1]), 3.6f * 1.0625f);
      EXPECT_FLOAT_EQ(c.normal[2], 1.0f);
      EXPECT_FLOAT_EQ(c.uv[0], c.position[0]);  // the disk's uv: d·tangent, d·(normal × tangent)
      EXPECT_FLOAT_EQ(c.uv[1], c.position[1]);
    }
  }
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, 1);  // point
  EXPECT_FLOAT_EQ(s.lights[0].position[1], -5.5f);
  EXPECT_FLOAT_EQ(s.lights[0].position[2], 2.0f);
  EXPECT_NEAR(s.lights[0].intensity, 125.66371 / M_PI, 1e-4);
  EXPECT_FLOAT_EQ(s.lights[0].range, 0.0f);
  EXPECT_FALSE(RasterSceneOf(LoadScene("wedges")).triangles[0].disk);
}

TEST(RasterGeometry, RefusalsNameTheSceneAndTheReason) {
  for (const auto& [name, reason] : std::vector<std::pair<std::string, std::string>>{
           {"thin-wires", "analytic shape"}, {"sdf-wires", "analytic shape"}, {"specular-spheres", "'specular'"}}) {
    try {
      RasterSceneOf(LoadScene(name));
      ADD_FAILURE() << name << " was not refused";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find("'" + name + "'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(ParseRasterScene("AALABRG2", "x"), UserError);      // truncated after the magic
  EXPECT_THROW(ParseRasterScene("NOTAFILE1234", "x"), UserError);  // wrong magic
  std::string bytes = RasterSceneBytes(RasterSceneOf(LoadScene("wedges")));
  EXPECT_THROW(ParseRasterScene(bytes + "x", "x"), UserError);  // trailing bytes
}

}  // namespace
}  // namespace aalab
