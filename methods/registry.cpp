#include "methods/registry.h"

#include "harness/core/error.h"
#include "methods/families.h"

namespace aalab {

const std::vector<MethodEntry>& MethodRegistry() {
  static const std::vector<MethodEntry> table = [] {
    std::vector<MethodEntry> all;
    auto add = [&all](std::vector<MethodEntry> rows, const char* source) {
      for (auto& r : rows) {
        r.source = source;
        all.push_back(std::move(r));
      }
    };
    // One line per family file, in listing order, with the family's sources: BibTeX keys of
    // reports/export_bibliography.cpp (what `aalab export` cites; "" = nothing to cite).
    add(SupersampleMethods(), "");
    add(MsaaMethods(), "d3d11_msaa");
    add(Fxaa1Methods(), "lottes2009fxaa");
    add(Fxaa311Methods(), "lottes2011fxaa311");
    add(SmaaMethods(), "jimenez2012smaa");
    add(RenderScaleMethods(), "flick2021fxaa,lottes2011fxaa311");
    add(AaaMethods(), "frostkiwi2024aaa");
    add(TaaMethods(), "karis2014taa,salvi2016taa");
    add(SpecularAaMethods(), "tokuyoshi2021gsaa");
    // Methods of a family whose presets come from another document as well.
    for (auto& r : all) {
      if (r.name == "fxaa-low" || r.name == "fxaa-medium" || r.name == "fxaa-high") r.source += ",flick2021fxaa";
      if (r.name == "fxaa-iter12") r.source += ",zeng_fxaa_notes";
    }
    return all;
  }();
  return table;
}

std::vector<std::string> MethodNames() {
  std::vector<std::string> names;
  for (const auto& e : MethodRegistry()) names.push_back(e.name);
  return names;
}

MethodPlan MakeMethod(const std::string& text) {
  const Spec spec = ParseSpec(text);
  for (const auto& e : MethodRegistry()) {
    if (e.name != spec.name) continue;
    ParamValues values = ResolveParams("method '" + e.name + "'", e.params, spec.overrides);
    MethodPlan plan = e.make(values);
    plan.name = e.name;
    plan.params = values;
    // Canonical spec: overrides in definition order, so equal specs compare equal.
    std::string canon = e.name;
    bool first = true;
    for (const auto& def : e.params) {
      for (const auto& [k, v] : spec.overrides) {
        if (k != def.name) continue;
        canon += (first ? ":" : ",") + k + "=";
        canon += def.kind == ParamKind::kChoice ? v : FormatNumber(values.Number(k));
        first = false;
      }
    }
    plan.spec = canon;
    return plan;
  }
  throw UserError("unknown method '" + spec.name + "' (valid: " + JoinNames(MethodNames()) + ")");
}

}  // namespace aalab
