/// The render of a jittered one-sample frame that also keeps what each sample hit, and the
/// exact motion vectors derived from it (TAA's inputs). Methods never see the tracer: they
/// get the frame and the per-pixel previous positions as data.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "core/render_spec.h"
#include "scenes/tracer.h"

namespace aalab {

/// A 1-spp frame with its per-pixel hit: shape index (-1: background) and world position.
struct SurfaceFrame {
  Image8 image;                     ///< RGBA8 back buffer, as RenderFrame's kCenter frame
  std::vector<int32_t> surface;     ///< row-major, width × height
  std::vector<glm::vec3> position;  ///< world-space hit point (unused for background)
};

/// Renders one sample per pixel at (x + 0.5 + jitter.x, y + 0.5 + jitter.y), through the
/// display transform, sRGB-encoded and quantised like RenderFrame (zero jitter: the same
/// bits as RenderFrame's kCenter frame). Rows in parallel; deterministic.
SurfaceFrame RenderSurfaceFrame(const Tracer& tracer, int width, int height, FrameJitter jitter,
                                TraceCounters* counters);

/// Motion vectors as previous positions: for every pixel of `frame` (≥ 1) of `scene`'s
/// sequence, the continuous pixel position (centres at +0.5) that the pixel's centre had in
/// frame − 1: the surface point its sample saw is moved through the shape's motion at
/// frame − 1 and projected with frame − 1's camera, minus the sample's jitter. Background
/// pixels (nothing to follow; the background is uniform) keep their own centre. A point
/// behind frame − 1's camera gets NaN (no history). Pure; row-major.
std::vector<glm::vec2> PreviousPositions(const Scene& scene, int frame, const SurfaceFrame& current,
                                         FrameJitter jitter);

/// View depth per pixel of `current` (row-major): the hit point's distance from `camera`'s
/// eye along its forward axis (perspective and orthographic alike); +Inf where the sample hit
/// nothing (the background). TAA's depth buffer (closest-depth dilation, disocclusion).
std::vector<float> SurfaceDepth(const Camera& camera, const SurfaceFrame& current);

}  // namespace aalab
