/// What a method asks the renderer for: sample pattern, samples per pixel, render scale, MSAA.
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

/// Where MSAA evaluates the one shading of a primitive in a pixel.
enum class MsaaShading {
  kCenter,    ///< the pixel centre on the primitive (attributes extrapolated past its edge)
  kCentroid,  ///< the centre when all samples are covered, else the first covered sample
};

/// When MSAA runs the alpha test of a cut-out material.
enum class MsaaAlphaTest {
  kShade,   ///< once per shading evaluation; a failed test discards all samples of that primitive
  kSample,  ///< at every coverage sample (sample-rate alpha test / alpha-to-coverage)
};

/// How MSAA's samples become a pixel.
enum class MsaaResolve {
  kDisplay,    ///< each sample through the display transform, box average in linear light (as SSAA)
  kHdrLinear,  ///< box average of scene-linear radiance, then the display transform once
};

/// The MSAA render request (docs/msaa.md): `samples` coverage samples per pixel at the
/// standard D3D11 / Vulkan positions, one shading evaluation per primitive per pixel.
/// samples == 0 means off (every other field is then ignored).
struct MsaaSpec {
  int samples = 0;  ///< 0 (off), 2, 4, 8 or 16
  MsaaShading shading = MsaaShading::kCenter;
  MsaaAlphaTest alpha_test = MsaaAlphaTest::kShade;
  MsaaResolve resolve = MsaaResolve::kDisplay;

  bool On() const { return samples > 0; }
};

/// A standard sample position, in 1/16 px from the pixel centre, y down.
struct SampleOffset16 {
  int x = 0, y = 0;
};

/// The standard sample positions of Direct3D 11 (functional spec 11.3 §19.2.4) and Vulkan
/// ("standard sample locations"), in sample index order, for n = 1, 2, 4, 8 or 16. Throws
/// InternalError for other n.
const std::vector<SampleOffset16>& StandardSamplePositions(int n);

/// The render a method asks for. Samples are tonemapped each, averaged in linear light with
/// a box filter over the pixel, sRGB-encoded and stored as RGBA8 (alpha 255).
struct RenderSpec {
  SamplePattern pattern = SamplePattern::kCenter;
  int grid = 1;        ///< n for kOrderedGrid / kStratified
  int spp = 1;         ///< samples per pixel for kJitter (derived for the others)
  double scale = 1.0;  ///< render size = round(scale · W) × round(scale · H)
  MsaaSpec msaa;       ///< MSAA (off by default); when on it replaces `pattern`

  /// Samples per pixel this pattern takes (MSAA: coverage samples).
  int SamplesPerPixel() const;
  /// True when this is the plain 1x frame (one centre sample, scale 1, no render-time AA):
  /// the frame `none` renders, which post filters share.
  bool IsPlain1x() const;
  /// Sample offsets inside the pixel, in [0, 1)², for patterns that do not jitter.
  std::vector<std::pair<float, float>> FixedOffsets() const;
};

}  // namespace aalab
