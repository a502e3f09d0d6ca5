/// SMAA 1x (Jimenez et al. 2012, reference shader SMAA.hlsl): edge detection, blending weight
/// calculation, neighbourhood blending. See methods/smaa.cpp for the method family, sources
/// and deviations, and docs/smaa.md.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "core/sampler.h"
#include "methods/method.h"

namespace aalab {

/// Everything that parameterises one SMAA 1x run (the reference's #defines).
struct SmaaParams {
  enum class Detection { kLuma, kColor };  ///< SMAALumaEdgeDetectionPS / SMAAColorEdgeDetectionPS
  Detection detection = Detection::kLuma;
  float threshold = 0.1f;                              ///< SMAA_THRESHOLD, [0, 0.5]
  int max_search_steps = 16;                           ///< SMAA_MAX_SEARCH_STEPS, [0, 112]
  int max_search_steps_diag = 8;                       ///< SMAA_MAX_SEARCH_STEPS_DIAG, [0, 20]
  int corner_rounding = 25;                            ///< SMAA_CORNER_ROUNDING, [0, 100]
  float local_contrast_factor = 2.0f;                  ///< SMAA_LOCAL_CONTRAST_ADAPTATION_FACTOR
  bool diag = true;                                    ///< false = SMAA_DISABLE_DIAG_DETECTION
  bool corner = true;                                  ///< false = SMAA_DISABLE_CORNER_DETECTION
  SubTexel subtexel = SubTexel::kFixed8;               ///< bilinear fraction precision of every fetch
  SamplerArithmetic sampler = SamplerArithmetic::kGl;  ///< texel/filter arithmetic (PostOptions)
};

/// The reference's presets: "low", "medium", "high", "ultra" (SMAA_PRESET_*). Throws
/// InternalError for another name.
SmaaParams SmaaPreset(const std::string& preset);

/// The debug views Smaa accepts besides "": "edges" (edge texture: red = left edge, green =
/// top edge) and "weights" (blend texture: red = r+g, the weights of the pixel's top edge;
/// green = b+a, the weights of its left edge; each saturated).
const std::vector<std::string>& SmaaDebugViews();

/// SMAA 1x on an 8-bit RGBA frame (sRGB-encoded values read as UNORM, blended in that
/// space). Returns the filtered rgb with alpha 255, or a debug view. Deterministic at any
/// thread count. Adds the texture fetches of all three passes to stats->taps when `stats`
/// is not null. The production path; same bits and taps as SmaaReference.
Image8 Smaa(const Image8& in, const SmaaParams& params, const std::string& debug_view, PostStats* stats);

/// The plain implementation: the three passes over every pixel, statement by statement as
/// SMAA.hlsl, every fetch through BilinearSampler (mode params.subtexel), the edge and blend
/// textures stored as 8-bit render targets. The reference Smaa is tested against.
Image8 SmaaReference(const Image8& in, const SmaaParams& params, const std::string& debug_view, PostStats* stats);

/// The edge texture of pass 1 alone (RGBA8: r = left edge, g = top edge, each 0 or 255).
Image8 SmaaEdgeTexture(const Image8& in, const SmaaParams& params);
/// The blend-weight texture of pass 2 on an edge texture (RGBA8, each weight rounded to 8
/// bits as the RGBA8 render target stores it).
Image8 SmaaBlendTexture(const Image8& edges, const SmaaParams& params);
/// Pass 3 alone: the input frame blended with a blend texture (RGBA8, as SmaaBlendTexture
/// returns); rgb rounded to 8 bits, alpha 255.
Image8 SmaaNeighborhoodBlend(const Image8& in, const Image8& blend, const SmaaParams& params);

// ---------------------------------------------------------------- textures (smaa_textures.cpp)

/// Area of the orthogonal pattern `pattern` (0..15, AreaTex.py's areaortho numbering) for
/// distances left/right in pixels and subsample offset `offset`, in double, as the
/// published script computes it: (area on one side, area on the other).
std::pair<double, double> SmaaAreaOrtho(int pattern, int left, int right, double offset);
/// Area of the diagonal pattern `pattern` (0..15, areadiag) for distances left/right, by the
/// script's 30×30 brute-force sampling, subsample offset (ox, oy).
std::pair<double, double> SmaaAreaDiag(int pattern, int left, int right, double ox, double oy);
/// The 160×560 area texture (RG in r/g of RGBA8; b = a = 0) for SMAA 1x: the orthogonal
/// block (x 0..79) and diagonal block (x 80..159) of subsample 0, rows 0..79, each value
/// int(255·area) (truncation, as the script's bytes()); the rows of the other subsample
/// indices (used only by T2x/S2x/4x) are left 0. Built on first use, then shared (const).
const Image8& SmaaAreaTexture();
/// The search-texture value (0, 1 or 2 pixels) of SearchTex.py's deltaLeft (right = false)
/// or deltaRight (right = true) for the bilinear edge values (e_left, e_top), each one of
/// the 16 values k/32 the pseudo-gather fetch can return; -1 when a value is not one of them.
int SmaaSearchDelta(bool right, double e_left, double e_top);
/// The 64×16 search texture (r of RGBA8, values 0 / 127 / 254): the 66×33 table cropped to
/// rows 17..32 and flipped vertically, as the script does. Built on first use (const).
const Image8& SmaaSearchTexture();

}  // namespace aalab
