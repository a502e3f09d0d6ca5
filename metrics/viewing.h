/// Viewing conditions: the display and observer a run's perceptual metrics assume — display
/// resolution, size and distance (or pixels per degree directly), peak luminance, ambient
/// light and frame rate — as named presets with overrides ("tv-1080p-2m:distance_m=3").
/// FLIP takes its pixels per degree from it, the perceptual temporal error its pixels per
/// degree and frame rate (metrics/METRICS.md "Viewing conditions").
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/params.h"

namespace aalab {

/// One resolved viewing condition. `ppd` is always set (given, or from the geometry).
struct ViewingCondition {
  std::string preset;  ///< the preset it started from
  std::string spec;    ///< canonical spec: the preset plus the overrides given, in order
  int display_width_px = 0, display_height_px = 0;
  double diagonal_in = 0.0;  ///< display diagonal in inches (square pixels assumed)
  double distance_m = 0.0;   ///< viewing distance
  double ppd = 0.0;          ///< pixels per degree of visual angle at the display centre
  bool ppd_given = false;    ///< ppd set by the preset or an override, not by the geometry
  double peak_cd_m2 = 0.0;   ///< display peak luminance, cd/m² (recorded, see METRICS.md)
  double ambient_lux = 0.0;  ///< illuminance of the surroundings, lux (recorded)
  double fps = 0.0;          ///< frames per second of a sequence

  /// The (key, value) pairs the report's settings carry, all as text: viewing, ppd, fps,
  /// display_px, display_diagonal_in, viewing_distance_m, peak_cd_m2, ambient_lux.
  std::vector<std::pair<std::string, std::string>> Settings() const;
  /// One line for people: "desktop-27in-4k-60cm: 3840x2160, 27 in at 0.6 m = 67.3 px/deg, ...".
  std::string Describe() const;
};

/// One preset of the table.
struct ViewingPreset {
  const char* name;
  const char* help;
  int width_px, height_px;
  double diagonal_in, distance_m;
  double ppd;  ///< > 0: given explicitly (overrides the geometry); 0: from the geometry
  double peak_cd_m2, ambient_lux, fps;
};

/// The preset table, the default first.
const std::vector<ViewingPreset>& ViewingPresets();

/// The default preset's name ("default": 67 pixels per degree, FLIP's default as aalab has
/// always used it; every result of a run without --viewing is unchanged).
inline constexpr const char* kDefaultViewing = "default";

/// Parameter table of the overrides (display_w, display_h, diagonal_in, distance_m, ppd,
/// peak_cd_m2, ambient_lux, fps) with their ranges.
std::vector<ParamDef> ViewingParams();

/// Pixels per degree at the centre of a display of `width_px` columns, `diagonal_in` inches
/// diagonal (aspect from the pixel counts, square pixels) seen from `distance_m`:
/// 1 / (2·atan(pitch / (2·distance)) in degrees), pitch = width_m / width_px.
double PixelsPerDegree(int width_px, int height_px, double diagonal_in, double distance_m);

/// Resolves "PRESET" or "PRESET:key=value,..." (an empty spec = the default preset). Giving
/// any of display_w, display_h, diagonal_in, distance_m recomputes ppd from the geometry
/// unless ppd is given too. Unknown preset or key, bad or out-of-range value: UserError
/// listing what is allowed.
ViewingCondition ResolveViewing(const std::string& spec);

}  // namespace aalab
