#include "methods/registry.h"

#include "harness/core/error.h"
#include "methods/families.h"

namespace aalab {

const std::vector<MethodEntry>& MethodRegistry() {
  static const std::vector<MethodEntry> table = [] {
    std::vector<MethodEntry> all;
    auto add = [&all](std::vector<MethodEntry> rows) {
      for (auto& r : rows) all.push_back(std::move(r));
    };
    // One line per family file, in listing order.
    add(SupersampleMethods());
    add(MsaaMethods());
    add(Fxaa1Methods());
    add(Fxaa311Methods());
    add(SmaaMethods());
    add(RenderScaleMethods());
    add(AaaMethods());
    add(TaaMethods());
    add(SpecularAaMethods());
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
