/// One (scene, method) sequence of a motion run (--frames > 1): collects every frame's
/// result and folds them into the report row — per-frame metrics pooled over the frames,
/// temporal metrics, per-frame series, timings and costs per frame.
#pragma once
#include <string>
#include <vector>

#include "harness/run/pipeline.h"
#include "metrics/temporal.h"
#include "metrics/temporal_perceptual.h"

namespace aalab {

class SequenceTrack {
 public:
  /// A sequence of `frames` frames seen under a viewing condition of `ppd` pixels per degree
  /// at `fps` frames per second (the perceptual temporal error's, metrics/temporal_perceptual.h).
  SequenceTrack(double ppd, double fps, int frames) : perceptual_(ppd, fps, frames) {}

  /// Adds frame k's output (frames in order) scored against that frame's reference;
  /// `image` is the frame PNG's path relative to the report folder.
  void AddFrame(const MethodOutput& out, const PreparedScene& frame, const std::string& image);

  /// Turns the last frame's row into the sequence's row: metrics pooled over the frames
  /// (arithmetic mean; null if null on any frame) plus the temporal metrics; timings, costs
  /// and taps per frame (the mean over frames of each repeat); the perceptual temporal
  /// error after the temporal metrics; per-frame series of psnr_db,
  /// edge_psnr_db, flip_mean and temporal_rmse; the frame images.
  void Finish(ResultRow* row) const;

 private:
  TemporalError temporal_;
  PerceptualTemporalError perceptual_;
  std::vector<std::vector<MetricValue>> metrics_;
  std::vector<ResultRow> rows_;  ///< each frame's row without images (timings, costs)
  std::vector<std::string> images_;
};

}  // namespace aalab
