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

TEST(RasterGeometry, RefusalsNameTheSceneAndTheReason) {
  for (const auto& [name, reason] :
       std::vector<std::pair<std::string, std::string>>{{"circle", "analytic shape"},
                                                        {"checker-plane", "'textures'"},
                                                        {"shadow-stipple", "'shadows'"},
                                                        {"specular-spheres", "'specular'"}}) {
    try {
      RasterSceneOf(LoadScene(name));
      ADD_FAILURE() << name << " was not refused";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find("'" + name + "'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(ParseRasterScene("AALABRG1", "x"), UserError);      // truncated after the magic
  EXPECT_THROW(ParseRasterScene("NOTAFILE1234", "x"), UserError);  // wrong magic
  std::string bytes = RasterSceneBytes(RasterSceneOf(LoadScene("wedges")));
  EXPECT_THROW(ParseRasterScene(bytes + "x", "x"), UserError);  // trailing bytes
}

}  // namespace
}  // namespace aalab
