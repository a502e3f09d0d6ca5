// Production temporal anti-aliasing (`taa-prod`, and the temporal upscaler rows `taau-*` of
// methods/taau.cpp): today's `taa` (methods/taa.cpp, kept bit-exact as the minimal variant)
// plus the techniques shipped engines add, each switchable by a parameter so that its
// contribution is measurable (docs/motion.md "Production TAA").
//
// Per frame t, for every output pixel o (centre c_o; the frame is rendered at rw × rh with
// jitter j_t, the output is W × H; s = rw / W, 1 for TAA, < 1 for TAAU; p = s·c_o is c_o in
// render pixels, i = the render pixel holding p):
//   1. reconstruct the current colour at p from the jittered samples (render pixel k's sample
//      lies at k + 0.5 + j_t):
//        `filter=box`   the one sample whose position lies in [p − 0.5, p + 0.5)² (for TAA the
//                       pixel's own sample, as `taa`): the still-frame limit of the
//                       exponential average of Halton-jittered samples is the pixel's box
//                       average, the reference's filter — the default, so the score is fair;
//        `filter=gauss` the 3x3 samples around i, weights exp(−2.29·(|k + 0.5 + j_t − p| /
//                       filter_size)²), normalised (Karis 2014 / UE4 PostProcessTemporalAA
//                       "Blackman-Harris fit", σ ≈ 0.47·size, in render pixels). Its still
//                       limit is the box convolved with that Gaussian (a softer pixel filter
//                       than the reference's box, which PSNR and FLIP then count as error);
//   2. motion: `dilate=on` takes the motion vector of the 3x3 pixel around i with the smallest
//      view depth (Karis 2014 "closest" velocity; Pedersen 2016 useDilation), so the edge
//      pixels of a moving object over a still background move with the object; the vector is
//      scaled to output pixels; previous output position h = c_o + v·(W / rw). No depth
//      (a captured sequence without depth): the pixel's own vector;
//   3. history: off-screen h (outside [0, W]×[0, H]) or no vector → none. `disocclusion=on`
//      drops it where the surface now visible was hidden: with depth, where the previous
//      frame's depth at h (nearest render texel) is nearer than the current closest depth by
//      more than `disocclusion_depth` (relative); and, with or without depth, where the
//      previous frame's motion vector at h differs from the current one by more than
//      `disocclusion_px` (Salvi 2016 / Jimenez 2016 motion-vector rejection). The motion test
//      is needed with depth too: a background pixel beside a moving object takes the
//      object's dilated vector, lands on background elsewhere, and the depth test passes
//      (docs/motion.md "Where taa-prod loses to none");
//   4. fetch the history at h: `history=bilinear` (2x2), `catmull-rom` (4x4 separable
//      Catmull-Rom, what UE4's 9 bilinear taps compute; Karis 2014), `catmull-rom-5` (the 4x4
//      without its corners, renormalised: Jimenez 2016 "Filmic SMAA", 5 bilinear taps);
//      clamped to [0, 1] (the history holds display-referred colours in [0, 1]; Catmull-Rom
//      overshoots), texels clamped to the edge;
//   5. rectify in YCoCg against the 3x3 raw samples around i exactly as `taa` (`clip=variance`
//      μ ± γσ ∩ min/max, Salvi 2016; `minmax`, Karis 2014; `none`), clipped toward the box
//      centre, extents + 1e-8 (Playdead's FLT_EPS: a flat box does not divide by zero);
//   6. blend o = H + α·(C − H) in YCoCg, clamp to [0, 1]. `feedback=fixed`: α = `alpha`.
//      `feedback=adaptive`: α = max(α_motion, α_luma), α_motion = alpha_min + (alpha_max −
//      alpha_min)·min(1, |v| / motion_px) (UE4: 0.04 → 0.2 over 40 px), α_luma = alpha_max −
//      (alpha_max − alpha_min)·(1 − d)², d = |Y_C − Y_H| / max(Y_C, Y_H, 0.2) (Lottes'
//      "unbiased luminance difference" as Pedersen 2016 uses it); so α ∈ [alpha_min, alpha_max];
//   7. store o as the history (`precision=rgba32f`, or rounded to half floats, `rgba16f`,
//      what engines store); `sharpen` > 0 adds s·(o − mean of the 4 neighbours) to the output
//      only (HDRP taaSharpenStrength form; history unsharpened); encode sRGB 8-bit.
// Without history: o = the reconstructed current colour.
// Safe choices, stated: the Gaussian's weight sum is never 0 (the nearest sample is within
// 1.2 px: weight ≥ e^−3.3 at size 1, and size ≥ 0.25); depths compare as floats, +Inf (the
// background) is "farthest"; a NaN previous position means no history.
// Sources (BibTeX keys of reports/export_bibliography.cpp where present): B. Karis, "High
// Quality Temporal Supersampling", SIGGRAPH 2014 Advances (karis2014taa); M. Salvi, "An
// Excursion in Temporal Supersampling", GDC 2016 (salvi2016taa); J. Jimenez, "Filmic SMAA:
// Sharp Morphological and Temporal Antialiasing", SIGGRAPH 2016 Advances; L. J. F. Pedersen,
// "Temporal Reprojection Anti-Aliasing in INSIDE", GDC 2016 (playdeadgames/temporal);
// T. Lottes, "TSSAA" (luminance-weighted feedback, 2011). ../shared/notes/temporal-and-taa.md.
#include "methods/taa_production.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "methods/taa.h"
#include "methods/taa_common.h"

namespace aalab {

std::array<float, 4> CatmullRomWeights(float t) {
  const float t2 = t * t, t3 = t2 * t;
  return {-0.5f * t3 + t2 - 0.5f * t, 1.5f * t3 - 2.5f * t2 + 1.0f, -1.5f * t3 + 2.0f * t2 + 0.5f * t,
          0.5f * t3 - 0.5f * t2};
}

int ClosestDepthPixel(const float* depth, int w, int h, int x, int y) {
  int best = y * w + x;
  float bd = depth[best];
  for (int dy = -1; dy <= 1; ++dy) {
    const int yy = std::clamp(y + dy, 0, h - 1);
    for (int dx = -1; dx <= 1; ++dx) {
      const int i = yy * w + std::clamp(x + dx, 0, w - 1);
      if (depth[i] < bd) {
        bd = depth[i];
        best = i;
      }
    }
  }
  return best;
}

float RoundToHalf(float v) {
  uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  const uint32_t sign = b & 0x80000000u;
  const uint32_t a = b & 0x7fffffffu;
  if (a >= 0x7f800000u) return v;  // Inf, NaN
  float mag;
  std::memcpy(&mag, &a, sizeof mag);
  float r;
  if (mag >= 65520.0f) {  // rounds past the largest half (65504)
    r = std::numeric_limits<float>::infinity();
  } else if (mag < 6.103515625e-05f) {                    // subnormal halves: a fixed step of 2^-24
    r = std::nearbyint(mag * 16777216.0f) / 16777216.0f;  // default rounding: ties to even
  } else {
    // Normal halves keep 10 of the float's 23 mantissa bits: round the low 13 to even.
    const uint32_t low = a & 0x1fffu, keep = a & ~0x1fffu;
    uint32_t out = keep;
    if (low > 0x1000u || (low == 0x1000u && (keep & 0x2000u))) out += 0x2000u;
    std::memcpy(&r, &out, sizeof r);
  }
  uint32_t rb;
  std::memcpy(&rb, &r, sizeof rb);
  rb |= sign;
  std::memcpy(&r, &rb, sizeof r);
  return r;
}

namespace {

using namespace taa_detail;  // Ycc, ToYCoCg, FromYCoCg, AddToBox, NarrowToVariance, ClipToBox

inline float Clamp01(float v) { return std::clamp(v, 0.0f, 1.0f); }

class TaaProdState : public TemporalState {
 public:
  explicit TaaProdState(TaaProdParams p) : p_(p) {
    for (int i = 0; i < 256; ++i) decode_[static_cast<size_t>(i)] = SrgbDecode8(static_cast<uint8_t>(i));
  }
  std::unique_ptr<TemporalState> Clone() const override { return std::make_unique<TaaProdState>(*this); }

  Image8 Step(const TemporalInput& in, PostStats* stats) override {
    AALAB_CHECK(in.frame != nullptr, "TAA needs a frame");
    const Image8& f = *in.frame;
    const int rw = f.Width(), rh = f.Height();
    const int W = in.output_width > 0 ? in.output_width : rw, H = in.output_height > 0 ? in.output_height : rh;
    const size_t rn = static_cast<size_t>(rw) * rh, n = static_cast<size_t>(W) * H;
    AALAB_CHECK(!in.previous || in.previous->size() == 2 * rn, "previous positions must match the frame size");
    AALAB_CHECK(!in.depth || in.depth->size() == rn, "depth must match the frame size");
    cur_.resize(3 * rn);
    ycc_.resize(rn);
    for (size_t i = 0; i < rn; ++i) {
      const uint8_t* px = f.Data().data() + 4 * i;
      for (int c = 0; c < 3; ++c) cur_[3 * i + c] = decode_[px[c]];
      ycc_[i] = ToYCoCg(&cur_[3 * i]);
    }
    const bool have_history =
        !history_.empty() && hist_w_ == W && hist_h_ == H && prev_rw_ == rw && prev_rh_ == rh && in.previous != nullptr;
    const bool use_depth = in.depth != nullptr;
    // Motion vectors in render pixels (previous − centre), NaN where none.
    mv_.assign(2 * rn, std::numeric_limits<float>::quiet_NaN());
    if (in.previous) {
      for (int y = 0; y < rh; ++y) {
        for (int x = 0; x < rw; ++x) {
          const size_t i = static_cast<size_t>(y) * rw + x;
          mv_[2 * i] = (*in.previous)[2 * i] - (static_cast<float>(x) + 0.5f);
          mv_[2 * i + 1] = (*in.previous)[2 * i + 1] - (static_cast<float>(y) + 0.5f);
        }
      }
    }
    next_.resize(4 * n);
    out_.resize(3 * n);
    const float sx = static_cast<float>(rw) / static_cast<float>(W),
                sy = static_cast<float>(rh) / static_cast<float>(H);
    ParallelFor(H, [&](int oy) {
      for (int ox = 0; ox < W; ++ox) {
        const size_t o = static_cast<size_t>(oy) * W + ox;
        float res[4];
        Pixel(in, ox, oy, rw, rh, W, H, sx, sy, have_history, use_depth, res);
        for (int c = 0; c < 3; ++c) {
          const float v = p_.precision == TaaPrecision::kFloat16 ? RoundToHalf(res[c]) : res[c];
          next_[4 * o + c] = v;
          out_[3 * o + c] = res[c];
        }
        next_[4 * o + 3] = res[3];
      }
    });
    Image8 result(W, H, 4, kUninitialized);  // every byte written below (alpha 255)
    const bool sharpen = p_.sharpen > 0.0f;
    ParallelFor(H, [&](int y) {
      uint8_t* row = result.Pixel(0, y);
      for (int x = 0; x < W; ++x) {
        const size_t i = static_cast<size_t>(y) * W + x;
        for (int c = 0; c < 3; ++c) {
          float v = out_[3 * i + c];
          if (sharpen) {
            const float nb = 0.25f * (out_[3 * (static_cast<size_t>(y) * W + std::max(x - 1, 0)) + c] +
                                      out_[3 * (static_cast<size_t>(y) * W + std::min(x + 1, W - 1)) + c] +
                                      out_[3 * (static_cast<size_t>(std::max(y - 1, 0)) * W + x) + c] +
                                      out_[3 * (static_cast<size_t>(std::min(y + 1, H - 1)) * W + x) + c]);
            v = Clamp01(v + p_.sharpen * (v - nb));
          }
          row[4 * x + c] = EncodeSrgb8(v);
        }
        row[4 * x + 3] = 255;
      }
    });
    history_.swap(next_);
    hist_w_ = W;
    hist_h_ = H;
    prev_rw_ = rw;
    prev_rh_ = rh;
    prev_mv_ = mv_;
    if (use_depth) {
      prev_depth_ = *in.depth;
    } else {
      prev_depth_.clear();
    }
    if (stats) stats->taps += static_cast<uint64_t>(n) * TapsPerPixel(have_history, use_depth);
    return result;
  }

 private:
  /// Texels read per output pixel: the 3x3 colour neighbourhood (reconstruction and box share
  /// it), the 3x3 depths (dilation) or 1 motion vector, 1 previous depth/motion (disocclusion),
  /// the history's texels (4, 16 or 12).
  uint64_t TapsPerPixel(bool have_history, bool use_depth) const {
    uint64_t t = 9 + ((p_.dilate && use_depth) ? 9 : 1);
    if (!have_history) return t;
    if (p_.disocclusion) t += 1;
    t += p_.history == TaaHistoryFilter::kBilinear ? 4 : (p_.history == TaaHistoryFilter::kCatmullRom ? 16 : 12);
    return t;
  }

  void Reconstruct(int ix, int iy, int rw, int rh, float px, float py, FrameJitter j, float* out) const {
    if (p_.reconstruct == TaaReconstruct::kBox) {
      const int kx = std::clamp(static_cast<int>(std::floor(px - j.x)), 0, rw - 1);
      const int ky = std::clamp(static_cast<int>(std::floor(py - j.y)), 0, rh - 1);
      const float* c = &cur_[3 * (static_cast<size_t>(ky) * rw + kx)];
      std::copy(c, c + 3, out);
      return;
    }
    float acc[3] = {0, 0, 0}, wsum = 0.0f;
    const float inv = 1.0f / (p_.filter_size * p_.filter_size);
    for (int ky = iy - 1; ky <= iy + 1; ++ky) {
      if (ky < 0 || ky >= rh) continue;
      for (int kx = ix - 1; kx <= ix + 1; ++kx) {
        if (kx < 0 || kx >= rw) continue;
        const float dx = static_cast<float>(kx) + 0.5f + j.x - px, dy = static_cast<float>(ky) + 0.5f + j.y - py;
        const float w = std::exp(-2.29f * (dx * dx + dy * dy) * inv);
        const float* c = &cur_[3 * (static_cast<size_t>(ky) * rw + kx)];
        for (int k = 0; k < 3; ++k) acc[k] += w * c[k];
        wsum += w;
      }
    }
    for (int k = 0; k < 3; ++k) out[k] = acc[k] / wsum;
  }

  /// The history at continuous output position (hx, hy): texels clamped to the edge.
  void FetchHistory(float hx, float hy, float* out) const {
    const float fx = hx - 0.5f, fy = hy - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float tx = fx - x0f, ty = fy - y0f;
    const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
    auto texel = [&](int x, int y) {
      return &history_[4 *
                       (static_cast<size_t>(std::clamp(y, 0, hist_h_ - 1)) * hist_w_ + std::clamp(x, 0, hist_w_ - 1))];
    };
    if (p_.history == TaaHistoryFilter::kBilinear) {
      const float *a = texel(x0, y0), *b = texel(x0 + 1, y0), *c0 = texel(x0, y0 + 1), *d = texel(x0 + 1, y0 + 1);
      for (int c = 0; c < 3; ++c) {
        const float top = a[c] + tx * (b[c] - a[c]);
        const float bot = c0[c] + tx * (d[c] - c0[c]);
        out[c] = top + ty * (bot - top);
      }
      return;
    }
    const std::array<float, 4> wx = CatmullRomWeights(tx), wy = CatmullRomWeights(ty);
    const bool five = p_.history == TaaHistoryFilter::kCatmullRom5;
    float acc[3] = {0, 0, 0}, wsum = 0.0f;
    for (int b = 0; b < 4; ++b) {
      for (int a = 0; a < 4; ++a) {
        if (five && (a == 0 || a == 3) && (b == 0 || b == 3)) continue;  // the corners
        const float w = wx[static_cast<size_t>(a)] * wy[static_cast<size_t>(b)];
        const float* t = texel(x0 - 1 + a, y0 - 1 + b);
        for (int c = 0; c < 3; ++c) acc[c] += w * t[c];
        wsum += w;
      }
    }
    for (int c = 0; c < 3; ++c) out[c] = Clamp01(acc[c] / wsum);
  }

  float HistoryCount(float hx, float hy) const {
    const int x = std::clamp(static_cast<int>(std::floor(hx)), 0, hist_w_ - 1);
    const int y = std::clamp(static_cast<int>(std::floor(hy)), 0, hist_h_ - 1);
    return history_[4 * (static_cast<size_t>(y) * hist_w_ + x) + 3];
  }

  void Box(int ix, int iy, int rw, int rh, float* lo, float* hi) const {
    float mn[3] = {1e30f, 1e30f, 1e30f}, mx[3] = {-1e30f, -1e30f, -1e30f}, m1[3] = {0, 0, 0}, m2[3] = {0, 0, 0};
    for (int dy = -1; dy <= 1; ++dy) {
      const int yy = std::clamp(iy + dy, 0, rh - 1);
      for (int dx = -1; dx <= 1; ++dx) {
        AddToBox(ycc_[static_cast<size_t>(yy) * rw + std::clamp(ix + dx, 0, rw - 1)], mn, mx, m1, m2);
      }
    }
    if (p_.clip == TaaRectify::kVariance) NarrowToVariance(mn, mx, m1, m2, p_.gamma);
    std::copy(mn, mn + 3, lo);
    std::copy(mx, mx + 3, hi);
  }

  void Pixel(const TemporalInput& in, int ox, int oy, int rw, int rh, int W, int H, float sx, float sy,
             bool have_history, bool use_depth, float* res) const {
    const float px = (static_cast<float>(ox) + 0.5f) * sx, py = (static_cast<float>(oy) + 0.5f) * sy;
    const int ix = std::clamp(static_cast<int>(std::floor(px)), 0, rw - 1);
    const int iy = std::clamp(static_cast<int>(std::floor(py)), 0, rh - 1);
    float cur[3];
    Reconstruct(ix, iy, rw, rh, px, py, in.jitter, cur);
    const auto fallback = [&] {
      for (int c = 0; c < 3; ++c) res[c] = Clamp01(cur[c]);
      res[3] = 1.0f;  // one frame accumulated
    };
    if (!have_history) return fallback();
    const int m = (p_.dilate && use_depth) ? ClosestDepthPixel(in.depth->data(), rw, rh, ix, iy) : iy * rw + ix;
    const float vx = mv_[2 * static_cast<size_t>(m)], vy = mv_[2 * static_cast<size_t>(m) + 1];
    const float ovx = vx / sx, ovy = vy / sy;  // output pixels
    const float hx = static_cast<float>(ox) + 0.5f + ovx, hy = static_cast<float>(oy) + 0.5f + ovy;
    if (!(hx >= 0.0f && hx <= static_cast<float>(W) && hy >= 0.0f && hy <= static_cast<float>(H))) return fallback();
    if (p_.disocclusion) {
      const int qx = std::clamp(static_cast<int>(std::floor(hx * sx)), 0, rw - 1);
      const int qy = std::clamp(static_cast<int>(std::floor(hy * sy)), 0, rh - 1);
      const size_t q = static_cast<size_t>(qy) * rw + qx;
      if (use_depth && !prev_depth_.empty()) {
        const float now = (*in.depth)[static_cast<size_t>(m)];
        if (prev_depth_[q] < now * (1.0f - p_.disocclusion_depth)) return fallback();
      }
      {
        // An unknown previous vector (frame 0 has none) cannot show a discontinuity.
        const float dx = prev_mv_[2 * q] - vx, dy = prev_mv_[2 * q + 1] - vy;
        if (dx * dx + dy * dy > p_.disocclusion_px * p_.disocclusion_px) return fallback();
      }
    }
    float h[3];
    FetchHistory(hx, hy, h);
    Ycc hy_ = ToYCoCg(h);
    if (p_.clip != TaaRectify::kNone) {
      float lo[3], hi[3];
      Box(ix, iy, rw, rh, lo, hi);
      hy_ = ClipToBox(hy_, lo, hi);
    }
    const Ycc cy = ToYCoCg(cur);
    // Frames accumulated: the nearest history texel's count (A channel).
    const float count = HistoryCount(hx, hy);
    float alpha = p_.alpha;
    if (p_.feedback == TaaFeedback::kAdaptive) {
      const float speed = std::sqrt(ovx * ovx + ovy * ovy);
      const float a_motion = p_.alpha_min + (p_.alpha_max - p_.alpha_min) * std::min(1.0f, speed / p_.motion_px);
      alpha = std::max(1.0f / (count + 1.0f), a_motion);
      if (p_.luma_weight) {
        const float d = std::fabs(cy.y - hy_.y) / std::max({cy.y, hy_.y, 0.2f});
        const float k = (1.0f - std::min(d, 1.0f)) * (1.0f - std::min(d, 1.0f));
        alpha = std::max(alpha, p_.alpha_max - (p_.alpha_max - p_.alpha_min) * k);
      }
    }
    res[3] = std::min(count + 1.0f, 255.0f);
    const Ycc o{hy_.y + alpha * (cy.y - hy_.y), hy_.co + alpha * (cy.co - hy_.co), hy_.cg + alpha * (cy.cg - hy_.cg)};
    FromYCoCg(o, res);
    for (int c = 0; c < 3; ++c) res[c] = Clamp01(res[c]);
  }

  TaaProdParams p_;
  std::array<float, 256> decode_{};
  std::vector<float> history_;  ///< output size: linear display RGB + frames accumulated, 4 floats per pixel
  int hist_w_ = 0, hist_h_ = 0, prev_rw_ = 0, prev_rh_ = 0;
  std::vector<float> prev_depth_, prev_mv_;  ///< the previous frame's, render size
  // Per-frame working buffers.
  std::vector<float> cur_, mv_, next_, out_;
  std::vector<Ycc> ycc_;
};

bool OnOff(const ParamValues& v, const std::string& name) { return v.Choice(name) == "on"; }

}  // namespace

std::unique_ptr<TemporalState> MakeTaaProdState(const TaaProdParams& p) { return std::make_unique<TaaProdState>(p); }

std::vector<ParamDef> TaaProdParamDefs() {
  const TaaProdParams d;
  return {
      ChoiceParam("filter", "box", {"box", "gauss"},
                  "current-frame reconstruction: the sample in the pixel's box (still limit: box, the reference's "
                  "filter) or 3x3 Gaussian exp(-2.29 (d/size)^2) (UE4; still limit: box (x) Gaussian)"),
      FloatParam("filter_size", d.filter_size, 0.25, 2.0, "filter=gauss: UE4 r.TemporalAAFilterSize"),
      ChoiceParam("dilate", "on", {"on", "off"}, "motion vector of the closest depth in 3x3"),
      ChoiceParam("history", "catmull-rom", {"catmull-rom", "catmull-rom-5", "bilinear"},
                  "history fetch: 4x4 Catmull-Rom (UE4 9-tap), 5-tap (Jimenez 2016) or bilinear"),
      ChoiceParam("disocclusion", "on", {"on", "off"},
                  "drop history where the previous depth was nearer or the motion differs"),
      FloatParam("disocclusion_depth", d.disocclusion_depth, 0.001, 1.0, "relative depth step that drops history"),
      FloatParam("disocclusion_px", d.disocclusion_px, 0.05, 64.0, "motion difference (px) that drops history"),
      ChoiceParam("clip", "variance", {"variance", "minmax", "none"}, "history rectification in YCoCg (as taa)"),
      FloatParam("gamma", d.gamma, 0.25, 4.0, "variance box half-width in standard deviations"),
      ChoiceParam("feedback", "adaptive", {"adaptive", "fixed"},
                  "current-frame weight: adaptive to motion and luminance difference, or fixed alpha"),
      FloatParam("alpha", d.alpha, 0.01, 1.0, "feedback=fixed: weight of the current frame"),
      FloatParam("alpha_min", d.alpha_min, 0.01, 1.0, "feedback=adaptive: weight when still and in agreement"),
      FloatParam("alpha_max", d.alpha_max, 0.01, 1.0, "feedback=adaptive: weight at motion_px or full contrast"),
      FloatParam("motion_px", d.motion_px, 0.5, 256.0, "feedback=adaptive: speed (px/frame) reaching alpha_max"),
      ChoiceParam(
          "luma_weight", "off", {"off", "on"},
          "feedback=adaptive: raise alpha with the current/history luminance difference (Lottes, Pedersen 2016)"),
      FloatParam("sharpen", d.sharpen, 0.0, 2.0, "unsharp amount on the output (0 = off; history unsharpened)"),
      ChoiceParam("precision", "rgba32f", {"rgba32f", "rgba16f"}, "history storage precision"),
  };
}

TaaProdParams TaaProdParamsFrom(const ParamValues& v) {
  TaaProdParams p;
  p.reconstruct = v.Choice("filter") == "gauss" ? TaaReconstruct::kGauss : TaaReconstruct::kBox;
  p.filter_size = static_cast<float>(v.Number("filter_size"));
  p.dilate = OnOff(v, "dilate");
  const std::string& h = v.Choice("history");
  p.history = h == "bilinear" ? TaaHistoryFilter::kBilinear
                              : (h == "catmull-rom-5" ? TaaHistoryFilter::kCatmullRom5 : TaaHistoryFilter::kCatmullRom);
  p.disocclusion = OnOff(v, "disocclusion");
  p.disocclusion_depth = static_cast<float>(v.Number("disocclusion_depth"));
  p.disocclusion_px = static_cast<float>(v.Number("disocclusion_px"));
  const std::string& c = v.Choice("clip");
  p.clip = c == "none" ? TaaRectify::kNone : (c == "minmax" ? TaaRectify::kMinMax : TaaRectify::kVariance);
  p.gamma = static_cast<float>(v.Number("gamma"));
  p.feedback = v.Choice("feedback") == "fixed" ? TaaFeedback::kFixed : TaaFeedback::kAdaptive;
  p.alpha = static_cast<float>(v.Number("alpha"));
  p.alpha_min = static_cast<float>(v.Number("alpha_min"));
  p.alpha_max = static_cast<float>(v.Number("alpha_max"));
  if (p.alpha_min > p.alpha_max) {
    throw UserError("alpha_min (" + FormatNumber(p.alpha_min) + ") must not exceed alpha_max (" +
                    FormatNumber(p.alpha_max) + ")");
  }
  p.motion_px = static_cast<float>(v.Number("motion_px"));
  p.luma_weight = OnOff(v, "luma_weight");
  p.sharpen = static_cast<float>(v.Number("sharpen"));
  p.precision = v.Choice("precision") == "rgba16f" ? TaaPrecision::kFloat16 : TaaPrecision::kFloat32;
  return p;
}

std::vector<MethodEntry> TaaProdMethods() {
  std::vector<ParamDef> defs = TaaProdParamDefs();
  defs.insert(defs.begin(), IntParam("samples", 16, 1, 256, "Halton(2,3) jitter points cycled (indices 1..samples)"));
  std::vector<MethodEntry> out;
  out.push_back({"taa-prod",
                 "production TAA: taa plus closest-depth motion dilation, Catmull-Rom history, disocclusion test, "
                 "adaptive feedback; each switchable (needs --frames > 1 to accumulate)",
                 defs, [](const ParamValues& v) {
                   MethodPlan plan;
                   plan.render.jitter.samples = v.Int("samples");
                   const TaaProdParams tp = TaaProdParamsFrom(v);
                   plan.make_state = [tp] { return MakeTaaProdState(tp); };
                   return plan;
                 }});
  // In `aalab run`'s default list: a run with --frames > 1 compares it (a still run's list
  // leaves methods with memory out; harness/run/runner.cpp). It beats `taa` on the speed sweep
  // (docs/motion.md "Speed sweep"), so it, not `taa`, is the default temporal method.
  out.back().in_default_list = true;
  return out;
}

}  // namespace aalab
