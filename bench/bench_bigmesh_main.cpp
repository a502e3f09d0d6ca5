// aalab_bench_bigmesh [n m] [WxH]: the big-mesh figures alone (bench/bench_bigmesh.h).
#include <cstdio>
#include <cstdlib>

#include "bench/bench_memory.h"
#include "bench/bench_bigmesh.h"

int main(int argc, char** argv) {
  std::fprintf(stderr, "%s\n", aalab::bench::ApplyBenchMemoryPolicy());
  const int n = argc > 2 ? std::atoi(argv[1]) : 1024, m = argc > 2 ? std::atoi(argv[2]) : 512;
  int w = 960, h = 540;
  if (argc > 3) std::sscanf(argv[3], "%dx%d", &w, &h);
  const aalab::BigMeshFigures f = aalab::MeasureBigMesh(n, m, w, h, 3);
  std::printf("triangles %llu, scene arrays %.1f MB, BVH build %.0f ms, RSS added by the tracer %.1f MB\n",
              static_cast<unsigned long long>(f.triangles), f.scene_mb, f.bvh_build_ms, f.rss_bvh_mb);
  std::printf("1x frame %dx%d: %.2f Mrays/s (1 thread), %.2f (2 threads); bare Embree %.2f / %.2f\n", w, h,
              f.render_mrays_t1, f.render_mrays_t2, f.bare_mrays_t1, f.bare_mrays_t2);
  return 0;
}
