/// Scene motion over a sequence of frames: the scene at a frame (keyframes linearly
/// interpolated), the camera at a frame, projection to pixels, and exact motion vectors
/// (where a surface point seen in frame t was in frame t − 1). scenes/README.md "Animation".
#pragma once
#include <optional>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace aalab {

/// Largest `--frames` a run accepts (also the largest declared sequence length).
inline constexpr int kMaxFrames = 100000;

/// The object's motion matrix at `frame`: T(pivot + translate) · Rz · Ry · Rx · S · T(−pivot),
/// each component linearly interpolated between the keys around `frame` (held outside them).
glm::mat4 ObjectMotionMatrix(const ObjectMotion& motion, double frame);

/// The scene's camera at `frame` (offset, roll and zoom interpolated and applied).
Camera CameraAtFrame(const Scene& scene, double frame);

/// The scene at `frame`: every moving shape transformed by its motion matrix, the camera
/// moved; the result has no animation (a still scene). For a still scene, a copy.
Scene SceneAtFrame(const Scene& scene, double frame);

/// Checks that a run of `frames` frames fits the scene's declared sequence (still scenes
/// take any count); throws UserError naming the scene and its `animation.frames`.
void CheckSequenceLength(const Scene& scene, int frames);

/// Continuous pixel position (x right, y down; pixel centres at +0.5) of a world point on a
/// width × height image seen by `camera` — the inverse of the tracer's camera rays. Empty
/// when the point is on or behind the perspective camera's eye plane.
std::optional<glm::vec2> ProjectToPixel(const Camera& camera, glm::vec3 world, int width, int height);

/// The world position in frame `to` of the point `world` on shape `shape` as seen in frame
/// `from`: through the inverse of the shape's motion at `from`, then its motion at `to`.
/// Still shapes: the point itself.
glm::vec3 MovePoint(const Scene& scene, int shape, glm::vec3 world, double from, double to);

}  // namespace aalab
