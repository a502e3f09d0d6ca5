// Scene motion: keyframe interpolation, the scene and camera at a frame, projection to
// pixels and point mapping between frames (exact motion vectors for TAA).
#include "scenes/motion.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "scenes/shapes.h"

namespace aalab {

namespace {

/// Index i and weight w so that the value at `frame` is lerp(keys[i], keys[i+1], w); held
/// before the first key and after the last (w = 0 on the clamped key).
template <typename Key>
void Bracket(const std::vector<Key>& keys, double frame, size_t* i, float* w) {
  AALAB_CHECK(!keys.empty(), "motion without keys");
  if (frame <= keys.front().frame || keys.size() == 1) {
    *i = 0;
    *w = 0.0f;
    return;
  }
  if (frame >= keys.back().frame) {
    *i = keys.size() - 1;
    *w = 0.0f;
    return;
  }
  size_t k = 0;
  while (keys[k + 1].frame <= frame) ++k;
  *i = k;
  *w = static_cast<float>((frame - keys[k].frame) / (keys[k + 1].frame - keys[k].frame));
}

template <typename T>
T Lerp(T a, T b, float w) {
  return a + (b - a) * w;
}

}  // namespace

glm::mat4 ObjectMotionMatrix(const ObjectMotion& motion, double frame) {
  size_t i = 0;
  float w = 0.0f;
  Bracket(motion.keys, frame, &i, &w);
  const MotionKey& a = motion.keys[i];
  const MotionKey& b = w > 0.0f ? motion.keys[i + 1] : a;
  const glm::vec3 t = Lerp(a.translate, b.translate, w);
  const glm::vec3 r = Lerp(a.rotate_deg, b.rotate_deg, w);
  const float s = Lerp(a.scale, b.scale, w);
  glm::mat4 to_pivot(1.0f), from_pivot(1.0f);
  to_pivot[3] = glm::vec4(-motion.pivot, 1.0f);
  from_pivot[3] = glm::vec4(motion.pivot, 1.0f);
  return from_pivot * MakeTransform(t, r, glm::vec3(s)) * to_pivot;
}

Camera CameraAtFrame(const Scene& scene, double frame) {
  Camera c = scene.camera;
  if (scene.animation.camera.empty()) return c;
  size_t i = 0;
  float w = 0.0f;
  Bracket(scene.animation.camera, frame, &i, &w);
  const CameraKey& a = scene.animation.camera[i];
  const CameraKey& b = w > 0.0f ? scene.animation.camera[i + 1] : a;
  const glm::vec3 offset = Lerp(a.offset, b.offset, w);
  const float roll = Lerp(a.roll_deg, b.roll_deg, w);
  const float zoom = Lerp(a.zoom, b.zoom, w);
  c.position += offset;
  c.look_at += offset;
  if (roll != 0.0f) {
    // Rodrigues rotation of `up` about the view direction, in double.
    const glm::dvec3 k = glm::normalize(glm::dvec3(c.look_at) - glm::dvec3(c.position));
    const glm::dvec3 u(c.up);
    const double th = glm::radians(static_cast<double>(roll));
    const glm::dvec3 r = u * std::cos(th) + glm::cross(k, u) * std::sin(th) + k * glm::dot(k, u) * (1.0 - std::cos(th));
    c.up = glm::vec3(glm::normalize(r));
  }
  if (zoom != 1.0f) {
    if (c.type == CameraType::kPerspective) {
      const double half = std::tan(glm::radians(static_cast<double>(c.fov_y_deg)) * 0.5) / zoom;
      c.fov_y_deg = static_cast<float>(glm::degrees(2.0 * std::atan(half)));
    } else {
      c.height /= zoom;
    }
  }
  return c;
}

Scene SceneAtFrame(const Scene& scene, double frame) {
  Scene out = scene;
  out.animation = Animation{};
  if (!scene.animation.Moves()) return out;
  out.camera = CameraAtFrame(scene, frame);
  for (Shape& s : out.shapes) {
    if (s.motion < 0) continue;
    const bool ok = TransformShape(s, ObjectMotionMatrix(scene.animation.objects[s.motion], frame));
    AALAB_CHECK(ok, "a motion matrix has a uniform scale");
    s.motion = -1;
  }
  return out;
}

void CheckSequenceLength(const Scene& scene, int frames) {
  if (frames < 1 || frames > kMaxFrames) {
    throw UserError("--frames " + std::to_string(frames) + " is out of range (1.." + std::to_string(kMaxFrames) + ")");
  }
  if (scene.animation.Moves() && frames > scene.animation.frames) {
    throw UserError("scene '" + scene.name + "' declares /animation/frames = " +
                    std::to_string(scene.animation.frames) + ": --frames " + std::to_string(frames) +
                    " runs past its sequence (allowed: 1.." + std::to_string(scene.animation.frames) + ")");
  }
}

std::optional<glm::vec2> ProjectToPixel(const Camera& c, glm::vec3 world, int width, int height) {
  // The tracer's camera basis and ray model (scenes/tracer.cpp), inverted, in double.
  const glm::dvec3 pos(c.position);
  const glm::dvec3 fwd = glm::normalize(glm::dvec3(glm::normalize(c.look_at - c.position)));
  const glm::dvec3 right = glm::normalize(glm::cross(fwd, glm::dvec3(c.up)));
  const glm::dvec3 up = glm::cross(right, fwd);
  const double aspect = static_cast<double>(width) / height;
  const glm::dvec3 d = glm::dvec3(world) - pos;
  double a = 0.0, b = 0.0, half_h = 0.0;
  if (c.type == CameraType::kPerspective) {
    const double z = glm::dot(d, fwd);
    if (!(z > 0.0)) return std::nullopt;
    a = glm::dot(d, right) / z;
    b = glm::dot(d, up) / z;
    half_h = std::tan(glm::radians(static_cast<double>(c.fov_y_deg)) * 0.5);
  } else {
    a = glm::dot(d, right);
    b = glm::dot(d, up);
    half_h = 0.5 * c.height;
  }
  const double nx = a / (half_h * aspect), ny = b / half_h;
  return glm::vec2(static_cast<float>((nx + 1.0) * 0.5 * width), static_cast<float>((1.0 - ny) * 0.5 * height));
}

glm::vec3 MovePoint(const Scene& scene, int shape, glm::vec3 world, double from, double to) {
  if (shape < 0 || !scene.animation.Moves()) return world;
  const int m = scene.shapes[static_cast<size_t>(shape)].motion;
  if (m < 0) return world;
  const ObjectMotion& om = scene.animation.objects[static_cast<size_t>(m)];
  const glm::dmat4 a(ObjectMotionMatrix(om, from)), b(ObjectMotionMatrix(om, to));
  const glm::dvec4 p = b * (glm::inverse(a) * glm::dvec4(glm::dvec3(world), 1.0));
  return glm::vec3(p);
}

}  // namespace aalab
