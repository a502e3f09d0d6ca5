/// The tracing figures of `make bench` (bench/bench_tracing.cpp): the reference rendering of
/// every synthetic library scene in Mrays/s against the bare Embree loop (Tracer::BareTrace:
/// rtcIntersect16, coherent primary rays, no shading) on the same scene, size and samples,
/// at 1 and 2 threads; and the big-mesh section (bench/bench_bigmesh.cpp's torus).
#pragma once
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_common.h"

namespace aalab::bench {

/// What the tracing figures registered, for their table and goals.
struct TracingBench {
  std::vector<std::string> scenes;
  std::map<std::string, uint64_t> rays;  ///< primary + shadow rays of one reference render, per scene
  // Filled by TracingTable:
  std::map<std::string, double> ratio_t1;         ///< reference / bare Mrays/s at 1 thread
  std::map<std::string, double> scaling;          ///< 1-thread time / 2-thread time
  std::map<std::string, double> scaling_fastest;  ///< the same, fastest samples (FastestRatio)
};

/// Loads the scenes (the synthetic library; the glTF real-* scenes are measured by their
/// suite, docs/real-content.md, and the big-mesh section) and registers the figures.
TracingBench RegisterTracingFigures(const Settings& cfg);

/// The "## Tracing" section; fills ratio_t1 and scaling.
void TracingTable(const Settings& cfg, TracingBench& tracing, BenchOutput& out);

/// The "## Big mesh" section: builds and traces the 1M-triangle torus (measured here, not registered).
void BigMeshTable(BenchOutput& out);

/// Goal: reference tracing ≥ 70% of the bare Embree loop on every scene (1 thread).
void TracingRatioGoal(const TracingBench& tracing, BenchOutput& out);

/// Goal: 2 threads ≥ 1.8× one thread, tracing, every scene.
void TracingScalingGoal(const TracingBench& tracing, BenchOutput& out);

}  // namespace aalab::bench
