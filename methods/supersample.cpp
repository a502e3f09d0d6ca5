// Supersampling methods: no AA and SSAA.
//
// Implements: `none` (one sample at the pixel centre, display transform, 8-bit, like a
// rasterizer's 1x back buffer) and supersampling that resolves like the reference (each
// sample tonemapped, box filter over the pixel area in linear light, sRGB encode, 8-bit):
//   ssaa-2x2     ordered 2×2 grid at ((i+0.5)/2, (j+0.5)/2); no parameters
//   ssaa-4x4     ordered 4×4 grid; no parameters
//   ssaa-rgss    4-sample rotated grid at (3/8,1/8) (7/8,3/8) (1/8,5/8) (5/8,7/8): every
//                row and column of a 4×4 sub-grid holds exactly one sample
//   ssaa-jitter  `spp` samples placed uniformly at random in the pixel (hash of pixel,
//                sample index and run seed), spp default 8, range 1..1024
// Sources: docs/design.md "Resolve"; FrostKiwi, "Analytical Anti-Aliasing" (seeds/004) on SSAA.
#include <cmath>

#include "core/error.h"
#include "methods/families.h"

namespace aalab {

namespace {

MethodPlan Plan(const std::string& name, const ParamValues& p, RenderSpec render) {
  MethodPlan plan;
  plan.name = name;
  plan.params = p;
  plan.render = render;
  return plan;
}

}  // namespace

std::vector<MethodEntry> SupersampleMethods() {
  std::vector<MethodEntry> out;
  out.push_back({"none", "no anti-aliasing: one sample at each pixel centre, 8-bit", {}, [](const ParamValues& p) {
                   return Plan("none", p, RenderSpec{});
                 }});
  out.push_back({"ssaa-2x2",
                 "supersampling, ordered 2x2 grid (4 spp), box resolve in linear light",
                 {},
                 [](const ParamValues& p) {
                   RenderSpec r;
                   r.pattern = SamplePattern::kOrderedGrid;
                   r.grid = 2;
                   return Plan("ssaa-2x2", p, r);
                 }});
  out.push_back({"ssaa-4x4",
                 "supersampling, ordered 4x4 grid (16 spp), box resolve in linear light",
                 {},
                 [](const ParamValues& p) {
                   RenderSpec r;
                   r.pattern = SamplePattern::kOrderedGrid;
                   r.grid = 4;
                   return Plan("ssaa-4x4", p, r);
                 }});
  out.push_back(
      {"ssaa-rgss", "supersampling, 4-sample rotated grid, box resolve in linear light", {}, [](const ParamValues& p) {
         RenderSpec r;
         r.pattern = SamplePattern::kRotatedGrid;
         return Plan("ssaa-rgss", p, r);
       }});
  out.push_back({"ssaa-jitter",
                 "supersampling, spp uniformly jittered samples (hash of pixel, index, seed)",
                 {IntParam("spp", 8, 1, 1024, "samples per pixel")},
                 [](const ParamValues& p) {
                   RenderSpec r;
                   r.pattern = SamplePattern::kJitter;
                   r.spp = p.Int("spp");
                   return Plan("ssaa-jitter", p, r);
                 }});
  // In `aalab run`'s default list: the baseline and the two ordered grids.
  for (auto& e : out) e.in_default_list = e.name == "none" || e.name == "ssaa-2x2" || e.name == "ssaa-4x4";
  return out;
}

}  // namespace aalab
