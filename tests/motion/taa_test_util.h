// Shared by the TAA tests (tests/motion/taa_test.cpp, taa_production_test.cpp): the still
// slanted-edge scene both converge on, and one frame's previous positions in the flat layout
// TemporalInput::previous takes.
#pragma once
#include <vector>

#include "harness/core/render_spec.h"
#include "scenes/motion.h"
#include "scenes/motion_render.h"
#include "../scenes/scene_test_util.h"

namespace aalab::testing {

/// A white quad's edge, 7° off vertical, on black: unlit, orthographic, nothing moves.
inline Scene StillEdgeScene() {
  return ParseText(R"({"name": "edge", "effects": ["unlit"],
    "camera": {"type": "orthographic", "position": [0,0,10], "look_at": [0,0,0], "height": 4},
    "materials": {"w": {"shading": "unlit", "color": [1, 1, 1]}},
    "objects": [{"shape": "quad", "size": [4, 8], "material": "w", "transform": {"translate": [-1.6, 0, 0], "rotate": [0, 0, 7]}}]})");
}

/// Frame k's previous positions (x, y per pixel, row-major) of the surface frame `sf`
/// rendered with jitter `j`; empty for frame 0 (no history).
inline std::vector<float> FlatPreviousPositions(const Scene& s, int k, const SurfaceFrame& sf, FrameJitter j) {
  std::vector<float> prev;
  if (k == 0) return prev;
  for (const glm::vec2& p : PreviousPositions(s, k, sf, j)) {
    prev.push_back(p.x);
    prev.push_back(p.y);
  }
  return prev;
}

}  // namespace aalab::testing
