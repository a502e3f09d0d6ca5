/// Frame rendering on top of the tracer: 1x and supersampled method frames (8-bit, the back
/// buffer) and the float reference with its noise floor and geometric edge mask.
#pragma once
#include <algorithm>
#include <cstdint>

#include "core/color.h"

#include "core/image.h"
#include "core/render_spec.h"
#include "scenes/tracer.h"

namespace aalab {

/// DisplayLinear (core/color.h) for one sample, inlined for the per-sample resolve
/// loops: the same operations in the same order, hence the same bits (a test compares it
/// with DisplayLinear over the whole float range, NaN and infinities included).
inline void DisplayLinearInline(const Display& d, const float rgb[3], float out[3]) {
  for (int c = 0; c < 3; ++c) {
    float v = rgb[c];
    if (!(v > 0.0f)) v = 0.0f;  // negatives and NaN → 0
    v = ApplyTonemap(d.tonemap, v * d.exposure);
    out[c] = std::clamp(v, 0.0f, 1.0f);
  }
}

/// The SSAA resolve of one pixel: each of its `count` samples through the display
/// transform, box average in linear light (double sums in sample order), sRGB encode,
/// round to 8 bits into p[0..2]. What RenderFrame does for every pixel.
inline void ResolveBoxPixel(const Display& display, const SampleResult* r, int count, uint8_t* p) {
  double sum[3] = {0, 0, 0};
  for (int s = 0; s < count; ++s) {
    float d[3];
    DisplayLinearInline(display, r[s].rgb, d);
    for (int c = 0; c < 3; ++c) sum[c] += d[c];
  }
  for (int c = 0; c < 3; ++c) p[c] = QuantizeUnorm8(SrgbEncode(static_cast<float>(sum[c] / count)));
}

/// Per-pixel cost maps a frame render can also return.
struct FrameStats {
  ImageF shading_evals;  ///< MSAA only: shading evaluations of each pixel (1 channel)
};

/// MSAA's resolve=hdr-linear of one pixel, display-linear: box average of the samples'
/// scene-linear radiance (double sums in sample order), then the display transform once (the
/// naive resolve of an HDR render target), into d[0..2].
inline void HdrLinearResolve(const Display& display, const SampleResult* r, int count, float d[3]) {
  double sum[3] = {0, 0, 0};
  for (int s = 0; s < count; ++s) {
    for (int c = 0; c < 3; ++c) sum[c] += r[s].rgb[c];
  }
  float mean[3];
  for (int c = 0; c < 3; ++c) mean[c] = static_cast<float>(sum[c] / count);
  DisplayLinearInline(display, mean, d);
}

/// HdrLinearResolve, sRGB-encoded and rounded to 8 bits into p[0..2].
inline void ResolveHdrLinearPixel(const Display& display, const SampleResult* r, int count, uint8_t* p) {
  float d[3];
  HdrLinearResolve(display, r, count, d);
  for (int c = 0; c < 3; ++c) p[c] = QuantizeUnorm8(SrgbEncode(d[c]));
}

/// Renders a method frame of width × height with the render spec's sample pattern: each
/// sample goes through the scene's display transform, samples are box-averaged in linear
/// light, sRGB-encoded and quantised to RGBA8 (alpha 255). `spec.scale` is ignored here (the
/// caller picks the size). Jitter is a hash of (pixel, sample index, seed): bit-identical at
/// any thread count. With `spec.msaa` on: Tracer::TraceMsaa at the standard sample
/// positions, resolved as `spec.msaa.resolve` says; `stats` (when not null) then receives
/// the per-pixel shading evaluations.
Image8 RenderFrame(const Tracer& tracer, int width, int height, const RenderSpec& spec, uint64_t seed,
                   TraceCounters* counters, FrameStats* stats = nullptr);

/// The float resolve of RenderFrame: the same samples (pattern, jitter, seed), each through the
/// display transform and box-averaged in linear light (double sums in sample order), written
/// as display-linear RGB float in [0, 1] — neither sRGB-encoded nor quantised (MSAA with
/// resolve=hdr-linear: HdrLinearResolve). RenderFrame's pixel is
/// QuantizeUnorm8(SrgbEncode(this pixel)).
ImageF RenderFrameLinear(const Tracer& tracer, int width, int height, const RenderSpec& spec, uint64_t seed,
                         TraceCounters* counters);

/// The supersampled ground truth.
struct Reference {
  ImageF image;          ///< sRGB-encoded RGB float (not quantised), all n×n samples
  ImageF half_a;         ///< the same from the strata with (i + j) even
  ImageF half_b;         ///< ... and (i + j) odd: independent of half_a
  ImageF edge_mask;      ///< 1 where the pixel's samples see more than one surface, a shadow
                         ///< boundary or an alpha cut-out; dilated by 1 px; else 0 (1 channel)
  ImageF edge_mask_raw;  ///< the same before dilation
  int grid = 0;          ///< n: n×n samples per pixel
};

/// Renders the reference: grid × grid stratified jittered samples per pixel (grid even, ≥ 2),
/// per-sample display transform, box resolve in linear light, sRGB encode, float.
Reference RenderReference(const Tracer& tracer, int width, int height, int grid, uint64_t seed,
                          TraceCounters* counters);

/// Validates a reference sample count: a perfect square n² with n even and 2 ≤ n ≤ 64
/// (4, 16, 64, 144, 256, ..., 4096). Returns n; throws UserError listing valid values.
int ReferenceGridForSpp(int spp);

}  // namespace aalab
