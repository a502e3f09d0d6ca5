#include "methods/registry.h"

#include <algorithm>

#include "core/error.h"
#include "methods/families.h"

namespace aalab {

namespace {

// One family file: its registry rows and what the listings say about the family.
struct FamilyRow {
  std::vector<MethodEntry> (*rows)();
  MethodFamily family;
};

// One line per family file, in listing order. name; title; files; docs page; source: BibTeX
// keys of reports/export_bibliography.cpp (what `aalab export` cites; "" = nothing to cite);
// gpu: the family has CUDA twins in gpu/ (methods/cuda/).
const std::vector<FamilyRow>& FamilyTable() {
  static const std::vector<FamilyRow> table = {
      {SupersampleMethods,
       {"supersample", "no AA (`none`: one centre sample, 8-bit); SSAA: ordered grids, 4-sample rotated grid, jittered",
        "methods/supersample.cpp", "", "", false}},
      {MsaaMethods,
       {"msaa",
        "MSAA (D3D11/Vulkan standard positions): one coverage ray per sample, one shading per primitive and pixel",
        "methods/msaa.cpp, scenes/tracer_msaa.cpp", "docs/msaa.md", "d3d11_msaa", false}},
      {Fxaa1Methods,
       {"fxaa1", "FXAA 1.0 (NVIDIA whitepaper presets 0-4, and 5 with 32 search steps)",
        "methods/fxaa1.cpp, methods/fxaa1_fast.cpp", "", "lottes2009fxaa", true}},
      {Fxaa311Methods,
       {"fxaa311",
        "FXAA 3.11 Quality presets; the Catlike Coding tutorial's low, medium, high; the widely copied 12-iteration "
        "GLSL",
        "methods/fxaa311.cpp, methods/fxaa311_fast.cpp", "docs/fxaa-fidelity.md", "lottes2011fxaa311", true}},
      {SmaaMethods,
       {"smaa", "SMAA 1x (the reference shader's presets); debug views `edges`, `weights`",
        "methods/smaa.cpp, methods/smaa_fast.cpp", "docs/smaa.md", "jimenez2012smaa", true}},
      {Cmaa2Methods,
       {"cmaa2",
        "Intel CMAA2 2.3 (CMAA2.hlsl, Apache-2.0): presets LOW, MEDIUM, HIGH, ULTRA; extra sharpness, colour edges",
        "methods/cmaa2.cpp", "docs/cmaa2.md", "intel2018cmaa2", false}},
      {RenderScaleMethods,
       {"render-scale", "render scale (default 4/3), rescaled to the output size; alone or with FXAA high at that size",
        "methods/render_scale.cpp, methods/rescale.cpp", "", "flick2021fxaa,lottes2011fxaa311", true}},
      {Fsr1Methods,
       {"fsr1",
        "AMD FSR 1: EASU upscaling from a lower render size (default 3/4), RCAS sharpening; alone or after FXAA high",
        "methods/fsr1.cpp", "docs/fsr1.md", "amd2021fsr1", false}},
      {AaaMethods,
       {"aaa", "analytical AA (FrostKiwi's article): the shipped shader and its variants",
        "methods/aaa.cpp, scenes/analytic.cpp", "docs/analytic-aa.md", "frostkiwi2024aaa", false}},
      {TaaMethods,
       {"taa",
        "TAA: Halton(2,3) jitter, exact reprojection, YCoCg variance clip, exponential blend (runs with `--frames`)",
        "methods/taa.cpp", "docs/motion.md", "karis2014taa,salvi2016taa", true}},
      {TaaProdMethods,
       {"taa-prod",
        "production TAA: closest-depth dilation, Catmull-Rom history, disocclusion test, adaptive feedback, "
        "optional Gaussian reconstruction, sharpening and RGBA16F history (runs with `--frames`)",
        "methods/taa_production.cpp", "docs/motion.md", "karis2014taa,salvi2016taa", true}},
      {TaauMethods,
       {"taau",
        "temporal upscaling: taa-prod rendering at 1/1.3 .. 1/2 of the output size, resolved at the output size",
        "methods/taau.cpp, methods/taa_production.cpp", "docs/motion.md", "karis2014taa,salvi2016taa", false}},
      {Fsr2Methods,
       {"fsr2",
        "AMD FSR 2.2.1 (GLSL shaders, MIT): temporal upscaling at 1x, 1.5x, 1.7x, 2x, 3x with depth, motion and "
        "RCAS (runs with `--frames`)",
        "methods/fsr2_methods.cpp, methods/fsr2_sequence.cpp, methods/fsr2_*.cpp", "docs/fsr2.md", "amd2023fsr2",
        false}},
      {SpecularAaMethods,
       {"specular-aa", "geometric specular AA: glTF GGX roughness widened by the shading normal's variance",
        "methods/specular_aa.cpp, scenes/tracer_gltf.cpp", "docs/real-content.md", "tokuyoshi2021gsaa", false}},
  };
  return table;
}

}  // namespace

const std::vector<MethodFamily>& MethodFamilies() {
  static const std::vector<MethodFamily> families = [] {
    std::vector<MethodFamily> out;
    for (const auto& f : FamilyTable()) out.push_back(f.family);
    return out;
  }();
  return families;
}

const std::vector<MethodEntry>& MethodRegistry() {
  static const std::vector<MethodEntry> table = [] {
    std::vector<MethodEntry> all;
    for (const auto& f : FamilyTable()) {
      for (auto& r : f.rows()) {
        r.family = f.family.name;
        r.source = f.family.source;
        r.has_gpu_twin = f.family.gpu_twin;
        all.push_back(std::move(r));
      }
    }
    // Methods of a family whose presets come from another document as well.
    for (auto& r : all) {
      if (r.name == "fxaa-low" || r.name == "fxaa-medium" || r.name == "fxaa-high") r.source += ",flick2021fxaa";
      if (r.name == "fxaa-iter12") r.source += ",zeng_fxaa_notes";
      if (r.name == "scale43-fxaa-high-easu-rcas") r.source += ",lottes2011fxaa311,flick2021fxaa";
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
    plan.family = e.family;
    plan.in_default_list = e.in_default_list;
    plan.has_gpu_twin = e.has_gpu_twin;
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

std::string MethodTableMarkdown() {
  auto code_list = [](const std::string& comma_separated) {
    std::string out, item;
    auto flush = [&] {
      while (!item.empty() && item.front() == ' ') item.erase(item.begin());
      if (!item.empty()) out += (out.empty() ? "`" : ", `") + item + "`";
      item.clear();
    };
    for (char c : comma_separated) {
      if (c == ',')
        flush();
      else
        item += c;
    }
    flush();
    return out;
  };
  std::string md = "| family | methods | parameters | GPU twin | files | docs |\n|---|---|---|---|---|---|\n";
  std::vector<std::string> defaults;
  for (const auto& f : MethodFamilies()) {
    std::string methods, params;
    std::vector<std::string> seen;
    for (const auto& e : MethodRegistry()) {
      if (e.family != f.name) continue;
      const std::string name = "`" + e.name + "`";
      methods += (methods.empty() ? "" : ", ") + (e.in_default_list ? "**" + name + "**" : name);
      if (e.in_default_list) defaults.push_back(e.name);
      for (const auto& def : e.params) {
        if (std::find(seen.begin(), seen.end(), def.name) != seen.end()) continue;
        seen.push_back(def.name);
        params += (params.empty() ? "`" : ", `") + def.name + "`";
      }
    }
    md += "| " + f.title + " | " + methods + " | " + (params.empty() ? "—" : params) + " | " +
          (f.gpu_twin ? "yes" : "—") + " | " + code_list(f.files) + " | " + (f.page.empty() ? "—" : code_list(f.page)) +
          " |\n";
  }
  md += "\nBold: `aalab run`'s default list (" + std::to_string(defaults.size()) +
        " methods; `--methods all` runs every one). Generated by `aalab list methods --markdown`.\n";
  return md;
}

}  // namespace aalab
