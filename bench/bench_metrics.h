/// The metric figures of `make bench` (bench/bench_metrics.cpp): ms per 1080p pair (the
/// fxaa311-p39 output of the real frame against the mesh reference) for each metric, side by
/// side with scikit-image (SSIM, PSNR) and OpenImageIO's idiff when installed, timed the same way.
#pragma once
#include <memory>

#include "bench/bench_common.h"
#include "bench/bench_flip_peer.h"
#include "metrics/metric.h"
#include "scenes/render.h"

namespace aalab::bench {

/// The metric pair and what the external tools measured on it.
struct MetricsBench {
  std::shared_ptr<Reference> ref;
  std::shared_ptr<ImageF> img, none;
  Json external;                             ///< bench.json's "external": skimage and idiff results
  double ssim_speedup = 0.0;                 ///< filled by MetricsTable: scikit-image SSIM / ours as in a run, 1 thread
  NvidiaFlipRun nvidia_flip;                 ///< NVIDIA's FLIP tool on the same pair (bench/bench_flip_peer.cpp)
  std::vector<BenchGoal> nvidia_flip_goals;  ///< filled by MetricsTable
};

/// Renders the pair (`real_frame`: the mesh scene's 1080p 1x frame) and registers the figures.
MetricsBench RegisterMetricFigures(const Settings& cfg, const Image8& real_frame);

/// Times scikit-image (bench/external_metrics.py), idiff and NVIDIA's FLIP tool on the same pair.
void RunExternalTools(const Settings& cfg, MetricsBench& metrics);

/// The "## Metrics" section and the FLIP-vs-NVIDIA rows; fills ssim_speedup and nvidia_flip_goals.
void MetricsTable(MetricsBench& metrics, BenchOutput& out);

/// Goals: FLIP vs NVIDIA's tool, SSIM as in a run ≥ 15× scikit-image, and 2 threads ≥ 1.8× one thread.
void MetricsGoals(const MetricsBench& metrics, BenchOutput& out);

}  // namespace aalab::bench
