// Internals shared by the tracer's files; not part of the public interface (only the scenes
// library includes it, the one place that knows Embree):
//   tracer.cpp        BVH build, camera rays, visibility (closest hits through cut-outs),
//                     Tracer::Trace (one shading per sample), BareTrace
//   tracer_shade.cpp  surface attributes, shadow rays and shading of a list of hits
//   tracer_msaa.cpp   Tracer::TraceMsaa: coverage samples, one shading per primitive
#pragma once
#include <embree3/rtcore.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "scenes/tracer.h"

namespace aalab {

struct Tracer::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string error;
  bool any_alpha = false;
  // camera basis
  glm::vec3 origin{0.0f}, forward{0.0f}, right{0.0f}, up{0.0f};

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace tracer_detail {

constexpr int kPacket = 16;
constexpr int kMaxAlphaLayers = 256;  // continuation rounds through cut-outs before giving up

/// A ray's closest hit (shape == -1: nothing).
struct Hit {
  float t = std::numeric_limits<float>::infinity();
  int shape = -1;
  unsigned prim = 0;
  float u = 0, v = 0;
  glm::vec3 ng{0.0f};
};

/// Surface attributes at a hit.
struct Surface {
  glm::vec3 p{0.0f};
  glm::vec3 n{0.0f};   // shading normal, facing the ray
  glm::vec3 ng{0.0f};  // geometric normal, facing the ray
  glm::vec2 uv{0.0f};
};

/// Where a ray continues after rejecting a hit at distance t (just past it).
inline float ContinuePast(float t) { return t + std::max(t * 2e-6f, 1e-6f); }

/// Grows v to at least n elements (never shrinks) and returns its data.
template <typename T>
T* Sized(std::vector<T>& v, size_t n) {
  if (v.size() < n) v.resize(n);
  return v.data();
}

/// Closest hits for n rays, in 16-wide packets. Ray k of the batch is ray idx[k] of the
/// arrays (idx == nullptr: ray k itself); hits[k] receives its hit. Rays with tnear >= tfar
/// are skipped. The packets hold the same rays, in the same lanes, whether or not an index
/// list is used, so the result never depends on how the caller stores its rays.
void IntersectRays(RTCScene scene, const glm::vec3* org, const glm::vec3* dir, const float* tnear,
                   const float* tfar, const int* idx, int n, Hit* hits, bool coherent);

/// Camera rays through `count` continuous pixel positions of a width × height image plane.
void CameraRays(const Tracer::Impl& im, const Camera& cam, const SamplePos* pos, int count, int width, int height,
                glm::vec3* org, glm::vec3* dir);

/// Working memory of the continuation loops, reused from call to call.
struct LayerScratch {
  std::vector<Hit> layer_hits;
  std::vector<int> active, next;
};

/// Closest hits of `count` camera rays (tnear 0, tfar ∞) that pass the alpha test at their
/// own position: with `alpha`, a ray whose hit is cut out continues just past it (a new packet
/// round) up to kMaxAlphaLayers rounds. Adds the rays to counters.primary_rays and
/// counters.coverage_rays, the alpha lookups to counters.texture_lookups.
void ClosestVisibleHits(const Tracer::Impl& im, const Scene& sc, bool alpha, const glm::vec3* org,
                        const glm::vec3* dir, int count, float* tnear, float* tfar, Hit* hits, LayerScratch& ls,
                        TraceCounters& counters);

/// Surface attributes of a hit on the ray (org, dir).
Surface SurfaceAt(const Scene& scene, const Hit& h, glm::vec3 org, glm::vec3 dir);

/// Working memory of ShadeHits, reused from call to call.
struct ShadeScratch {
  std::vector<Surface> surf;
  std::vector<uint32_t> blocked;
  std::vector<int> who_sample, who_light;
  std::vector<glm::vec3> so, sd;
  std::vector<float> stn, stf;
  LayerScratch layers;
};

/// Shades n hits seen along the rays (org[i], dir[i]) with the scene's declared effects:
/// surface attributes, shadow rays (alpha-tested when `alpha`), lambert, specular and
/// textures. out[i] receives radiance, the surface index and the shadowed-light bits;
/// hits with shape < 0 get the background. Adds shadow rays and colour lookups to counters.
void ShadeHits(const Tracer::Impl& im, const Scene& sc, bool alpha, const Hit* hits, const glm::vec3* org,
               const glm::vec3* dir, int n, ShadeScratch& scratch, SampleResult* out, TraceCounters& counters);

}  // namespace tracer_detail
}  // namespace aalab
