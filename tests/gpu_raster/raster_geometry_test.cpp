// The raster path's scene file (core/raster_geometry.h) and its export (scenes/raster_export.h):
// what wedges.json says, worked out from the file (9 quads 2.6 × 0.9, rotated about z by the
// listed angles, orthographic camera of height 9), survives the bytes unchanged; refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/raster_geometry.h"
#include "scenes/library.h"
#include "scenes/raster_export.h"
#include "scenes/texture_image.h"

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

// real-glossy.json: one glTF quad (2 triangles) with a normal map, a metallic-roughness
// texture and TANGENT. The file carries the glTF material as the Scene holds it, each image
// as aalab's own mip chain (byte for byte, each level half the one above down to 1 × 1), the
// decode tables aalab fetches with, and each corner's tangent.
TEST(RasterGeometry, GltfMaterialImagesAndTangentsSurviveTheBytes) {
  const Scene sc0 = LoadScene("real-glossy");
  const Scene* sc = &sc0;
  const RasterScene s = ParseRasterScene(RasterSceneBytes(RasterSceneOf(*sc)), "test");
  EXPECT_TRUE(s.textures);
  EXPECT_TRUE(s.normal_map);
  EXPECT_FALSE(s.alpha_test);
  ASSERT_EQ(s.materials.size(), sc->materials.size());
  ASSERT_EQ(s.triangles.size(), 2u);
  const Material& m = sc->materials[static_cast<size_t>(sc->shapes[0].material)];
  ASSERT_TRUE(m.gltf.has_value());
  const RasterMaterial& rm = s.materials[static_cast<size_t>(s.triangles[0].material)];
  ASSERT_TRUE(rm.gltf);
  EXPECT_FLOAT_EQ(rm.pbr.roughness, m.gltf->roughness);
  EXPECT_FLOAT_EQ(rm.pbr.metallic, m.gltf->metallic);
  EXPECT_FLOAT_EQ(rm.pbr.base_factor[0], m.gltf->base_factor.x);
  EXPECT_FLOAT_EQ(rm.pbr.normal_scale, m.gltf->normal_scale);
  EXPECT_EQ(rm.pbr.alpha_mode, 0);
  EXPECT_EQ(rm.pbr.base.image, -1);  // base colour factor only
  ASSERT_GE(rm.pbr.mr.image, 0);
  ASSERT_GE(rm.pbr.normal.image, 0);
  EXPECT_NE(rm.pbr.mr.image, rm.pbr.normal.image);
  EXPECT_EQ(s.images.size(), 2u);
  for (const auto& [ref, tex] : {std::pair{rm.pbr.mr, m.gltf->mr_tex}, std::pair{rm.pbr.normal, m.gltf->normal_tex}}) {
    const MipChain& chain = *sc->images[static_cast<size_t>(tex.image)];
    const RasterImage& img = s.images[static_cast<size_t>(ref.image)];
    EXPECT_EQ(img.format, 1);  // linear data (metallic-roughness, normals)
    EXPECT_EQ(ref.wrap_s, static_cast<int>(tex.wrap_s));
    ASSERT_EQ(img.levels.size(), chain.levels.size());
    EXPECT_EQ(img.levels.back().width, 1);
    EXPECT_EQ(img.levels.back().height, 1);
    for (size_t k = 0; k < img.levels.size(); ++k) {
      EXPECT_EQ(img.levels[k].width, chain.levels[k].width);
      EXPECT_TRUE(img.levels[k].rgba == chain.levels[k].bytes) << "level " << k;
    }
  }
  for (int k = 0; k < 256; ++k) {
    EXPECT_EQ(s.srgb_table[static_cast<size_t>(k)], Srgb8Table()[k]);
    EXPECT_EQ(s.unorm_table[static_cast<size_t>(k)], Unorm8Table()[k]);
  }
  EXPECT_FLOAT_EQ(s.srgb_table[255], 1.0f);
  EXPECT_NEAR(s.srgb_table[128], 0.21586, 1e-5);  // the sRGB EOTF of 128/255
  const Shape& shape = sc->shapes[0];
  ASSERT_FALSE(shape.tangents.empty());
  const glm::uvec3 t0 = shape.triangles[0];
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(s.triangles[0].corners[0].tangent[static_cast<size_t>(k)], shape.tangents[t0.x][k]);
    EXPECT_EQ(s.triangles[0].corners[2].tangent[static_cast<size_t>(k)], shape.tangents[t0.z][k]);
  }
  EXPECT_EQ(std::fabs(s.triangles[0].corners[0].tangent[3]), 1.0f);  // handedness ±1
}

// The default suite's fence and foliage: MASK materials with a base colour texture (sRGB),
// single- and double-sided as their files say; the alpha_test flag carried.
TEST(RasterGeometry, MaskMaterialsOfTheFenceAndFoliage) {
  for (const char* name : {"real-fence", "real-foliage"}) {
    const Scene sc0 = LoadScene(name);
    const Scene* sc = &sc0;
    const RasterScene s = ParseRasterScene(RasterSceneBytes(RasterSceneOf(*sc)), "test");
    EXPECT_TRUE(s.alpha_test) << name;
    int masks = 0;
    for (size_t i = 0; i < s.materials.size(); ++i) {
      const Material& m = sc->materials[i];
      ASSERT_TRUE(s.materials[i].gltf);
      EXPECT_EQ(s.materials[i].pbr.double_sided, m.gltf->double_sided) << name;
      EXPECT_FLOAT_EQ(s.materials[i].pbr.alpha_cutoff, m.alpha_cutoff) << name;
      if (s.materials[i].pbr.alpha_mode == 1) {
        ++masks;
        ASSERT_GE(s.materials[i].pbr.base.image, 0);
        EXPECT_EQ(s.images[static_cast<size_t>(s.materials[i].pbr.base.image)].format, 0) << name;  // sRGB colour
      }
    }
    EXPECT_EQ(masks, 1) << name;
  }
}

// A version 2 file (written before glTF materials) is still read: the bytes of a
// one-triangle scene in the version 2 layout, built here field by field.
TEST(RasterGeometry, VersionTwoFilesAreStillRead) {
  std::string b = "AALABRG2";
  auto u32 = [&](uint32_t v) { b.append(reinterpret_cast<const char*>(&v), 4); };
  auto i32 = [&](int32_t v) { b.append(reinterpret_cast<const char*>(&v), 4); };
  auto f32 = [&](float v) { b.append(reinterpret_cast<const char*>(&v), 4); };
  u32(2);
  b += "v2";
  i32(0);                                                                           // perspective
  for (float f : {1.f, 2.f, 3.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f, 40.f, 2.f}) f32(f);  // camera
  f32(0.5f);                                                                        // exposure
  i32(2);                                                                           // aces
  for (float f : {0.1f, 0.2f, 0.3f, 0.05f, 0.05f, 0.05f}) f32(f);
  i32(1);  // lambert
  i32(0);  // shadows
  u32(0);  // lights
  u32(1);  // one material: lit, colour, no pattern
  i32(1);
  for (float f : {0.25f, 0.5f, 0.75f}) f32(f);
  i32(-1);
  for (float f : {1.f, 1.f, 0.f, 0.5f}) f32(f);
  u32(7);
  for (int k = 0; k < 6; ++k) f32(0.f);
  u32(1);  // one triangle
  for (int32_t v : {0, 0, 0, 0}) i32(v);
  for (int k = 0; k < 4; ++k) f32(0.f);
  for (int c = 0; c < 3; ++c)
    for (float f : {float(c), float(c * c), -1.f, 0.f, 0.f, 1.f, 0.5f, 0.25f}) f32(f);
  const RasterScene s = ParseRasterScene(b, "v2.geom");
  EXPECT_EQ(s.name, "v2");
  EXPECT_FLOAT_EQ(s.exposure, 0.5f);
  EXPECT_EQ(s.tonemap, 2);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_FALSE(s.materials[0].gltf);
  EXPECT_FLOAT_EQ(s.materials[0].color[2], 0.75f);
  EXPECT_TRUE(s.images.empty());
  EXPECT_FALSE(s.textures);
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_FLOAT_EQ(s.triangles[0].corners[2].position[1], 4.0f);
  EXPECT_FLOAT_EQ(s.triangles[0].corners[2].uv[1], 0.25f);
  EXPECT_FLOAT_EQ(s.triangles[0].corners[2].tangent[3], 0.0f);  // none in version 2
  // The same bytes with a version this build does not know: refused, naming what it reads.
  std::string v9 = b;
  v9[7] = '9';
  try {
    ParseRasterScene(v9, "v9.geom");
    ADD_FAILURE() << "version 9 was not refused";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("reads versions 2..3"), std::string::npos) << e.what();
  }
  // A glTF texture naming an image the file does not hold.
  RasterScene bad;
  bad.materials.resize(1);
  bad.materials[0].gltf = true;
  bad.materials[0].pbr.normal.image = 0;
  try {
    ParseRasterScene(RasterSceneBytes(bad), "bad.geom");
    ADD_FAILURE() << "image 0 of 0 was not refused";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("names image 0 of 0"), std::string::npos) << e.what();
  }
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
  EXPECT_THROW(ParseRasterScene("AALABRG3", "x"), UserError);      // truncated after the magic
  EXPECT_THROW(ParseRasterScene("NOTAFILE1234", "x"), UserError);  // wrong magic
  std::string bytes = RasterSceneBytes(RasterSceneOf(LoadScene("wedges")));
  EXPECT_THROW(ParseRasterScene(bytes + "x", "x"), UserError);  // trailing bytes
}

}  // namespace
}  // namespace aalab
