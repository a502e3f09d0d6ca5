/// The Embree tracer: one BVH per scene, built once and shared by every method; traces camera
/// samples at arbitrary continuous pixel positions at any resolution, in 16-wide packets, and
/// shades them with exactly the effects the scene declares: per sample (Trace) or, for MSAA,
/// once per primitive and pixel (TraceMsaa).
#pragma once
#include <cstdint>
#include <limits>
#include <memory>

#include "core/render_spec.h"
#include "scenes/scene.h"

namespace aalab {

/// Work counters (hardware-independent cost). Integers: sums are order-independent.
struct TraceCounters {
  uint64_t samples = 0;          ///< camera samples shaded
  uint64_t primary_rays = 0;     ///< camera rays, including continuations through alpha cut-outs
  uint64_t shadow_rays = 0;      ///< shadow rays (only with the `shadows` effect)
  uint64_t texture_lookups = 0;  ///< colour-texture and alpha-pattern evaluations
  uint64_t coverage_rays = 0;    ///< camera rays that decide visibility at a sample position (with
                                 ///< continuations); MSAA's shading rays at pixel centres are not
  uint64_t shading_evals = 0;    ///< surface shading evaluations (background samples cost none;
                                 ///< MSAA: one per primitive and pixel, discarded ones included)

  TraceCounters& operator+=(const TraceCounters& o) {
    samples += o.samples;
    primary_rays += o.primary_rays;
    shadow_rays += o.shadow_rays;
    texture_lookups += o.texture_lookups;
    coverage_rays += o.coverage_rays;
    shading_evals += o.shading_evals;
    return *this;
  }
};

/// One shaded camera sample.
struct SampleResult {
  float rgb[3] = {0, 0, 0};                          ///< scene-linear radiance
  int32_t surface = -1;                              ///< index of the shape seen (-1: background)
  uint32_t shadowed = 0;                             ///< bit i: shadow-casting light i is blocked at this sample
  float t = std::numeric_limits<float>::infinity();  ///< ray distance to the surface seen (+inf: background)
  float position[3] = {0, 0, 0};                     ///< world-space hit point (origin + t·dir; 0 for background)
};

/// Camera sample position on a width × height image plane, in continuous pixel coordinates
/// (pixel (x, y) covers [x, x+1) × [y, y+1); y down).
struct SamplePos {
  float x = 0, y = 0;
};

/// How image textures (glTF) are filtered for a batch of camera samples: the UV derivatives
/// are the difference to the camera ray `px` pixels to the right and `px` pixels down, taken
/// on the hit triangle's plane (what a GPU's 2 × 2 quad computes at the render's own sample
/// spacing); px = 0 samples level 0 bilinearly (the reference's truth). Procedural textures
/// ignore it (they stay point-sampled). docs/real-content.md "Texture sampling".
struct TextureFootprint {
  float px = 1.0f;    ///< sample spacing in pixels of the image plane traced (0: level 0 only)
  int max_aniso = 1;  ///< 1: trilinear; 2..16: anisotropic probes
  /// Geometric specular AA (RenderSpec::specular_aa): σ² > 0 turns it on; the normal's
  /// derivatives are taken over the same footprint as the texture's.
  float gsaa_sigma2 = 0.0f;
  float gsaa_kappa = 0.0f;
  bool gsaa = false;              ///< specular AA on (RenderSpec::specular_aa.enabled)
  bool gsaa_mapped = false;       ///< derivatives of the normal-mapped normal (else the vertex normal)
  float gsaa_toksvig = 0.0f;      ///< weight of the normal map's variance (scenes/toksvig.h)
  float gsaa_toksvig_max = 0.0f;  ///< clamp of the normal map's added α²
};

/// The alpha-to-coverage mask of `samples` MSAA samples at pixel (px, py): the first
/// ⌊α·N + d⌋ sample indices, d = (Bayer4[py mod 4][px mod 4] + 0.5) / 16 (methods/msaa.cpp).
uint32_t AlphaToCoverageMask(float alpha, int samples, int px, int py);

/// Which fields of SampleResult Tracer::Trace writes: all of them, or only rgb, surface and
/// shadowed (t and position are left as they were: for callers that never read them, such as
/// the reference's resolve).
enum class SampleFields { kAll, kShading };

class Tracer {
 public:
  /// Builds the Embree scene (BVH) for `scene`. The Scene must outlive the Tracer.
  explicit Tracer(const Scene& scene);
  ~Tracer();
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  /// Traces and shades `count` samples on a width × height image plane. Thread-safe (call
  /// from many threads at once); results depend only on the inputs.
  void Trace(const SamplePos* pos, int count, int width, int height, SampleResult* out, TraceCounters* counters,
             TextureFootprint footprint = {}, SampleFields fields = SampleFields::kAll) const;

  /// MSAA (docs/msaa.md): traces `pixels` pixels of `msaa.samples` = N coverage samples each
  /// (sample_pos[p·N + s], sample index order) with one visibility ray per sample, then
  /// shades each distinct primitive a pixel's samples see once, at the shading point
  /// `msaa.shading` picks (centre_pos[p] is pixel p's centre), and gives that colour to all
  /// of the primitive's samples in out[p·N + s]. With `msaa.alpha_test` kShade a primitive
  /// whose alpha test fails at its shading point is discarded from all its samples, which
  /// then see what lies behind it. shading_evals[p] (when not null) receives pixel p's
  /// number of shading evaluations. Thread-safe; results depend only on the inputs.
  void TraceMsaa(const SamplePos* sample_pos, const SamplePos* centre_pos, int pixels, const MsaaSpec& msaa, int width,
                 int height, SampleResult* out, uint32_t* shading_evals, TraceCounters* counters,
                 TextureFootprint footprint = {}) const;

  const Scene& GetScene() const { return scene_; }

  /// The limit the benchmark measures tracing against: a bare Embree loop over the camera
  /// rays of a width × height image with grid × grid samples per pixel (strata centres),
  /// pixel by pixel in 8×8-pixel tiles (tiles in parallel), 16-wide coherent packets
  /// (rtcIntersect16), no shading, no alpha continuation, no shadow rays. Returns the number
  /// of rays that hit something (so the work cannot be optimised away).
  uint64_t BareTrace(int width, int height, int grid) const;

  /// The Embree state; opaque outside the tracer's files (scenes/tracer_internal.h).
  struct Impl;

 private:
  const Scene& scene_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aalab
