// Specular anti-aliasing: the GGX roughness of glTF materials is widened by the variance of the
// shading normal over the pixel footprint, so that a normal-mapped or curved glossy surface
// does not sparkle where its normal varies faster than the pixel grid. Two terms, as engines
// pair them (Unity HDRP: GeometricNormalVariance + TextureNormalVariance):
//
// 1. Geometric: Y. Tokuyoshi and A. S. Kaplanyan, "Stable Geometric Specular Antialiasing with
//    Projected-Space NDF Filtering", JCGT 10(2), 2021, listing 5 (the isotropic filter; their
//    i3D 2019 paper "Improved Geometric Specular Antialiasing" is its first form):
//      α'² = min(1, α² + min(σ² · (|∂N/∂x|² + |∂N/∂y|²), κ)),  σ² = 1/(2π), κ = 0.18,
//    α the GGX alpha (roughness²), ∂N/∂x, ∂N/∂y the screen-space derivatives of the normal:
//    by default the interpolated vertex normal, as the paper's listing differentiates it
//    (derivatives=vertex); derivatives=mapped takes the final normal-mapped normal instead (what
//    `gsaa` did before 2026-11: fed the mapped normal, the filter widens lobes wherever the map
//    has detail, including where the truth leaves the highlight dark, and measured worse than
//    no AA on real-glossy; docs/lighting.md "Specular AA"). The normal where the camera rays one
//    pixel right and one pixel down meet the hit triangle's plane (scenes/tracer_gltf.cpp).
// 2. Texture (toksvig > 0): the normal map's own variance per mip level, from the length r of the
//    footprint's mean unit normal (Toksvig 2005; the vMF form of Neubelt & Pettineo 2013, the
//    relation HDRP's TextureNormalVariance uses): α'² += 1/(2κ), κ = (3r − r³)/(1 − r²)
//    (scenes/toksvig.h). The magnified level-0 texels add nothing; minified levels add the
//    spread the mip averaging removed from the normal.
// One sample per pixel otherwise (the 1x frame's pattern).
// Parameters:
//   sigma2       variance of the pixel filter kernel, default 1/(2π), [0, 4]
//   kappa        clamp of the added geometric α², default 0.18, [0, 1]
//   derivatives  vertex (default) | mapped: whose normal the geometric term differentiates
//   toksvig      weight of the normal map's variance term, default 0 (off), [0, 1]; 1 is the
//                published relation. Off by default because it measured worse than no AA
//                on real-glossy under the sun (docs/lighting.md "Specular AA": that map's
//                normals are bimodal, flat or steep, which one widened lobe cannot represent)
//   toksvig_max  clamp of the texture term's added α², default 0.04, [0, 1] (HDRP clamps its
//                normal filtering by the material's threshold², default 0.2²)
// Presets: `gsaa` (the paper's constants, vertex derivatives, texture term off; add it with
// `gsaa:toksvig=1`).
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
  r.specular_aa.mapped_derivatives = p.Choice("derivatives") == "mapped";
  r.specular_aa.toksvig = p.Number("toksvig");
  r.specular_aa.toksvig_max = p.Number("toksvig_max");
  plan.render = r;
  return plan;
}

}  // namespace

std::vector<MethodEntry> SpecularAaMethods() {
  return {
      {"gsaa",
       "specular AA: GGX roughness widened by the vertex normal's variance over the pixel (Tokuyoshi & Kaplanyan "
       "2021); "
       "toksvig=1 adds the normal map's own variance per mip level (Toksvig / vMF), 1 spp",
       {FloatParam("sigma2", 0.15915494309189535, 0.0, 4.0, "variance of the pixel filter kernel (1/(2 pi))"),
        FloatParam("kappa", 0.18, 0.0, 1.0, "clamp of the added alpha^2"),
        ChoiceParam("derivatives", "vertex", {"vertex", "mapped"},
                    "whose normal the geometric term differentiates (mapped: the normal-mapped normal)"),
        FloatParam("toksvig", 0.0, 0.0, 1.0, "weight of the normal map's variance term (0: off; 1: Toksvig / vMF)"),
        FloatParam("toksvig_max", 0.04, 0.0, 1.0, "clamp of the normal map term's added alpha^2 (HDRP: threshold^2)")},
       MakeSpecularAa}};
}

}  // namespace aalab
