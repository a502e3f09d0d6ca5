/// FXAA 1.0 (Timothy Lottes, NVIDIA whitepaper "FXAA", 2009/2011, presets 0-5) as a pure
/// post filter on an 8-bit RGBA frame. See methods/fxaa1.cpp for the algorithm, the
/// parameters and every deviation from the GPU shader.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/sampler.h"
#include "methods/method.h"

namespace aalab {

/// The whitepaper's tuning defines (FXAA_SUBPIX = 1 in every preset, so it is not a knob).
struct Fxaa1Params {
  float edge_threshold = 1.0f / 8.0f;       ///< FXAA_EDGE_THRESHOLD, [0, 1]
  float edge_threshold_min = 1.0f / 24.0f;  ///< FXAA_EDGE_THRESHOLD_MIN, [0, 1]
  int search_steps = 16;                    ///< FXAA_SEARCH_STEPS, [1, 64]
  int search_acceleration = 1;              ///< FXAA_SEARCH_ACCELERATION, [1, 4]
  float search_threshold = 1.0f / 4.0f;     ///< FXAA_SEARCH_THRESHOLD, [0, 1]
  float subpix_cap = 3.0f / 4.0f;           ///< FXAA_SUBPIX_CAP, [0, 1]
  float subpix_trim = 1.0f / 4.0f;          ///< FXAA_SUBPIX_TRIM, [0, 0.99]
  /// FXAA_SUBPIX_FASTER: true = lowpass is the 5-tap cross (N+W+M+E+S)/5, the "lower quality
  /// sub-pixel aliasing removal filter" of preset 0; false = the 3x3 box (presets 1-5).
  bool subpix_faster = false;
  SamplerArithmetic sampler = SamplerArithmetic::kGl;  ///< texel/filter arithmetic (PostOptions)
};

/// FxaaLuma's green weight, 0.587/0.299 rounded to float once: luma = g · this + r.
inline constexpr float kFxaa1LumaGreen = static_cast<float>(0.587 / 0.299);

/// Throws UserError naming the first field of `p` outside the registry's range.
void Fxaa1CheckParams(const Fxaa1Params& p);

/// The whitepaper presets 0-4, plus 5 (preset 4 with 32 search steps, as the shader
/// header's FXAA_PRESET 5). Throws UserError for any other number.
Fxaa1Params Fxaa1Preset(int preset);

/// The debug views Fxaa1 accepts besides "" (normal output), in whitepaper order:
/// passthrough, horzvert, pair, negpos, offset.
const std::vector<std::string>& Fxaa1DebugViews();

/// Everything FXAA 1.0 computes for one pixel, for tests and debug views. Lumas are in
/// FxaaLuma units (0 .. 1 + 0.587/0.299 ≈ 2.963). Positions and distances are in texels.
struct Fxaa1Trace {
  // Local contrast check.
  float luma_n = 0, luma_w = 0, luma_m = 0, luma_e = 0, luma_s = 0;
  float range_max = 0, range = 0;
  bool early_exit = false;  ///< range < max(EDGE_THRESHOLD_MIN, rangeMax·EDGE_THRESHOLD)
  // Sub-pixel aliasing test and lowpass.
  float blend_l = 0;  ///< amount of rgbL blended in at the end, in [0, CAP]
  float rgb_l[3] = {0, 0, 0};
  // Vertical/horizontal edge test.
  float edge_vert = 0, edge_horz = 0;
  bool horz_span = false;  ///< edgeHorz >= edgeVert: the edge runs along x
  // Pairing and end-of-edge search.
  bool pair_n = false;  ///< paired with N (horz) / W (vert); false = S / E
  float luma_pair = 0;  ///< average luma of M and its pair (the shader's lumaN)
  float gradient = 0;   ///< |luma(pair) - lumaM| · SEARCH_THRESHOLD (the stop limit)
  float luma_end_n = 0, luma_end_p = 0;
  bool done_n = false, done_p = false;  ///< the search found an end (else ran out of steps)
  int fetches_n = 0, fetches_p = 0;     ///< search fetch instructions issued per direction
  float dst_n = 0, dst_p = 0;           ///< distance from the pixel centre to posN / posP
  bool direction_n = false;             ///< dstN < dstP: the negative end is nearer
  bool shifted = false;                 ///< the nearer end's luma-sign test allowed a shift
  /// Signed sub-pixel shift in texels, perpendicular to the edge: along y when horz_span,
  /// along x otherwise; negative = towards -y / -x. |offset| <= 0.5.
  float offset = 0;
  float rgb_f[3] = {0, 0, 0};    ///< the re-sampled colour at the shifted position
  float rgb_out[3] = {0, 0, 0};  ///< final colour before 8-bit quantisation
};

/// Runs FXAA 1.0 on pixel (x, y) of `tex`'s frame; every fetch goes through `tex` (and is
/// counted there). The same code path Fxaa1 uses for its normal output.
Fxaa1Trace Fxaa1TracePixel(BilinearSampler& tex, int x, int y, const Fxaa1Params& p);

/// FXAA 1.0 over a whole RGBA8 frame, read as UNORM (k/255, sRGB-encoded values, as the
/// whitepaper's "Alias sRGB as UNORM" integration). Output: RGBA8, round-to-nearest,
/// alpha 255. `debug_view` is "" or one of Fxaa1DebugViews() (else UserError); `stats`
/// (optional) gets the texture taps added: every bilinear probe and exact texel read,
/// an anisotropic search fetch counting as search_acceleration probes. Parallel over rows,
/// bit-identical at any thread count. Throws UserError for parameters out of range.
/// This is the production path (luma plane once per frame, row-wise contrast check, only
/// edge pixels through Fxaa1TracePixel; debug views through Fxaa1Reference): same bits and
/// taps as Fxaa1Reference.
Image8 Fxaa1(const Image8& in, const Fxaa1Params& p, const std::string& debug_view, PostStats* stats);

/// The simple implementation of Fxaa1: Fxaa1TracePixel for every pixel. Kept as the
/// reference the production path is tested against, bit for bit.
Image8 Fxaa1Reference(const Image8& in, const Fxaa1Params& p, const std::string& debug_view, PostStats* stats);

}  // namespace aalab
