// SMAA 1x — Enhanced Subpixel Morphological Antialiasing, the reference shader's three passes.
//
// Implements Jimenez, Echevarria, Sousa, Gutierrez, "SMAA: Enhanced Subpixel Morphological
// Antialiasing" (Eurographics 2012) as its public reference implementation SMAA.hlsl
// (iryoku/smaa, read at commit 71c806a) computes it, statement by statement in float32:
//   1. edge detection (SMAALumaEdgeDetectionPS or SMAAColorEdgeDetectionPS): threshold, then
//      local contrast adaptation; the edge texture is an 8-bit RG render target;
//   2. blending weight calculation (SMAABlendingWeightCalculationPS): diagonal patterns
//      (SMAACalculateDiagWeights), orthogonal edge searches with the search texture, crossing
//      edges, the area texture, corner rounding; written to an RGBA8 render target;
//   3. neighbourhood blending (SMAANeighborhoodBlendingPS).
// Methods (post-only, on the 1x 8-bit frame), the reference's SMAA_PRESET_* values:
//   smaa-low      threshold 0.15, max_search_steps 4,  diag off, corner off
//   smaa-medium   threshold 0.10, max_search_steps 8,  diag off, corner off
//   smaa-high     threshold 0.10, max_search_steps 16, max_search_steps_diag 8,  corner_rounding 25
//   smaa-ultra    threshold 0.05, max_search_steps 32, max_search_steps_diag 16, corner_rounding 25
// Parameters (every method; the preset gives the defaults; `aalab list methods` lists them):
//   threshold               [0..0.5]  SMAA_THRESHOLD (reference range)
//   max_search_steps        [0..112]  SMAA_MAX_SEARCH_STEPS (each step covers 2 pixels)
//   max_search_steps_diag   [0..20]   SMAA_MAX_SEARCH_STEPS_DIAG (unused when diag=off); 8 low/medium
//   corner_rounding         [0..100]  SMAA_CORNER_ROUNDING (unused when corner=off); 25 low/medium
//   local_contrast          [0..10]   SMAA_LOCAL_CONTRAST_ADAPTATION_FACTOR, default 2
//   diag   {on|off}   off = SMAA_DISABLE_DIAG_DETECTION
//   corner {on|off}   off = SMAA_DISABLE_CORNER_DETECTION
//   detection {luma|color}   luma = SMAALumaEdgeDetectionPS (the reference's recommendation),
//                            color = SMAAColorEdgeDetectionPS
//   subtexel {8bit|exact}    bilinear fraction precision of every fetch; 8bit (default) as a
//                            GPU filters, exact = float32 fractions (see below)
// Debug views: `edges` (pass 1's texture: red = left edge, green = top edge) and `weights`
// (pass 2's texture: red = r+g = the weights of the pixel's top edge, green = b+a = of its
// left edge, bytes added and saturated).
//
// Sources: iryoku/smaa SMAA.hlsl (presets, all three passes), Scripts/AreaTex.py and
//   Scripts/SearchTex.py (the textures, generated here by our own code in smaa_textures.cpp);
//   the Eurographics 2012 paper. docs/smaa.md explains the choices below at more length.
//
// Fidelity and deviations (read with SMAA.hlsl open):
//   * Orientation. Our frames are stored top row first and texcoords grow downward, as in
//     Direct3D: "top" is the row above (y − 1), "left" x − 1. The shader is not symmetric
//     under a vertical flip, so a GL port that flips the image gives different pixels.
//   * Coordinates. texcoord = ((x + 0.5)/W, (y + 0.5)/H) in float32, SMAA_RT_METRICS =
//     (1/W, 1/H, W, H); the vertex shaders' offsets are evaluated per pixel (a rasteriser
//     interpolates the same affine values). mad(a, b, c) is a·b + c with two roundings (the
//     build has -ffp-contract=off; a GPU compiler may fuse it into one).
//   * Fetches. SMAASamplePoint (edge detection's colour reads) are exact texel reads
//     (BilinearSampler::Texel): a point sampler at a texel's centre returns that texel. Every
//     other fetch (SMAASample, SMAASampleLevelZero, ...Offset: edge, area, search, blend and
//     colour textures) is a bilinear fetch through BilinearSampler with clamp addressing;
//     integer offsets are added in texel space. The area and search textures are 8-bit (the
//     shipped textures' values: int(255·v)), the edge texture RG8 (0 or 255), the blend
//     texture RGBA8 (each weight rounded to nearest), as the reference's render targets.
//   * Sub-texel precision (the design decision). SMAA reads two edges with one
//     bilinear fetch at quarter/eighth-texel positions and then tests the result with `> 0`,
//     `== 0`, `> 0.8281` and round(). Its positions are exact only when 1/W is a power of
//     two: at other sizes ((x + 0.5)/W)·W misses x + 0.5 by a float rounding error, and an
//     exact float bilinear filter then mixes in ~1e-7 of the neighbouring texel. A
//     neighbour's edge then makes `e.g > 0` true at a pixel without an edge and ends the
//     `e.r == 0.0` searches early: spurious searches and weights. A GPU filters with 8 bits
//     of sub-texel precision, which removes those errors. We do the same: every SMAA fetch
//     uses SubTexel::kFixed8 (fraction rounded to the nearest 1/256). `subtexel=exact` keeps
//     float fractions, to show the effect. Round to nearest is our choice; hardware rounding
//     of the fraction is vendor-specific (documented in docs/smaa.md).
//   * round() is HLSL's round_ne (nearest, ties to even): std::nearbyint.
//   * The colour pass blends the sRGB-encoded values read as UNORM (docs/design.md "Colour": post filters
//     run on encoded values); the reference recommends an sRGB read/write in pass 3 only
//     and says it "will work anyway, but will perform antialiasing in gamma space" without.
//   * Output rgb rounded to 8 bits (round to nearest), alpha 255 (the shader returns the
//     blended alpha).
//   * Not implemented: depth edge detection (a post filter gets no depth), predication,
//     reprojection/temporal modes (T2x, S2x, 4x) — only SMAA 1x, subsample indices 0.
//   * max_search_steps_diag = 0: the diagonal search loop never runs and the shader would
//     read its uninitialised `out` value; we start it at 0 (the weights cannot depend on it:
//     the pattern needs d.x + d.y > 2).
//   * Degenerate sizes: every fetch clamps, so 1×1 and 1×N frames are defined (no edges
//     survive in a flat direction).
#include "methods/smaa.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "methods/families.h"
#include "methods/smaa_shader.h"

namespace aalab {

using smaa_detail::Frame;

namespace {

// dot(rgb, float3(0.2126, 0.7152, 0.0722)) in float32, in dot's order.
inline float Luma(const Float4& c) { return (c.r * 0.2126f + c.g * 0.7152f) + c.b * 0.0722f; }

inline float MaxAbsDiff(const Float4& a, const Float4& b) {
  const float r = std::fabs(a.r - b.r), g = std::fabs(a.g - b.g), bl = std::fabs(a.b - b.b);
  return std::max(std::max(r, g), bl);
}

// Pass 1 for pixel (x, y): writes the edge texel (r = left, g = top; 0 or 255).
void EdgePixel(BilinearSampler& tex, int x, int y, const SmaaParams& p, uint8_t* out) {
  const float thr = p.threshold;
  float dx, dy, mx, my;
  float ex, ey;
  if (p.detection == SmaaParams::Detection::kLuma) {
    const float L = Luma(tex.Texel(x, y));
    const float Lleft = Luma(tex.Texel(x - 1, y));
    const float Ltop = Luma(tex.Texel(x, y - 1));
    dx = std::fabs(L - Lleft);
    dy = std::fabs(L - Ltop);
    ex = dx >= thr ? 1.0f : 0.0f;  // step(threshold, delta)
    ey = dy >= thr ? 1.0f : 0.0f;
    if (ex * 1.0f + ey * 1.0f == 0.0f) return;  // discard
    const float Lright = Luma(tex.Texel(x + 1, y));
    const float Lbottom = Luma(tex.Texel(x, y + 1));
    mx = std::max(dx, std::fabs(L - Lright));
    my = std::max(dy, std::fabs(L - Lbottom));
    const float Lleftleft = Luma(tex.Texel(x - 2, y));
    const float Ltoptop = Luma(tex.Texel(x, y - 2));
    mx = std::max(mx, std::fabs(Lleft - Lleftleft));
    my = std::max(my, std::fabs(Ltop - Ltoptop));
  } else {
    const Float4 C = tex.Texel(x, y);
    dx = MaxAbsDiff(C, tex.Texel(x - 1, y));
    dy = MaxAbsDiff(C, tex.Texel(x, y - 1));
    ex = dx >= thr ? 1.0f : 0.0f;
    ey = dy >= thr ? 1.0f : 0.0f;
    if (ex * 1.0f + ey * 1.0f == 0.0f) return;
    mx = std::max(dx, MaxAbsDiff(C, tex.Texel(x + 1, y)));
    my = std::max(dy, MaxAbsDiff(C, tex.Texel(x, y + 1)));
    // The colour variant compares C with the left-left / top-top texel (the luma variant
    // compares Lleft with Lleftleft): as SMAA.hlsl writes it.
    mx = std::max(mx, MaxAbsDiff(C, tex.Texel(x - 2, y)));
    my = std::max(my, MaxAbsDiff(C, tex.Texel(x, y - 2)));
  }
  const float final_delta = std::max(mx, my);
  ex *= p.local_contrast_factor * dx >= final_delta ? 1.0f : 0.0f;
  ey *= p.local_contrast_factor * dy >= final_delta ? 1.0f : 0.0f;
  out[0] = QuantizeUnorm8(ex);
  out[1] = QuantizeUnorm8(ey);
}

void CheckInputs(const Image8& in, const SmaaParams& p) {
  AALAB_CHECK(in.Channels() == 4, "SMAA needs an RGBA8 frame");
  AALAB_CHECK(p.max_search_steps >= 0 && p.max_search_steps_diag >= 0, "SMAA search steps must be >= 0");
}

// Sums per-chunk tap counts (fixed chunk order).
uint64_t Sum(const std::vector<uint64_t>& v) {
  uint64_t s = 0;
  for (uint64_t t : v) s += t;
  return s;
}

constexpr int kGrain = 8;

Image8 EdgesRef(const Image8& in, const SmaaParams& p, uint64_t* taps) {
  Image8 edges(in.Width(), in.Height(), 4, 0);
  std::vector<uint64_t> t(static_cast<size_t>((in.Height() + kGrain - 1) / kGrain), 0);
  ParallelForChunks(in.Height(), kGrain, [&](int y0, int y1) {
    BilinearSampler tex(in, p.subtexel, p.sampler);
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < in.Width(); ++x) EdgePixel(tex, x, y, p, edges.Pixel(x, y));
    }
    t[static_cast<size_t>(y0 / kGrain)] = tex.Taps();
  });
  if (taps) *taps += Sum(t);
  return edges;
}

Image8 WeightsRef(const Image8& edges, const SmaaParams& p, uint64_t* taps) {
  const Frame f(edges.Width(), edges.Height());
  Image8 blend(edges.Width(), edges.Height(), 4, 0);
  const Image8& area_tex = SmaaAreaTexture();
  const Image8& search_tex = SmaaSearchTexture();
  std::vector<uint64_t> t(static_cast<size_t>((edges.Height() + kGrain - 1) / kGrain), 0);
  ParallelForChunks(edges.Height(), kGrain, [&](int y0, int y1) {
    BilinearSampler es(edges, p.subtexel, p.sampler), as(area_tex, p.subtexel, p.sampler),
        ss(search_tex, p.subtexel, p.sampler);
    smaa_detail::SamplerEdges reader(es);
    smaa_detail::WeightsShader<smaa_detail::SamplerEdges> shader(reader, as, ss, p, f);
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < edges.Width(); ++x) {
        const Float4 w = shader.Run(x, y);
        uint8_t* o = blend.Pixel(x, y);
        o[0] = QuantizeUnorm8(w.r);
        o[1] = QuantizeUnorm8(w.g);
        o[2] = QuantizeUnorm8(w.b);
        o[3] = QuantizeUnorm8(w.a);
      }
    }
    t[static_cast<size_t>(y0 / kGrain)] = es.Taps() + as.Taps() + ss.Taps();
  });
  if (taps) *taps += Sum(t);
  return blend;
}

Image8 BlendRef(const Image8& in, const Image8& blend, const SmaaParams& p, uint64_t* taps) {
  const Frame f(in.Width(), in.Height());
  Image8 out(in.Width(), in.Height(), 4);
  std::vector<uint64_t> t(static_cast<size_t>((in.Height() + kGrain - 1) / kGrain), 0);
  ParallelForChunks(in.Height(), kGrain, [&](int y0, int y1) {
    BilinearSampler bs(blend, p.subtexel, p.sampler), cs(in, p.subtexel, p.sampler);
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < in.Width(); ++x) smaa_detail::BlendPixel(bs, cs, f, x, y, out.Pixel(x, y));
    }
    t[static_cast<size_t>(y0 / kGrain)] = bs.Taps() + cs.Taps();
  });
  if (taps) *taps += Sum(t);
  return out;
}

}  // namespace

namespace smaa_detail {

// The debug views from the edge and blend textures (shared with smaa_fast.cpp).
Image8 EdgesView(const Image8& edges) {
  Image8 v(edges.Width(), edges.Height(), 4, 0);
  for (size_t i = 0; i < edges.PixelCount(); ++i) {
    v.Data()[4 * i] = edges.Data()[4 * i];
    v.Data()[4 * i + 1] = edges.Data()[4 * i + 1];
    v.Data()[4 * i + 3] = 255;
  }
  return v;
}

Image8 WeightsView(const Image8& blend) {
  Image8 v(blend.Width(), blend.Height(), 4, 0);
  for (size_t i = 0; i < blend.PixelCount(); ++i) {
    const uint8_t* b = &blend.Data()[4 * i];
    v.Data()[4 * i] = static_cast<uint8_t>(std::min(255, b[0] + b[1]));
    v.Data()[4 * i + 1] = static_cast<uint8_t>(std::min(255, b[2] + b[3]));
    v.Data()[4 * i + 3] = 255;
  }
  return v;
}

// Which view a debug_view string names: 0 normal, 1 edges, 2 weights; UserError otherwise.
int ParseView(const std::string& view) {
  if (view.empty()) return 0;
  if (view == "edges") return 1;
  if (view == "weights") return 2;
  throw UserError("SMAA has no debug view '" + view + "' (available: " + JoinNames(SmaaDebugViews()) + ")");
}

}  // namespace smaa_detail

const std::vector<std::string>& SmaaDebugViews() {
  static const std::vector<std::string> views = {"edges", "weights"};
  return views;
}

SmaaParams SmaaPreset(const std::string& preset) {
  SmaaParams p;
  if (preset == "low") {
    p.threshold = 0.15f, p.max_search_steps = 4, p.diag = false, p.corner = false;
  } else if (preset == "medium") {
    p.threshold = 0.1f, p.max_search_steps = 8, p.diag = false, p.corner = false;
  } else if (preset == "high") {
    p.threshold = 0.1f, p.max_search_steps = 16, p.max_search_steps_diag = 8, p.corner_rounding = 25;
  } else if (preset == "ultra") {
    p.threshold = 0.05f, p.max_search_steps = 32, p.max_search_steps_diag = 16, p.corner_rounding = 25;
  } else {
    throw InternalError("unknown SMAA preset '" + preset + "'");
  }
  return p;
}

Image8 SmaaEdgeTexture(const Image8& in, const SmaaParams& params) {
  CheckInputs(in, params);
  return EdgesRef(in, params, nullptr);
}

Image8 SmaaBlendTexture(const Image8& edges, const SmaaParams& params) {
  CheckInputs(edges, params);
  return WeightsRef(edges, params, nullptr);
}

Image8 SmaaNeighborhoodBlend(const Image8& in, const Image8& blend, const SmaaParams& params) {
  CheckInputs(in, params);
  AALAB_CHECK(blend.Width() == in.Width() && blend.Height() == in.Height() && blend.Channels() == 4,
              "SMAA blend texture must be RGBA8 of the frame's size");
  return BlendRef(in, blend, params, nullptr);
}

Image8 SmaaReference(const Image8& in, const SmaaParams& params, const std::string& debug_view, PostStats* stats) {
  CheckInputs(in, params);
  const int view = smaa_detail::ParseView(debug_view);
  if (in.Empty()) return in;
  uint64_t taps = 0;
  const Image8 edges = EdgesRef(in, params, &taps);
  if (view == 1 && stats) stats->taps += taps;  // a debug view counts the passes it ran
  if (view == 1) return smaa_detail::EdgesView(edges);
  const Image8 blend = WeightsRef(edges, params, &taps);
  if (view == 2 && stats) stats->taps += taps;
  if (view == 2) return smaa_detail::WeightsView(blend);
  Image8 out = BlendRef(in, blend, params, &taps);
  if (stats) stats->taps += taps;
  return out;
}

// ---------------------------------------------------------------------------------------
// Registry rows.

namespace {

std::vector<ParamDef> SmaaParamDefs(const SmaaParams& d, double threshold) {
  return {
      FloatParam("threshold", threshold, 0.0, 0.5,
                 "edge detection threshold (SMAA_THRESHOLD): 0.1 catches most visible edges, 0.05 'catches them all'"),
      IntParam("max_search_steps", d.max_search_steps, 0, 112,
               "horizontal/vertical search steps each side (SMAA_MAX_SEARCH_STEPS), 2 px per step"),
      IntParam("max_search_steps_diag", d.max_search_steps_diag, 0, 20,
               "diagonal search steps each side (SMAA_MAX_SEARCH_STEPS_DIAG), 1 px per step; used when diag=on"),
      IntParam("corner_rounding", d.corner_rounding, 0, 100,
               "how much sharp corners are rounded, percent (SMAA_CORNER_ROUNDING); used when corner=on"),
      FloatParam("local_contrast", d.local_contrast_factor, 0.0, 10.0,
                 "drop an edge when a neighbouring edge has this many times its contrast "
                 "(SMAA_LOCAL_CONTRAST_ADAPTATION_FACTOR)"),
      ChoiceParam("diag", d.diag ? "on" : "off", {"on", "off"},
                  "diagonal pattern detection (off = SMAA_DISABLE_DIAG_DETECTION)"),
      ChoiceParam("corner", d.corner ? "on" : "off", {"on", "off"},
                  "corner detection/rounding (off = SMAA_DISABLE_CORNER_DETECTION)"),
      ChoiceParam("detection", "luma", {"luma", "color"},
                  "edge detection on luma (dot with 0.2126/0.7152/0.0722) or on the max rgb difference"),
      ChoiceParam("subtexel", "8bit", {"8bit", "exact"},
                  "bilinear fraction of every fetch: 8bit as GPUs filter (default), exact float32 (shows "
                  "spurious weights at non-power-of-two sizes)"),
  };
}

MethodEntry SmaaEntry(const std::string& preset, double threshold, const std::string& help) {
  const std::string name = "smaa-" + preset;
  const SmaaParams defaults = SmaaPreset(preset);
  AALAB_CHECK(defaults.threshold == static_cast<float>(threshold), "SMAA preset threshold table mismatch");
  return {name, help, SmaaParamDefs(defaults, threshold), [name](const ParamValues& v) {
            SmaaParams sp;
            sp.threshold = static_cast<float>(v.Number("threshold"));
            sp.max_search_steps = v.Int("max_search_steps");
            sp.max_search_steps_diag = v.Int("max_search_steps_diag");
            sp.corner_rounding = v.Int("corner_rounding");
            sp.local_contrast_factor = static_cast<float>(v.Number("local_contrast"));
            sp.diag = v.Choice("diag") == "on";
            sp.corner = v.Choice("corner") == "on";
            sp.detection =
                v.Choice("detection") == "color" ? SmaaParams::Detection::kColor : SmaaParams::Detection::kLuma;
            sp.subtexel = v.Choice("subtexel") == "exact" ? SubTexel::kExact : SubTexel::kFixed8;
            MethodPlan plan;
            plan.name = name;
            plan.params = v;
            plan.post = [sp](const Image8& in, const PostOptions& options, PostStats* stats) {
              SmaaParams p = sp;
              p.sampler = options.sampler;
              return Smaa(in, p, options.debug_view, stats);
            };
            plan.post_reference = [sp](const Image8& in, const PostOptions& options, PostStats* stats) {
              SmaaParams p = sp;
              p.sampler = options.sampler;
              return SmaaReference(in, p, options.debug_view, stats);
            };
            plan.config = sp;
            plan.debug_views = SmaaDebugViews();
            return plan;
          }};
}

}  // namespace

std::vector<MethodEntry> SmaaMethods() {
  std::vector<MethodEntry> out = {
      SmaaEntry("low", 0.15, "SMAA 1x, reference preset LOW: threshold 0.15, 4 search steps, no diagonals, no corners"),
      SmaaEntry("medium", 0.1,
                "SMAA 1x, reference preset MEDIUM: threshold 0.1, 8 search steps, no diagonals, no corners"),
      SmaaEntry("high", 0.1,
                "SMAA 1x, reference preset HIGH: threshold 0.1, 16 search steps, 8 diagonal, corner rounding 25"),
      SmaaEntry("ultra", 0.05,
                "SMAA 1x, reference preset ULTRA: threshold 0.05, 32 search steps, 16 diagonal, corner rounding 25"),
  };
  for (auto& e : out) e.in_default_list = e.name == "smaa-high";  // in `aalab run`'s default list
  return out;
}

}  // namespace aalab
