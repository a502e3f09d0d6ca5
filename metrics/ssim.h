/// SSIM (Wang, Bovik, Sheikh, Simoncelli 2004), mean of per-channel SSIM over R, G, B on
/// sRGB-encoded values. Definition, border rule and precision: the block at the top of
/// metrics/ssim.cpp and metrics/METRICS.md.
#pragma once
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"

namespace aalab {

/// Window and constants (the choices of Wang et al. 2004): Gaussian σ = 1.5 truncated to
/// 11×11 (radius 5), K1 = 0.01, K2 = 0.03, data range L = 1.
inline constexpr int kSsimRadius = 5;
inline constexpr double kSsimSigma = 1.5;
inline constexpr double kSsimK1 = 0.01;
inline constexpr double kSsimK2 = 0.03;

/// Result of ComputeSsim.
struct SsimResult {
  /// Mean of `per_channel`; empty when SSIM is undefined, with `null_reason`.
  std::optional<double> ssim;
  /// Mean SSIM of R, G, B over the valid region (all 0 when `ssim` is empty).
  std::array<double, 3> per_channel{};
  std::string null_reason;
};

/// SSIM of two same-size RGB images (channels 0..2; any further channel is ignored), values
/// sRGB-encoded in [0, 1]. Symmetric in (a, b); SSIM(x, x) = 1 exactly. The SSIM map is
/// averaged over the "valid" region only: pixels at least 5 from every border, where the
/// 11×11 window lies inside the image (matches scikit-image's default crop). Images narrower
/// or shorter than 11 pixels give an empty `ssim` with reason "image smaller than the 11x11
/// SSIM window". Window sums in float32 over tile-centred values, the map in double
/// (metrics/ssim_float.cpp): within the bound derived there of ComputeSsimReference's double
/// value; bit-identical at any thread count and on every SIMD path.
/// Throws UserError when the shapes differ or there are fewer than 3 channels.
SsimResult ComputeSsim(const ImageF& a, const ImageF& b);

/// The reference's half of SSIM (its window means E_w[y] and E_w[y²] per channel over the
/// valid region, and its pixels for the cross term), which depends on the reference alone: a
/// run scores every method against one reference, so the runner prepares it once per scene.
struct SsimReferenceSide;
/// Prepares the reference side of ComputeSsim(image, reference) (same checks as ComputeSsim
/// where they concern the reference alone). Memory: 24 bytes per valid pixel. The side keeps
/// a pointer to `reference` (for the cross term): the reference must outlive it.
std::shared_ptr<const SsimReferenceSide> PrepareSsimReference(const ImageF& reference);
/// Refused: the side would point at a temporary.
std::shared_ptr<const SsimReferenceSide> PrepareSsimReference(ImageF&& reference) = delete;
/// ComputeSsim(image, reference) against a prepared reference: the same values bit for bit
/// (the same float sums in the same order; the reference's are formed once). UserError when the
/// image's size differs from the reference's or it has fewer than 3 channels.
SsimResult ComputeSsim(const ImageF& image, const SsimReferenceSide& reference);

/// The simple implementation of the definition in double precision (one loop nest per pass,
/// every window sum in tap order): the reference the float32 production path is held to.
SsimResult ComputeSsimReference(const ImageF& a, const ImageF& b);

/// The per-pixel SSIM map of channel c (0, 1 or 2) over the valid region ((W − 10) × (H − 10),
/// row-major), as ComputeSsim forms it; empty when the image is smaller than the window.
/// Same checks as ComputeSsim; UserError for another channel. For precision checks.
std::vector<double> SsimMap(const ImageF& a, const ImageF& b, int c);
/// The same map by ComputeSsimReference's double-precision sums.
std::vector<double> SsimMapReference(const ImageF& a, const ImageF& b, int c);

}  // namespace aalab
