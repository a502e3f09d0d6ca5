/// Analytical anti-aliasing (AAA) at render time: one camera ray per pixel centre, plus, for
/// the outlines of disks, spheres and capsules, the signed distance to the outline and its
/// exact screen-space gradient (what dFdx / dFdy approximate), an alpha from them, and the
/// shape composited over what lies behind it. FrostKiwi, "Analytical Anti-Aliasing"
/// (seeds/004); docs/analytic-aa.md.
#pragma once
#include <cstdint>

#include "core/image.h"
#include "core/render_spec.h"
#include "scenes/tracer.h"

namespace aalab {

/// The pixel size of one method: `p_object` for kObject, √(gx² + gy²) for kLength,
/// |gx| + |gy| for kFwidth (gx, gy: the distance's change per pixel step in x and y).
double AaaPixelSizeOf(AaaPixelSize method, double p_object, double gx, double gy);

/// The article's alpha (circle-analyticalCompare.fs) from the signed distance d to the
/// nominal outline (positive outside, the shape's own units), the pixel size p of the chosen
/// method and the per-object pixel size p_object. The demo quad is grown by p_object, so
/// the shader's "1 − dist" is p_object − d; then dist += p·shrink and
///   t = (p_object − d − p·shrink) / (p·smoothing),
/// division and linstep: clamp(t, 0, 1) (division is unclamped in the shader and clamped by
/// the fixed-point framebuffer: the same value); smoothstep: clamp then t²(3 − 2t).
/// With p = p_object, shrink = 0.5 and smoothing = 1 this is a 1 px ramp centred on the
/// outline: alpha = clamp(0.5 − d/p).
double AaaAlpha(const AnalyticSpec& spec, double d, double p, double p_object);

/// Counters of one analytic render.
struct AnalyticCounters {
  uint64_t edge_pixels = 0;           ///< pixels whose centre sample's surface differs from a 4-neighbour's
  uint64_t analytic_edge_pixels = 0;  ///< ... of those, pixels within one pixel size of an analytic
                                      ///< outline (|d| < px): their coverage came from the distance
  uint64_t analytic_pixels = 0;       ///< all pixels where an outline got a fractional alpha
  uint64_t distance_evals = 0;        ///< signed-distance evaluations (shape × pixel)
};

/// Renders the AAA frame (RGBA8, alpha 255). Shapes that get analytic coverage: disks,
/// spheres and capsules whose colour is constant (unlit, or lambert not declared; no
/// texture; no alpha cut-out). Everything else (triangles, cylinders, lit or textured
/// shapes) is rendered as `none` renders it. Layers are composited front to back in
/// display-linear light (each colour through the display transform, as an sRGB
/// framebuffer blends), over the first surface behind them that is not an analytic shape.
/// Deterministic at any thread count.
Image8 RenderAnalyticFrame(const Tracer& tracer, int width, int height, const AnalyticSpec& spec,
                           TraceCounters* counters, AnalyticCounters* analytic);

}  // namespace aalab
