/// The raster path's scene file (docs/gpu.md "The raster path"): a triangle scene as plain
/// data, written by `aalab export-geometry` (scenes/raster_export.h builds it from a Scene)
/// and read by the stand-alone raster tool (gpu/raster/), which links neither Embree nor OIIO.
///
/// Binary, little-endian, in this order (i32 / u32 / f32 are 4 bytes):
///   "AALABRG3" (8 bytes; version 2 added textures, uv, point and spot lights and disks;
///             version 3 added glTF materials, image textures and per-corner tangents — the
///             parts marked [v3] below; a version 2 file is still read, without them)
///   u32 name length, name bytes (UTF-8, no terminator)
///   camera:   i32 type (0 perspective, 1 orthographic); f32 position[3], look_at[3], up[3],
///             fov_y_deg, height
///   display:  f32 exposure; i32 tonemap (0 none, 1 reinhard, 2 aces)
///   shading:  f32 background[3], ambient[3]; i32 lambert (the scene declares `lambert`);
///             i32 shadows (the scene declares `shadows`)
///   [v3] i32 gltf flags: bit 0 the scene declares `textures`, bit 1 `normal_map`, bit 2
///             `alpha_test` (the tracer's ShadeGltf / CutoutKeeps read textures, normal maps
///             and the MASK test only under these)
///   u32 light count; per light: i32 type (0 directional, 1 point, 2 spot); f32 direction[3],
///             color[3], intensity, position[3], range, cos_inner, cos_outer; i32 shadows
///             (the light casts shadows) (scenes/scene.h Light)
///   u32 material count; per material: i32 lit (1: lambert, 0: unlit); f32 color[3];
///             i32 pattern (−1: no texture, 0 checker, 1 stripes, 2 noise; the scene's
///             procedural texture, scenes/scene.h Texture, only when it declares `textures`);
///             f32 scale, cos, sin (stripes: the tracer's cos/sin of its angle, as the
///             tracer computes them), duty; u32 seed; f32 color_a[3], color_b[3];
///             [v3] i32 gltf (0: none; 1: a glTF material, then) i32 unlit; f32
///             base_factor[4], metallic, roughness, normal_scale, alpha_cutoff; i32 alpha_mode
///             (0 OPAQUE, 1 MASK), double_sided; three texture references (baseColor,
///             metallicRoughness, normal), each i32 image (−1: none), i32 wrap_s, wrap_t
///             (0 REPEAT, 1 CLAMP_TO_EDGE, 2 MIRRORED_REPEAT)
///   [v3] f32 srgb_table[256], unorm_table[256]: the linear value of each 8-bit code as aalab
///             decodes it (scenes/texture_image.h Srgb8Table, Unorm8Table), which the GPU looks
///             up rather than decode itself
///   [v3] u32 image count; per image: i32 format (0: sRGB colour + linear alpha, 1: linear
///             unorm), u32 level count; per level: u32 width, height, then width·height·4
///             bytes RGBA8, top row first — aalab's own decoded mip chain (scenes/texture_image.h
///             BuildMipChain), so the GPU filters the tracer's texels
///   u32 triangle count; per triangle: i32 shape (index in Scene::shapes), i32 material,
///             i32 smooth (1: the corner normals are the mesh's, 0: flat); i32 disk (1: the
///             triangle is half of an analytic disk's bounding square, drawn as an impostor
///             that keeps only the disk), f32 disk centre[3], radius; then three
///             corners of f32 position[3], normal[3] (flat: the face normal
///             (p1 − p0) × (p2 − p0), unnormalised, in all three, which the tracer's
///             geometric normal equals up to sign and length), uv[2] (Shape::uvs),
///             [v3] tangent[4] (glTF TANGENT xyz + handedness w; 0 when the mesh has none)
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

/// A glTF material's use of an image (scenes/scene.h TextureRef, default sampler only).
struct RasterTextureRef {
  int32_t image = -1;              ///< index into RasterScene::images (−1: none)
  int32_t wrap_s = 0, wrap_t = 0;  ///< 0 REPEAT, 1 CLAMP_TO_EDGE, 2 MIRRORED_REPEAT (WrapMode order)
};

/// The parts of a glTF material (scenes/scene.h GltfMaterial) the raster path shades.
struct RasterGltf {
  bool unlit = false;  ///< KHR_materials_unlit: the base colour as radiance
  std::array<float, 4> base_factor{1, 1, 1, 1};
  float metallic = 1.0f, roughness = 1.0f, normal_scale = 1.0f, alpha_cutoff = 0.5f;
  int32_t alpha_mode = 0;  ///< 0 OPAQUE, 1 MASK
  bool double_sided = true;
  RasterTextureRef base, mr, normal;
};

struct RasterMaterial {
  bool lit = false;  ///< lambert shading (else unlit: the colour as radiance)
  std::array<float, 3> color{1, 1, 1};
  RasterTexture texture;  ///< replaces `color` when pattern ≥ 0
  bool gltf = false;      ///< a glTF material: `pbr` replaces everything above
  RasterGltf pbr;
};

/// One mip level of an image, RGBA8, top row first.
struct RasterMipLevel {
  int32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

/// A texture image as aalab decoded it and built its mip chain.
struct RasterImage {
  int32_t format = 0;  ///< 0 sRGB colour + linear alpha (TexelFormat::kSrgb8), 1 linear (kUnorm8)
  std::vector<RasterMipLevel> levels;
};

struct RasterCorner {
  std::array<float, 3> position{0, 0, 0};
  std::array<float, 3> normal{0, 0, 0};
  std::array<float, 2> uv{0, 0};
  std::array<float, 4> tangent{0, 0, 0, 0};  ///< glTF TANGENT (xyz, handedness w); 0: none
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
  /// The effects that gate glTF shading in the tracer: `textures`, `normal_map`, `alpha_test`.
  bool textures = false, normal_map = false, alpha_test = false;
  std::vector<RasterLight> lights;
  std::vector<RasterMaterial> materials;
  /// The linear value of each 8-bit code: sRGB colour channels, and linear channels / alpha.
  std::array<float, 256> srgb_table{}, unorm_table{};
  std::vector<RasterImage> images;
  std::vector<RasterTriangle> triangles;
  /// Whether any material is a glTF one (the fragment shader's glTF branch).
  bool AnyGltf() const {
    for (const auto& m : materials)
      if (m.gltf) return true;
    return false;
  }
};

/// The file's bytes for `scene` (pure; always the newest version, AALABRG3).
std::string RasterSceneBytes(const RasterScene& scene);
/// Parses a file's bytes; throws UserError naming `origin`, the byte offset and what was
/// expected when the data is truncated, has the wrong magic or holds an out-of-range value.
/// Reads versions 2 and 3; names the versions it reads when the magic is another AALABRG.
RasterScene ParseRasterScene(const std::string& bytes, const std::string& origin);

}  // namespace aalab
