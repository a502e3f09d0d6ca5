// Sequences of a motion run: pooling per-frame results into one report row.
#include "harness/run/sequence.h"

#include "core/error.h"

namespace aalab {

void SequenceTrack::AddFrame(const MethodOutput& out, const PreparedScene& frame, const std::string& image) {
  const ImageF out_f = ToFloat(out.output, 3);
  temporal_.AddFrame(out_f, frame.ref.image, &frame.ref.edge_mask);
  perceptual_.AddFrame(out_f, frame.ref.image);
  std::vector<MetricValue> values;
  for (const auto& m : out.row.metrics) values.push_back({m.name, m.value, m.null_reason});
  metrics_.push_back(std::move(values));
  ResultRow r = out.row;
  r.metrics.clear();
  r.images.clear();
  rows_.push_back(std::move(r));
  images_.push_back(image);
}

namespace {

/// Timing per frame: sample i is the mean over frames of each frame's sample i.
Timing MeanTiming(const std::vector<ResultRow>& rows, Timing ResultRow::*member) {
  Timing t;
  const size_t n = (rows.front().*member).samples_ms.size();
  for (size_t i = 0; i < n; ++i) {
    double sum = 0.0;
    for (const auto& r : rows) sum += (r.*member).samples_ms.at(i);
    t.samples_ms.push_back(sum / static_cast<double>(rows.size()));
  }
  t.Summarize();
  return t;
}

double MeanOf(const std::vector<ResultRow>& rows, double ResultRow::*member) {
  double sum = 0.0;
  for (const auto& r : rows) sum += r.*member;
  return sum / static_cast<double>(rows.size());
}

}  // namespace

void SequenceTrack::Finish(ResultRow* row) const {
  AALAB_CHECK(!rows_.empty(), "a sequence needs frames");
  row->metrics.clear();
  for (const auto& v : PoolFrames(metrics_)) row->metrics.push_back({v.name, v.value, v.null_reason});
  for (const auto& v : temporal_.Values()) row->metrics.push_back({v.name, v.value, v.null_reason});
  for (const auto& v : perceptual_.Values()) row->metrics.push_back({v.name, v.value, v.null_reason});
  row->render = MeanTiming(rows_, &ResultRow::render);
  row->post = MeanTiming(rows_, &ResultRow::post);
  row->resample = MeanTiming(rows_, &ResultRow::resample);
  row->total = MeanTiming(rows_, &ResultRow::total);
  row->primary_rays_per_px = MeanOf(rows_, &ResultRow::primary_rays_per_px);
  row->shadow_rays_per_px = MeanOf(rows_, &ResultRow::shadow_rays_per_px);
  row->texture_lookups_per_px = MeanOf(rows_, &ResultRow::texture_lookups_per_px);
  row->taps_per_px = MeanOf(rows_, &ResultRow::taps_per_px);
  row->frame_series.clear();
  for (const std::string name : {"psnr_db", "edge_psnr_db", "flip_mean"}) {
    std::vector<std::optional<double>> series;
    for (const auto& frame : metrics_) {
      std::optional<double> v;
      for (const auto& m : frame) {
        if (m.name == name) v = m.value;
      }
      series.push_back(v);
    }
    row->frame_series.emplace_back(name, std::move(series));
  }
  std::vector<std::optional<double>> te = {std::nullopt};  // frame 0 has no predecessor
  for (double v : temporal_.PerFrameRmse()) te.push_back(v);
  row->frame_series.emplace_back("temporal_rmse", std::move(te));
  row->frame_images = images_;
}

}  // namespace aalab
