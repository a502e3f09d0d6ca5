/// SSIM (Wang, Bovik, Sheikh, Simoncelli 2004), mean of per-channel SSIM over R, G, B on
/// sRGB-encoded values. Definition, border rule and precision: the block at the top of
/// metrics/ssim.cpp and metrics/METRICS.md.
#pragma once
#include <array>
#include <memory>
#include <optional>
#include <string>

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
/// SSIM window". Double precision throughout; bit-identical at any thread count.
/// Throws UserError when the shapes differ or there are fewer than 3 channels.
/// Production path (vectorised kernels); the same bits as ComputeSsimReference.
SsimResult ComputeSsim(const ImageF& a, const ImageF& b);

/// The reference's half of SSIM (its window means E_w[y] and E_w[y²] per channel over the
/// valid region, and its pixels for the cross term), which depends on the reference alone: a
/// run scores every method against one reference, so the runner prepares it once per scene.
struct SsimReferenceSide;
/// Prepares the reference side of ComputeSsim(image, reference) (same checks as ComputeSsim
/// where they concern the reference alone). Memory: 48 bytes per valid pixel. The side keeps
/// a pointer to `reference` (for the cross term): the reference must outlive it.
std::shared_ptr<const SsimReferenceSide> PrepareSsimReference(const ImageF& reference);
/// Refused: the side would point at a temporary.
std::shared_ptr<const SsimReferenceSide> PrepareSsimReference(ImageF&& reference) = delete;
/// ComputeSsim(image, reference) against a prepared reference: the same values bit for bit
/// (the same sums in the same order; the reference's are formed once). UserError when the
/// image's size differs from the reference's or it has fewer than 3 channels.
SsimResult ComputeSsim(const ImageF& image, const SsimReferenceSide& reference);

/// The simple implementation of ComputeSsim (one loop nest per pass, exactly the sums of the
/// definition above), kept as the reference the production path is tested against.
SsimResult ComputeSsimReference(const ImageF& a, const ImageF& b);

}  // namespace aalab
