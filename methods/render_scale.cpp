// Render scale, alone and combined with FXAA (Catlike Coding, Custom SRP 17, seed 000:
// "Combine FXAA and render scale"; Timothy Lottes, SIGGRAPH 2011, suggests 4/3 + FXAA).
//
// Implements:
//   scale43            render at round(scale·W) × round(scale·H) with one sample at each pixel
//                      centre, then rescale to W × H; no post filter.
//   scale43-fxaa-high  the same, with the tutorial's high-quality FXAA (fxaa-high: preset 39's
//                      steps, sqrt-luminance in alpha, thresholds 0.0833 / 0.166, subpix
//                      0.75) applied at the scaled size before the rescale — FXAA works on
//                      the scaled buffer, as in the tutorial.
// The runner renders at the scaled size, applies plan.post, then calls
// RescaleFrame(frame, W, H, plan.rescale, &stats) (methods/rescale.h).
//
// Parameters (both methods):
//   scale    [0.25..4]  default 4/3   render scale (2 = 4× the pixels; < 1 renders fewer)
//   rescale  {bilinear|bicubic}  default bilinear — the tutorial's render-scale setting
//            "Bicubic Rescaling" is Off unless chosen (its 4/3 + FXAA figure is bilinear
//            first, then "can be smoothed further by using bicubic rescaling"); bicubic is
//            the B-spline from four bilinear taps, applied for up- and downscaling.
// Deviations: see methods/rescale.cpp (filtering on sRGB-encoded values) and
// methods/fxaa311.cpp (FXAA fidelity notes).
#include "core/error.h"
#include "methods/families.h"
#include "methods/fxaa311.h"
#include "methods/rescale.h"

namespace aalab {

namespace {

Rescale ParseRescaleChoice(const std::string& name) {
  if (name == "bilinear") return Rescale::kBilinear;
  if (name == "bicubic") return Rescale::kBicubic;
  throw UserError("unknown rescale '" + name + "' (allowed: bilinear, bicubic)");
}

std::vector<ParamDef> ScaleParams() {
  return {FloatParam("scale", 4.0 / 3.0, 0.25, 4.0,
                     "render scale: the frame is rendered at round(scale*W) x round(scale*H)"),
          ChoiceParam("rescale", "bilinear", {"bilinear", "bicubic"},
                      "filter that brings the frame back to W x H: one bilinear tap, or the "
                      "B-spline bicubic from 4 bilinear taps")};
}

MethodPlan ScalePlan(const std::string& name, const ParamValues& v, bool fxaa) {
  MethodPlan plan;
  plan.name = name;
  plan.params = v;
  plan.render.pattern = SamplePattern::kCenter;
  plan.render.scale = v.Number("scale");
  plan.rescale = ParseRescaleChoice(v.Choice("rescale"));
  if (fxaa) {
    const Fxaa311Params fp = FxaaTutorialHighParams();
    SetFxaa311Post(plan, fp);
  }
  return plan;
}

}  // namespace

std::vector<MethodEntry> RenderScaleMethods() {
  std::vector<MethodEntry> out;
  out.push_back({"scale43", "render scale alone (default 4/3), centre samples, rescaled to the output size",
                 ScaleParams(), [](const ParamValues& v) { return ScalePlan("scale43", v, false); }});
  out.push_back({"scale43-fxaa-high", "render scale (default 4/3) + tutorial high-quality FXAA at that size, rescaled",
                 ScaleParams(), [](const ParamValues& v) { return ScalePlan("scale43-fxaa-high", v, true); }});
  out.back().in_default_list = true;
  return out;
}

}  // namespace aalab
