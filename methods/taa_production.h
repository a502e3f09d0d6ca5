/// The production TAA (methods/taa_production.cpp): the state and the pieces tests check on
/// their own (hand-worked Catmull-Rom weights, closest-depth dilation, half rounding).
#pragma once
#include <array>
#include <memory>
#include <string>

#include "methods/method.h"

namespace aalab {

/// How the current frame's colour at a pixel centre is rebuilt from the jittered samples.
enum class TaaReconstruct {
  kBox,    ///< the one sample whose jittered position lies in the pixel's box (still limit: box filter)
  kGauss,  ///< 3x3 samples weighted exp(-2.29·(d/size)²) (UE4's Blackman-Harris fit, σ ≈ 0.47·size)
};
/// How the history is fetched at the reprojected position.
enum class TaaHistoryFilter {
  kBilinear,     ///< 2x2 texels (today's `taa`)
  kCatmullRom,   ///< 4x4 texels, separable Catmull-Rom (what UE4's 9-tap bilinear trick computes)
  kCatmullRom5,  ///< the 4x4 without its 4 corners, renormalised (Jimenez 2016's 5 bilinear taps)
};
enum class TaaRectify { kVariance, kMinMax, kNone };
enum class TaaFeedback { kFixed, kAdaptive };
enum class TaaPrecision { kFloat32, kFloat16 };

/// Every setting of the production TAA (defaults: the registry row `taa-prod`).
struct TaaProdParams {
  TaaReconstruct reconstruct = TaaReconstruct::kBox;
  float filter_size = 1.0f;  ///< kGauss: UE4 r.TemporalAAFilterSize
  bool dilate = true;        ///< motion of the closest depth in 3x3
  TaaHistoryFilter history = TaaHistoryFilter::kCatmullRom;
  bool disocclusion = true;
  float disocclusion_depth = 0.05f;  ///< relative depth step that drops history
  float disocclusion_px = 1.0f;      ///< motion difference (render px) that drops history
  TaaRectify clip = TaaRectify::kVariance;
  float gamma = 1.0f;
  TaaFeedback feedback = TaaFeedback::kAdaptive;
  float alpha = 0.1f;        ///< kFixed: weight of the current frame
  float alpha_min = 0.04f;   ///< kAdaptive: floor of the weight when still (UE4 0.04)
  float alpha_max = 0.2f;    ///< kAdaptive: weight at motion_px and beyond (UE4 0.2), or at full contrast
  float motion_px = 8.0f;    ///< kAdaptive: output px per frame at which alpha reaches alpha_max
  bool luma_weight = false;  ///< kAdaptive: also raise alpha with the luminance difference (Lottes)
  float sharpen = 0.0f;      ///< unsharp amount on the output only (0 = off)
  TaaPrecision precision = TaaPrecision::kFloat32;
};

/// Catmull-Rom (B = 0, C = 0.5) weights of the 4 texels x0 − 1 .. x0 + 2 for a sample at
/// fraction t ∈ [0, 1) past texel x0; they sum to 1.
std::array<float, 4> CatmullRomWeights(float t);

/// The pixel of the 3×3 neighbourhood of (x, y) (clamped to the w × h image) with the smallest
/// depth; the centre wins ties, the others in row-major order. Returns y·w + x of that pixel.
int ClosestDepthPixel(const float* depth, int w, int h, int x, int y);

/// v rounded to the nearest IEEE half (ties to even; overflow to ±Inf), back as a float:
/// what an RGBA16F history stores.
float RoundToHalf(float v);

/// A fresh production TAA state.
std::unique_ptr<TemporalState> MakeTaaProdState(const TaaProdParams& p);

/// Reads the family's parameters (the taa-prod rows' table) into TaaProdParams; UserError for
/// an unknown choice.
TaaProdParams TaaProdParamsFrom(const ParamValues& v);

/// The parameter table the taa-prod and taau rows share (defaults as TaaProdParams).
std::vector<ParamDef> TaaProdParamDefs();

}  // namespace aalab
