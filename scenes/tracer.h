/// The Embree tracer: one BVH per scene, built once and shared by every method; traces camera
/// samples at arbitrary continuous pixel positions at any resolution, in 16-wide packets, and
/// shades them with exactly the effects the scene declares.
#pragma once
#include <cstdint>
#include <memory>

#include "scenes/scene.h"

namespace aalab {

/// Work counters (hardware-independent cost). Integers: sums are order-independent.
struct TraceCounters {
  uint64_t samples = 0;          ///< camera samples shaded
  uint64_t primary_rays = 0;     ///< camera rays, including continuations through alpha cut-outs
  uint64_t shadow_rays = 0;      ///< shadow rays (only with the `shadows` effect)
  uint64_t texture_lookups = 0;  ///< colour-texture and alpha-pattern evaluations

  TraceCounters& operator+=(const TraceCounters& o) {
    samples += o.samples;
    primary_rays += o.primary_rays;
    shadow_rays += o.shadow_rays;
    texture_lookups += o.texture_lookups;
    return *this;
  }
};

/// One shaded camera sample.
struct SampleResult {
  float rgb[3] = {0, 0, 0};  ///< scene-linear radiance
  int32_t surface = -1;      ///< index of the shape seen (-1: background)
  uint32_t shadowed = 0;     ///< bit i: shadow-casting light i is blocked at this sample
  float position[3] = {0, 0, 0};  ///< world-space hit point (origin + t·dir; 0 for background)
};

/// Camera sample position on a width × height image plane, in continuous pixel coordinates
/// (pixel (x, y) covers [x, x+1) × [y, y+1); y down).
struct SamplePos {
  float x = 0, y = 0;
};

class Tracer {
 public:
  /// Builds the Embree scene (BVH) for `scene`. The Scene must outlive the Tracer.
  explicit Tracer(const Scene& scene);
  ~Tracer();
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  /// Traces and shades `count` samples on a width × height image plane. Thread-safe (call
  /// from many threads at once); results depend only on the inputs.
  void Trace(const SamplePos* pos, int count, int width, int height, SampleResult* out,
             TraceCounters* counters) const;

  const Scene& GetScene() const { return scene_; }

  /// The limit the benchmark measures tracing against: a bare Embree loop over the camera
  /// rays of a width × height image with grid × grid samples per pixel (strata centres),
  /// pixel by pixel in 8×8-pixel tiles (tiles in parallel), 16-wide coherent packets
  /// (rtcIntersect16), no shading, no alpha continuation, no shadow rays. Returns the number
  /// of rays that hit something (so the work cannot be optimised away).
  uint64_t BareTrace(int width, int height, int grid) const;

 private:
  struct Impl;
  const Scene& scene_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aalab
