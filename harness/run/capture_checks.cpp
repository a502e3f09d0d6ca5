// Mismatch checks of a user's capture: bias and interior error that AA cannot explain.
#include "harness/run/capture_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/color.h"

namespace aalab {

namespace {

std::string Fixed(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

/// Interior RMS of none − f(reference).
template <class F>
double InteriorRms(const ImageF& none, const ImageF& ref, const ImageF& mask, F&& f) {
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < none.PixelCount(); ++i) {
    if (mask.Data()[i] > 0.5f) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = none.Data()[3 * i + static_cast<size_t>(c)] - f(ref.Data()[3 * i + static_cast<size_t>(c)]);
      sum += d * d;
    }
    ++n;
  }
  return n ? std::sqrt(sum / (3.0 * static_cast<double>(n))) : 0.0;
}

}  // namespace

CaptureCheck CheckCapture(const ImageF& none, const ImageF& ref, const ImageF& mask) {
  CaptureCheck r;
  double sq_in = 0, sq_edge = 0;
  for (size_t i = 0; i < none.PixelCount(); ++i) {
    const bool edge = mask.Data()[i] > 0.5f;
    for (int c = 0; c < 3; ++c) {
      const double d =
          static_cast<double>(none.Data()[3 * i + static_cast<size_t>(c)]) - ref.Data()[3 * i + static_cast<size_t>(c)];
      (edge ? sq_edge : sq_in) += d * d;
      if (!edge) r.bias[c] += d;
    }
    ++(edge ? r.edge_px : r.interior_px);
  }
  if (r.interior_px == 0) return r;  // all edge: nothing to check against
  for (double& b : r.bias) b /= static_cast<double>(r.interior_px);
  r.interior_rms = std::sqrt(sq_in / (3.0 * static_cast<double>(r.interior_px)));
  r.edge_rms = r.edge_px ? std::sqrt(sq_edge / (3.0 * static_cast<double>(r.edge_px))) : 0.0;
  r.rms_if_linear = InteriorRms(none, ref, mask, [](float v) { return SrgbEncode(std::clamp(v, 0.0f, 1.0f)); });
  r.rms_if_double_encoded = InteriorRms(none, ref, mask, [](float v) { return SrgbDecode(v); });
  // The best exposure gain g on the linear reference: a coarse search, then a fine one.
  r.rms_with_gain = r.interior_rms;
  for (double step : {0.05, 0.005}) {
    const double centre = r.best_gain;
    for (int k = -20; k <= 20; ++k) {
      const double g = centre + step * k;
      if (g <= 0) continue;
      const double rms = InteriorRms(none, ref, mask, [g](float v) {
        return SrgbEncode(std::clamp(static_cast<float>(g * SrgbDecode(v)), 0.0f, 1.0f));
      });
      if (rms < r.rms_with_gain) {
        r.rms_with_gain = rms;
        r.best_gain = g;
      }
    }
  }

  const double levels = 255.0;
  double worst = 0;
  for (double b : r.bias) worst = std::fabs(b) > std::fabs(worst) ? b : worst;
  const bool biased = std::fabs(worst) > kBiasLimit;
  const bool unexplained = r.interior_rms > kInteriorRmsFloor && r.interior_rms > kInteriorToEdgeLimit * r.edge_rms;
  if (!biased && !unexplained) return r;
  std::string what;
  if (biased) {
    what = "over the interior (non-edge) pixels, none is on average " + Fixed(std::fabs(worst) * levels, 1) +
           " levels (of 255) " + (worst > 0 ? "brighter" : "darker") +
           " than the reference (per channel R, G, B: " + Fixed(r.bias[0] * levels, 1) + ", " +
           Fixed(r.bias[1] * levels, 1) + ", " + Fixed(r.bias[2] * levels, 1) +
           "; AA changes edges, not the mean of flat areas)";
  }
  if (unexplained) {
    what += std::string(what.empty() ? "" : "; ") + "the interior error (RMS " + Fixed(r.interior_rms * levels, 1) +
            " levels) is " +
            (r.edge_rms > 0 ? Fixed(r.interior_rms / r.edge_rms, 2) + "x the edge error" : "there with no edges") +
            " — anti-aliasing cannot explain it";
  }
  // The likely cause: the reading that fits best, if one fits much better.
  std::string cause;
  if (r.rms_if_linear < 0.5 * r.interior_rms) {
    cause =
        "the reference looks like linear values stored as display-encoded: sRGB-encoding it brings the interior "
        "error to RMS " +
        Fixed(r.rms_if_linear * levels, 1) +
        " levels (write the 16-bit PNG after the sRGB transform, or give the linear values as .exr)";
  } else if (r.rms_if_double_encoded < 0.5 * r.interior_rms) {
    cause =
        "the reference looks sRGB-encoded twice (or the frame is linear): decoding it once brings the interior "
        "error to RMS " +
        Fixed(r.rms_if_double_encoded * levels, 1) +
        " levels (give an .exr reference as linear, "
        "display-linear values)";
  } else if (r.rms_with_gain < 0.5 * r.interior_rms && std::fabs(r.best_gain - 1.0) > 0.02) {
    cause = "an exposure difference: the reference times " + Fixed(r.best_gain, 3) +
            " in linear light brings the interior error to RMS " + Fixed(r.rms_with_gain * levels, 1) +
            " levels (lock exposure; set the view's display exposure)";
  }
  r.warnings.push_back("none does not match the reference in a way AA can explain: " + what + ". " +
                       (cause.empty() ? std::string("Likely causes: ") : "Most likely " + cause + ". Other causes: ") +
                       "a view transform on one image only (Blender's Filmic or AgX instead of Standard), sRGB vs "
                       "linear encoding, exposure or tonemap, a different camera, frame or resolution, or a noisy 1x "
                       "frame (renderer noise, dithering)");
  return r;
}

}  // namespace aalab
