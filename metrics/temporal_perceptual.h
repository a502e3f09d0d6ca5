/// Perceptual temporal error (metrics/METRICS.md "Perceptual temporal error"): how visible
/// the change of a method's error over a sequence is at the run's viewing condition.
///
/// Per frame t, the lightness error e_t(x) = L*(S ⊛ Y(T_t))/100 − L*(S ⊛ Y(R_t))/100, with Y
/// the linear luminance of the sRGB-encoded method frame T_t and reference R_t, S FLIP's
/// achromatic spatial CSF (a Gaussian of σ = sqrt(0.0047/(2π²))° = 0.0154°, i.e. 1.03 px at
/// 67 px/deg) and L* CIE 1976 lightness. Then
///   temporal_csf_rmse   = sqrt(mean over t ≥ 1 and pixels of (e_t − e_{t−1})²): the
///                         adjacent-frame change, spatially CSF-weighted;
///   temporal_perceptual = sqrt(mean over pixels of (1/M²)·Σ_{k=1}^{M−1} w(f_k)²·|Ê_k|²) over
///                         windows of M ≤ 32 frames, Ê the DFT of e over the window's frames,
///                         f_k = min(k, M−k)·fps/M, w = |H|/max|H| Watson's (1986) temporal
///                         CSF: the whole window's variation of the error (with w ≡ 1 exactly
///                         its variance over time, by Parseval), each temporal frequency
///                         weighted by the eye's sensitivity to it.
#pragma once
#include <string>
#include <vector>

#include "core/image.h"
#include "metrics/metric.h"

namespace aalab {

/// Watson's (1986) temporal sensitivity |H(f)| = |(i2πfτ + 1)^−9 − ζ·(i2πfκτ + 1)^−10| with
/// τ = 4.94 ms, κ = 1.33, ζ = 0.9 (the fit to Robson's 1966 flicker data, without the gain ξ),
/// divided by its maximum over f ≥ 0: 1 at the peak (8.55 Hz), → 0 at high frequencies.
double TemporalCsfWeight(double hz);

/// The frequency of TemporalCsfWeight's peak, Hz (found once on a 0.001 Hz grid).
double TemporalCsfPeakHz();

/// The largest window of the spectral term, frames.
inline constexpr int kPerceptualWindow = 32;

/// Window lengths for a sequence of `frames` frames: ceil(frames / 32) windows, as equal as
/// possible, longer ones first (33 → 17, 16). Empty for frames < 2.
std::vector<int> PerceptualWindows(int frames);

/// The weighted spectral energy of one pixel's error over a window of M = values.size()
/// frames: (1/M²)·Σ_{k=1}^{M−1} weight(k)²·|Σ_t values[t]·e^{−2πikt/M}|², with
/// weight(k) = TemporalCsfWeight(min(k, M−k)·fps/M). fps ≤ 0: weight ≡ 1 (the population
/// variance of `values`, by Parseval). Exposed for tests.
double WindowEnergy(const std::vector<double>& values, double fps);

/// Accumulates the two values frame by frame (frames in order, all the same size).
class PerceptualTemporalError {
 public:
  /// `ppd`, `fps`: the viewing condition (finite, > 0); `frames`: the sequence length (the
  /// windows are fixed by it).
  PerceptualTemporalError(double ppd, double fps, int frames);
  /// Adds frame t: the method's frame and the reference (sRGB-encoded float RGB, [0, 1]).
  void AddFrame(const ImageF& image, const ImageF& reference);
  /// temporal_perceptual, temporal_csf_rmse (null with a reason before two frames).
  std::vector<MetricValue> Values() const;

 private:
  void FlushWindow();
  double fps_;
  std::vector<double> kernel_;  ///< FLIP's 1-D achromatic CSF kernel at ppd
  std::vector<int> windows_;
  size_t window_ = 0;
  int frames_ = 0, width_ = 0, height_ = 0;
  std::vector<std::vector<float>> window_errors_;  ///< e_t of the open window's frames
  std::vector<float> prev_error_;
  double adjacent_sum_ = 0.0;
  size_t adjacent_terms_ = 0;
  double spectral_sum_ = 0.0;  ///< Σ over windows of M · Σ_x energy
  size_t spectral_terms_ = 0;  ///< Σ over windows of M · pixels
};

/// Names of the values PerceptualTemporalError::Values returns, in order.
std::vector<std::string> PerceptualTemporalNames();

/// Lightness error image (1 channel, row-major) of a frame: L*(S ⊛ Y(image))/100 − L*(S ⊛
/// Y(reference))/100 with the 1-D kernel `kernel` applied along x then y, borders clamped.
/// Exposed for tests.
std::vector<float> LightnessError(const ImageF& image, const ImageF& reference, const std::vector<double>& kernel);

}  // namespace aalab
