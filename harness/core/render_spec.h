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

/// Analytical anti-aliasing's pixel size (FrostKiwi, "Analytical Anti-Aliasing", seeds/004):
/// a per-object constant, length(vec2(dFdx(d), dFdy(d))) or fwidth(d) = |dFdx d| + |dFdy d|.
enum class AaaPixelSize { kObject, kLength, kFwidth };
/// How the distance becomes alpha: the article's division (1 − dist)/(px·k) (clamped by the
/// fixed-point framebuffer), linearstep (clamped explicitly) or smoothstep (Hermite).
enum class AaaBlend { kDivision, kLinstep, kSmoothstep };

/// Analytic edge coverage for disks, spheres and capsules (methods/aaa.cpp documents the
/// parameters, scenes/analytic.h the renderer). Off by default.
struct AnalyticSpec {
  bool enabled = false;
  AaaPixelSize pixel_size = AaaPixelSize::kObject;
  AaaBlend blend = AaaBlend::kDivision;
  double shrink = 0.5;     ///< the article's radius adjust: dist += px · shrink
  double smoothing = 1.0;  ///< the article's smoothingAmount: the ramp is px · smoothing wide
};

/// The render a method asks for. Samples are tonemapped each, averaged in linear light with
/// a box filter over the pixel, sRGB-encoded and stored as RGBA8 (alpha 255).
struct RenderSpec {
  SamplePattern pattern = SamplePattern::kCenter;
  int grid = 1;        ///< n for kOrderedGrid / kStratified
  int spp = 1;         ///< samples per pixel for kJitter (derived for the others)
  double scale = 1.0;  ///< render size = round(scale · W) × round(scale · H)
  AnalyticSpec aaa;    ///< analytical AA (off unless aaa.enabled); uses the kCenter pattern

  /// Samples per pixel this pattern takes.
  int SamplesPerPixel() const;
  /// Sample offsets inside the pixel, in [0, 1)², for patterns that do not jitter.
  std::vector<std::pair<float, float>> FixedOffsets() const;
};

}  // namespace aalab
