// Temporal upscaling (TAAU): the production TAA (methods/taa_production.cpp) rendering its
// jittered frame below the output size and resolving at the output size — the way games pair
// render scale with a temporal upscaler. Rows `taau-77`, `taau-67`, `taau-59`, `taau-50`: render
// scale 1/1.3, 1/1.5, 1/1.7, 1/2 (AMD FSR 2 "Ultra Quality", "Quality", "Balanced",
// "Performance"; UE TSR and DLSS use the same ratios). The jitter sequence is lengthened with the
// scale as FSR 2 prescribes (ffxFsr2GetJitterPhaseCount: phases = ⌊8·(output / render)²⌋, so
// that every output pixel receives samples at a comparable density): 13, 18, 23 and 32 Halton
// (2,3) points for the four ratios (computed from the nominal ratio; `samples` overrides).
// Every production-TAA parameter applies; the reconstruction measures the sample distances in
// render pixels (the input's sample spacing), the history lives at the output size, and the
// motion vectors are scaled to output pixels (methods/taa_production.cpp, step 2).
// Cost: the render at the lower size plus the resolve at the output size (no separate rescale).
// Sources: AMD FidelityFX Super Resolution 2 documentation (jitter phase count, quality
// modes); B. Karis, "High Quality Temporal Supersampling", SIGGRAPH 2014 (UE4 TAAU).
#include <cmath>

#include "methods/families.h"
#include "methods/taa_production.h"

namespace aalab {

int TaauJitterPhases(double ratio) { return static_cast<int>(std::floor(8.0 * ratio * ratio + 1e-9)); }

std::vector<MethodEntry> TaauMethods() {
  struct Mode {
    const char* name;
    double ratio;
    const char* label;
  };
  const Mode modes[] = {{"taau-77", 1.3, "1/1.3 (FSR 2 Ultra Quality)"},
                        {"taau-67", 1.5, "1/1.5 (FSR 2 Quality)"},
                        {"taau-59", 1.7, "1/1.7 (FSR 2 Balanced)"},
                        {"taau-50", 2.0, "1/2 (FSR 2 Performance)"}};
  std::vector<MethodEntry> out;
  for (const Mode& m : modes) {
    std::vector<ParamDef> defs = TaaProdParamDefs();
    defs.insert(defs.begin(), IntParam("samples", TaauJitterPhases(m.ratio), 1, 256,
                                       "Halton(2,3) jitter points cycled (default floor(8 ratio^2), FSR 2)"));
    const double scale = 1.0 / m.ratio;
    out.push_back({m.name,
                   std::string("temporal upscaling: taa-prod rendering at scale ") + m.label +
                       ", resolved at the output size (needs --frames > 1)",
                   defs, [scale](const ParamValues& v) {
                     MethodPlan plan;
                     plan.render.scale = scale;
                     plan.render.jitter.samples = v.Int("samples");
                     const TaaProdParams tp = TaaProdParamsFrom(v);
                     plan.make_state = [tp] { return MakeTaaProdState(tp); };
                     return plan;
                   }});
  }
  return out;
}

}  // namespace aalab
