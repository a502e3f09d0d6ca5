// Temporal metrics: the frame-to-frame change of the error image against the per-frame
// reference (no optical flow: the reference moves with the scene), and per-frame pooling.
// Definitions, units and sources: metrics/METRICS.md "Temporal".
#include "metrics/temporal.h"

#include <cmath>

#include "core/error.h"
#include "metrics/families.h"

namespace aalab {

void TemporalError::AddFrame(const ImageF& image, const ImageF& reference, const ImageF* edge_mask) {
  RequireSameShape(image, reference, "temporal error: image vs reference");
  const int W = image.Width(), H = image.Height();
  AALAB_CHECK(image.Channels() == 3, "temporal error expects RGB images");
  ImageF err(W, H, 3);
  for (size_t i = 0; i < err.Data().size(); ++i) err.Data()[i] = image.Data()[i] - reference.Data()[i];
  if (frames_ > 0) {
    AALAB_CHECK(prev_error_.Width() == W && prev_error_.Height() == H, "frames of a sequence share one size");
    const bool masks = have_mask_ && edge_mask != nullptr;
    double frame_sum = 0.0;
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        double px = 0.0;
        for (int c = 0; c < 3; ++c) {
          const double d = static_cast<double>(err.At(x, y, c)) - static_cast<double>(prev_error_.At(x, y, c));
          px += d * d;
        }
        frame_sum += px;
        if (masks && (edge_mask->At(x, y, 0) > 0.5f || prev_mask_.At(x, y, 0) > 0.5f)) {
          edge_sum_sq_ += px;
          edge_count_ += 3;
        }
      }
    }
    sum_sq_ += frame_sum;
    const size_t terms = static_cast<size_t>(W) * static_cast<size_t>(H) * 3;
    count_ += terms;
    per_frame_.push_back(std::sqrt(frame_sum / static_cast<double>(terms)));
  }
  prev_error_ = std::move(err);
  have_mask_ = edge_mask != nullptr;
  if (edge_mask) prev_mask_ = *edge_mask;
  ++frames_;
}

std::vector<MetricEntry> TemporalMetrics() {
  MetricEntry e{"temporal",
                "frame-to-frame change of the error image (method − reference), RMS over all pixels, as a PSNR, and "
                "over the edge masks (--frames N > 1)",
                {{"temporal_rmse", "Temporal RMSE", "", Improves::kLower, kSignificantDigits,
                  "RMS over pixels and frame pairs of the change of the error image (method − reference) from frame "
                  "to frame: flicker and crawl the reference does not have (0..1, --frames > 1).",
                  "Rewards a steady error: any frame-to-frame change the reference does not have counts the same at "
                  "every spatial scale, so single-pixel popping weighs as much as wide shimmer, and a steadily wrong "
                  "(blurred or aliased but still) image scores 0."},
                 {"temporal_psnr_db", "Temporal PSNR", "dB", Improves::kHigher, 2,
                  "10·log10(1 / temporal MSE): the temporal RMSE as a PSNR.", ""},
                 {"temporal_edge_rmse", "Temporal edge RMSE", "", Improves::kLower, kSignificantDigits,
                  "The temporal RMSE over the edge masks of both frames of each pair.", ""}}};
  e.inputs = MetricInputs::kSequence;
  return {e};
}

std::vector<std::string> TemporalMetricNames() { return OutputKeys(TemporalMetrics().front()); }

std::vector<MetricValue> TemporalError::Values() const {
  std::vector<MetricValue> out;
  if (frames_ < 2) {
    for (const auto& n : TemporalMetricNames()) out.push_back({n, std::nullopt, "needs at least 2 frames"});
    return out;
  }
  const double mean = sum_sq_ / static_cast<double>(count_);
  out.push_back({"temporal_rmse", std::sqrt(mean), ""});
  if (mean > 0.0) {
    out.push_back({"temporal_psnr_db", 10.0 * std::log10(1.0 / mean), ""});
  } else {
    out.push_back({"temporal_psnr_db", std::nullopt, "identical"});  // Δe ≡ 0: infinite, as PSNR
  }
  if (edge_count_ > 0) {
    out.push_back({"temporal_edge_rmse", std::sqrt(edge_sum_sq_ / static_cast<double>(edge_count_)), ""});
  } else {
    out.push_back({"temporal_edge_rmse", std::nullopt, "no edge pixels in any frame"});
  }
  return out;
}

std::vector<MetricValue> PoolFrames(const std::vector<std::vector<MetricValue>>& frames) {
  AALAB_CHECK(!frames.empty(), "pooling needs at least one frame");
  std::vector<MetricValue> out = frames.front();
  for (size_t m = 0; m < out.size(); ++m) {
    double sum = 0.0;
    bool null = false;
    for (size_t k = 0; k < frames.size(); ++k) {
      const MetricValue& v = frames[k][m];
      AALAB_CHECK(v.name == out[m].name, "frames must list the same metrics");
      if (!v.value) {
        out[m].value.reset();
        out[m].null_reason = "null on frame " + std::to_string(k) + ": " + v.null_reason;
        null = true;
        break;
      }
      sum += *v.value;
    }
    if (!null) {
      out[m].value = sum / static_cast<double>(frames.size());
      out[m].null_reason.clear();
    }
  }
  return out;
}

}  // namespace aalab
