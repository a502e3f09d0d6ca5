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

/// The sub-pixel offset of one frame's sample from the pixel centre, in pixels, in [−0.5, 0.5).
struct FrameJitter {
  float x = 0.0f, y = 0.0f;
};

/// Per-frame sub-pixel jitter of a one-sample-per-pixel render (TAA). Off when `samples` is
/// 0. The method states the sequence; the offset of a given frame is per-frame data the
/// runner computes (FrameJitterAt) and passes to the renderer.
struct JitterSpec {
  int samples = 0;  ///< Halton(2,3) points cycled through (0: no jitter)
  /// A method's own sequence instead of the Halton points below: the offset of frame `frame`
  /// given `samples` (FSR 2: the negated ffxFsr2GetJitterOffset, methods/fsr2_sequence.h).
  /// Null: FrameJitterAt's Halton(2,3).
  FrameJitter (*sequence)(int frame, int samples) = nullptr;
};

/// Halton(2,3) jitter of frame `frame` (≥ 0): the points of indices 1..samples cycled
/// ((frame mod samples) + 1; index 0 is the degenerate (0, 0)), minus 0.5 — the convention of
/// Playdead's FrustumJitter and Unity URP; spec.sequence(frame, samples) when it is set. Zero
/// offset when spec.samples == 0.
FrameJitter FrameJitterAt(const JitterSpec& spec, int frame);

/// The radical inverse of `index` in `base` (the Halton sequence's coordinate), exact in double.
double RadicalInverse(int base, int index);
/// Where MSAA evaluates the one shading of a primitive in a pixel.
enum class MsaaShading {
  kCenter,    ///< the pixel centre on the primitive (attributes extrapolated past its edge)
  kCentroid,  ///< the centre when all samples are covered, else the first covered sample
};

/// When MSAA runs the alpha test of a cut-out material.
enum class MsaaAlphaTest {
  kShade,     ///< once per shading evaluation; a failed test discards all samples of that primitive
  kSample,    ///< at every coverage sample (sample-rate alpha test)
  kCoverage,  ///< alpha-to-coverage: the shading point's alpha picks how many samples stay
              ///< (⌊α·N + Bayer 4×4 dither⌋, in sample index order; docs/msaa.md)
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

/// Geometric specular anti-aliasing (Tokuyoshi & Kaplanyan, "Stable Geometric Specular
/// Antialiasing with Projected-Space NDF Filtering", JCGT 10(2), 2021, listing 5; methods/
/// specular_aa.cpp): the GGX roughness of glTF materials widened by the variance of the shading
/// normal over the pixel footprint, α'² = min(1, α² + min(σ²·(|∂n/∂x|² + |∂n/∂y|²), κ)). Off by default.
struct SpecularAaSpec {
  bool enabled = false;
  double sigma2 = 0.15915494309189535;  ///< variance of the pixel filter kernel (1/(2π))
  double kappa = 0.18;                  ///< clamp of the added α²
  /// Whose derivatives the geometric term takes: false, the interpolated vertex normal (the
  /// paper's listing); true, the final normal-mapped normal (aalab's `gsaa` before 2026-11).
  bool mapped_derivatives = false;
  /// Weight of the normal map's own variance (Toksvig / vMF, scenes/toksvig.h): 0 off, 1 on.
  double toksvig = 1.0;
  /// Clamp of the texture term's added α² (HDRP clamps its normal-filtering widening by the
  /// material's threshold², default 0.2² = 0.04).
  double toksvig_max = 0.04;
};

/// The render a method asks for. Samples are tonemapped each, averaged in linear light with
/// a box filter over the pixel, sRGB-encoded and stored as RGBA8 (alpha 255).
struct RenderSpec {
  SamplePattern pattern = SamplePattern::kCenter;
  int grid = 1;                ///< n for kOrderedGrid / kStratified
  int spp = 1;                 ///< samples per pixel for kJitter (derived for the others)
  double scale = 1.0;          ///< render size = round(scale · W) × round(scale · H)
  MsaaSpec msaa;               ///< MSAA (off by default); when on it replaces `pattern`
  AnalyticSpec aaa;            ///< analytical AA (off unless aaa.enabled); uses the kCenter pattern
  JitterSpec jitter;           ///< TAA: per-frame jitter of the kCenter sample (off by default)
  SpecularAaSpec specular_aa;  ///< geometric specular AA of glTF materials (off by default)

  /// Samples per pixel this pattern takes (MSAA: coverage samples).
  int SamplesPerPixel() const;
  /// True when this is the plain 1x frame (one centre sample, scale 1, no render-time AA: no
  /// MSAA, no TAA jitter):
  /// the frame `none` renders, which post filters share.
  bool IsPlain1x() const;
  /// Sample offsets inside the pixel, in [0, 1)², for patterns that do not jitter.
  std::vector<std::pair<float, float>> FixedOffsets() const;
};

}  // namespace aalab
