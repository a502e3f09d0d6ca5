// A million-triangle mesh through the tracer (bench/bench_bigmesh.h).
#include "bench/bench_bigmesh.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>

#include "core/parallel.h"
#include "scenes/render.h"
#include "scenes/tracer.h"

namespace aalab {

namespace {

double ResidentMb() {
  std::ifstream f("/proc/self/statm");
  long pages = 0, resident = 0;
  f >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1e6;
}

double Seconds(const std::chrono::steady_clock::time_point& t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// A torus (major radius 1, minor 0.35) of n × m quads with smooth normals, lit by a sun.
Scene TorusScene(int n, int m) {
  Scene s;
  s.name = "bigmesh";
  s.effects[static_cast<int>(Effect::kLambert)] = true;
  s.camera.position = {0.0f, 1.6f, 2.4f};
  s.camera.look_at = {0.0f, 0.0f, 0.0f};
  s.camera.fov_y_deg = 50.0f;
  s.ambient = glm::vec3(0.2f);
  Light sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  s.lights.push_back(sun);
  Material mat;
  mat.name = "m";
  mat.shading = Shading::kLambert;
  s.materials.push_back(mat);
  Shape sh;
  sh.source = "bench torus";
  const double kTau = 6.283185307179586;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double u = kTau * i / n, v = kTau * j / m;
      const glm::dvec3 c(std::cos(u), 0.0, std::sin(u));
      const glm::dvec3 nrm = c * std::cos(v) + glm::dvec3(0, 1, 0) * std::sin(v);
      sh.positions.push_back(glm::vec3(c + 0.35 * nrm));
      sh.normals.push_back(glm::vec3(nrm));
      sh.uvs.emplace_back(static_cast<float>(i) / n, static_cast<float>(j) / m);
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const unsigned a = static_cast<unsigned>(i * m + j), b = static_cast<unsigned>(((i + 1) % n) * m + j);
      const unsigned c = static_cast<unsigned>(((i + 1) % n) * m + (j + 1) % m),
                     d = static_cast<unsigned>(i * m + (j + 1) % m);
      sh.triangles.emplace_back(a, b, c);
      sh.triangles.emplace_back(a, c, d);
    }
  }
  s.shapes.push_back(std::move(sh));
  return s;
}

}  // namespace

BigMeshFigures MeasureBigMesh(int n, int m, int width, int height, int reps) {
  BigMeshFigures f;
  const Scene scene = TorusScene(n, m);
  const Shape& sh = scene.shapes[0];
  f.triangles = sh.triangles.size();
  f.scene_mb = static_cast<double>(sh.positions.size() * (sizeof(glm::vec3) * 2 + sizeof(glm::vec2)) +
                                   sh.triangles.size() * sizeof(glm::uvec3)) /
               1e6;
  SetThreadCount(0);
  const double rss0 = ResidentMb();
  const auto t0 = std::chrono::steady_clock::now();
  const Tracer tracer(scene);
  f.bvh_build_ms = Seconds(t0) * 1e3;
  f.rss_bvh_mb = ResidentMb() - rss0;
  const double rays = static_cast<double>(width) * height;
  for (int threads : {1, 2}) {
    SetThreadCount(threads);
    double best_r = 1e30, best_b = 1e30;
    for (int r = 0; r < reps; ++r) {
      auto t = std::chrono::steady_clock::now();
      TraceCounters c;
      const Image8 img = RenderFrame(tracer, width, height, RenderSpec{}, 1, &c);
      best_r = std::min(best_r, Seconds(t));
      t = std::chrono::steady_clock::now();
      volatile uint64_t hits = tracer.BareTrace(width, height, 1);
      (void)hits;
      best_b = std::min(best_b, Seconds(t));
    }
    (threads == 1 ? f.render_mrays_t1 : f.render_mrays_t2) = rays / best_r / 1e6;
    (threads == 1 ? f.bare_mrays_t1 : f.bare_mrays_t2) = rays / best_b / 1e6;
  }
  SetThreadCount(0);
  return f;
}

}  // namespace aalab
