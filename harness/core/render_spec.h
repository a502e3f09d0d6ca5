/// What a method asks the renderer for: sample pattern, samples per pixel, render scale.
#pragma once
#include <utility>
#include <vector>

namespace aalab {

/// Where a method's samples go inside each pixel.
enum class SamplePattern {
  kCenter,       ///< one sample at the pixel centre (a rasterizer's 1x frame)
  kOrderedGrid,  ///< n × n samples at ((i + 0.5) / n, (j + 0.5) / n)
  kRotatedGrid,  ///< the 4-sample rotated grid (RGSS)
  kJitter,       ///< `spp` uniformly jittered samples (hash of pixel, index, seed)
  kStratified,   ///< n × n strata, one jittered sample in each (the reference's pattern)
};

/// The render a method asks for. Samples are tonemapped each, averaged in linear light with
/// a box filter over the pixel, sRGB-encoded and stored as RGBA8 (alpha 255).
struct RenderSpec {
  SamplePattern pattern = SamplePattern::kCenter;
  int grid = 1;        ///< n for kOrderedGrid / kStratified
  int spp = 1;         ///< samples per pixel for kJitter (derived for the others)
  double scale = 1.0;  ///< render size = round(scale · W) × round(scale · H)

  /// Samples per pixel this pattern takes.
  int SamplesPerPixel() const;
  /// Sample offsets inside the pixel, in [0, 1)², for patterns that do not jitter.
  std::vector<std::pair<float, float>> FixedOffsets() const;
};

}  // namespace aalab
