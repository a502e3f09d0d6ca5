/// The raster path's scene file (docs/gpu.md "The raster path"): a triangle scene as plain
/// data, written by `aalab export-geometry` (scenes/raster_export.h builds it from a Scene)
/// and read by the stand-alone raster tool (gpu/raster/), which links neither Embree nor OIIO.
///
/// Binary, little-endian, in this order (i32 / u32 / f32 are 4 bytes):
///   "AALABRG2" (8 bytes; version 2 added textures, uv, point and spot lights and disks)
///   u32 name length, name bytes (UTF-8, no terminator)
///   camera:   i32 type (0 perspective, 1 orthographic); f32 position[3], look_at[3], up[3],
///             fov_y_deg, height
///   display:  f32 exposure; i32 tonemap (0 none, 1 reinhard, 2 aces)
///   shading:  f32 background[3], ambient[3]; i32 lambert (the scene declares `lambert`);
///             i32 shadows (the scene declares `shadows`)
///   u32 light count; per light: i32 type (0 directional, 1 point, 2 spot); f32 direction[3],
///             color[3], intensity, position[3], range, cos_inner, cos_outer; i32 shadows
///             (the light casts shadows) (scenes/scene.h Light)
///   u32 material count; per material: i32 lit (1: lambert, 0: unlit); f32 color[3];
///             i32 pattern (−1: no texture, 0 checker, 1 stripes, 2 noise; the scene's
///             procedural texture, scenes/scene.h Texture, only when it declares `textures`);
///             f32 scale, cos, sin (stripes: the tracer's cos/sin of its angle, as the
///             tracer computes them), duty; u32 seed; f32 color_a[3], color_b[3]
///   u32 triangle count; per triangle: i32 shape (index in Scene::shapes), i32 material,
///             i32 smooth (1: the corner normals are the mesh's, 0: flat); i32 disk (1: the
///             triangle is half of an analytic disk's bounding square, drawn as an impostor
///             that keeps only the disk), f32 disk centre[3], radius; then three
///             corners of f32 position[3], normal[3] (flat: the face normal
///             (p1 − p0) × (p2 − p0), unnormalised, in all three, which the tracer's
///             geometric normal equals up to sign and length), uv[2] (Shape::uvs)
/// Values are the Scene's own floats (world space, after transforms), so nothing is rounded
/// on the way.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace aalab {

struct RasterLight {
  int32_t type = 0;                          ///< 0 directional, 1 point, 2 spot (LightType order)
  std::array<float, 3> direction{0, -1, 0};  ///< the direction the light travels
  std::array<float, 3> color{1, 1, 1};
  float intensity = 1.0f;  ///< aalab's internal unit (Light::intensity)
  std::array<float, 3> position{0, 0, 0};
  float range = 0.0f;  ///< 0: infinite
  float cos_inner = 1.0f, cos_outer = 0.70710678f;
  bool shadows = false;  ///< casts shadows (when the scene declares `shadows`)
};

/// A procedural texture (scenes/scene.h Texture) as the raster path evaluates it.
struct RasterTexture {
  int32_t pattern = -1;  ///< −1 none, 0 checker, 1 stripes, 2 noise (TexturePattern order)
  float scale = 1.0f;
  float cos_angle = 1.0f, sin_angle = 0.0f;  ///< stripes: the tracer's std::cos/std::sin of the angle
  float duty = 0.5f;
  uint32_t seed = 0;
  std::array<float, 3> color_a{0, 0, 0}, color_b{1, 1, 1};
};

struct RasterMaterial {
  bool lit = false;  ///< lambert shading (else unlit: the colour as radiance)
  std::array<float, 3> color{1, 1, 1};
  RasterTexture texture;  ///< replaces `color` when pattern ≥ 0
};

struct RasterCorner {
  std::array<float, 3> position{0, 0, 0};
  std::array<float, 3> normal{0, 0, 0};
  std::array<float, 2> uv{0, 0};
};

struct RasterTriangle {
  int32_t shape = 0, material = 0;
  bool smooth = false;
  /// Half of a disk's bounding square: the fragment shader keeps the points within `radius`
  /// of `center` (the disk's own plane; the corners carry its normal and uv frame).
  bool disk = false;
  std::array<float, 3> center{0, 0, 0};
  float radius = 0.0f;
  std::array<RasterCorner, 3> corners;
};

struct RasterScene {
  std::string name;
  bool orthographic = false;
  std::array<float, 3> position{0, 0, 5}, look_at{0, 0, 0}, up{0, 1, 0};
  float fov_y_deg = 45.0f, height = 2.0f;
  float exposure = 1.0f;
  int tonemap = 0;  ///< 0 none, 1 reinhard, 2 aces (core/color.h Tonemap order)
  std::array<float, 3> background{0, 0, 0}, ambient{0, 0, 0};
  bool lambert = false;
  bool shadows = false;  ///< shadow rays to the shadow-casting lights, against every triangle and disk
  std::vector<RasterLight> lights;
  std::vector<RasterMaterial> materials;
  std::vector<RasterTriangle> triangles;
};

/// The file's bytes for `scene` (pure).
std::string RasterSceneBytes(const RasterScene& scene);
/// Parses a file's bytes; throws UserError naming `origin`, the byte offset and what was
/// expected when the data is truncated, has the wrong magic or holds an out-of-range value.
RasterScene ParseRasterScene(const std::string& bytes, const std::string& origin);

}  // namespace aalab
