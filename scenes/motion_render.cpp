// Jittered 1-spp frames with per-pixel hits, and exact motion vectors from the known motion.
#include "scenes/motion_render.h"

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "scenes/motion.h"
#include "scenes/render.h"

namespace aalab {

SurfaceFrame RenderSurfaceFrame(const Tracer& tracer, int width, int height, FrameJitter jitter,
                                TraceCounters* counters) {
  AALAB_CHECK(width > 0 && height > 0, "render size must be positive");
  const Display& display = tracer.GetScene().display;
  SurfaceFrame out;
  out.image = Image8(width, height, 4, 255);
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  out.surface.assign(n, -1);
  out.position.assign(n, glm::vec3(0.0f));
  std::vector<TraceCounters> per_row(static_cast<size_t>(height));
  ParallelFor(height, [&](int y) {
    std::vector<SamplePos> pos(static_cast<size_t>(width));
    std::vector<SampleResult> res(static_cast<size_t>(width));
    for (int x = 0; x < width; ++x) {
      pos[static_cast<size_t>(x)] = {static_cast<float>(x) + (0.5f + jitter.x),
                                     static_cast<float>(y) + (0.5f + jitter.y)};
    }
    tracer.Trace(pos.data(), width, width, height, res.data(), &per_row[static_cast<size_t>(y)]);
    for (int x = 0; x < width; ++x) {
      const SampleResult& r = res[static_cast<size_t>(x)];
      ResolveBoxPixel(display, &r, 1, out.image.Pixel(x, y));
      const size_t i = static_cast<size_t>(y) * width + x;
      out.surface[i] = r.surface;
      out.position[i] = glm::vec3(r.position[0], r.position[1], r.position[2]);
    }
  });
  if (counters) {
    for (const auto& c : per_row) *counters += c;
  }
  return out;
}

std::vector<glm::vec2> PreviousPositions(const Scene& scene, int frame, const SurfaceFrame& current,
                                         FrameJitter jitter) {
  AALAB_CHECK(frame >= 1, "motion vectors need a previous frame");
  const int width = current.image.Width(), height = current.image.Height();
  const Camera prev_cam = CameraAtFrame(scene, frame - 1);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<glm::vec2> out(current.surface.size());
  ParallelFor(height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const size_t i = static_cast<size_t>(y) * width + x;
      const glm::vec2 centre(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const int shape = current.surface[i];
      if (shape < 0) {
        out[i] = centre;
        continue;
      }
      const glm::vec3 p = MovePoint(scene, shape, current.position[i], frame, frame - 1);
      const auto q = ProjectToPixel(prev_cam, p, width, height);
      out[i] = q ? glm::vec2(q->x - jitter.x, q->y - jitter.y) : glm::vec2(nan, nan);
    }
  });
  return out;
}

std::vector<float> SurfaceDepth(const Camera& camera, const SurfaceFrame& current) {
  const glm::vec3 forward = CameraBasisOf(camera).forward;
  std::vector<float> out(current.surface.size(), std::numeric_limits<float>::infinity());
  for (size_t i = 0; i < out.size(); ++i) {
    if (current.surface[i] >= 0) out[i] = glm::dot(current.position[i] - camera.position, forward);
  }
  return out;
}

}  // namespace aalab
