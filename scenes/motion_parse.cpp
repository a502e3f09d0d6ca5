// Scene-file motion fields: `animation` (sequence length, camera keys) and per-object
// `motion` (pivot, transform keys). Every error names the JSON path, the value and the range.
#include "scenes/motion_parse.h"

#include <cmath>
#include <string>

#include "scenes/motion.h"

namespace aalab {

namespace {

constexpr double kMaxCoord = 1e8;  // as scene_parse.cpp: positions stay within ±1e8

/// The key's `frame`: a number inside the sequence, after the previous key's.
double KeyFrame(const JsonField& key, int frames, double previous, bool first) {
  const JsonField f = key.Child("frame");
  if (!f.Value().is_number()) f.Fail("expected a number (the key's time in frames)");
  const double t = f.Value().get<double>();
  if (!std::isfinite(t) || t < 0.0 || t > frames - 1) {
    f.Fail("frame " + std::to_string(t) + " is outside the sequence: keys lie in [0, " + std::to_string(frames - 1) +
           "] (animation.frames = " + std::to_string(frames) + ")");
  }
  if (!first && !(t > previous))
    f.Fail("key frames must increase strictly (previous key at " + std::to_string(previous) + ")");
  return t;
}

}  // namespace

Animation ParseAnimation(const JsonField& f) {
  f.RequireObject({"frames", "camera"});
  Animation a;
  a.frames = f.Child("frames").Integer(2, kMaxFrames);
  if (f.Has("camera")) {
    const JsonField keys = f.Child("camera");
    if (keys.ArraySize() == 0) keys.Fail("give at least one camera key (or leave 'camera' out)");
    for (size_t i = 0; i < keys.ArraySize(); ++i) {
      const JsonField k = keys.At(i);
      k.RequireObject({"frame", "offset", "roll", "zoom"});
      CameraKey c;
      c.frame = KeyFrame(k, a.frames, i ? a.camera.back().frame : 0.0, i == 0);
      c.offset = k.Vec3Or("offset", glm::vec3(0.0f), -kMaxCoord, kMaxCoord);
      c.roll_deg = static_cast<float>(k.NumberOr("roll", 0.0, -3600.0, 3600.0));
      c.zoom = static_cast<float>(k.NumberOr("zoom", 1.0, 0.01, 100.0));
      a.camera.push_back(c);
    }
  }
  return a;
}

ObjectMotion ParseObjectMotion(const JsonField& f, int frames) {
  if (frames == 0) {
    f.Fail("an object's motion needs a top-level 'animation' with 'frames' (the sequence length)");
  }
  f.RequireObject({"pivot", "keys"});
  ObjectMotion m;
  m.pivot = f.Vec3Or("pivot", glm::vec3(0.0f), -kMaxCoord, kMaxCoord);
  const JsonField keys = f.Child("keys");
  if (keys.ArraySize() == 0) keys.Fail("a motion needs at least one key");
  for (size_t i = 0; i < keys.ArraySize(); ++i) {
    const JsonField k = keys.At(i);
    k.RequireObject({"frame", "translate", "rotate", "scale"});
    MotionKey key;
    key.frame = KeyFrame(k, frames, i ? m.keys.back().frame : 0.0, i == 0);
    key.translate = k.Vec3Or("translate", glm::vec3(0.0f), -kMaxCoord, kMaxCoord);
    key.rotate_deg = k.Vec3Or("rotate", glm::vec3(0.0f), -3600.0, 3600.0);
    key.scale = static_cast<float>(k.NumberOr("scale", 1.0, 0.001, 1000.0));
    m.keys.push_back(key);
  }
  return m;
}

}  // namespace aalab
