// Scene motion: keyframe interpolation, bad motion input, the scene at a frame, and exact
// motion vectors checked against the tracer.
#include <gtest/gtest.h>

#include <cmath>

#include "core/render_spec.h"
#include "scenes/motion.h"
#include "scenes/motion_render.h"
#include "scenes/render.h"
#include "scenes/tracer.h"
#include "../scenes/scene_test_util.h"

namespace aalab {
namespace {

using testing::MakeScene;
using testing::ParseError;
using testing::ParseText;

const char* kMat = R"({"m": {"shading": "unlit"}})";

std::string MovingSphere(const std::string& keys, const std::string& animation = R"(, "animation": {"frames": 11})") {
  return MakeScene(R"(["unlit"])", kMat,
                   R"([{"shape": "sphere", "radius": 0.5, "material": "m", "motion": {"keys": )" + keys + "}}]",
                   animation);
}

TEST(MotionScene, KeysInterpolateLinearlyAndHoldOutside) {
  const Scene s = ParseText(MovingSphere(R"([{"frame": 2}, {"frame": 10, "translate": [1, 0, 0], "scale": 2}])"));
  ASSERT_TRUE(s.animation.Moves());
  // Frame 6 is halfway between the keys: translate 0.5, scale 1.5 (about the origin pivot).
  const Scene f6 = SceneAtFrame(s, 6);
  EXPECT_FLOAT_EQ(f6.shapes[0].center.x, 0.5f);
  EXPECT_FLOAT_EQ(f6.shapes[0].radius, 0.75f);
  EXPECT_FALSE(f6.animation.Moves());
  // Before the first key: held at the first key (identity).
  EXPECT_FLOAT_EQ(SceneAtFrame(s, 0).shapes[0].center.x, 0.0f);
  EXPECT_FLOAT_EQ(SceneAtFrame(s, 10).shapes[0].center.x, 1.0f);
}

TEST(MotionScene, CameraPanRollZoom) {
  const Scene s = ParseText(MakeScene(R"(["unlit"])", kMat, R"([{"shape": "sphere", "radius": 0.5, "material": "m"}])",
                                      R"(, "animation": {"frames": 5, "camera": [{"frame": 0},
                                         {"frame": 4, "offset": [2, 0, 0], "roll": 90, "zoom": 4}]})"));
  const Camera c = CameraAtFrame(s, 2);
  EXPECT_FLOAT_EQ(c.position.x, 1.0f);
  EXPECT_FLOAT_EQ(c.look_at.x, 1.0f);
  EXPECT_FLOAT_EQ(c.height, 4.0f / 2.5f);  // zoom 2.5 at frame 2
  // Roll 45°: up (0,1,0) about the view direction (0,0,-1) turns to (1,1,0)/√2 (right-handed).
  EXPECT_NEAR(c.up.x, std::sqrt(0.5f), 1e-6);
  EXPECT_NEAR(c.up.y, std::sqrt(0.5f), 1e-6);
  // ProjectToPixel inverts the camera: the look-at point is the image centre.
  const auto q = ProjectToPixel(c, c.look_at, 40, 20);
  ASSERT_TRUE(q);
  EXPECT_NEAR(q->x, 20.0f, 1e-4);
  EXPECT_NEAR(q->y, 10.0f, 1e-4);
}

TEST(MotionScene, BadMotionInputNamesTheField) {
  struct Case {
    std::string json, expect_path, expect_text;
  };
  const std::vector<Case> cases = {
      {MovingSphere(R"([{"frame": 0}, {"frame": 11}])"), "/objects/0/motion/keys/1/frame", "outside the sequence"},
      {MovingSphere(R"([{"frame": -1}])"), "/objects/0/motion/keys/0/frame", "outside the sequence"},
      {MovingSphere(R"([{"frame": 4}, {"frame": 4}])"), "/objects/0/motion/keys/1/frame", "increase strictly"},
      {MovingSphere(R"([{"frame": 1, "scale": 0}])"), "/objects/0/motion/keys/0/scale", "0.001"},
      {MovingSphere(R"([{"frame": 1, "translate": [1e9, 0, 0]}])"), "/objects/0/motion/keys/0/translate", ""},
      {MovingSphere(R"([{"frame": 1, "rotate": [0, "x", 0]}])"), "/objects/0/motion/keys/0/rotate", ""},
      {MovingSphere(R"([])"), "/objects/0/motion/keys", "at least one key"},
      {MovingSphere(R"([{"frame": 1, "speed": 2}])"), "/objects/0/motion/keys/0", "speed"},
      {MovingSphere(R"([{"frame": 1}])", ""), "/objects/0/motion", "animation"},
      {MovingSphere(R"([{"frame": 1}])", R"(, "animation": {"frames": 1})"), "/animation/frames", ""},
      {MovingSphere(R"([{"frame": 1}])", R"(, "animation": {"frames": 10, "camera": [{"frame": 2, "zoom": 0}]})"),
       "/animation/camera/0/zoom", "0.01"},
      {MovingSphere(R"([{"frame": 1}])", R"(, "animation": {"frames": 10, "camera": [{"frame": 1e99}]})"),
       "/animation/camera/0/frame", "outside the sequence"},
      {MakeScene(R"(["unlit"])", kMat, R"([{"shape": "sphere", "radius": 0.5, "material": "m"}])",
                 R"(, "animation": {"frames": 10})"),
       "/animation", "moves nothing"},
  };
  for (const Case& c : cases) {
    const std::string e = ParseError(c.json);
    EXPECT_NE(e.find(c.expect_path), std::string::npos) << c.json << "\n -> " << e;
    EXPECT_NE(e.find(c.expect_text), std::string::npos) << c.json << "\n -> " << e;
  }
}

TEST(MotionScene, SequenceLengthIsChecked) {
  const Scene s = ParseText(MovingSphere(R"([{"frame": 1}])"));
  EXPECT_NO_THROW(CheckSequenceLength(s, 11));
  EXPECT_THROW(CheckSequenceLength(s, 12), UserError);
  EXPECT_THROW(CheckSequenceLength(s, 0), UserError);
  const Scene still =
      ParseText(MakeScene(R"(["unlit"])", kMat, R"([{"shape": "sphere", "radius": 0.5, "material": "m"}])"));
  EXPECT_NO_THROW(CheckSequenceLength(still, 500));
}

TEST(MotionScene, HaltonJitterIsTheRadicalInverseMinusHalf) {
  // Halton(2,3) indices 1..4 by hand: (1/2, 1/3), (1/4, 2/3), (3/4, 1/9), (1/8, 4/9).
  JitterSpec spec;
  spec.samples = 16;
  const double expect[4][2] = {{0.5, 1.0 / 3}, {0.25, 2.0 / 3}, {0.75, 1.0 / 9}, {0.125, 4.0 / 9}};
  for (int f = 0; f < 4; ++f) {
    const FrameJitter j = FrameJitterAt(spec, f);
    EXPECT_FLOAT_EQ(j.x, static_cast<float>(expect[f][0] - 0.5));
    EXPECT_FLOAT_EQ(j.y, static_cast<float>(expect[f][1] - 0.5));
  }
  EXPECT_EQ(FrameJitterAt(spec, 16).x, FrameJitterAt(spec, 0).x);  // cycles
  EXPECT_EQ(FrameJitterAt(JitterSpec{}, 3).x, 0.0f);               // off
}

// A box that turns and moves about a pivot, seen by a panning, zooming, rolling perspective
// camera: the motion vector of every pixel must land on the same surface point in the
// previous frame, as the tracer sees it there.
TEST(MotionScene, MotionVectorsLandOnTheSameSurfacePoint) {
  const Scene s = ParseText(R"({"name": "mv", "effects": ["unlit"],
    "camera": {"type": "perspective", "position": [0.3, 0.4, 6], "look_at": [0, 0, 0], "fov_y": 40},
    "materials": {"m": {"shading": "unlit"}},
    "objects": [{"shape": "box", "size": [2, 1.5, 1], "material": "m", "transform": {"rotate": [20, 30, 0]},
                 "motion": {"pivot": [0.2, 0, 0], "keys": [{"frame": 0}, {"frame": 7, "translate": [0.4, -0.2, 0.3],
                            "rotate": [3, 5, 8], "scale": 1.1}]}}],
    "animation": {"frames": 8, "camera": [{"frame": 0}, {"frame": 7, "offset": [0.2, 0.1, -0.3], "roll": 4, "zoom": 1.2}]}})");
  const int W = 48, H = 36, t = 5;
  const Scene now = SceneAtFrame(s, t), before = SceneAtFrame(s, t - 1);
  const Tracer tr_now(now), tr_before(before);
  JitterSpec spec;
  spec.samples = 16;
  const FrameJitter j = FrameJitterAt(spec, t);
  const SurfaceFrame sf = RenderSurfaceFrame(tr_now, W, H, j, nullptr);
  const std::vector<glm::vec2> prev = PreviousPositions(s, t, sf, j);
  int checked = 0, matched = 0;
  for (int i = 0; i < W * H; ++i) {
    if (sf.surface[i] < 0) continue;
    ++checked;
    // The sample's own position in frame t − 1: the pixel centre's previous position plus the jitter.
    const SamplePos q{prev[i].x + j.x, prev[i].y + j.y};
    SampleResult r;
    tr_before.Trace(&q, 1, W, H, &r, nullptr);
    if (r.surface != sf.surface[i]) continue;  // occluded or off the box in t − 1
    const glm::vec3 expect = MovePoint(s, sf.surface[i], sf.position[i], t, t - 1);
    const glm::vec3 got(r.position[0], r.position[1], r.position[2]);
    EXPECT_LT(glm::length(got - expect), 2e-4f) << "pixel " << i;
    ++matched;
  }
  EXPECT_GT(checked, W * H / 5);
  // Only points hidden in t − 1 (self-occlusion at the silhouette) may miss.
  EXPECT_GE(matched, checked * 95 / 100);
}

}  // namespace
}  // namespace aalab
