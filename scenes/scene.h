/// Scene model: camera, display, materials, lights, objects and the declared effects.
/// Scene files are JSON (scenes/README.md documents every field); ParseScene validates them.
#pragma once
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/color.h"
#include "scenes/texture_image.h"

namespace aalab {

/// Shading effects a scene may call for. The tracer simulates only the declared ones.
enum class Effect { kUnlit, kLambert, kShadows, kSpecular, kTextures, kAlphaTest, kAlphaBlend, kNormalMap };
constexpr int kEffectCount = 8;
/// "unlit", "lambert", "shadows", "specular", "textures", "alpha_test", "alpha_blend", "normal_map".
const char* EffectName(Effect e);

/// Procedural texture patterns, evaluated at a surface's (u, v) with no filtering (point
/// sampled: the aliasing source the AA methods face).
enum class TexturePattern { kChecker, kStripes, kNoise };

/// A procedural texture: a scalar pattern value t in [0, 1] mixes color_a (t = 0) and
/// color_b (t = 1); alpha tests compare t against the material's cutoff.
struct Texture {
  TexturePattern pattern = TexturePattern::kChecker;
  float scale = 1.0f;      ///< pattern cells per uv unit
  float angle_deg = 0.0f;  ///< stripes: direction of the stripes' normal in the uv plane
  float duty = 0.5f;       ///< stripes: fraction of each period with t = 1
  uint32_t seed = 0;       ///< noise: hash seed
  glm::vec3 color_a{0.0f};
  glm::vec3 color_b{1.0f};
};

/// Evaluates the texture's pattern value t ∈ [0, 1] at uv (pure).
float EvaluatePattern(const Texture& tex, glm::vec2 uv);

/// kPbr: the glTF 2.0 metallic-roughness BRDF (glTF specification, appendix B), for
/// materials read from glTF files (scenes/gltf_load.h).
enum class Shading { kUnlit, kLambert, kPbr };

/// glTF alpha modes: opaque, cut-out at alphaCutoff, blended over what lies behind.
enum class AlphaMode { kOpaque, kMask, kBlend };

/// A material's use of an image texture: which of Scene::images, with the sampler's wraps
/// and filters, the texture coordinate set and the KHR_texture_transform.
struct TextureRef {
  int image = -1;  ///< index into Scene::images (-1: none)
  WrapMode wrap_s = WrapMode::kRepeat, wrap_t = WrapMode::kRepeat;
  SamplerFilter filter;  ///< the sampler's magFilter / minFilter
  int texcoord = 0;      ///< TEXCOORD_n: 0 (Shape::uvs) or 1 (Shape::uvs1)
  /// KHR_texture_transform as the 2 × 3 affine map uv' = m · (u, v, 1) (identity: none);
  /// UV derivatives map through its linear part.
  glm::mat3x2 uv_transform{1.0f};
  bool transformed = false;
  bool Has() const { return image >= 0; }
};

/// The glTF part of a material (Material::gltf): factors times textures, as the glTF 2.0
/// specification defines them.
struct GltfMaterial {
  glm::vec4 base_factor{1.0f};  ///< baseColorFactor (linear RGBA)
  TextureRef base_tex;          ///< baseColorTexture (sRGB RGB, linear alpha)
  float metallic = 1.0f, roughness = 1.0f;
  TextureRef mr_tex;      ///< metallicRoughnessTexture: B = metallic, G = roughness
  TextureRef normal_tex;  ///< normalTexture (tangent space, linear)
  float normal_scale = 1.0f;
  glm::vec3 emissive{0.0f};  ///< emissiveFactor × KHR_materials_emissive_strength
  TextureRef emissive_tex;   ///< emissiveTexture (sRGB)
  TextureRef occlusion_tex;  ///< occlusionTexture (R), applied to the ambient term only
  float occlusion_strength = 1.0f;
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  bool double_sided = true;  ///< doubleSided (false: back faces are still drawn; see docs)
};

struct Material {
  std::string name;
  Shading shading = Shading::kUnlit;
  glm::vec3 color{1.0f};             ///< base colour (scene-linear; may exceed 1 for emitters)
  std::optional<Texture> texture;    ///< replaces `color` when present (needs `textures`)
  glm::vec3 specular{0.0f};          ///< Blinn-Phong specular colour (needs `specular`)
  float shininess = 0.0f;            ///< Blinn-Phong exponent
  std::optional<Texture> alpha;      ///< cut-out pattern (needs `alpha_test`)
  float alpha_cutoff = 0.5f;         ///< surface is kept where pattern t >= cutoff
                                     ///< (glTF MASK: where alpha >= alphaCutoff)
  std::optional<GltfMaterial> gltf;  ///< a material read from a glTF file

  /// True when hits on it may be rejected by an alpha test (procedural `alpha` or glTF MASK).
  bool CutOut() const { return alpha.has_value() || (gltf && gltf->alpha_mode == AlphaMode::kMask); }
  /// True for a glTF BLEND material.
  bool Blended() const { return gltf && gltf->alpha_mode == AlphaMode::kBlend; }
};

enum class LightType { kDirectional, kPoint, kSpot };

/// A punctual light. `intensity` is held in aalab's internal unit, the glTF / Blender value
/// divided by π (docs/lighting.md "Units"): a white Lambert surface facing a light of internal
/// intensity E reflects radiance E. Scene files and glTF files state lux (directional) and
/// candela (point, spot); ParseScene and GltfPunctualLights divide by π.
struct Light {
  LightType type = LightType::kDirectional;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  ///< directional, spot: the direction light travels
  glm::vec3 position{0.0f};                ///< point, spot: position
  glm::vec3 color{1.0f};
  float intensity = 1.0f;  ///< directional: irradiance / π; point, spot: intensity / π (/d²)
  bool shadows = false;    ///< casts shadows (needs `shadows`)
  /// Spot: cosines of KHR_lights_punctual's innerConeAngle and outerConeAngle.
  float cos_inner = 1.0f, cos_outer = 0.70710678f;
  /// Point, spot: KHR_lights_punctual `range` (0: infinite; else the smooth window
  /// clamp(1 − (d/range)⁴, 0, 1) of the specification's recommended falloff).
  float range = 0.0f;
};

struct Environment;  // scenes/ibl.h: an image-based lighting environment, prefiltered

enum class CameraType { kPerspective, kOrthographic };

struct Camera {
  CameraType type = CameraType::kPerspective;
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 look_at{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_deg = 45.0f;  ///< perspective: vertical field of view
  float height = 2.0f;      ///< orthographic: world-space height of the view
};

/// Geometry after parsing, in world space (transforms already applied).
enum class ShapeKind { kTriangles, kSphere, kDisk, kCapsule, kCylinder };

struct Shape {
  ShapeKind kind = ShapeKind::kTriangles;
  std::string source;  ///< the scene-file shape name ("box", "mesh", ...) for messages
  int material = 0;    ///< index into Scene::materials
  // kTriangles
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   ///< per vertex (empty: flat shading)
  std::vector<glm::vec2> uvs;       ///< per vertex
  std::vector<glm::vec2> uvs1;      ///< per vertex, glTF TEXCOORD_1 (empty: none)
  std::vector<glm::vec4> tangents;  ///< per vertex, xyz + handedness w (glTF meshes; may be empty)
  std::vector<glm::uvec3> triangles;
  // kSphere / kDisk: centre + radius (+ normal for the disk, + frame for uv)
  glm::vec3 center{0.0f};
  float radius = 0.0f;
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec3 tangent{1.0f, 0.0f, 0.0f};
  // kCapsule / kCylinder: segment from p0 to p1 with `radius`
  glm::vec3 p0{0.0f}, p1{0.0f};
  /// Index into Scene::animation.objects of this shape's motion (-1: the shape is still).
  int motion = -1;
};

/// One keyframe of an object's motion: a transform applied after the object's own
/// `transform`, about the motion's pivot (scenes/README.md "Animation").
struct MotionKey {
  double frame = 0.0;  ///< sequence time in frames, within [0, Animation::frames − 1]
  glm::vec3 translate{0.0f};
  glm::vec3 rotate_deg{0.0f};  ///< about X, then Y, then Z, around the pivot
  float scale = 1.0f;          ///< uniform (analytic shapes stay exact)
};

/// One keyframe of the camera's motion, relative to the scene's `camera`.
struct CameraKey {
  double frame = 0.0;
  glm::vec3 offset{0.0f};  ///< added to both position and look_at (a pan / dolly)
  float roll_deg = 0.0f;   ///< rotation of `up` about the view direction
  float zoom = 1.0f;       ///< divides tan(fov_y / 2) (perspective) or height (orthographic)
};

/// The keyframes of one moving object, linearly interpolated between keys (held before
/// the first and after the last).
struct ObjectMotion {
  glm::vec3 pivot{0.0f};  ///< world-space point the rotation and scale are about
  std::vector<MotionKey> keys;
};

/// A scene's motion over a sequence of frames. frames == 0: a still scene (any number of
/// frames shows the same image).
struct Animation {
  int frames = 0;                     ///< length of the declared sequence, 2..100000
  std::vector<CameraKey> camera;      ///< empty: the camera is still
  std::vector<ObjectMotion> objects;  ///< referenced by Shape::motion
  bool Moves() const { return frames > 0; }
};

struct Scene {
  std::string name;
  std::string description;
  std::string path;  ///< the file it came from ("" for built in code)
  std::array<bool, kEffectCount> effects{};
  Camera camera;
  Display display;
  glm::vec3 background{0.0f};
  glm::vec3 ambient{0.0f};  ///< added to lambert lighting
  std::vector<Material> materials;
  std::vector<Light> lights;
  /// Image-based lighting (scene file "environment"); null: none (the scene renders as
  /// before environments existed, bit for bit).
  std::shared_ptr<const Environment> environment;
  std::vector<Shape> shapes;
  /// Decoded image textures (glTF), shared by copies of the scene (SceneAtFrame).
  std::vector<std::shared_ptr<const MipChain>> images;
  Animation animation;  ///< motion over time; shapes and camera above are the base pose
                        ///< it applies to (SceneAtFrame in scenes/motion.h)
  /// Every file this scene was built from, beyond `path` (meshes, glTF buffers and images,
  /// environment maps), as given after resolving against their base folder. Whoever reads a
  /// file for the scene appends it here; the output-folder rule treats each as an input
  /// that `--out` may not equal, contain or replace.
  std::vector<std::string> files_read;
  /// What loading noticed and the user should know (glTF extensions used but not drawn, a
  /// static pose drawn for an animated file); printed when read, carried into the report.
  std::vector<std::string> notes;
  /// Per glTF file loaded: its name, load wall time and texture bytes (stored / as RGBA8).
  struct FileLoad {
    std::string file;
    double seconds = 0.0;
    size_t texture_bytes = 0, texture_bytes8 = 0, triangles = 0;
  };
  std::vector<FileLoad> load;

  bool Has(Effect e) const { return effects[static_cast<int>(e)]; }
  /// Names of the declared effects, in enum order.
  std::vector<std::string> EffectNames() const;
};

/// The camera's orthonormal basis as the tracer builds its rays, in float and in this order:
/// forward = normalize(look_at − position), right = normalize(forward × up),
/// up' = right × forward. Everything that must agree with the tracer's rays bit for bit
/// (the analytic coverage, the exact reference) starts from this one definition.
struct CameraBasis {
  glm::vec3 forward, right, up;
};
CameraBasis CameraBasisOf(const Camera& cam);

/// Parses and validates a scene file. Every error is a UserError naming the file, the JSON
/// path (e.g. /objects/3/radius), the bad value and what is allowed. Mesh paths are relative
/// to the scene file's folder.
Scene LoadSceneFile(const std::string& path);

/// Parses scene JSON text; `origin` names it in messages and `base_dir` resolves mesh paths.
Scene ParseScene(const std::string& json_text, const std::string& origin, const std::string& base_dir);

}  // namespace aalab
