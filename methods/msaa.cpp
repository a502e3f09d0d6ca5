// MSAA: multisample anti-aliasing as a GPU does it, emulated on the ray tracer.
//
// Implements msaa-2x, msaa-4x, msaa-8x, msaa-16x: coverage (and depth) at N sample
// positions per pixel, ONE shading evaluation per primitive and pixel whose colour goes to
// every covered sample, then a box resolve. Geometric edges get N coverage levels; what the
// shading evaluates — textures, specular highlights, shadow rays, the alpha test — is
// evaluated once per primitive and pixel and aliases exactly like the 1x frame.
// The emulation (scenes/tracer_msaa.cpp, docs/msaa.md): one visibility ray per coverage
// sample; per distinct primitive one shading point; the renderer resolves.
//
// Sample positions: the standard patterns, in 1/16 px from the pixel centre, y down, in
// sample index order (core/render_spec.cpp, StandardSamplePositions):
//   2x  (4,4) (-4,-4)
//   4x  (-2,-6) (6,-2) (-6,2) (2,6)
//   8x  (1,-3) (-1,3) (5,1) (-3,-5) (-5,5) (-7,-1) (3,7) (7,-7)
//   16x (1,1) (-1,-3) (-3,2) (4,-1) (-5,-2) (2,5) (5,3) (3,-5) (-2,6) (0,-7) (-4,-6) (-6,4)
//       (-8,0) (7,-4) (6,7) (-7,-8)
// Sources: Direct3D 11.3 functional specification §19.2.4 "Standard Multisample Pattern"
// (patterns given in 1/16 px), §3.5.4 (pixel-frequency shading replicated to the covered
// samples), §3.5.5 (centroid: the centre when all samples are covered, else the first
// covered sample in index order); Vulkan specification, "Multisampling", standard sample
// locations (the same table as (x + 8) / 16 in [0,1]², checked entry by entry; Mesa's
// u_sample_positions.c: "standardized in both Vulkan and Direct3D").
//
// Parameters (all four methods):
//   shading     {center|centroid}  default center — where the one shading evaluation is
//               made: the pixel centre on the primitive (attributes extrapolated past its
//               edge, the hardware default), or the centroid rule above
//   alpha_test  {shade|sample|a2c}  default shade — alpha test once per shading evaluation (a
//               failed test discards the primitive from all its samples, like `discard`; the
//               hardware default), at every coverage sample (sample-rate alpha test), or
//               alpha-to-coverage: the shading point's alpha keeps ⌊α·N + d⌋ of the N
//               samples (the first in index order, ANDed with the primitive's coverage), d the
//               pixel's threshold in the 4×4 Bayer ordered-dither matrix ((b + 0.5)/16; B. E.
//               Bayer, "An optimum method for two-level rendition of continuous-tone
//               pictures", ICC 1973), so N samples and 16 dither phases give 16·N alpha levels
//   resolve     {display|hdr-linear}  default display — each sample through the display
//               transform, box average in linear light, sRGB encode (as SSAA and the
//               reference); hdr-linear averages scene-linear radiance and applies the display
//               transform once (the naive resolve of an HDR render target)
#include "core/error.h"
#include "methods/families.h"

namespace aalab {

namespace {

std::vector<ParamDef> MsaaParams() {
  return {
      ChoiceParam("shading", "center", {"center", "centroid"},
                  "where a primitive is shaded: the pixel centre (extrapolated) or the centroid rule"),
      ChoiceParam("alpha_test", "shade", {"shade", "sample", "a2c"},
                  "alpha test once per shading evaluation (discard), at every coverage sample, or alpha-to-coverage"),
      ChoiceParam("resolve", "display", {"display", "hdr-linear"},
                  "tonemap each sample then average (display) or average radiance then tonemap (hdr-linear)")};
}

/// The render request of msaa-<n>x with resolved parameters.
RenderSpec MsaaRender(int samples, const ParamValues& p) {
  RenderSpec r;
  r.msaa.samples = samples;
  r.msaa.shading = p.Choice("shading") == "centroid" ? MsaaShading::kCentroid : MsaaShading::kCenter;
  const std::string& at = p.Choice("alpha_test");
  r.msaa.alpha_test = at == "sample" ? MsaaAlphaTest::kSample
                      : at == "a2c"  ? MsaaAlphaTest::kCoverage
                                     : MsaaAlphaTest::kShade;
  r.msaa.resolve = p.Choice("resolve") == "hdr-linear" ? MsaaResolve::kHdrLinear : MsaaResolve::kDisplay;
  return r;
}

}  // namespace

std::vector<MethodEntry> MsaaMethods() {
  std::vector<MethodEntry> out;
  for (const int n : {2, 4, 8, 16}) {
    const std::string name = "msaa-" + std::to_string(n) + "x";
    out.push_back({name,
                   "MSAA " + std::to_string(n) +
                       "x: coverage at the standard D3D/Vulkan positions, one shading per primitive and pixel",
                   MsaaParams(), [n, name](const ParamValues& p) {
                     MethodPlan plan;
                     plan.name = name;
                     plan.params = p;
                     plan.render = MsaaRender(n, p);
                     return plan;
                   }});
  }
  for (auto& e : out) e.in_default_list = e.name == "msaa-4x";  // in `aalab run`'s default list
  return out;
}

}  // namespace aalab
