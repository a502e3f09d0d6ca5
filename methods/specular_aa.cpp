// Geometric specular anti-aliasing: the GGX roughness of glTF materials is widened by the
// variance of the shading normal over the pixel footprint, so that a normal-mapped or curved
// glossy surface does not sparkle where its normal varies faster than the pixel grid.
//
// Implements Y. Tokuyoshi and A. S. Kaplanyan, "Stable Geometric Specular Antialiasing with
// Projected-Space NDF Filtering", JCGT 10(2), 2021, listing 5 (the isotropic filter; their
// i3D 2019 paper "Improved Geometric Specular Antialiasing" is its first form):
//   α'² = min(1, α² + min(σ² · (|∂N/∂x|² + |∂N/∂y|²), κ)),  σ² = 1/(2π), κ = 0.18,
// α the GGX alpha (roughness²), ∂N/∂x and ∂N/∂y the screen-space derivatives of the shading
// normal. The paper's listing differentiates the interpolated vertex normal; aalab
// differentiates the final (normal-mapped) normal, as a pixel shader's ddx(N), ddy(N) of the
// normal it shades with does: the normal where the camera rays one pixel right and one pixel
// down meet the hit triangle's plane, its normal texture fetched there with the same footprint
// (scenes/tracer_gltf.cpp). One sample per pixel otherwise (the 1x frame's pattern).
// Parameters:
//   sigma2  variance of the pixel filter kernel, default 1/(2π), [0, 4]
//   kappa   clamp of the added α², default 0.18, [0, 1]
// Presets: `gsaa` (the paper's constants).
#include "methods/families.h"

namespace aalab {

namespace {

MethodPlan MakeSpecularAa(const ParamValues& p) {
  MethodPlan plan;
  plan.params = p;
  RenderSpec r;
  r.specular_aa.enabled = true;
  r.specular_aa.sigma2 = p.Number("sigma2");
  r.specular_aa.kappa = p.Number("kappa");
  plan.render = r;
  return plan;
}

}  // namespace

std::vector<MethodEntry> SpecularAaMethods() {
  return {{"gsaa",
           "geometric specular AA (Tokuyoshi & Kaplanyan 2021): GGX roughness widened by the normal's variance over the pixel, 1 spp",
           {FloatParam("sigma2", 0.15915494309189535, 0.0, 4.0, "variance of the pixel filter kernel (1/(2 pi))"),
            FloatParam("kappa", 0.18, 0.0, 1.0, "clamp of the added alpha^2")},
           MakeSpecularAa}};
}

}  // namespace aalab
