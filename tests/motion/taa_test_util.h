// Shared by the TAA tests (tests/motion/taa_test.cpp, taa_production_test.cpp): the still
// slanted-edge scene both converge on, and one jittered frame with its previous positions in
// the flat layout TemporalInput::previous takes.
#pragma once
#include <vector>

#include "core/render_spec.h"
#include "methods/method.h"
#include "scenes/motion.h"
#include "scenes/motion_render.h"
#include "scenes/render.h"
#include "../scenes/scene_test_util.h"

namespace aalab::testing {

/// A white quad's edge, 7° off vertical, on black: unlit, orthographic, nothing moves.
inline Scene StillEdgeScene() {
  return ParseText(R"({"name": "edge", "effects": ["unlit"],
    "camera": {"type": "orthographic", "position": [0,0,10], "look_at": [0,0,0], "height": 4},
    "materials": {"w": {"shading": "unlit", "color": [1, 1, 1]}},
    "objects": [{"shape": "quad", "size": [4, 8], "material": "w", "transform": {"translate": [-1.6, 0, 0], "rotate": [0, 0, 7]}}]})");
}

/// The still edge at w × h: the scene, its tracer, the 16-spp reference and `none`'s frame.
struct StillEdge {
  StillEdge(int w, int h)
      : scene(StillEdgeScene()),
        tracer(scene),
        ref(RenderReference(tracer, w, h, 16, 1, nullptr)),
        none(RenderFrame(tracer, w, h, RenderSpec{}, 1, nullptr)) {}
  StillEdge(const StillEdge&) = delete;
  StillEdge& operator=(const StillEdge&) = delete;
  Scene scene;
  Tracer tracer;
  Reference ref;
  Image8 none;
};

/// Frame k of scene `s` (traced by `tracer`, the scene at frame k) for a temporal method:
/// rendered at w × h with the plan's jitter, with its previous positions (x, y per pixel,
/// row-major; empty at frame 0, no history).
struct TaaFrame {
  FrameJitter jitter;
  SurfaceFrame sf;
  std::vector<float> previous;
  /// The step's input (pointers into this frame): frame, previous positions, index, jitter.
  TemporalInput Input(int k) const {
    TemporalInput in;
    in.frame = &sf.image;
    in.previous = k > 0 ? &previous : nullptr;
    in.frame_index = k;
    in.jitter = jitter;
    return in;
  }
};

inline TaaFrame RenderTaaFrame(const Scene& s, const Tracer& tracer, const JitterSpec& spec, int k, int w, int h) {
  TaaFrame f;
  f.jitter = FrameJitterAt(spec, k);
  f.sf = RenderSurfaceFrame(tracer, w, h, f.jitter, nullptr);
  if (k > 0) {
    for (const glm::vec2& p : PreviousPositions(s, k, f.sf, f.jitter)) {
      f.previous.push_back(p.x);
      f.previous.push_back(p.y);
    }
  }
  return f;
}

}  // namespace aalab::testing
