/// Checks of a user's capture that anti-aliasing cannot explain (docs/own-frames.md
/// "Mismatch warnings"): `none` (the 1x frame) should differ from its reference mostly at
/// edges. A mean signed bias over interior pixels, or interior error far above what the
/// edges show, means the two images do not show the same thing the same way (a Filmic view
/// transform, a linear reference read as sRGB, another exposure, another camera).
#pragma once
#include <string>
#include <vector>

#include "core/image.h"

namespace aalab {

/// Mean signed bias over interior pixels above this (sRGB-encoded units: 3 of 255 levels).
inline constexpr double kBiasLimit = 3.0 / 255.0;
/// Interior RMS error above this share of the edge RMS error, and above kInteriorRmsFloor,
/// is "far above what the edges explain".
inline constexpr double kInteriorToEdgeLimit = 0.5;
inline constexpr double kInteriorRmsFloor = 0.03;  ///< ≈ 30.5 dB interior PSNR

/// What the check measured on one frame (sRGB-encoded units; interior = not in the mask).
struct CaptureCheck {
  double bias[3] = {0, 0, 0};  ///< mean of none − reference over interior pixels, per channel
  double interior_rms = 0, edge_rms = 0;
  size_t interior_px = 0, edge_px = 0;
  /// Interior RMS error if the reference had been read differently: as linear values that
  /// still need the sRGB encode, or as sRGB values that were wrongly encoded once more.
  double rms_if_linear = 0, rms_if_double_encoded = 0;
  double best_gain = 1;               ///< the exposure gain on the linear reference that fits none best
  double rms_with_gain = 0;           ///< interior RMS with that gain
  std::vector<std::string> warnings;  ///< empty: nothing AA cannot explain
};

/// Runs the checks. `none` and `reference`: float RGB, sRGB-encoded; `edge_mask`: 1 = edge.
CaptureCheck CheckCapture(const ImageF& none, const ImageF& reference, const ImageF& edge_mask);

}  // namespace aalab
