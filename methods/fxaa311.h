/// FXAA 3.11 Quality (PC), Timothy Lottes 2011, as one step-table-driven post filter.
/// See methods/fxaa311.cpp for the method family, sources and the list of deviations.
#pragma once
#include <string>
#include <vector>

#include "core/image.h"
#include "core/sampler.h"
#include "methods/method.h"

namespace aalab {

/// Everything that parameterises one FXAA 3.11 Quality pass.
struct Fxaa311Params {
  /// Where the shader's luma comes from.
  enum class Luma {
    /// FXAA_GREEN_AS_LUMA 0: a first pass writes dot(rgb, (0.299, 0.587, 0.114)) of the
    /// sRGB-encoded colour into alpha, rounded to 8 bits like an RGBA8 back buffer; every
    /// tap then reads luma from alpha (bilinear taps filter the stored alpha).
    kRec601,
    /// seed 003's GLSL: rgb2luma(rgb) = dot(rgb, (0.299, 0.587, 0.114)) of each tap's
    /// (filtered) rgb, in float, at every tap; nothing is stored.
    kRec601Rgb,
    /// FXAA_GREEN_AS_LUMA 1: the green channel of each tap.
    kGreen,
    /// The Catlike Coding tutorial: sqrt of linear luminance (Unity's Luminance():
    /// 0.2126729, 0.7151522, 0.0721750) of the sRGB-decoded colour, written into alpha at 8
    /// bits by a first pass (the tutorial's "Apply Color Grading With Luma" pass); every tap
    /// then reads alpha.
    kSqrtLuminance,
  };
  /// Which float evaluation order the expressions follow where the two sources differ.
  enum class Order {
    kFxaa311,     ///< Fxaa3_11.h FxaaPixelShader (seed 004), statement by statement
    kSeed003Glsl  ///< seed 003's GLSL (five expressions associate differently; see .cpp)
  };

  /// Search step sizes P0..P(n-1) in texels, n >= 2. P0 places the first pair of search
  /// taps; P1..P(n-2) are advanced before a further fetch; P(n-1) is advanced after the
  /// final fetch (a guess) and never fetched.
  std::vector<float> steps;
  float subpix = 0.75f;                ///< fxaaQualitySubpix, amount of sub-pixel blending
  float edge_threshold = 0.166f;       ///< fxaaQualityEdgeThreshold (relative to max luma)
  float edge_threshold_min = 0.0833f;  ///< fxaaQualityEdgeThresholdMin (absolute)
  Luma luma = Luma::kRec601;
  Order order = Order::kFxaa311;
  SamplerArithmetic sampler = SamplerArithmetic::kGl;  ///< texel/filter arithmetic (PostOptions)
};

/// Parses "rec601" | "rec601-rgb" | "green" | "sqrt-luminance"; throws UserError listing them.
Fxaa311Params::Luma ParseFxaa311Luma(const std::string& name);
/// The names ParseFxaa311Luma accepts, in that order.
const std::vector<std::string>& Fxaa311LumaNames();

/// The luma pre-pass: for kRec601 and kSqrtLuminance a copy of `in` (RGBA8) whose alpha
/// holds the luma rounded to 8 bits (StoreUnorm8, GL's UNORM store); for kGreen and
/// kRec601Rgb a plain copy (those modes read luma from rgb at each tap). kRec601 reads the
/// texels as TexelValue(k, sampler), as the GPU pre-pass reads them through the texture unit.
Image8 Fxaa311LumaFrame(const Image8& in, Fxaa311Params::Luma luma, SamplerArithmetic sampler = SamplerArithmetic::kGl);

/// The luma the shader reads from one tap of the frame Fxaa311LumaFrame prepared
/// (FxaaLuma): alpha, green, or dot(rgb, (0.299, 0.587, 0.114)) evaluated as
/// r·0.299 + (g·0.587 + b·0.114) in float32 (the order llvmpipe evaluates GLSL dot()).
float Fxaa311TapLuma(const Float4& tap, Fxaa311Params::Luma luma);

/// FXAA 3.11 Quality on an 8-bit RGBA frame (sRGB-encoded values read as UNORM). Returns a
/// frame of the same size: the filtered rgb, alpha 255. Pure and deterministic: rows run in
/// parallel chunks and the output is bit-identical at any thread count. When `stats` is not
/// null, adds the number of texture fetches of the filter pass (the luma pre-pass is not
/// counted: on a GPU it is folded into the pass that writes the frame) to stats->taps.
/// Pixels where the shader would divide by a zero luma range (possible only with
/// edge_threshold_min = 0) are returned unchanged instead of going through 1/0.
/// Requires params.steps.size() >= 2 (InternalError otherwise).
/// This is the production path (luma plane once per frame, row-wise early exit, only edge
/// pixels through the search); it returns the same bits and tap count as Fxaa311Reference.
Image8 Fxaa311(const Image8& in, const Fxaa311Params& params, PostStats* stats);

/// The simple implementation of Fxaa311: the luma pre-pass frame, then ShadePixel for every
/// pixel through BilinearSampler, statement by statement as the shader. Kept as the
/// reference the fast path is tested against (bit for bit, taps included).
Image8 Fxaa311Reference(const Image8& in, const Fxaa311Params& params, PostStats* stats);

/// Gives `plan` (its name already set) FXAA 3.11 with `fp` as its post filter: `post` the
/// production path, `post_reference` the reference, both with the run's sampler arithmetic
/// (PostOptions::sampler) and no debug views; `config` = fp. Used by the FXAA 3.11 rows and
/// by the render-scale rows that end in FXAA.
void SetFxaa311Post(MethodPlan& plan, const Fxaa311Params& fp);

/// The FXAA 3.11 quality presets this build knows (10..15, 20..29, 39), ascending.
std::vector<int> Fxaa311PresetIds();
/// Step table P0..P(n-1) of a quality preset, as Fxaa3_11.h #defines it (FXAA_QUALITY__P*).
/// Throws InternalError for an unknown preset.
const std::vector<float>& Fxaa311PresetSteps(int preset);

/// The Catlike Coding tutorial's quality levels as full step tables: the first step of 1,
/// then EDGE_STEP_SIZES, then LAST_EDGE_STEP_GUESS. `level` is "low" | "medium" | "high";
/// throws InternalError otherwise.
const std::vector<float>& FxaaTutorialSteps(const std::string& level);

/// The FXAA post filter of the tutorial's "high" level with its defaults (sqrt-luminance
/// luma, thresholds 0.0833 / 0.166, subpix 0.75): used by render-scale methods.
Fxaa311Params FxaaTutorialHighParams();

}  // namespace aalab
