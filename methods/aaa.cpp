// Analytical anti-aliasing (AAA): shapes compute their own edge coverage from a signed
// distance and the size of a pixel — one sample per pixel, no post filter.
//
// Implements the knobs of FrostKiwi's "Analytical Anti-Aliasing" (seeds/004,
// circle-analyticalCompare.fs and circle-analytical.fs) as a render request (AnalyticSpec,
// interpreted by scenes/analytic.cpp) for disks, spheres and capsules; triangles and
// cylinders render as `none` does. alpha = blend((p_obj − d − px·shrink) / (px·smoothing)),
// d the signed distance to the nominal outline, p_obj the per-object pixel size (the demo
// grows its quad by one pixel, hence the p_obj term), px the chosen pixel size.
// Parameters (all presets take all of them as overrides):
//   pixel_size  object | length | fwidth     default object  (SIMPLE / DFD / FWIDTH in the demo)
//   blend       division | linstep | smoothstep  default division
//   shrink      radius adjust in pixels, [-2, 2], default 0.5 (circle-analytical.fs'
//               "dist += pixelSize * 0.5": with the 1 px grown quad, a ramp centred on the outline)
//   smoothing   ramp width in pixels, [0.25, 4], default 1 (smoothingAmount)
// Presets:
//   aaa               object, division, shrink 0.5, smoothing 1: the article's shipped 2-D shader
//                     (a 1 px linear ramp centred on the outline)
//   aaa-length        pixel size length(vec2(dFdx(d), dFdy(d)))  (Shapes' "Corrected LAA")
//   aaa-fwidth        pixel size fwidth(d) = |dFdx d| + |dFdy d|  (Shapes' "Fast LAA")
//   aaa-smoothstep    smoothstep(1, 1 − px, dist) instead of the division
//   aaa-sqrt2         smoothing √2 px kept centred (shrink 1 − √2/2): the article's "diagonal
//                     pixel size" button, where an opaque pixel always has a transparent one in front
//   aaa-inside        shrink 1: the compare demo's initial radius adjust, the ramp inside the
//                     outline (the shape shrinks by half a pixel)
//   aaa-fwidth-inside fwidth with shrink 1: the "rhombous warping" case of small circles
//   aaa-3d            length, shrink 1, smoothing √2: 3DAnalytical.fs' alpha = −dist/(px·√2)
#include <cmath>

#include "core/error.h"
#include "methods/families.h"

namespace aalab {

namespace {

constexpr double kSqrt2 = 1.4142135623730951;

struct AaaPreset {
  const char* name;
  const char* help;
  const char* pixel_size;
  const char* blend;
  double shrink;
  double smoothing;
};

MethodPlan MakeAaa(const ParamValues& p) {
  MethodPlan plan;
  plan.params = p;
  RenderSpec r;
  r.aaa.enabled = true;
  const std::string& ps = p.Choice("pixel_size");
  r.aaa.pixel_size = ps == "object"   ? AaaPixelSize::kObject
                     : ps == "length" ? AaaPixelSize::kLength
                                      : AaaPixelSize::kFwidth;
  const std::string& bl = p.Choice("blend");
  r.aaa.blend = bl == "division" ? AaaBlend::kDivision : bl == "linstep" ? AaaBlend::kLinstep : AaaBlend::kSmoothstep;
  r.aaa.shrink = p.Number("shrink");
  r.aaa.smoothing = p.Number("smoothing");
  plan.render = r;
  return plan;
}

}  // namespace

std::vector<MethodEntry> AaaMethods() {
  static const AaaPreset kPresets[] = {
      {"aaa", "analytical AA: 1 px linear ramp centred on disk/sphere/capsule outlines, per-object pixel size",
       "object", "division", 0.5, 1.0},
      {"aaa-length", "analytical AA, pixel size length(dFdx, dFdy) of the distance", "length", "division", 0.5, 1.0},
      {"aaa-fwidth", "analytical AA, pixel size fwidth(distance) = |dFdx| + |dFdy|", "fwidth", "division", 0.5, 1.0},
      {"aaa-smoothstep", "analytical AA, smoothstep blend over 1 px", "object", "smoothstep", 0.5, 1.0},
      {"aaa-sqrt2", "analytical AA, sqrt(2) px ramp centred on the outline", "object", "division", 1.0 - kSqrt2 / 2.0,
       kSqrt2},
      {"aaa-inside", "analytical AA, 1 px ramp inside the outline (shrink 1)", "object", "division", 1.0, 1.0},
      {"aaa-fwidth-inside", "analytical AA, fwidth pixel size with shrink 1 (rhombic small circles)", "fwidth",
       "division", 1.0, 1.0},
      {"aaa-3d", "analytical AA as the article's 3D demo: -dist/(length*sqrt(2)), ramp inside", "length", "division",
       1.0, kSqrt2},
  };
  std::vector<MethodEntry> out;
  for (const AaaPreset& pr : kPresets) {
    out.push_back({pr.name,
                   pr.help,
                   {ChoiceParam("pixel_size", pr.pixel_size, {"object", "length", "fwidth"},
                                "pixel size: per-object constant, length(dFdx, dFdy) or fwidth"),
                    ChoiceParam("blend", pr.blend, {"division", "linstep", "smoothstep"},
                                "distance to alpha: division (framebuffer-clamped), linearstep or smoothstep"),
                    FloatParam("shrink", pr.shrink, -2.0, 2.0, "radius adjust in pixels (dist += px * shrink)"),
                    FloatParam("smoothing", pr.smoothing, 0.25, 4.0, "ramp width in pixels")},
                   MakeAaa});
  }
  for (auto& e : out) e.in_default_list = e.name == "aaa";  // in `aalab run`'s default list
  return out;
}

}  // namespace aalab
