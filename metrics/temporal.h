/// Temporal metrics of a frame sequence against the per-frame reference (metrics/METRICS.md
/// "Temporal"): the change of the error image from frame to frame, and per-frame metrics
/// pooled over the frames.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "metrics/metric.h"

namespace aalab {

/// Temporal error of one method over a sequence, fed frame by frame. With e_t = T_t − R_t
/// (method minus reference, sRGB-encoded [0, 1], per channel) and Δe_t = e_t − e_{t−1}:
///   temporal_rmse      = sqrt(mean over t ≥ 1, pixels and RGB of Δe_t²)
///   temporal_psnr_db   = 10·log10(1 / mean Δe²)  (null when Δe ≡ 0: no flicker at all)
///   temporal_edge_rmse = the RMS over pixels in E_{t−1} ∪ E_t (the edge masks)
/// Sums in double, row-major, frames in order.
class TemporalError {
 public:
  /// Adds frame t. All images the same size; `edge_mask` (1 channel) may be null.
  void AddFrame(const ImageF& image, const ImageF& reference, const ImageF* edge_mask);
  /// Frames added so far.
  int Frames() const { return frames_; }
  /// RMS of Δe over all pixels for each frame t ≥ 1 (the per-frame series; frame 0 has none).
  const std::vector<double>& PerFrameRmse() const { return per_frame_; }
  /// temporal_rmse, temporal_psnr_db, temporal_edge_rmse (null before two frames).
  std::vector<MetricValue> Values() const;

 private:
  ImageF prev_error_;
  ImageF prev_mask_;
  bool have_mask_ = false;
  int frames_ = 0;
  double sum_sq_ = 0.0;
  size_t count_ = 0;  ///< pixel·channel terms in sum_sq_
  double edge_sum_sq_ = 0.0;
  size_t edge_count_ = 0;
  std::vector<double> per_frame_;
};

/// Names of the values TemporalError::Values returns, in order.
std::vector<std::string> TemporalMetricNames();

/// Pools per-frame metric values over frames: the arithmetic mean of each named value over
/// the frames. A value that is null on any frame is null, its reason naming the first such
/// frame. `frames[k]` holds frame k's values, every frame the same names in the same order.
std::vector<MetricValue> PoolFrames(const std::vector<std::vector<MetricValue>>& frames);

}  // namespace aalab
