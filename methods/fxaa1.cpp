// FXAA 1.0 — Timothy Lottes, NVIDIA whitepaper "FXAA" (v1.0, 25/01/11; seeds/002), presets 0-5.
//
// What it implements
//   A single-pass post filter on the 8-bit LDR frame, read as UNORM (k·fl(1/255) of the
//   sRGB-encoded values: whitepaper "Integration / Alias sRGB as UNORM"), written back as
//   RGBA8 with round-to-nearest and alpha 255. Per pixel, following "Implementation /
//   Algorithm Overview" steps 1-8:
//     1 luma            FxaaLuma: g·(0.587/0.299) + r                ("Luminance Conversion")
//     2 early exit      range(N,W,M,E,S) < max(EDGE_THRESHOLD_MIN, rangeMax·EDGE_THRESHOLD)
//                                                                    ("Local Contrast Check")
//     - sub-pixel test  blendL = min(CAP, max(0, |lumaL−lumaM|/range − TRIM)·TRIM_SCALE),
//                       lumaL = (N+W+E+S)/4, rgbL = 3x3 box (or the 5-tap cross in preset 0)
//                                                                    ("Sub-pixel Aliasing Test")
//     3 orientation     edgeVert / edgeHorz weighted 3x3 high-pass, horzSpan = Horz >= Vert
//                                                                    ("Vertical/Horizontal Edge Test")
//     4 pairing         the neighbour 90° to the edge with the larger |Δluma| (N/W on ties)
//     5 end search      both directions in one loop; stop when |lumaEnd − lumaPair| >=
//                       SEARCH_THRESHOLD·gradient; SEARCH_STEPS fetches per direction, each
//                       a box of SEARCH_ACCELERATION texel pairs    ("End-of-edge Search")
//     6 sub-pixel shift 0.5 − dst(nearer end)/(dstN+dstP) towards the pair, if the nearer
//                       end's luma lies on the other side of the pair average than lumaM
//     7 re-sample       one bilinear fetch at the shifted position
//     8 lowpass blend   lerp(rgbF, rgbL, blendL)
//   The whitepaper prints steps 1-3 and the search loop; the statements it leaves out
//   (pairing, gradient, start offsets, dstN/dstP, the shift and the debug colours) follow
//   the FxaaShader.h that ships with the whitepaper's sample (FXAA 1.0 SDK header), read
//   for facts only.
//   This file holds the reference (Fxaa1Reference, Fxaa1TracePixel for every pixel), the
//   debug views and the registry rows; the production path `Fxaa1` is methods/fxaa1_fast.cpp.
//
// Parameters (registry names; defaults are preset 3; ranges are what the registry accepts)
//   edge_threshold       FXAA_EDGE_THRESHOLD       [0..1]     p0 1/4, p1-p5 1/8
//   edge_threshold_min   FXAA_EDGE_THRESHOLD_MIN   [0..1]     p0 1/12, p1 1/16, p2-p5 1/24
//   search_steps         FXAA_SEARCH_STEPS         [1..64]    p0 2, p1 4, p2 8, p3 16, p4 24, p5 32
//   search_acceleration  FXAA_SEARCH_ACCELERATION  [1..4]     p0 4, p1 3, p2 2, p3-p5 1
//   search_threshold     FXAA_SEARCH_THRESHOLD     [0..1]     1/4 in every preset
//   subpix_cap           FXAA_SUBPIX_CAP           [0..1]     p0 2/3, p1-p5 3/4
//   subpix_trim          FXAA_SUBPIX_TRIM          [0..0.99]  1/4 in every preset
//   subpix_faster        FXAA_SUBPIX_FASTER        [0..1]     p0 1, p1-p5 0
//   FXAA_SUBPIX is 1 in every preset and is not a knob; SUBPIX_TRIM_SCALE = 1/(1 − TRIM).
//   Lumas are in FxaaLuma units (0 .. 2.963), so the thresholds are too, as on the GPU.
//
// Debug views (whitepaper "Algorithm Overview", colours as the shader header draws them;
// pixels that take the early exit are drawn grey, lumaM / (1 + 0.587/0.299), in every view)
//   passthrough  edges red (1,0,0) blending to yellow (1,1,0) by blendL/CAP
//   horzvert     horizontal edges gold (1,0.75,0), vertical edges blue (0,0.5,1)
//   pair         paired with N/W blue (0,0,1), with S/E green (0,1,0)
//   negpos       negative end nearer red (1,0,0), else blue (0,0,1)
//   offset       −x red (1,0,0), +x blue (0,0,1), −y gold (1,0.6,0.2), +y skyblue (0.2,0.6,1),
//                mixed with the grey by |2·offset| (0 = grey, a full half-texel shift = pure
//                colour); no shift = grey
//
// Deviations from the GPU shader (all float32 unless said)
//   - Bilinear filtering uses the exact float32 fraction (BilinearSampler); hardware uses 8 bits
//     of sub-texel precision. This only touches the final shifted fetch: every search fetch
//     lies on a texel centre along the edge and halfway across it (fractions 0 and 0.5).
//   - Positions are kept in texel units (pixel centre x+0.5, y+0.5) instead of normalised
//     coordinates stepped by rcpFrame; all search positions are then exact half-integers.
//   - Luma is a separate multiply and add (the build uses -ffp-contract=off), where the
//     whitepaper notes one fused multiply-add; results differ by at most 1 ulp.
//   - Anisotropic fetch (SEARCH_ACCELERATION N > 1): the shader calls
//     FxaaTextureGrad(tex, pos, offNP) with max anisotropy 4, using anisotropic filtering
//     "as a box filter". Probe count and placement are implementation-defined in hardware;
//     we emulate the ideal box: the mean of N bilinear probes through the shared sampler at
//     pos + (k − (N−1)/2)·axis, k = 0..N−1. With the start offset (N+1)/2 and step N, the
//     probes land on texel centres along the edge, so one fetch averages exactly N texel
//     pairs and successive fetches tile the edge without gaps or overlap.
//   - Tap counting: every Texel/Sample call of the sampler is one tap, so one anisotropic
//     fetch counts N taps. It is one shader instruction, but the texture unit spends one
//     bilinear probe per texel pair it averages (anisotropic filtering costs extra filter
//     cycles), and counting probes keeps taps comparable with the unaccelerated presets,
//     whose reach costs the same number of pairs. Fxaa1Trace reports the instruction count
//     (fetches_n / fetches_p) separately. The shader's 4 corner fetches happen only after
//     the early exit, so an early-exit pixel costs 5 taps, an edge pixel
//     9 + search probes + 1 (the final fetch, issued even when the shift is 0).
//   - Division guards. rangeL/range: range = 0 passes the early exit only when both edge
//     thresholds are 0; the shader then divides 0/0 (NaN). A flat neighbourhood has no
//     sub-pixel aliasing, so blendL = 0 there. dstN + dstP: always >= 2·start >= 2 texels
//     (every search position is at least `start` away from the centre), so the shader
//     never divides by zero; the code still returns a zero shift if it were not positive.
//     Passthrough view blendL/CAP: CAP = 0 draws green 0.
//   - Debug views are computed from the full per-pixel trace, so their tap counts are those
//     of the normal output (the shader returns early at each view's stage).
//   - The offset view: the header lerps with FxaaLerp3(grey, colour, |o|), i.e. grey·|o| +
//     colour·(1−|o|), which draws tiny shifts fully saturated and the largest ones grey,
//     discontinuous with the grey of "no shift"; we mix grey·(1−|o|) + colour·|o|, which
//     matches the whitepaper's description (colour marks the direction of the shift).
#include "methods/fxaa1.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/params.h"
#include "methods/families.h"

namespace aalab {
namespace {

constexpr float kLumaGreen = kFxaa1LumaGreen;

struct Rgb {
  float r = 0, g = 0, b = 0;
};

Rgb ToRgb(const Float4& f) { return Rgb{f.r, f.g, f.b}; }
Rgb operator+(Rgb a, Rgb b) { return Rgb{a.r + b.r, a.g + b.g, a.b + b.b}; }
Rgb operator*(Rgb a, float s) { return Rgb{a.r * s, a.g * s, a.b * s}; }

// Step 1 — "Luminance Conversion": luma from red and green only,
// rgb.y * (0.587/0.299) + rgb.x (range 0 .. 2.963).
float FxaaLuma(const Rgb& c) { return c.g * kLumaGreen + c.r; }

// Step 2 — "Local Contrast Check": rangeMin/rangeMax over M, N, W, S, E in the shader's
// min/max nesting; early exit when range < max(EDGE_THRESHOLD_MIN, rangeMax·EDGE_THRESHOLD)
// (strict '<' as printed: a range equal to the threshold is processed).
bool LocalContrastExit(Fxaa1Trace& t, const Fxaa1Params& p) {
  const float range_min = std::min(t.luma_m, std::min(std::min(t.luma_n, t.luma_w), std::min(t.luma_s, t.luma_e)));
  t.range_max = std::max(t.luma_m, std::max(std::max(t.luma_n, t.luma_w), std::max(t.luma_s, t.luma_e)));
  t.range = t.range_max - range_min;
  return t.range < std::max(p.edge_threshold_min, t.range_max * p.edge_threshold);
}

// "Sub-pixel Aliasing Test": the ratio of pixel contrast |lumaL − lumaM| (lumaL = mean of
// N, W, E, S) to local contrast `range`, trimmed and capped:
//   blendL = min(CAP, max(0, rangeL/range − TRIM) · 1/(1 − TRIM)).
// Guard: range = 0 (only reachable with both edge thresholds 0) gives blendL = 0 instead of
// the shader's 0/0.
float SubpixBlend(const Fxaa1Trace& t, const Fxaa1Params& p) {
  const float luma_l = (t.luma_n + t.luma_w + t.luma_e + t.luma_s) * 0.25f;
  const float range_l = std::fabs(luma_l - t.luma_m);
  const float ratio = t.range > 0.0f ? range_l / t.range : 0.0f;
  const float trim_scale = 1.0f / (1.0f - p.subpix_trim);
  const float blend = std::max(0.0f, ratio - p.subpix_trim) * trim_scale;
  return std::min(p.subpix_cap, blend);
}

// The lowpass colour blended in at the end ("Sub-pixel Aliasing Test"): the box filter of
// the complete 3x3 neighbourhood, summed in the whitepaper's order
// (N + W + M + E + S) + (NW + NE + SW + SE), times 1/9. With FXAA_SUBPIX_FASTER (preset 0,
// "a lower quality sub-pixel aliasing removal filter") the 5-tap cross (N+W+E+S+M)·1/5.
Rgb Lowpass(const Rgb nb[3][3], bool faster) {
  const Rgb& n = nb[0][1];
  const Rgb& w = nb[1][0];
  const Rgb& m = nb[1][1];
  const Rgb& e = nb[1][2];
  const Rgb& s = nb[2][1];
  if (faster) return (n + w + e + s + m) * (1.0f / 5.0f);
  Rgb l = n + w + m + e + s;
  l = l + (nb[0][0] + nb[0][2] + nb[2][0] + nb[2][2]);
  return l * (1.0f / 9.0f);
}

// Step 3 — "Vertical/Horizontal Edge Test": weighted magnitudes of the row and column
// high-passes of the 3x3 lumas; horzSpan = edgeHorz >= edgeVert (ties are horizontal).
void EdgeOrientation(Fxaa1Trace& t, const float lu[3][3]) {
  const float nw = lu[0][0], n = lu[0][1], ne = lu[0][2];
  const float w = lu[1][0], m = lu[1][1], e = lu[1][2];
  const float sw = lu[2][0], s = lu[2][1], se = lu[2][2];
  t.edge_vert = std::fabs((0.25f * nw) + (-0.5f * n) + (0.25f * ne)) +
                std::fabs((0.50f * w) + (-1.0f * m) + (0.50f * e)) +
                std::fabs((0.25f * sw) + (-0.5f * s) + (0.25f * se));
  t.edge_horz = std::fabs((0.25f * nw) + (-0.5f * w) + (0.25f * sw)) +
                std::fabs((0.50f * n) + (-1.0f * m) + (0.50f * s)) +
                std::fabs((0.25f * ne) + (-0.5f * e) + (0.25f * se));
  t.horz_span = t.edge_horz >= t.edge_vert;
}

// Step 4 — "End-of-edge Search", first paragraph: pair the pixel with its highest-contrast
// neighbour 90° to the edge (N or S for a horizontal span, W or E for a vertical one);
// pairN = gradientN >= gradientS (ties pick N / W). Sets the pair's average luma (the
// search reference), the stop limit gradient·SEARCH_THRESHOLD, and returns the side of the
// pair as −1 (towards −y / −x) or +1: the shader's lengthSign in texel units.
float PairNeighbour(Fxaa1Trace& t, const Fxaa1Params& p) {
  const float luma_a = t.horz_span ? t.luma_n : t.luma_w;
  const float luma_b = t.horz_span ? t.luma_s : t.luma_e;
  const float gradient_a = std::fabs(luma_a - t.luma_m);
  const float gradient_b = std::fabs(luma_b - t.luma_m);
  t.pair_n = gradient_a >= gradient_b;
  t.luma_pair = t.pair_n ? (luma_a + t.luma_m) * 0.5f : (luma_b + t.luma_m) * 0.5f;
  t.gradient = (t.pair_n ? gradient_a : gradient_b) * p.search_threshold;
  return t.pair_n ? -1.0f : 1.0f;
}

// One search fetch at (u, v): SEARCH_ACCELERATION = 1 is a plain bilinear fetch
// (FxaaTexture); N > 1 emulates FxaaTextureGrad(tex, pos, offNP) with 4x anisotropic
// filtering used "as a box filter" over N texels along the edge: the mean of N bilinear
// probes at pos + (k − (N−1)/2)·axis. Every probe goes through the shared sampler and
// counts one tap.
Rgb SearchFetch(BilinearSampler& tex, float u, float v, float ax, float ay, int n) {
  if (n == 1) return ToRgb(tex.Sample(u, v));
  Rgb sum;
  for (int k = 0; k < n; ++k) {
    const float o = static_cast<float>(k) - static_cast<float>(n - 1) * 0.5f;
    sum = sum + ToRgb(tex.Sample(u + ax * o, v + ay * o));
  }
  const float nf = static_cast<float>(n);
  return Rgb{sum.r / nf, sum.g / nf, sum.b / nf};
}

// Step 5 — "End-of-edge Search" loop: from the line between M and its pair (half a texel
// towards the pair), search both directions along the edge in one loop until the average
// luma of the pair changes by >= gradient, or SEARCH_STEPS fetches. Start offset ±(N+1)/2
// texels (1, 1.5, 2, 2.5 for N = 1..4) and step N texels (the header's
// FXAA_SEARCH_ACCELERATION blocks). As in the loop printed in the whitepaper, a direction
// still searching after the last fetch has already advanced one more step.
void SearchEnds(Fxaa1Trace& t, BilinearSampler& tex, float cu, float cv, float side, const Fxaa1Params& p) {
  const float ax = t.horz_span ? 1.0f : 0.0f;
  const float ay = t.horz_span ? 0.0f : 1.0f;
  const int accel = p.search_acceleration;
  // posN: on the pixel boundary towards the pair.
  const float pu = cu + (t.horz_span ? 0.0f : side * 0.5f);
  const float pv = cv + (t.horz_span ? side * 0.5f : 0.0f);
  const float start = static_cast<float>(accel + 1) * 0.5f;
  const float step = static_cast<float>(accel);
  float nu = pu - ax * start, nv = pv - ay * start;
  float qu = pu + ax * start, qv = pv + ay * start;
  t.luma_end_n = t.luma_pair;
  t.luma_end_p = t.luma_pair;
  t.done_n = false;
  t.done_p = false;
  for (int i = 0; i < p.search_steps; ++i) {
    if (!t.done_n) {
      t.luma_end_n = FxaaLuma(SearchFetch(tex, nu, nv, ax, ay, accel));
      ++t.fetches_n;
    }
    if (!t.done_p) {
      t.luma_end_p = FxaaLuma(SearchFetch(tex, qu, qv, ax, ay, accel));
      ++t.fetches_p;
    }
    t.done_n = t.done_n || (std::fabs(t.luma_end_n - t.luma_pair) >= t.gradient);
    t.done_p = t.done_p || (std::fabs(t.luma_end_p - t.luma_pair) >= t.gradient);
    if (t.done_n && t.done_p) break;
    if (!t.done_n) {
      nu -= ax * step;
      nv -= ay * step;
    }
    if (!t.done_p) {
      qu += ax * step;
      qv += ay * step;
    }
  }
  t.dst_n = t.horz_span ? cu - nu : cv - nv;
  t.dst_p = t.horz_span ? qu - cu : qv - cv;
}

// Step 6 — sub-pixel shift: the nearer end (directionN = dstN < dstP; ties take P) decides.
// If lumaM and that end's luma lie on the same side of the pair average, the pixel is in
// the part of the span that gets no filtering (shift 0). Otherwise shift towards the pair by
// 0.5 − dst/(dstN + dstP): half a texel at the end, falling linearly to 0 at the middle.
float SubPixelShift(Fxaa1Trace& t, float side) {
  t.direction_n = t.dst_n < t.dst_p;
  const float luma_end = t.direction_n ? t.luma_end_n : t.luma_end_p;
  float length_sign = side;
  if (((t.luma_m - t.luma_pair) < 0.0f) == ((luma_end - t.luma_pair) < 0.0f)) length_sign = 0.0f;
  t.shifted = length_sign != 0.0f;
  const float span_length = t.dst_p + t.dst_n;
  const float dst = t.direction_n ? t.dst_n : t.dst_p;
  // Guard: span_length >= 2 by construction (see the header block); never divide by <= 0.
  if (!(span_length > 0.0f)) return 0.0f;
  return (0.5f + (dst * (-1.0f / span_length))) * length_sign;
}

// Step 8 — FxaaLerp3(rgbL, rgbF, blendL) in the shader's operation order:
// (−blendL·rgbF) + ((rgbL·blendL) + rgbF) = rgbF + blendL·(rgbL − rgbF).
float Lerp3(float a, float b, float amount_of_a) { return (-amount_of_a * b) + ((a * amount_of_a) + b); }

enum class View { kNormal, kPassthrough, kHorzVert, kPair, kNegPos, kOffset };

View ParseView(const std::string& name) {
  if (name.empty()) return View::kNormal;
  const auto& names = Fxaa1DebugViews();
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<View>(i + 1);
  }
  throw UserError("fxaa1: unknown debug view '" + name + "' (valid: " + JoinNames(names) + ")");
}

void CheckRange(const char* name, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi)) {
    throw UserError(std::string("fxaa1: parameter ") + name + "=" + FormatNumber(v) + " is out of range [" +
                    FormatNumber(lo) + ".." + FormatNumber(hi) + "]");
  }
}

// Debug colours (see the header block). `grey` is lumaO = lumaM / (1 + 0.587/0.299).
Rgb DebugColour(const Fxaa1Trace& t, View view, const Fxaa1Params& p) {
  const float grey = t.luma_m / (1.0f + kLumaGreen);
  const Rgb g{grey, grey, grey};
  if (t.early_exit) return g;
  switch (view) {
    case View::kPassthrough: return Rgb{1.0f, p.subpix_cap > 0.0f ? t.blend_l / p.subpix_cap : 0.0f, 0.0f};
    case View::kHorzVert: return t.horz_span ? Rgb{1.0f, 0.75f, 0.0f} : Rgb{0.0f, 0.5f, 1.0f};
    case View::kPair: return t.pair_n ? Rgb{0.0f, 0.0f, 1.0f} : Rgb{0.0f, 1.0f, 0.0f};
    case View::kNegPos: return t.direction_n ? Rgb{1.0f, 0.0f, 0.0f} : Rgb{0.0f, 0.0f, 1.0f};
    case View::kOffset: {
      if (t.offset == 0.0f) return g;
      const float amount = std::min(1.0f, std::fabs(t.offset) * 2.0f);
      Rgb c;
      if (!t.horz_span) {
        c = t.offset < 0.0f ? Rgb{1.0f, 0.0f, 0.0f} : Rgb{0.0f, 0.0f, 1.0f};
      } else {
        c = t.offset < 0.0f ? Rgb{1.0f, 0.6f, 0.2f} : Rgb{0.2f, 0.6f, 1.0f};
      }
      return Rgb{Lerp3(c.r, grey, amount), Lerp3(c.g, grey, amount), Lerp3(c.b, grey, amount)};
    }
    case View::kNormal: break;
  }
  throw InternalError("fxaa1: DebugColour called for the normal view");
}

}  // namespace

void Fxaa1CheckParams(const Fxaa1Params& p) {
  CheckRange("edge_threshold", p.edge_threshold, 0.0, 1.0);
  CheckRange("edge_threshold_min", p.edge_threshold_min, 0.0, 1.0);
  CheckRange("search_steps", p.search_steps, 1, 64);
  CheckRange("search_acceleration", p.search_acceleration, 1, 4);
  CheckRange("search_threshold", p.search_threshold, 0.0, 1.0);
  CheckRange("subpix_cap", p.subpix_cap, 0.0, 1.0);
  CheckRange("subpix_trim", p.subpix_trim, 0.0, 0.99);
}

Fxaa1Params Fxaa1Preset(int preset) {
  Fxaa1Params p;  // preset 3
  switch (preset) {
    case 0:
      p.edge_threshold = 1.0f / 4.0f;
      p.edge_threshold_min = 1.0f / 12.0f;
      p.search_steps = 2;
      p.search_acceleration = 4;
      p.subpix_cap = 2.0f / 3.0f;
      p.subpix_faster = true;
      return p;
    case 1:
      p.edge_threshold_min = 1.0f / 16.0f;
      p.search_steps = 4;
      p.search_acceleration = 3;
      return p;
    case 2:
      p.search_steps = 8;
      p.search_acceleration = 2;
      return p;
    case 3: return p;
    case 4: p.search_steps = 24; return p;
    case 5: p.search_steps = 32; return p;
    default: break;
  }
  throw UserError("fxaa1: unknown preset " + std::to_string(preset) + " (valid: 0..5)");
}

const std::vector<std::string>& Fxaa1DebugViews() {
  static const std::vector<std::string> views = {"passthrough", "horzvert", "pair", "negpos", "offset"};
  return views;
}

Fxaa1Trace Fxaa1TracePixel(BilinearSampler& tex, int x, int y, const Fxaa1Params& p) {
  Fxaa1Trace t;
  // Whitepaper "Local Contrast Check": N, W, M, E, S with integer texel offsets
  // (FxaaTextureOffset = exact texel reads, clamp-to-edge).
  Rgb nb[3][3];
  nb[0][1] = ToRgb(tex.Texel(x, y - 1));
  nb[1][0] = ToRgb(tex.Texel(x - 1, y));
  nb[1][1] = ToRgb(tex.Texel(x, y));
  nb[1][2] = ToRgb(tex.Texel(x + 1, y));
  nb[2][1] = ToRgb(tex.Texel(x, y + 1));
  t.luma_n = FxaaLuma(nb[0][1]);
  t.luma_w = FxaaLuma(nb[1][0]);
  t.luma_m = FxaaLuma(nb[1][1]);
  t.luma_e = FxaaLuma(nb[1][2]);
  t.luma_s = FxaaLuma(nb[2][1]);
  const Rgb& rgb_m = nb[1][1];
  if (LocalContrastExit(t, p)) {
    t.early_exit = true;
    t.rgb_out[0] = rgb_m.r;
    t.rgb_out[1] = rgb_m.g;
    t.rgb_out[2] = rgb_m.b;
    return t;
  }
  t.blend_l = SubpixBlend(t, p);

  // The corners, fetched after the early exit as in the whitepaper's listing.
  nb[0][0] = ToRgb(tex.Texel(x - 1, y - 1));
  nb[0][2] = ToRgb(tex.Texel(x + 1, y - 1));
  nb[2][0] = ToRgb(tex.Texel(x - 1, y + 1));
  nb[2][2] = ToRgb(tex.Texel(x + 1, y + 1));
  const Rgb rgb_l = Lowpass(nb, p.subpix_faster);
  t.rgb_l[0] = rgb_l.r;
  t.rgb_l[1] = rgb_l.g;
  t.rgb_l[2] = rgb_l.b;

  float lu[3][3];
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) lu[j][i] = FxaaLuma(nb[j][i]);
  }
  EdgeOrientation(t, lu);
  const float side = PairNeighbour(t, p);

  const float cu = static_cast<float>(x) + 0.5f;
  const float cv = static_cast<float>(y) + 0.5f;
  SearchEnds(t, tex, cu, cv, side, p);
  t.offset = SubPixelShift(t, side);

  // Step 7 — re-sample the input at the shifted position (one bilinear fetch).
  const Rgb rgb_f = ToRgb(tex.Sample(cu + (t.horz_span ? 0.0f : t.offset), cv + (t.horz_span ? t.offset : 0.0f)));
  t.rgb_f[0] = rgb_f.r;
  t.rgb_f[1] = rgb_f.g;
  t.rgb_f[2] = rgb_f.b;
  // Step 8 — blend the lowpass in by the sub-pixel amount.
  t.rgb_out[0] = Lerp3(rgb_l.r, rgb_f.r, t.blend_l);
  t.rgb_out[1] = Lerp3(rgb_l.g, rgb_f.g, t.blend_l);
  t.rgb_out[2] = Lerp3(rgb_l.b, rgb_f.b, t.blend_l);
  return t;
}

Image8 Fxaa1Reference(const Image8& in, const Fxaa1Params& p, const std::string& debug_view, PostStats* stats) {
  Fxaa1CheckParams(p);
  const View view = ParseView(debug_view);
  AALAB_CHECK(in.Channels() == 4, "fxaa1 needs an RGBA8 frame");
  Image8 out(in.Width(), in.Height(), 4, 255);
  if (in.Empty()) return out;

  const int height = in.Height();
  const int width = in.Width();
  constexpr int kGrain = 8;  // rows per chunk; chunking depends on the height alone
  std::vector<uint64_t> chunk_taps(static_cast<size_t>((height + kGrain - 1) / kGrain), 0);
  ParallelForChunks(height, kGrain, [&](int y0, int y1) {
    BilinearSampler tex(in, SubTexel::kExact, p.sampler);
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < width; ++x) {
        const Fxaa1Trace t = Fxaa1TracePixel(tex, x, y, p);
        uint8_t* o = out.Pixel(x, y);
        if (view == View::kNormal) {
          if (t.early_exit) {
            // FxaaFilterReturn(rgbM): the input texel, untouched.
            const uint8_t* src = in.Pixel(x, y);
            o[0] = src[0];
            o[1] = src[1];
            o[2] = src[2];
          } else {
            o[0] = QuantizeUnorm8(t.rgb_out[0]);
            o[1] = QuantizeUnorm8(t.rgb_out[1]);
            o[2] = QuantizeUnorm8(t.rgb_out[2]);
          }
        } else {
          const Rgb c = DebugColour(t, view, p);
          o[0] = QuantizeUnorm8(c.r);
          o[1] = QuantizeUnorm8(c.g);
          o[2] = QuantizeUnorm8(c.b);
        }
        o[3] = 255;
      }
    }
    chunk_taps[static_cast<size_t>(y0 / kGrain)] = tex.Taps();
  });
  if (stats != nullptr) {
    for (uint64_t taps : chunk_taps) stats->taps += taps;  // chunk order
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// Registry rows: fxaa1-p0 .. fxaa1-p5.

namespace {

std::vector<ParamDef> Fxaa1ParamDefs(const Fxaa1Params& d) {
  return {
      FloatParam("edge_threshold", d.edge_threshold, 0.0, 1.0,
                 "FXAA_EDGE_THRESHOLD: skip pixels whose local luma range < this x local max luma"),
      FloatParam("edge_threshold_min", d.edge_threshold_min, 0.0, 1.0,
                 "FXAA_EDGE_THRESHOLD_MIN: floor of the contrast threshold (skips darks), luma units"),
      IntParam("search_steps", d.search_steps, 1, 64, "FXAA_SEARCH_STEPS: end-of-edge search fetches per direction"),
      IntParam("search_acceleration", d.search_acceleration, 1, 4,
               "FXAA_SEARCH_ACCELERATION: texel pairs per search fetch (anisotropic box filter)"),
      FloatParam("search_threshold", d.search_threshold, 0.0, 1.0,
                 "FXAA_SEARCH_THRESHOLD: end of edge when the pair luma changes by this x gradient"),
      FloatParam("subpix_cap", d.subpix_cap, 0.0, 1.0,
                 "FXAA_SUBPIX_CAP: most lowpass blended in for sub-pixel aliasing"),
      FloatParam("subpix_trim", d.subpix_trim, 0.0, 0.99,
                 "FXAA_SUBPIX_TRIM: sub-pixel contrast ratio below which no lowpass is blended"),
      IntParam("subpix_faster", d.subpix_faster ? 1 : 0, 0, 1,
               "FXAA_SUBPIX_FASTER: 1 = 5-tap cross lowpass (preset 0), 0 = 3x3 box"),
  };
}

Fxaa1Params ParamsFromValues(const ParamValues& v) {
  Fxaa1Params p;
  p.edge_threshold = static_cast<float>(v.Number("edge_threshold"));
  p.edge_threshold_min = static_cast<float>(v.Number("edge_threshold_min"));
  p.search_steps = v.Int("search_steps");
  p.search_acceleration = v.Int("search_acceleration");
  p.search_threshold = static_cast<float>(v.Number("search_threshold"));
  p.subpix_cap = static_cast<float>(v.Number("subpix_cap"));
  p.subpix_trim = static_cast<float>(v.Number("subpix_trim"));
  p.subpix_faster = v.Int("subpix_faster") != 0;
  return p;
}

// Preset defaults as the exact fractions of the whitepaper (double), so listings print
// 0.041666666666666664 for 1/24 rather than the float rounding.
std::vector<ParamDef> PresetDefs(int preset) {
  std::vector<ParamDef> defs = Fxaa1ParamDefs(Fxaa1Preset(preset));
  auto set = [&defs](const std::string& name, double v) {
    for (auto& d : defs) {
      if (d.name == name) d.default_number = v;
    }
  };
  set("edge_threshold", preset == 0 ? 1.0 / 4.0 : 1.0 / 8.0);
  set("edge_threshold_min", preset == 0 ? 1.0 / 12.0 : preset == 1 ? 1.0 / 16.0 : 1.0 / 24.0);
  set("search_threshold", 1.0 / 4.0);
  set("subpix_cap", preset == 0 ? 2.0 / 3.0 : 3.0 / 4.0);
  set("subpix_trim", 1.0 / 4.0);
  return defs;
}

MethodEntry Fxaa1Entry(int preset, const std::string& help, bool in_default_list = false) {
  const std::string name = "fxaa1-p" + std::to_string(preset);
  MethodEntry entry{name, help, PresetDefs(preset), [name](const ParamValues& v) {
                      const Fxaa1Params params = ParamsFromValues(v);
                      MethodPlan plan;
                      plan.name = name;
                      plan.params = v;
                      plan.render = RenderSpec{};  // 1x centre samples
                      plan.post = [params](const Image8& in, const PostOptions& options, PostStats* stats) {
                        Fxaa1Params p = params;
                        p.sampler = options.sampler;
                        return Fxaa1(in, p, options.debug_view, stats);
                      };
                      plan.post_reference = [params](const Image8& in, const PostOptions& options, PostStats* stats) {
                        Fxaa1Params p = params;
                        p.sampler = options.sampler;
                        return Fxaa1Reference(in, p, options.debug_view, stats);
                      };
                      plan.config = params;
                      plan.debug_views = Fxaa1DebugViews();
                      return plan;
                    }};
  entry.in_default_list = in_default_list;
  return entry;
}

}  // namespace

std::vector<MethodEntry> Fxaa1Methods() {
  return {
      Fxaa1Entry(0, "FXAA 1.0 preset 0: fastest; 2 search steps of 4 texels, cross lowpass"),
      Fxaa1Entry(1, "FXAA 1.0 preset 1: 4 search steps of 3 texels, 3x3 lowpass"),
      Fxaa1Entry(2, "FXAA 1.0 preset 2: 8 search steps of 2 texels (some search dithering)"),
      Fxaa1Entry(3, "FXAA 1.0 preset 3 (default): 16 single-texel search steps", /*in_default_list=*/true),
      Fxaa1Entry(4, "FXAA 1.0 preset 4: 24 single-texel search steps"),
      Fxaa1Entry(5, "FXAA 1.0 preset 5 (shader header): 32 single-texel search steps"),
  };
}

}  // namespace aalab
