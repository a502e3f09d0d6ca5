// Viewing conditions: named presets of display + observer, resolved with overrides into the
// pixels per degree and frame rate the perceptual metrics use. Formulas and the preset table
// are documented in metrics/METRICS.md "Viewing conditions".
#include "metrics/viewing.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>

#include "core/error.h"

namespace aalab {

const std::vector<ViewingPreset>& ViewingPresets() {
  // name, help, display px, diagonal (in), distance (m), explicit ppd (0: geometry),
  // peak cd/m², ambient lux, fps. The default keeps FLIP's 67 px/deg exactly (a 0.7 m wide
  // 3840-px display at 0.7 m gives 67.02 by the geometry; aalab has always used 67).
  static const std::vector<ViewingPreset> table = {
      {"default", "FLIP's observer as aalab always used it: 67 px/deg (0.7 m wide 4K display at 0.7 m)", 3840, 2160,
       31.62, 0.7, 67.0, 200.0, 250.0, 60.0},
      {"desktop-27in-4k-60cm", "27-inch 4K monitor at 60 cm", 3840, 2160, 27.0, 0.6, 0.0, 300.0, 250.0, 60.0},
      {"desktop-24in-1080p-60cm", "24-inch 1080p monitor at 60 cm", 1920, 1080, 24.0, 0.6, 0.0, 250.0, 250.0, 60.0},
      {"laptop-14in-1080p-50cm", "14-inch 1080p laptop at 50 cm", 1920, 1080, 14.0, 0.5, 0.0, 300.0, 250.0, 60.0},
      {"tv-1080p-2m", "55-inch 1080p TV at 2 m", 1920, 1080, 55.0, 2.0, 0.0, 400.0, 100.0, 60.0},
      {"tv-4k-2m", "65-inch 4K TV at 2 m", 3840, 2160, 65.0, 2.0, 0.0, 600.0, 100.0, 60.0},
      {"handheld", "6.1-inch 2532x1170 phone at 30 cm", 2532, 1170, 6.1, 0.3, 0.0, 600.0, 500.0, 60.0},
  };
  return table;
}

std::vector<ParamDef> ViewingParams() {
  return {IntParam("display_w", 3840, 1, 65536, "display width, pixels"),
          IntParam("display_h", 2160, 1, 65536, "display height, pixels"),
          FloatParam("diagonal_in", 31.62, 0.5, 1000.0, "display diagonal, inches"),
          FloatParam("distance_m", 0.7, 0.05, 100.0, "viewing distance, metres"),
          FloatParam("ppd", 67.0, 1.0, 1000.0, "pixels per degree (given: overrides the geometry)"),
          FloatParam("peak_cd_m2", 200.0, 1.0, 10000.0, "display peak luminance, cd/m2"),
          FloatParam("ambient_lux", 250.0, 0.0, 100000.0, "ambient illuminance, lux"),
          FloatParam("fps", 60.0, 1.0, 1000.0, "frames per second of a sequence")};
}

double PixelsPerDegree(int width_px, int height_px, double diagonal_in, double distance_m) {
  const double w = width_px, h = height_px;
  const double width_m = diagonal_in * 0.0254 * w / std::sqrt(w * w + h * h);
  const double pitch = width_m / w;
  const double pixel_deg = 2.0 * std::atan(pitch / (2.0 * distance_m)) * 180.0 / std::numbers::pi;
  return 1.0 / pixel_deg;
}

ViewingCondition ResolveViewing(const std::string& text) {
  const Spec spec = ParseSpec(text.empty() ? std::string(kDefaultViewing) : text);
  const ViewingPreset* preset = nullptr;
  for (const auto& p : ViewingPresets()) {
    if (spec.name == p.name) preset = &p;
  }
  if (!preset) {
    std::vector<std::string> names;
    for (const auto& p : ViewingPresets()) names.emplace_back(p.name);
    throw UserError("--viewing '" + text + "': unknown preset '" + spec.name + "' (allowed: " + JoinNames(names) +
                    ", each optionally with :key=value overrides)");
  }
  // The preset's values become the defaults of the table, then the overrides apply.
  std::vector<ParamDef> defs = ViewingParams();
  for (auto& d : defs) {
    if (d.name == "display_w") d.default_number = preset->width_px;
    if (d.name == "display_h") d.default_number = preset->height_px;
    if (d.name == "diagonal_in") d.default_number = preset->diagonal_in;
    if (d.name == "distance_m") d.default_number = preset->distance_m;
    if (d.name == "peak_cd_m2") d.default_number = preset->peak_cd_m2;
    if (d.name == "ambient_lux") d.default_number = preset->ambient_lux;
    if (d.name == "fps") d.default_number = preset->fps;
  }
  const ParamValues v = ResolveParams("--viewing '" + text + "'", defs, spec.overrides);
  ViewingCondition c;
  c.preset = preset->name;
  c.display_width_px = v.Int("display_w");
  c.display_height_px = v.Int("display_h");
  c.diagonal_in = v.Number("diagonal_in");
  c.distance_m = v.Number("distance_m");
  c.peak_cd_m2 = v.Number("peak_cd_m2");
  c.ambient_lux = v.Number("ambient_lux");
  c.fps = v.Number("fps");
  bool ppd_override = false, geometry_override = false;
  for (const auto& name : v.Overridden()) {
    ppd_override = ppd_override || name == "ppd";
    geometry_override = geometry_override || name == "display_w" || name == "display_h" || name == "diagonal_in" ||
                        name == "distance_m";
  }
  if (ppd_override) {
    c.ppd = v.Number("ppd");
    c.ppd_given = true;
  } else if (preset->ppd > 0.0 && !geometry_override) {
    c.ppd = preset->ppd;
    c.ppd_given = true;
  } else {
    c.ppd = PixelsPerDegree(c.display_width_px, c.display_height_px, c.diagonal_in, c.distance_m);
    if (!(c.ppd >= 1.0 && c.ppd <= 1000.0)) {
      throw UserError("--viewing '" + text + "': the display geometry gives " + FormatNumber(c.ppd) +
                      " pixels per degree, outside 1..1000");
    }
  }
  c.spec = spec.name;
  for (size_t i = 0; i < spec.overrides.size(); ++i) {
    c.spec += (i == 0 ? ":" : ",") + spec.overrides[i].first + "=" + spec.overrides[i].second;
  }
  return c;
}

namespace {

/// The shortest "%g" text without an exponent that reads back as v ("67", "0.6", "55.04364145434214").
std::string Num(double v) {
  char buf[64];
  for (int p = 1; p <= 17; ++p) {
    std::snprintf(buf, sizeof buf, "%.*g", p, v);
    if (std::strtod(buf, nullptr) == v && !std::strchr(buf, 'e')) return buf;
  }
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> ViewingCondition::Settings() const {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%dx%d", display_width_px, display_height_px);
  return {{"viewing", spec},
          {"ppd", Num(ppd)},
          {"fps", Num(fps)},
          {"display_px", buf},
          {"display_diagonal_in", Num(diagonal_in)},
          {"viewing_distance_m", Num(distance_m)},
          {"peak_cd_m2", Num(peak_cd_m2)},
          {"ambient_lux", Num(ambient_lux)}};
}

std::string ViewingCondition::Describe() const {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "%s: %dx%d, %.4g in at %.3g m = %.4g px/deg%s, %.4g cd/m2 peak, %.4g lux ambient, %.4g fps",
                spec.c_str(), display_width_px, display_height_px, diagonal_in, distance_m, ppd,
                ppd_given ? " (given)" : "", peak_cd_m2, ambient_lux, fps);
  return buf;
}

}  // namespace aalab
