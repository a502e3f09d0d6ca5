// Property tests: invariants every method and metric must keep, on inputs built to probe them.
//
//  * FXAA (every FXAA 1.0 and 3.11 method in the registry) leaves a constant image unchanged.
//  * FXAA commutes with transposing the image, except at orientation ties (see the rule
//    below), and the pixels that differ are exactly explained by the rule.
//  * SSAA of a scene without edges or texture equals `none` up to 8-bit quantisation.
//  * The symmetric metrics (PSNR, MSE, SSIM, edge/interior PSNR, |error| percentiles) are
//    symmetric bit for bit.
//
// The transpose rule. Transposing swaps x and y: N <-> W, S <-> E, NE <-> SW. Every FXAA
// decision maps onto its transposed counterpart except one:
//   * horzSpan = edgeHorz >= edgeVert. Transposition swaps edgeHorz and edgeVert, so on a tie
//     (equal values) both images pick "horizontal" and the pixel is filtered along x in one
//     and along y in the other. This is the only tie-break that is not symmetric.
//   * The pair choice (gradientN >= gradientS, N/W on a tie) and the nearer end
//     (dstN < dstP, P on a tie) ARE symmetric: N (-y) maps to W (-x), both the "negative"
//     side, and the search runs towards -x / -y in both images.
//   * Float evaluation order: FXAA 1.0 evaluates edgeHorz of the transposed image with exactly
//     the operations of edgeVert of the original (bit-identical, tested). FXAA 3.11 sums the
//     same nine lumas in another association in the two orientations
//     (|H3| + (2|H1| + |H2|) vs |V3| + (2|V1| + |V2|) with H3' = V2, H2' = V3), so values
//     that tie in exact arithmetic may round apart differently: a tie is therefore "equal to
//     within float rounding", |edgeHorz − edgeVert| <= kTieEpsilon, evaluated exactly.
//   * Other sums in another order (FXAA 1.0's 3x3 lowpass and lumaL, FXAA 3.11's subpixA
//     and the bilinear weights of a tap whose two fractions are both non-zero) change the
//     unquantised colour by a few ulps. Such a difference can change the 8-bit output only
//     where the colour lies within float rounding of a rounding boundary (k + 0.5)/255;
//     FXAA 1.0's trace shows the unquantised colour, so those pixels are identified exactly.
//   * FXAA 3.11's end-of-edge test |lumaEnd| >= gradient/4 (and the sign of the nearer end's
//     lumaEnd) compares a bilinear tap whose value can differ by ulps between the orientations
//     (the four weights are summed in another order once both fractions are non-zero, which
//     normalised coordinates of non-power-of-two sizes make common): a pixel whose exact tap
//     value ties the threshold may stop its search at different steps. An exact model of the
//     shader's decisions (Fxaa311Oracle) finds those ties.
// So the rule tested: the outputs agree at every pixel, except possibly where an orientation
// tie, an end-of-edge tie (3.11) or a rounding-boundary tie occurs; the counts are printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/sampler.h"
#include "methods/fxaa1.h"
#include "methods/fxaa311.h"
#include "methods/registry.h"
#include "metrics/metrics.h"
#include "scenes/render.h"
#include "scenes/scene.h"
#include "scenes/tracer.h"

namespace aalab {
namespace {

// ---------------------------------------------------------------------------------------
// Helpers.

Image8 Solid(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
  Image8 img(w, h, 4, 255);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.Pixel(x, y);
      p[0] = r;
      p[1] = g;
      p[2] = b;
    }
  }
  return img;
}

Image8 Transpose(const Image8& in) {
  Image8 out(in.Height(), in.Width(), in.Channels());
  for (int y = 0; y < in.Height(); ++y) {
    for (int x = 0; x < in.Width(); ++x) {
      for (int c = 0; c < in.Channels(); ++c) out.At(y, x, c) = in.At(x, y, c);
    }
  }
  return out;
}

/// Deterministic 64-bit LCG (no std:: distributions: their output is implementation-defined).
struct Rng {
  uint64_t s;
  explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ULL + 1) {}
  uint32_t Next() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<uint32_t>(s >> 33);
  }
  int Below(int n) { return static_cast<int>(Next() % static_cast<uint32_t>(n)); }
};

/// Test images: i.i.d. noise, random axis-aligned and slanted shapes with random colours
/// (long edges, corners, thin lines), and a smooth gradient with sparse speckles.
Image8 TestImage(int kind, int w, int h, uint64_t seed) {
  Rng rng(seed);
  Image8 img(w, h, 4, 255);
  if (kind == 0) {
    for (auto& v : img.Data()) v = static_cast<uint8_t>(rng.Below(256));
    for (size_t i = 3; i < img.Data().size(); i += 4) img.Data()[i] = 255;
    return img;
  }
  if (kind == 1) {
    img = Solid(w, h, static_cast<uint8_t>(rng.Below(256)), static_cast<uint8_t>(rng.Below(256)),
                static_cast<uint8_t>(rng.Below(256)));
    for (int k = 0; k < 12; ++k) {
      const uint8_t r = static_cast<uint8_t>(rng.Below(256)), g = static_cast<uint8_t>(rng.Below(256)),
                    b = static_cast<uint8_t>(rng.Below(256));
      // A half-plane a·x + b·y < c with a random slope, clipped to a random box.
      const int x0 = rng.Below(w), y0 = rng.Below(h), x1 = x0 + 1 + rng.Below(w), y1 = y0 + 1 + rng.Below(h);
      const double a = rng.Below(2001) - 1000.0, bb = rng.Below(2001) - 1000.0;
      const double c = a * (x0 + x1) * 0.5 + bb * (y0 + y1) * 0.5;
      for (int y = y0; y < std::min(y1, h); ++y) {
        for (int x = x0; x < std::min(x1, w); ++x) {
          if (a * (x + 0.5) + bb * (y + 0.5) < c) {
            uint8_t* p = img.Pixel(x, y);
            p[0] = r;
            p[1] = g;
            p[2] = b;
          }
        }
      }
    }
    return img;
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.Pixel(x, y);
      p[0] = static_cast<uint8_t>((x * 255) / std::max(1, w - 1));
      p[1] = static_cast<uint8_t>((y * 255) / std::max(1, h - 1));
      p[2] = static_cast<uint8_t>(((x + y) * 127) / std::max(1, w + h - 2));
      if (rng.Below(9) == 0) {
        p[0] = static_cast<uint8_t>(rng.Below(256));
        p[1] = static_cast<uint8_t>(rng.Below(256));
      }
    }
  }
  return img;
}

/// The edge-threshold parameters of registry row `name` (those named *threshold, the search
/// threshold excepted), from its parameter table.
std::vector<std::string> ThresholdParams(const std::string& name) {
  std::vector<std::string> out;
  for (const auto& e : MethodRegistry()) {
    if (e.name != name) continue;
    for (const auto& def : e.params) {
      if (def.name.find("threshold") != std::string::npos && def.name != "search_threshold") out.push_back(def.name);
    }
  }
  return out;
}

std::vector<std::string> PostOnlyMethods() {
  std::vector<std::string> names;
  for (const auto& e : MethodRegistry()) {
    if (MakeMethod(e.name).IsPostOnly()) names.push_back(e.name);
  }
  return names;
}

// ---------------------------------------------------------------------------------------
// Constant images.

TEST(FxaaInvariants, EveryPostFilterIsTheIdentityOnAConstantImage) {
  const auto names = PostOnlyMethods();
  std::map<std::string, int> per_family;  // the registry's family of each post filter
  for (const auto& n : names) ++per_family[MakeMethod(n).family];
  EXPECT_EQ(per_family["fxaa1"], 6);     // fxaa1-p0 .. p5
  EXPECT_GE(per_family["fxaa311"], 21);  // 17 quality presets, tutorial low/medium/high, iter12
  EXPECT_EQ(per_family["smaa"], 4);      // smaa-low .. smaa-ultra
  EXPECT_EQ(per_family["cmaa2"], 4);     // cmaa2-low .. cmaa2-ultra: skipped below, see there
  const std::vector<std::array<uint8_t, 3>> colours = {{0, 0, 0},     {255, 255, 255}, {128, 128, 128},
                                                       {12, 200, 77}, {1, 254, 3},     {255, 0, 255}};
  const std::vector<std::pair<int, int>> sizes = {{1, 1}, {2, 2}, {1, 9}, {9, 1}, {3, 3}, {13, 7}};
  for (const auto& n : names) {
    // CMAA2 is not the identity on a flat frame, on purpose: its shader reads 0 outside the
    // frame (D3D's out-of-bounds load), so the border is an edge against black and the four
    // corners darken, as on a GPU (docs/cmaa2.md "Outside the frame";
    // Cmaa2.FlatFrameChangesOnlyTheCornersAgainstTheBlackOutside checks exactly that).
    if (MakeMethod(n).family == "cmaa2") continue;
    // Defaults, and with the edge thresholds 0 where the filter has them, so that no pixel
    // takes the early exit (FXAA: edge_threshold and edge_threshold_min; SMAA: threshold 0
    // marks every pixel's left and top edges).
    std::string zero;
    for (const auto& def : ThresholdParams(n)) zero += (zero.empty() ? ":" : ",") + def + "=0";
    for (const std::string& spec : {n, n + zero}) {
      const MethodPlan plan = MakeMethod(spec);
      for (const auto& c : colours) {
        for (const auto& [w, h] : sizes) {
          const Image8 in = Solid(w, h, c[0], c[1], c[2]);
          const Image8 out = plan.post(in, PostOptions{}, nullptr);
          EXPECT_TRUE(out == in) << spec << " " << w << "x" << h << " colour " << int(c[0]) << "," << int(c[1]) << ","
                                 << int(c[2]);
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// Transposition: FXAA 1.0, classified with the per-pixel trace.

struct TransposeCount {
  int pixels = 0, processed = 0, ties = 0, differ = 0, differ_at_ties = 0, differ_by_rounding = 0;
};

/// True when some channel of `a` and `b` (float colours within float rounding of each
/// other) quantises to different 8-bit codes: a rounding-boundary tie.
bool RoundingTie(const float* a, const float* b, const uint8_t* qa, const uint8_t* qb) {
  bool any = false;
  for (int c = 0; c < 3; ++c) {
    if (qa[c] == qb[c]) continue;
    if (std::fabs(a[c] - b[c]) > 1e-5f) return false;
    any = true;
  }
  return any;
}

TransposeCount CheckFxaa1Transpose(const Image8& img, const Fxaa1Params& p, const std::string& where) {
  TransposeCount n;
  const Image8 t_img = Transpose(img);
  const Image8 out = Transpose(Fxaa1(img, p, "", nullptr));
  const Image8 t_out = Fxaa1(t_img, p, "", nullptr);
  BilinearSampler ta(img), tb(t_img);
  for (int y = 0; y < img.Height(); ++y) {
    for (int x = 0; x < img.Width(); ++x) {
      ++n.pixels;
      const Fxaa1Trace a = Fxaa1TracePixel(ta, x, y, p);
      const Fxaa1Trace b = Fxaa1TracePixel(tb, y, x, p);
      const std::string at = where + " pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
      EXPECT_EQ(a.early_exit, b.early_exit) << at;
      const bool differ = !(out.At(y, x, 0) == t_out.At(y, x, 0) && out.At(y, x, 1) == t_out.At(y, x, 1) &&
                            out.At(y, x, 2) == t_out.At(y, x, 2));
      n.differ += differ;
      if (a.early_exit) {
        EXPECT_FALSE(differ) << at;
        continue;
      }
      ++n.processed;
      // The orientation measures swap bit for bit (same operations in the same order).
      EXPECT_EQ(a.edge_horz, b.edge_vert) << at;
      EXPECT_EQ(a.edge_vert, b.edge_horz) << at;
      const bool tie = a.edge_horz == a.edge_vert;
      n.ties += tie;
      if (tie) {
        // Both pick "horizontal": the documented asymmetric tie-break.
        EXPECT_TRUE(a.horz_span && b.horz_span) << at;
        n.differ_at_ties += differ;
        continue;
      }
      // Away from ties every decision maps onto its transposed counterpart exactly.
      EXPECT_NE(a.horz_span, b.horz_span) << at;
      EXPECT_EQ(a.pair_n, b.pair_n) << at;
      EXPECT_EQ(a.luma_pair, b.luma_pair) << at;
      EXPECT_EQ(a.done_n, b.done_n) << at;
      EXPECT_EQ(a.done_p, b.done_p) << at;
      EXPECT_EQ(a.dst_n, b.dst_n) << at;
      EXPECT_EQ(a.dst_p, b.dst_p) << at;
      EXPECT_EQ(a.direction_n, b.direction_n) << at;
      EXPECT_EQ(a.offset, b.offset) << at;
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(a.rgb_f[c], b.rgb_f[c]) << at;  // the shifted fetch is bit-identical
        EXPECT_NEAR(a.rgb_out[c], b.rgb_out[c], 1e-6f) << at;
      }
      if (differ) {
        // Only a rounding boundary can make the outputs differ here.
        const bool rounding = RoundingTie(a.rgb_out, b.rgb_out, out.Pixel(y, x), t_out.Pixel(y, x));
        EXPECT_TRUE(rounding) << at << " differs without a tie";
        n.differ_by_rounding += rounding;
      }
    }
  }
  return n;
}

TEST(FxaaInvariants, Fxaa1CommutesWithTransposeExceptAtOrientationTies) {
  TransposeCount total;
  for (int preset = 0; preset <= 5; ++preset) {
    const Fxaa1Params p = Fxaa1Preset(preset);
    for (int kind = 0; kind < 3; ++kind) {
      for (const auto& [w, h] : std::vector<std::pair<int, int>>{{29, 17}, {16, 16}, {1, 12}, {40, 3}}) {
        const Image8 img = TestImage(kind, w, h, 1000 + 10 * kind + w);
        const std::string where = "fxaa1-p" + std::to_string(preset) + " kind " + std::to_string(kind) + " " +
                                  std::to_string(w) + "x" + std::to_string(h);
        const TransposeCount n = CheckFxaa1Transpose(img, p, where);
        total.pixels += n.pixels;
        total.processed += n.processed;
        total.ties += n.ties;
        total.differ += n.differ;
        total.differ_at_ties += n.differ_at_ties;
        total.differ_by_rounding += n.differ_by_rounding;
      }
    }
  }
  // Every differing pixel is explained: an orientation tie or a rounding boundary.
  EXPECT_EQ(total.differ, total.differ_at_ties + total.differ_by_rounding);
  // The rule is not vacuous on these images: ties happen and some of them do differ.
  EXPECT_GT(total.ties, 0);
  EXPECT_GT(total.differ_at_ties, 0);
  std::printf(
      "fxaa1 transpose: %d pixels, %d processed, %d orientation ties, %d differ (%d at ties, %d at "
      "rounding boundaries)\n",
      total.pixels, total.processed, total.ties, total.differ, total.differ_at_ties, total.differ_by_rounding);
}

// ---------------------------------------------------------------------------------------
// Transposition: FXAA 3.11, classified by an exact model of the shader's decisions.

/// FXAA 3.11 Quality for one pixel in exact arithmetic (double; texel-unit positions at
/// their ideal values), recording every comparison whose two sides are equal to within float
/// rounding. It follows ShadePixel (methods/fxaa311.cpp) decision by decision; the float
/// implementation must agree with it wherever no comparison is near a tie (checked below),
/// which also makes it an independent double-precision cross-check of the filter.
struct Fxaa311Model {
  // Transposition-relevant ties (the two orientations may break them differently).
  bool orientation_tie = false;  ///< |edgeHorz - edgeVert| within rounding
  bool end_tie = false;          ///< an end-of-edge test |lumaEnd| >= gradient/4 within rounding
  bool span_sign_tie = false;    ///< the nearer end's lumaEnd within rounding of 0 (goodSpan)
  bool rounding_tie = false;     ///< an output channel within rounding of (k + 0.5)/255
  // Ties that both orientations evaluate on bit-identical floats: no transposition effect,
  // but the float implementation may break them unlike the model.
  bool other_tie = false;
  bool copied = false;        ///< early exit or zero range: the input pixel
  double rgb[3] = {0, 0, 0};  ///< unquantised output (when !copied)
};

constexpr double kTieEpsilon = 1e-5;  // luma units; float rounding of the shader's sums is < 4e-6

class Fxaa311Oracle {
 public:
  Fxaa311Oracle(const Image8& img, const MethodPlan& plan, std::vector<float> steps)
      : img_(img), w_(img.Width()), h_(img.Height()), steps_(std::move(steps)) {
    luma_ = ParseFxaa311Luma(plan.params.Choice("luma"));
    subpix_ = static_cast<float>(plan.params.Number("subpix"));
    thr_ = static_cast<float>(plan.params.Number("edge_threshold"));
    thr_min_ = static_cast<float>(plan.params.Number("edge_threshold_min"));
    // Texel lumas exactly as the shader reads them at texel centres (the luma pre-pass).
    const Image8 lf = Fxaa311LumaFrame(img, luma_);
    BilinearSampler tex(lf);
    lumas_.resize(static_cast<size_t>(w_) * h_);
    for (int y = 0; y < h_; ++y) {
      for (int x = 0; x < w_; ++x) lumas_[Index(x, y)] = Fxaa311TapLuma(tex.Texel(x, y), luma_);
    }
  }

  Fxaa311Model Pixel(int x, int y) const {
    Fxaa311Model r;
    auto near = [](double a, double b) { return std::fabs(a - b) <= kTieEpsilon; };
    const double M = L(x, y), N0 = L(x, y - 1), S0 = L(x, y + 1), W = L(x - 1, y), E = L(x + 1, y);
    const double NW = L(x - 1, y - 1), NE = L(x + 1, y - 1), SW = L(x - 1, y + 1), SE = L(x + 1, y + 1);
    const double range_max = std::max({M, N0, S0, W, E}), range_min = std::min({M, N0, S0, W, E});
    const double range = range_max - range_min;
    const double limit = std::max(static_cast<double>(thr_min_), range_max * static_cast<double>(thr_));
    r.other_tie |= near(range, limit);
    if (range < limit || range == 0.0) {
      r.copied = true;
      return r;
    }
    const double eh = std::fabs(-2 * W + NW + SW) + 2 * std::fabs(-2 * M + N0 + S0) + std::fabs(-2 * E + NE + SE);
    const double ev = std::fabs(-2 * N0 + NW + NE) + 2 * std::fabs(-2 * M + W + E) + std::fabs(-2 * S0 + SW + SE);
    r.orientation_tie = near(eh, ev);
    const bool horz = eh >= ev;
    const double N = horz ? N0 : W, S = horz ? S0 : E;
    const double subpix_b = (2 * (N0 + S0 + W + E) + (NW + SW + NE + SE)) / 12.0 - M;
    const double gn = N - M, gs = S - M;
    r.other_tie |= near(std::fabs(gn), std::fabs(gs));
    const bool pair_n = std::fabs(gn) >= std::fabs(gs);
    const double gradient_scaled = std::max(std::fabs(gn), std::fabs(gs)) / 4.0;
    const double sign = pair_n ? -1.0 : 1.0;
    const double half_nn = (pair_n ? N + M : S + M) * 0.5;
    const double luma_mm = M - half_nn;
    r.other_tie |= near(luma_mm, 0.0);
    const double subpix_c = std::clamp(std::fabs(subpix_b) / range, 0.0, 1.0);
    // Texel-unit positions: `along` the edge (x for a horizontal span), `across` it.
    const double c_along = (horz ? x : y) + 0.5;
    const double across = (horz ? y : x) + 0.5 + sign * 0.5;
    auto end_luma = [&](double along) { return Tap(horz, along, across) - half_nn; };
    const std::vector<float>& P = steps_;
    double n = c_along - P[0], p = c_along + P[0];
    double end_n = end_luma(n), end_p = end_luma(p);
    auto done = [&](double end) {
      r.end_tie |= near(std::fabs(end), gradient_scaled);
      return std::fabs(end) >= gradient_scaled;
    };
    bool done_n = done(end_n), done_p = done(end_p);
    if (!done_n) n -= P[1];
    if (!done_p) p += P[1];
    for (size_t k = 2; k < P.size() && (!done_n || !done_p); ++k) {
      if (!done_n) end_n = end_luma(n);
      if (!done_p) end_p = end_luma(p);
      done_n = done(end_n);
      done_p = done(end_p);
      if (!done_n) n -= P[k];
      if (!done_p) p += P[k];
    }
    const double dst_n = c_along - n, dst_p = p - c_along;
    const bool direction_n = dst_n < dst_p;
    const double end = direction_n ? end_n : end_p;
    r.span_sign_tie = near(end, 0.0);
    const bool good_span = (end < 0.0) != (luma_mm < 0.0);
    const double subpix_f = (-2 * subpix_c + 3) * subpix_c * subpix_c;
    const double subpix_h = subpix_f * subpix_f * static_cast<double>(subpix_);
    const double offset = -std::min(dst_n, dst_p) / (dst_n + dst_p) + 0.5;
    const double shift = std::max(good_span ? offset : 0.0, subpix_h) * sign;
    const double fu = horz ? x + 0.5 : x + 0.5 + shift;
    const double fv = horz ? y + 0.5 + shift : y + 0.5;
    Bilinear(fu, fv, r.rgb);
    for (double v : r.rgb) {
      const double code = v * 255.0;
      r.rounding_tie |= std::fabs(code - std::floor(code) - 0.5) <= 2e-3;
    }
    return r;
  }

 private:
  size_t Index(int x, int y) const { return static_cast<size_t>(y) * w_ + x; }
  double L(int x, int y) const { return lumas_[Index(std::clamp(x, 0, w_ - 1), std::clamp(y, 0, h_ - 1))]; }
  /// Exact bilinear weights at texel-space (u, v), clamp-to-edge, as BilinearSampler.
  template <typename F>
  void Weights(double u, double v, F&& f) const {
    const double xf = u - 0.5, yf = v - 0.5;
    const double x0 = std::floor(xf), y0 = std::floor(yf);
    const double fx = xf - x0, fy = yf - y0;
    const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
    f(ix, iy, (1 - fx) * (1 - fy));
    f(ix + 1, iy, fx * (1 - fy));
    f(ix, iy + 1, (1 - fx) * fy);
    f(ix + 1, iy + 1, fx * fy);
  }
  /// A search tap's luma: the bilinear blend of the texel lumas (alpha lumas are filtered as
  /// stored; rgb lumas are linear in the filtered rgb, so the blend of texel lumas is exact).
  double Tap(bool horz, double along, double across) const {
    const double u = horz ? along : across, v = horz ? across : along;
    double sum = 0;
    Weights(u, v, [&](int x, int y, double wgt) { sum += wgt * L(x, y); });
    return sum;
  }
  void Bilinear(double u, double v, double* rgb) const {
    rgb[0] = rgb[1] = rgb[2] = 0;
    Weights(u, v, [&](int x, int y, double wgt) {
      const uint8_t* p = img_.Pixel(std::clamp(x, 0, w_ - 1), std::clamp(y, 0, h_ - 1));
      for (int c = 0; c < 3; ++c) rgb[c] += wgt * (p[c] / 255.0);
    });
  }

  const Image8& img_;
  int w_, h_;
  std::vector<float> steps_;
  Fxaa311Params::Luma luma_;
  float subpix_, thr_, thr_min_;
  std::vector<float> lumas_;
};

TEST(FxaaInvariants, Fxaa311CommutesWithTransposeExceptAtTies) {
  int methods = 0;
  struct {
    int pixels = 0, orientation = 0, end = 0, span_sign = 0, rounding = 0, differ = 0;
    int differ_orientation = 0, differ_search = 0, differ_rounding = 0, checked = 0;
  } n;
  for (const auto& name : PostOnlyMethods()) {
    // FXAA 3.11 rows only (by their typed configuration). SMAA: only its orthogonal part
    // commutes with transposition (its diagonal weights go to the top-edge slots only);
    // tests/methods/smaa_test.cpp checks that part.
    const MethodPlan plan = MakeMethod(name);
    const Fxaa311Params* config = plan.Config<Fxaa311Params>();
    if (config == nullptr) continue;
    ++methods;
    for (int kind = 0; kind < 3; ++kind) {
      for (const auto& [w, h] : std::vector<std::pair<int, int>>{{29, 17}, {16, 16}, {1, 12}, {40, 3}}) {
        const Image8 img = TestImage(kind, w, h, 2000 + 10 * kind + w);
        const Image8 direct = plan.post(img, PostOptions{}, nullptr);
        const Image8 t_out = plan.post(Transpose(img), PostOptions{}, nullptr);
        const Fxaa311Oracle oracle(img, plan, config->steps);
        for (int y = 0; y < h; ++y) {
          for (int x = 0; x < w; ++x) {
            const std::string at = name + " kind " + std::to_string(kind) + " " + std::to_string(w) + "x" +
                                   std::to_string(h) + " pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
            ++n.pixels;
            const Fxaa311Model m = oracle.Pixel(x, y);
            const uint8_t* a = direct.Pixel(x, y);
            const uint8_t* b = t_out.Pixel(y, x);
            const bool differ = a[0] != b[0] || a[1] != b[1] || a[2] != b[2];
            n.orientation += m.orientation_tie;
            n.end += m.end_tie;
            n.span_sign += m.span_sign_tie;
            n.rounding += m.rounding_tie;
            n.differ += differ;
            // The model agrees with the implementation wherever it is not at any tie.
            if (!m.orientation_tie && !m.end_tie && !m.span_sign_tie && !m.rounding_tie && !m.other_tie) {
              ++n.checked;
              for (int c = 0; c < 3; ++c) {
                const double want = m.copied ? img.At(x, y, c) : m.rgb[c] * 255.0;
                EXPECT_NEAR(a[c], want, m.copied ? 0.0 : 0.5) << at << " channel " << c;
              }
            }
            if (!differ) continue;
            if (m.orientation_tie) {
              ++n.differ_orientation;
            } else if (m.end_tie || m.span_sign_tie) {
              ++n.differ_search;
            } else if (m.rounding_tie) {
              ++n.differ_rounding;
            } else {
              ADD_FAILURE() << at << " differs from the transposed image's result without a tie";
            }
          }
        }
      }
    }
  }
  EXPECT_GE(methods, 21);
  EXPECT_GT(n.differ_orientation, 0);
  EXPECT_GT(n.checked, n.pixels / 2);
  std::printf(
      "fxaa311 transpose: %d methods, %d pixels; ties: %d orientation, %d end-of-edge, %d span sign, "
      "%d rounding; %d differ (%d at orientation ties, %d at search ties, %d at rounding ties); model "
      "checked on %d tie-free pixels\n",
      methods, n.pixels, n.orientation, n.end, n.span_sign, n.rounding, n.differ, n.differ_orientation, n.differ_search,
      n.differ_rounding, n.checked);
}

// ---------------------------------------------------------------------------------------
// SSAA without edges or texture equals `none` up to quantisation.

/// A frame-filling quad (orthographic camera: every ray is parallel) with `materials`,
/// `effects` and optional lights.
Scene FlatScene(const std::string& effects, const std::string& material, const std::string& extra) {
  return ParseScene(
      R"({"name": "flat", "effects": )" + effects +
          R"(, "camera": {"type": "orthographic", "position": [0,0,10], "look_at": [0,0,0], "height": 4},)"
          R"( "materials": {"m": )" +
          material + R"(}, "objects": [{"shape": "quad", "size": [100,100], "material": "m"}])" + extra + "}",
      "flat.json", ".");
}

std::vector<std::string> SupersamplingMethods() {
  std::vector<std::string> names;
  for (const auto& e : MethodRegistry()) {
    const MethodPlan plan = MakeMethod(e.name);
    if (!plan.post && plan.render.scale == 1.0 && plan.render.SamplesPerPixel() > 1) names.push_back(e.name);
  }
  return names;
}

/// True when registry row `name` has a parameter `param`.
bool HasParam(const std::string& name, const std::string& param) {
  for (const auto& e : MethodRegistry()) {
    if (e.name != name) continue;
    for (const auto& def : e.params) {
      if (def.name == param) return true;
    }
  }
  return false;
}

int MaxAbsDiff(const Image8& a, const Image8& b) {
  int d = 0;
  for (size_t i = 0; i < a.Data().size(); ++i) d = std::max(d, std::abs(int(a.Data()[i]) - int(b.Data()[i])));
  return d;
}

TEST(SsaaInvariants, EverySupersamplingMethodEqualsNoneWithoutEdgesOrTexture) {
  const auto methods = SupersamplingMethods();
  EXPECT_GE(methods.size(), 4u);  // ssaa-2x2, ssaa-4x4, ssaa-rgss, ssaa-jitter
  struct Case {
    std::string what;
    Scene scene;
    int max_diff;  // 0: every sample sees the same radiance
  };
  const std::vector<Case> cases = {
      {"unlit constant", FlatScene(R"(["unlit"])", R"({"shading": "unlit", "color": [0.3, 0.5, 0.7]})", ""), 0},
      {"lit by a directional light + ambient, tonemapped",
       FlatScene(R"(["lambert"])", R"({"shading": "lambert", "color": [0.8, 0.6, 0.4]})",
                 R"(, "ambient": [0.05, 0.05, 0.1], "display": {"exposure": 1.7, "tonemap": "aces"},
                    "light_units": "aalab-pi", "lights": [{"type": "directional", "direction": [0.3, -0.2, -1], "intensity": 1.5}])"),
       0},
      // A point light makes smooth shading: the box average over a pixel differs from the
      // centre sample by a second-order term, well below one 8-bit step.
      {"lit by a distant point light",
       FlatScene(
           R"(["lambert"])", R"({"shading": "lambert", "color": [0.9, 0.9, 0.9]})",
           R"(, "light_units": "aalab-pi", "lights": [{"type": "point", "position": [3, 2, 40], "intensity": 1500}])"),
       1},
  };
  for (const auto& c : cases) {
    Tracer tracer(c.scene);
    for (const auto& [w, h] : std::vector<std::pair<int, int>>{{12, 7}, {1, 1}, {5, 1}}) {
      const Image8 none = RenderFrame(tracer, w, h, RenderSpec{}, 1, nullptr);
      if (c.max_diff > 0 && w > 1) {
        // Not vacuous: the shading does vary across the frame.
        EXPECT_NE(none.At(0, 0, 0), none.At(w - 1, h - 1, 0)) << c.what;
      }
      for (const auto& name : methods) {
        // With a sample count of its own (ssaa-jitter), also an odd one.
        for (const std::string& spec : {name, HasParam(name, "spp") ? name + ":spp=3" : name}) {
          const Image8 ss = RenderFrame(tracer, w, h, MakeMethod(spec).render, 7, nullptr);
          EXPECT_LE(MaxAbsDiff(ss, none), c.max_diff) << c.what << " " << spec << " " << w << "x" << h;
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// Metric symmetry.

ImageF RandomImage(int w, int h, uint64_t seed, const ImageF* near = nullptr, float amount = 1.0f) {
  Rng rng(seed);
  ImageF img(w, h, 3);
  for (size_t i = 0; i < img.Data().size(); ++i) {
    const float r = static_cast<float>(rng.Below(256)) / 255.0f;
    img.Data()[i] = near ? std::clamp(near->Data()[i] + (r - 0.5f) * amount, 0.0f, 1.0f) : r;
  }
  return img;
}

TEST(MetricInvariants, SymmetricMetricsAreSymmetricBitForBit) {
  // Symmetric by definition: everything built on |a - b| or (a - b)^2 and SSIM. Not symmetric:
  // FLIP (reference and test play different roles) and edge_error_removed (relative to the
  // no-AA image).
  const std::set<std::string> symmetric = {"psnr_db", "mse",         "edge_psnr_db", "edge_rmse",   "interior_psnr_db",
                                           "ssim",    "abs_err_p50", "abs_err_p95",  "abs_err_p99", "abs_err_max"};
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{37, 23}, {11, 11}, {64, 12}}) {
    const ImageF a = RandomImage(w, h, 5 + w);
    const ImageF b = RandomImage(w, h, 9 + w, &a, 0.2f);
    ImageF mask(w, h, 1);
    Rng rng(77);
    for (float& v : mask.Data()) v = rng.Below(3) == 0 ? 1.0f : 0.0f;
    MetricInput ab, ba;
    ab.image = &a;
    ab.reference = &b;
    ab.edge_mask = &mask;
    ba.image = &b;
    ba.reference = &a;
    ba.edge_mask = &mask;
    const auto x = ComputeAllMetrics(ab), y = ComputeAllMetrics(ba);
    ASSERT_EQ(x.size(), y.size());
    int seen = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      if (!symmetric.count(x[i].name)) continue;
      ++seen;
      ASSERT_TRUE(x[i].value.has_value()) << x[i].name << " " << x[i].null_reason;
      ASSERT_TRUE(y[i].value.has_value()) << y[i].name;
      EXPECT_EQ(*x[i].value, *y[i].value) << x[i].name << " " << w << "x" << h;
    }
    EXPECT_EQ(seen, static_cast<int>(symmetric.size()));
    // The per-metric entry points too, and a metric of an image with itself.
    EXPECT_EQ(MeanSquaredError(a, b).mse, MeanSquaredError(b, a).mse);
    const SsimResult sab = ComputeSsim(a, b), sba = ComputeSsim(b, a);
    ASSERT_TRUE(sab.ssim && sba.ssim);
    EXPECT_EQ(*sab.ssim, *sba.ssim);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(sab.per_channel[c], sba.per_channel[c]);
    EXPECT_EQ(*ComputeSsim(a, a).ssim, 1.0);
    EXPECT_FALSE(PsnrFromMse(MeanSquaredError(a, a).mse).has_value());  // identical: null, never Inf
  }
}

}  // namespace
}  // namespace aalab
