// One colour and marker per method (see html_method_style.h).
#include "reports/html_method_style.h"

#include <array>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <map>

namespace aalab::html {

namespace {

/// FNV-1a, 32 bit: a stable hash (std::hash may differ between standard libraries).
std::uint32_t Fnv1a(const std::string& s) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : s) {
    h ^= c;
    h *= 16777619u;
  }
  return h;
}

struct Shape {
  const char* name;
  const char* path;
};
constexpr std::array<Shape, 6> kShapes = {{
    {"circle", "M-1,0a1,1 0 1,0 2,0a1,1 0 1,0 -2,0Z"},
    {"square", "M-0.86,-0.86H0.86V0.86H-0.86Z"},
    {"diamond", "M0,-1.2L1.2,0L0,1.2L-1.2,0Z"},
    {"triangle", "M0,-1.2L1.1,0.8H-1.1Z"},
    {"triangle-down", "M0,1.2L1.1,-0.8H-1.1Z"},
    {"plus", "M-0.38,-1.1H0.38V-0.38H1.1V0.38H0.38V1.1H-0.38V0.38H-1.1V-0.38H-0.38Z"},
}};

}  // namespace

std::string MethodFamily(const std::string& spec) {
  size_t i = 0;
  while (i < spec.size() && std::isalpha(static_cast<unsigned char>(spec[i]))) ++i;
  if (i == 0) return spec;  // no leading letters: the whole spec (as the page's family())
  while (i < spec.size() && std::isdigit(static_cast<unsigned char>(spec[i]))) ++i;
  return spec.substr(0, i);
}

MethodStyle StyleOfMethod(const std::string& spec) {
  // The registry's families (aalab list methods), colour-blind-friendly where it counts
  // (Okabe-Ito first); other families hash into the extra palette.
  static const std::map<std::string, std::string> kFamily = {
      {"none", "#7f7f7f"}, {"ssaa", "#0072b2"},    {"msaa", "#56b4e9"},  {"fxaa1", "#e69f00"}, {"fxaa311", "#d55e00"},
      {"fxaa", "#f0e442"}, {"smaa", "#009e73"},    {"cmaa2", "#cc79a7"}, {"taa", "#6a3d9a"},   {"taau", "#b15928"},
      {"gsaa", "#17becf"}, {"scale43", "#8c564b"}, {"rcas", "#bcbd22"},  {"aaa", "#1f3f7f"},   {"fsr1", "#e7298a"},
  };
  static const std::array<const char*, 8> kExtra = {"#66a61e", "#a6761d", "#7570b3", "#1b9e77",
                                                    "#e6ab02", "#666666", "#d95f02", "#386cb0"};
  const std::string family = MethodFamily(spec);
  MethodStyle s;
  const auto it = kFamily.find(family);
  s.colour = it != kFamily.end() ? it->second : kExtra[Fnv1a(family) % kExtra.size()];
  const size_t shape = spec == family ? 0 : 1 + Fnv1a(spec) % (kShapes.size() - 1);
  s.marker = kShapes[shape].name;
  s.path = kShapes[shape].path;
  return s;
}

std::string MarkerSvg(const std::string& spec, double x, double y, double r, const std::string& fill) {
  const MethodStyle s = StyleOfMethod(spec);
  char head[160];
  std::snprintf(head, sizeof head, "<path class=\"mk\" transform=\"translate(%.1f %.1f) scale(%.2f)\" d=\"", x, y, r);
  return std::string(head) + s.path + "\" fill=\"" + (fill.empty() ? s.colour : fill) + "\" stroke=\"" + s.colour +
         "\" vector-effect=\"non-scaling-stroke\" data-marker=\"" + s.marker + "\"/>";
}

}  // namespace aalab::html
