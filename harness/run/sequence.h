/// One (scene, method) sequence of a motion run (--frames > 1): collects every frame's
/// result and folds them into the report row — per-frame metrics pooled over the frames,
/// temporal metrics, per-frame series, timings and costs per frame.
#pragma once
#include <string>
#include <vector>

#include "harness/run/pipeline.h"
#include "metrics/temporal.h"

namespace aalab {

class SequenceTrack {
 public:
  /// Adds frame k's output (frames in order) scored against that frame's reference;
  /// `image` is the frame PNG's path relative to the report folder.
  void AddFrame(const MethodOutput& out, const PreparedScene& frame, const std::string& image);

  /// Turns the last frame's row into the sequence's row: metrics pooled over the frames
  /// (arithmetic mean; null if null on any frame) plus the temporal metrics; timings, costs
  /// and taps per frame (the mean over frames of each repeat); per-frame series of psnr_db,
  /// edge_psnr_db, flip_mean and temporal_rmse; the frame images.
  void Finish(ResultRow* row) const;

 private:
  TemporalError temporal_;
  std::vector<std::vector<MetricValue>> metrics_;
  std::vector<ResultRow> rows_;  ///< each frame's row without images (timings, costs)
  std::vector<std::string> images_;
};

}  // namespace aalab
