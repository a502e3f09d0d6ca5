/// The speed-sweep chart (docs/motion.md "Speed sweep"): for runs over the scenes
/// `motion-speed-<kind>-<speed>`, pooled temporal_perceptual and pooled FLIP against speed,
/// one line per method, one chart pair per kind of motion.
#pragma once
#include <string>
#include <vector>

#include "reports/result.h"

namespace aalab {

/// One point of the sweep: a method's pooled measures on one scene of the family.
struct SpeedPoint {
  std::string kind;    ///< translate, rotate, zoom, disocclude (the scene name's middle)
  double speed = 0.0;  ///< px per frame at 320x180 (from the name: "0p25" → 0.25)
  std::string method;  ///< the row's spec
  double temporal_perceptual = 0.0, flip_mean = 0.0;
};

/// The sweep's points in report order (rows with both measures only); empty when the report
/// has no scene of the family.
std::vector<SpeedPoint> SpeedSweepPoints(const Report& report);

/// Appends the section (static inline SVG) when the report has sweep scenes; nothing otherwise.
void AppendSpeedSection(std::string& html, const Report& report);

/// The points as CSV: kind,speed,method,temporal_perceptual,flip_mean (header line first).
std::string SpeedSweepCsv(const Report& report);

}  // namespace aalab
