/// The cost of a big mesh (issue: a model of a million triangles or more): a procedural torus
/// of 2·n·m triangles, its Embree BVH build time, the memory it adds, and tracing speed.
#pragma once
#include <cstdint>

namespace aalab {

struct BigMeshFigures {
  uint64_t triangles = 0;
  double scene_mb = 0;         ///< the Scene's vertex, normal, uv and index arrays (computed from sizes)
  double rss_bvh_mb = 0;       ///< resident memory added by building the Tracer (BVH + Embree's copy), /proc/self/statm
  double bvh_build_ms = 0;     ///< Tracer construction (rtcCommitScene, high quality, robust)
  double render_mrays_t1 = 0;  ///< RenderFrame 1x (lambert + sun) primary rays per second, 1 thread
  double render_mrays_t2 = 0;  ///< the same at 2 threads
  double bare_mrays_t1 = 0;    ///< Tracer::BareTrace, 1 thread
  double bare_mrays_t2 = 0;
};

/// Builds the torus (n × m quads), measures once per figure (best of `reps`) at width × height.
BigMeshFigures MeasureBigMesh(int n, int m, int width, int height, int reps);

}  // namespace aalab
