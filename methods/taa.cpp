// Temporal anti-aliasing (TAA): one jittered sample per pixel and frame, accumulated over
// frames in a history that is reprojected with exact motion vectors, rectified against the
// current frame's neighbourhood and blended exponentially.
//
// Implements `taa`, per frame t (pixel centre c, this frame's linear colour C(c)):
//   1. render: one sample at c + j_t, j_t = Halton(2,3) of index (t mod samples) + 1, minus
//      0.5 (Playdead INSIDE FrustumJitter "Halton_2_3_X16"; Unity URP; index 0 is skipped:
//      it is the degenerate (0, 0) point) — the render request's JitterSpec, the offset is
//      per-frame data (core/render_spec.h);
//   2. reproject: the history (linear display RGB, float — never 8-bit) is fetched bilinearly
//      (texel centres at +0.5, clamp to edge) at the previous position of c, which the runner
//      computes exactly from the known motion (scenes/motion_render.h); no previous position
//      (off-screen, first frame, point behind the camera) → no history, output = C(c);
//   3. rectify in YCoCg (Karis 2014): over the 3×3 neighbourhood of C (clamped at the
//      border), `clip=variance`: the box μ ± γσ (Salvi 2016) intersected with the min/max
//      box; `clip=minmax`: the min/max box (Karis 2014 "clamp" neighbourhood); `clip=none`:
//      no rectification (the plain accumulation the convergence bound in
//      tests/motion/taa_test.cpp is derived for). The history is clipped toward the box
//      centre along the line to it (Playdead's clip_aabb "optimized" form; Bevy), extents
//      + 1e-8 so a flat neighbourhood does not divide by zero (Playdead's FLT_EPS);
//   4. blend: out = H' + α·(C − H') (exponential moving average), written to the history
//      and, sRGB-encoded and quantised, to the 8-bit output.
//
// Parameters:
//   samples  [1..256]  default 16   Halton(2,3) points cycled (Playdead X16, Filament
//                                   HALTON_23_X16; UE4 r.TemporalAASamples = 8)
//   alpha    [0.01..1] default 0.1  weight of the current frame (Unity URP frameInfluence
//                                   0.1, Bevy 0.1, Salvi 2016 "typically 10%"; UE4 0.04,
//                                   Filament 0.12). 1 = no accumulation.
//   clip     {variance|minmax|none} default variance
//   gamma    [0.25..4] default 1    variance box half-width in σ (Salvi 2016; Filament and
//                                   Bevy 1.0; URP 0.9, HDRP/MSAAFilter 1.5)
//
// Simplifications, stated: the current colour is the jittered sample itself (no Gaussian
// "unjitter" reconstruction as in UE4; the EMA of uniformly jittered samples converges to the
// pixel's box average, which is the reference's filter); no velocity dilation (motion is
// exact per pixel; background pixels keep zero motion since the background is uniform); no
// Karis inverse-luma weights (colours are display-referred in [0, 1] already); bilinear
// history (Playdead's default), not Catmull-Rom; no sharpening; no motion-dependent alpha.
// Sources: B. Karis, "High Quality Temporal Supersampling", SIGGRAPH 2014 Advances;
// M. Salvi, "An Excursion in Temporal Supersampling", GDC 2016; L. J. F. Pedersen, "Temporal
// Reprojection Anti-Aliasing in INSIDE", GDC 2016 (playdeadgames/temporal);
// ../shared/notes/temporal-and-taa.md collects the defaults above with their sources.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "methods/families.h"
#include "methods/taa.h"
#include "methods/taa_avx2.h"
#include "methods/taa_common.h"
#include "methods/taa_encode.h"
#include "methods/taa_sse2.h"

namespace aalab {

namespace {

enum class Clip { kVariance, kMinMax, kNone };

struct TaaParams {
  float alpha = 0.1f;
  float gamma = 1.0f;
  Clip clip = Clip::kVariance;
};

using namespace taa_detail;  // Ycc, ToYCoCg, ..., ClipToBox (taa_common.h), Encode8 (taa_encode.h)

}  // namespace

uint8_t EncodeSrgb8(float v) { return Encoder()(v); }

void EncodeSrgb8Rgba(const float* r, const float* g, const float* b, int w, uint8_t* rgba) {
  Encoder().Rgba(r, g, b, w, rgba);
}

namespace {

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_TAA_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define AALAB_TAA_CLONES
#endif

/// Rectify's box for one channel of one row, every pixel at once: the 3×3 neighbourhood's
/// min/max (and with `variance`, intersected with μ ± γσ), each value formed exactly as
/// Rectify forms it (same operations, same order: rows top to bottom, columns left to right).
/// r0, r1, r2: the rows above, at and below (clamped), padded by one replicated texel on each
/// side (texel x at index x + 1).
// std::min / std::max of floats as selects the compiler vectorises (same results: std::min(a,
// b) is b < a ? b : a, std::max(a, b) is a < b ? b : a).
inline float Min(float a, float b) { return b < a ? b : a; }
inline float Max(float a, float b) { return a < b ? b : a; }

// The min/max are separable (each column's over the three rows, then three columns): the
// planes hold no NaN and no −0 (YCoCg of decoded colours ≥ +0: sums of products of +0 or
// more, and x − x is +0), so the minimum and maximum of the 9 values do not depend on the
// order they are taken in, and 1e30 / −1e30 (Rectify's start values) lie outside the range.
// The sums keep Rectify's order. cmn, cmx: scratch of w + 2 floats.
template <bool kVariance>
AALAB_TAA_CLONES void BoxRow(const float* __restrict r0, const float* __restrict r1, const float* __restrict r2, int w,
                             float gamma, float* __restrict cmn, float* __restrict cmx, float* __restrict lo,
                             float* __restrict hi) {
  for (int x = 0; x < w + 2; ++x) {
    cmn[x] = Min(Min(r0[x], r1[x]), r2[x]);
    cmx[x] = Max(Max(r0[x], r1[x]), r2[x]);
  }
  for (int x = 0; x < w; ++x) {
    float mn = Min(Min(cmn[x], cmn[x + 1]), cmn[x + 2]), mx = Max(Max(cmx[x], cmx[x + 1]), cmx[x + 2]);
    if constexpr (kVariance) {
      float m1 = 0.0f, m2 = 0.0f;
      const float* rows[3] = {r0, r1, r2};
      for (int k = 0; k < 3; ++k) {
        for (int d = 0; d < 3; ++d) {
          const float v = rows[k][x + d];
          m1 += v;
          m2 += v * v;
        }
      }
      const float mu = m1 / 9.0f;
      const float sigma = std::sqrt(std::fabs(m2 / 9.0f - mu * mu));  // -fno-math-errno: no branch
      mn = Max(mn, mu - gamma * sigma);
      mx = Min(mx, mu + gamma * sigma);
    }
    lo[x] = mn;
    hi[x] = mx;
  }
}

/// The history fetch's footprint for one row, every pixel at once: FetchHistory's values
/// (fractions tx, ty; offsets of the four clamped texels into the interleaved history) from
/// the previous positions (prev: x, y per pixel). The position is first clamped into
/// [0, w] × [0, h], which leaves every position that has history (StepFast's `valid`)
/// unchanged (-0 becomes +0: the same fx) and gives the others (NaN, off-screen) a footprint
/// inside the history whose fetch is discarded. floor(f) as truncation minus (f < trunc(f)):
/// f lies in [-0.5, w - 0.5], where both are the same integer; written so the loop
/// vectorises (std::floor does not without -fno-trapping-math).
AALAB_TAA_CLONES void FootprintRow(const float* __restrict prev, int w, int hw, int hh, float* __restrict tx,
                                   float* __restrict ty, int32_t* __restrict off) {
  const float fw = static_cast<float>(hw), fh = static_cast<float>(hh);
  for (int x = 0; x < w; ++x) {
    const float px = Min(fw, Max(0.0f, prev[2 * x])), py = Min(fh, Max(0.0f, prev[2 * x + 1]));
    const float fx = px - 0.5f, fy = py - 0.5f;
    const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
    const int x0 = ix - (fx < static_cast<float>(ix) ? 1 : 0), y0 = iy - (fy < static_cast<float>(iy) ? 1 : 0);
    tx[x] = fx - static_cast<float>(x0);
    ty[x] = fy - static_cast<float>(y0);
    const int xa = std::clamp(x0, 0, hw - 1), xb = std::clamp(x0 + 1, 0, hw - 1);
    const int ya = std::clamp(y0, 0, hh - 1), yb = std::clamp(y0 + 1, 0, hh - 1);
    off[4 * x] = 3 * (ya * hw + xa);
    off[4 * x + 1] = 3 * (ya * hw + xb);
    off[4 * x + 2] = 3 * (yb * hw + xa);
    off[4 * x + 3] = 3 * (yb * hw + xb);
  }
}

/// FetchHistory's lerps for one row at the footprints of FootprintRow (a gather: scalar),
/// planar RGB out.
void LerpRow(const float* __restrict hist, const float* __restrict tx, const float* __restrict ty,
             const int32_t* __restrict off, int w, float* __restrict r, float* __restrict g, float* __restrict b) {
  for (int x = 0; x < w; ++x) {
    const float *a = hist + off[4 * x], *bb = hist + off[4 * x + 1], *c0 = hist + off[4 * x + 2],
                *d = hist + off[4 * x + 3];
    float h[3];
    for (int c = 0; c < 3; ++c) {
      const float top = a[c] + tx[x] * (bb[c] - a[c]);
      const float bot = c0[c] + tx[x] * (d[c] - c0[c]);
      h[c] = top + ty[x] * (bot - top);
    }
    r[x] = h[0];
    g[x] = h[1];
    b[x] = h[2];
  }
}

/// ToYCoCg in place over a planar row, every pixel at once: the current frame's planes, and
/// the fetched history in the scalar tail. Pixels without history get the YCoCg of
/// FootprintRow's safe fetch, which BlendRow discards (it takes the current colour there),
/// instead of StepReference's 0: no select, so the loop vectorises (a select after float
/// arithmetic does not, with trapping math).
AALAB_TAA_CLONES void HistoryYccRow(int w, float* __restrict r, float* __restrict g, float* __restrict b) {
  for (int x = 0; x < w; ++x) {
    const float rgb[3] = {r[x], g[x], b[x]};
    const Ycc v = ToYCoCg(rgb);
    r[x] = v.y;
    g[x] = v.co;
    b[x] = v.cg;
  }
}

/// The rest of a row's step, every pixel at once: ClipToBox of the history (when `clip`),
/// the blend with the current YCoCg (cy, cco, ccg: the padded plane rows, texel x at x + 1),
/// FromYCoCg and the clamp, exactly as StepReference; pixels without history (previous
/// position outside [0, fw] × [0, fh] or NaN) take the current linear colour (cr, cg, cb,
/// planar). Writes the new history (3 floats per pixel) and the planar output colour for
/// the encode. The scalar form of taa_sse2.h's HistoryBlendRow4 (with LerpRow and
/// HistoryYccRow): builds without SSE2 and the last W mod 4 pixels of a row.
struct RowIn {
  const float *hy, *hco, *hcg;  // history in YCoCg
  const float *lo[3], *hi[3];   // the box (when clip)
  const float *cy, *cco, *ccg;  // current YCoCg, padded
  const float *cr, *cg, *cb;    // current linear RGB, planar
  const float* prev;            // previous positions, x and y per pixel
  float fw, fh;                 // the frame's size
};
// std::clamp(v, 0, 1) as selects: v < 0 ? 0 : (1 < v ? 1 : v).
inline float Clamp01(float v) { return v < 0.0f ? 0.0f : (1.0f < v ? 1.0f : v); }

template <bool kClip>
AALAB_TAA_CLONES void BlendRow(const RowIn& in, int w, float alpha, float* __restrict next, float* __restrict outr,
                               float* __restrict outg, float* __restrict outb) {
  for (int x = 0; x < w; ++x) {
    float h[3] = {in.hy[x], in.hco[x], in.hcg[x]};
    if constexpr (kClip) {
      float centre[3], v[3], m = 0.0f;
      for (int c = 0; c < 3; ++c) {
        centre[c] = 0.5f * (in.hi[c][x] + in.lo[c][x]);
        const float ext = 0.5f * (in.hi[c][x] - in.lo[c][x]) + 1e-8f;
        v[c] = h[c] - centre[c];
        m = Max(m, std::fabs(v[c] / ext));
      }
      const bool inside = m <= 1.0f;
      const float div = inside ? 1.0f : m;  // every lane divides (by 1 where the result is unused)
      for (int c = 0; c < 3; ++c) {
        const float moved = centre[c] + v[c] / div;
        h[c] = inside ? h[c] : moved;
      }
    }
    const float oy = h[0] + alpha * (in.cy[x + 1] - h[0]);
    const float oco = h[1] + alpha * (in.cco[x + 1] - h[1]);
    const float ocg = h[2] + alpha * (in.ccg[x + 1] - h[2]);
    const float t = oy - ocg;
    const float px = in.prev[2 * x], py = in.prev[2 * x + 1];
    const bool ok = px >= 0.0f && px <= in.fw && py >= 0.0f && py <= in.fh;
    const float c0 = in.cr[x], c1 = in.cg[x], c2 = in.cb[x];
    const float o[3] = {ok ? Clamp01(t + oco) : c0, ok ? Clamp01(oy + ocg) : c1, ok ? Clamp01(t - oco) : c2};
    for (int c = 0; c < 3; ++c) next[3 * x + c] = o[c];
    outr[x] = o[0];
    outg[x] = o[1];
    outb[x] = o[2];
  }
}

class TaaState : public TemporalState {
 public:
  explicit TaaState(TaaParams p) : p_(p) {
    for (int i = 0; i < 256; ++i) decode_[static_cast<size_t>(i)] = SrgbDecode8(static_cast<uint8_t>(i));
  }

  std::unique_ptr<TemporalState> Clone() const override { return std::make_unique<TaaState>(*this); }

  /// Makes Step run StepReference (the simple implementation) instead of StepFast.
  void UseReference() { reference_ = true; }

  /// The history's 3 floats per pixel (without StepFast's padding).
  std::vector<float> History() const {
    if (history_.empty()) return {};
    return {history_.begin(), history_.begin() + 3 * static_cast<ptrdiff_t>(hist_w_) * hist_h_};
  }

  Image8 Step(const TemporalInput& in, PostStats* stats) override {
    AALAB_CHECK(in.frame != nullptr, "TAA needs a frame");
    return reference_ ? StepReference(in, stats) : StepFast(in, stats);
  }

 private:
  bool HaveHistory(const TemporalInput& in, int W, int H) const {
    const size_t n = static_cast<size_t>(W) * static_cast<size_t>(H);
    return !history_.empty() && hist_w_ == W && hist_h_ == H && in.previous && in.previous->size() == 2 * n;
  }

  /// The production step: the same values as StepReference, bit for bit, organised for a
  /// CPU. Per chunk of kChunkRows rows, the current frame's YCoCg goes into three padded
  /// planes (one replicated texel on each side, so the clamped 3×3 neighbourhood is plain
  /// reads). Each row then runs, where the CPU has them, the AVX-512 kernel on 16-pixel
  /// blocks (box, footprint, fetch, clip, blend, history and encoded output in registers)
  /// and the AVX2 kernel on 8-pixel blocks (the same, with the boxes from BoxRow):
  /// taa_avx2.h. The rest of the row: the boxes (BoxRow), the footprints (FootprintRow),
  /// the SSE2 kernel on 4-pixel blocks (taa_sse2.h), the scalar LerpRow, HistoryYccRow and
  /// BlendRow for the last W mod 4 pixels (all of the row without SSE2), then the encode
  /// (Encode8::Rgba). tests/motion/taa_test.cpp compares the two, output and history.
  static constexpr int kChunkRows = 16;
  Image8 StepFast(const TemporalInput& in, PostStats* stats) {
    const Image8& f = *in.frame;
    const int W = f.Width(), H = f.Height();
    const size_t n = static_cast<size_t>(W) * static_cast<size_t>(H);
    if (3 * n > static_cast<size_t>(INT32_MAX)) return StepReference(in, stats);  // FootprintRow's int offsets
    const size_t pw = static_cast<size_t>(W) + 2;
    const bool have_history = HaveHistory(in, W, H);
    const bool clip = p_.clip != Clip::kNone;
    // One float past the pixels: taa_sse2.h loads a texel's RGB as 4 floats (the history
    // becomes next_ on the next step; a history made by StepReference is padded here).
    next_.resize(3 * n + 1);
    if (have_history && history_.size() < 3 * n + 1) history_.resize(3 * n + 1);
    Image8 result(W, H, 4, kUninitialized);  // every byte written below (alpha 255)
    const Encode8& encode = Encoder();
    ParallelForChunks(H, kChunkRows, [&](int y0, int y1) {
      // Row buffers, written whole before they are read (no fill): the history in YCoCg, the
      // box (3 + 3), the output colour (3), the current colour (3), the footprint.
      const size_t w = static_cast<size_t>(W);
      // The current frame's YCoCg for the chunk's rows and the one above and below it (when
      // inside the frame): three padded planes, local row r = frame row ya + r, held in a
      // ring of three rows (slot r mod 3). Each row is made just before the first frame row
      // that reads it, so that the planes are read back from the cache, not from memory (2
      // rows in kChunkRows made twice).
      const int ya = std::max(y0 - 1, 0);
      constexpr size_t kRing = 3;  // rows y − 1, y and y + 1
      const size_t prow = have_history ? kRing : 0;
      const size_t pn = prow * pw;  // one plane
      const auto pbuf = std::make_unique_for_overwrite<float[]>(3 * pn);
      const float* plane[3] = {pbuf.get(), pbuf.get() + pn, pbuf.get() + 2 * pn};
      size_t made = 0;  // plane rows made so far
      auto make_plane_row = [&](size_t r) {
        const size_t slot = (r % kRing) * pw;
        float* py = pbuf.get() + slot;
        float* pco = py + pn;
        float* pcg = pco + pn;
        const uint8_t* src = f.Row(ya + static_cast<int>(r));
        // With AVX2 eight pixels at a time (gathers); the rest linear RGB first (table
        // reads), then YCoCg in place (a vectorised loop).
        const int d = YccPlaneRowAvx2(src, W, decode_.data(), py + 1, pco + 1, pcg + 1);
        for (int x = d; x < W; ++x) {
          py[x + 1] = decode_[src[4 * x]];
          pco[x + 1] = decode_[src[4 * x + 1]];
          pcg[x + 1] = decode_[src[4 * x + 2]];
        }
        HistoryYccRow(W - d, py + 1 + d, pco + 1 + d, pcg + 1 + d);
        for (float* p : {py, pco, pcg}) {
          p[0] = p[1];
          p[W + 1] = p[W];
        }
      };
      const auto buf = std::make_unique_for_overwrite<float[]>(17 * w + 2 * (w + 2));
      const auto off = std::make_unique_for_overwrite<int32_t[]>(4 * w);
      float* hy = buf.get();
      float* hco = hy + w;
      float* hcg = hco + w;
      float* lo[3] = {hcg + w, hcg + 2 * w, hcg + 3 * w};
      float* hi[3] = {hcg + 4 * w, hcg + 5 * w, hcg + 6 * w};
      float* outc[3] = {hcg + 7 * w, hcg + 8 * w, hcg + 9 * w};
      float* cur[3] = {hcg + 10 * w, hcg + 11 * w, hcg + 12 * w};
      float* tx = hcg + 13 * w;
      float* ty = hcg + 14 * w;
      float* cmn = hcg + 15 * w;  // BoxRow's scratch, w + 2 floats each
      float* cmx = cmn + w + 2;
      for (int y = y0; y < y1; ++y) {
        const uint8_t* src = f.Row(y);
        // The current linear colour of pixels [x0, W) into cur (the SSE2 kernel decodes its
        // own, only where a pixel has no history).
        auto decode_from = [&](int x0) {
          for (int x = x0; x < W; ++x) {
            for (int c = 0; c < 3; ++c) cur[c][x] = decode_[src[4 * x + c]];
          }
        };
        float* next = &next_[3 * static_cast<size_t>(y) * W];
        uint8_t* row = result.Row(y);
        if (!have_history) {
          decode_from(0);
          for (int x = 0; x < W; ++x) {
            for (int c = 0; c < 3; ++c) next[3 * x + c] = cur[c][x];
          }
          encode.Rgba(cur[0], cur[1], cur[2], W, row);
          continue;
        }
        for (const size_t last = static_cast<size_t>(std::min(y + 1, H - 1) - ya); made <= last; ++made) {
          make_plane_row(made);
        }
        const float* prev = &(*in.previous)[2 * static_cast<size_t>(y) * W];
        const size_t rm = static_cast<size_t>(std::max(y - 1, 0) - ya) % kRing * pw,
                     rc = static_cast<size_t>(y - ya) % kRing * pw,
                     rp = static_cast<size_t>(std::min(y + 1, H - 1) - ya) % kRing * pw;
        // The boxes of pixels [wide, W): the AVX-512 kernel forms those of [0, wide) itself.
        const int wide = TaaHasAvx512() ? W - W % 16 : 0;
        if (clip && wide < W) {
          for (int c = 0; c < 3; ++c) {
            const float* pl = plane[c] + wide;
            if (p_.clip == Clip::kVariance) {
              BoxRow<true>(pl + rm, pl + rc, pl + rp, W - wide, p_.gamma, cmn, cmx, lo[c] + wide, hi[c] + wide);
            } else {
              BoxRow<false>(pl + rm, pl + rc, pl + rp, W - wide, p_.gamma, cmn, cmx, lo[c] + wide, hi[c] + wide);
            }
          }
        }
        const float fw = static_cast<float>(W), fh = static_cast<float>(H);
        // Pixels [0, avx) finished by the AVX2 kernel (footprint, fetch, clip, blend, history
        // and encoded output), [avx, done) by the SSE2 kernel, the rest by the scalar rows.
        const Avx2RowIn ai{history_.data(),
                           prev,
                           W,
                           H,
                           {lo[0], lo[1], lo[2]},
                           {hi[0], hi[1], hi[2]},
                           plane[0] + rc,
                           plane[1] + rc,
                           plane[2] + rc,
                           src,
                           decode_.data(),
                           encode.Tables(),
                           {{plane[0] + rm, plane[0] + rc, plane[0] + rp},
                            {plane[1] + rm, plane[1] + rc, plane[1] + rp},
                            {plane[2] + rm, plane[2] + rc, plane[2] + rp}},
                           p_.clip == Clip::kVariance,
                           p_.gamma};
        const int avx = HistoryBlendRow8Avx2(ai, W, clip, p_.alpha, next, row);
        int done = avx;
        if (avx == W) continue;
        FootprintRow(prev + 2 * avx, W - avx, W, H, tx + avx, ty + avx, off.get() + 4 * static_cast<size_t>(avx));
#if defined(__SSE2__)
        done = W - W % 4;
        const Sse2RowIn si{history_.data(),
                           tx,
                           ty,
                           off.get(),
                           prev,
                           fw,
                           fh,
                           {lo[0], lo[1], lo[2]},
                           {hi[0], hi[1], hi[2]},
                           plane[0] + rc,
                           plane[1] + rc,
                           plane[2] + rc,
                           src,
                           decode_.data()};
        if (clip) {
          HistoryBlendRow4<true>(si, avx, done, p_.alpha, next, outc[0], outc[1], outc[2]);
        } else {
          HistoryBlendRow4<false>(si, avx, done, p_.alpha, next, outc[0], outc[1], outc[2]);
        }
#endif
        if (done < W) {
          // FetchHistory and ToYCoCg for the rest of the row (all of it without SSE2): the
          // gather and lerps (scalar), YCoCg (vectorised); then the clip and blend.
          const int d = done, rest = W - done;
          decode_from(d);
          LerpRow(history_.data(), tx + d, ty + d, off.get() + 4 * d, rest, hy + d, hco + d, hcg + d);
          HistoryYccRow(rest, hy + d, hco + d, hcg + d);
          RowIn ri{hy + d,
                   hco + d,
                   hcg + d,
                   {lo[0] + d, lo[1] + d, lo[2] + d},
                   {hi[0] + d, hi[1] + d, hi[2] + d},
                   plane[0] + rc + d,
                   plane[1] + rc + d,
                   plane[2] + rc + d,
                   cur[0] + d,
                   cur[1] + d,
                   cur[2] + d,
                   prev + 2 * d,
                   fw,
                   fh};
          float* nd = next + 3 * d;
          if (clip) {
            BlendRow<true>(ri, rest, p_.alpha, nd, outc[0] + d, outc[1] + d, outc[2] + d);
          } else {
            BlendRow<false>(ri, rest, p_.alpha, nd, outc[0] + d, outc[1] + d, outc[2] + d);
          }
        }
        encode.Rgba(outc[0] + avx, outc[1] + avx, outc[2] + avx, W - avx, row + 4 * static_cast<size_t>(avx));
      }
    });
    history_.swap(next_);
    hist_w_ = W;
    hist_h_ = H;
    if (stats) stats->taps += static_cast<uint64_t>(n) * (have_history ? 13u : 1u);  // 9 neighbours + 4 history texels
    return result;
  }

  /// The simple implementation of the step (one loop nest per pass, per pixel), kept as the
  /// reference StepFast is tested against.
  Image8 StepReference(const TemporalInput& in, PostStats* stats) {
    const Image8& f = *in.frame;
    const int W = f.Width(), H = f.Height();
    const size_t n = static_cast<size_t>(W) * static_cast<size_t>(H);
    // Current frame: linear RGB and YCoCg (buffers reused from frame to frame).
    cur_.resize(3 * n);
    ycc_.resize(n);
    ParallelFor(H, [&](int y) {
      for (int x = 0; x < W; ++x) {
        const size_t i = static_cast<size_t>(y) * W + x;
        const uint8_t* px = f.Pixel(x, y);
        for (int c = 0; c < 3; ++c) cur_[3 * i + c] = decode_[px[c]];
        ycc_[i] = ToYCoCg(&cur_[3 * i]);
      }
    });
    const bool have_history = HaveHistory(in, W, H);
    next_.resize(3 * n);
    Image8 result(W, H, 4, 255);
    const Encode8& encode = Encoder();
    ParallelFor(H, [&](int y) {
      uint8_t* row = result.Pixel(0, y);
      for (int x = 0; x < W; ++x) {
        const size_t i = static_cast<size_t>(y) * W + x;
        float* out = &next_[3 * i];
        const float* c = &cur_[3 * i];
        const float px = have_history ? (*in.previous)[2 * i] : 0.0f;
        const float py = have_history ? (*in.previous)[2 * i + 1] : 0.0f;
        if (!have_history ||
            !(px >= 0.0f && px <= static_cast<float>(W) && py >= 0.0f && py <= static_cast<float>(H))) {
          std::copy(c, c + 3, out);
        } else {
          float h[3];
          FetchHistory(px, py, h);
          Ycc hy = ToYCoCg(h);
          if (p_.clip != Clip::kNone) hy = Rectify(hy, x, y, W, H, ycc_);
          const Ycc cy = ycc_[i];
          const Ycc o{hy.y + p_.alpha * (cy.y - hy.y), hy.co + p_.alpha * (cy.co - hy.co),
                      hy.cg + p_.alpha * (cy.cg - hy.cg)};
          FromYCoCg(o, out);
          for (int k = 0; k < 3; ++k) out[k] = std::clamp(out[k], 0.0f, 1.0f);
        }
        for (int k = 0; k < 3; ++k) row[4 * x + k] = encode(out[k]);
      }
    });
    history_.swap(next_);
    hist_w_ = W;
    hist_h_ = H;
    if (stats) stats->taps += static_cast<uint64_t>(n) * (have_history ? 13u : 1u);  // 9 neighbours + 4 history texels
    return result;
  }

  /// Bilinear fetch of the history at continuous pixel position (px, py), clamp to edge.
  void FetchHistory(float px, float py, float* out) const {
    const float fx = px - 0.5f, fy = py - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float tx = fx - x0f, ty = fy - y0f;
    const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
    // Clamp to edge once per fetch (the four texels), then the same lerps per channel.
    const int xa = std::clamp(x0, 0, hist_w_ - 1), xb = std::clamp(x0 + 1, 0, hist_w_ - 1);
    const int ya = std::clamp(y0, 0, hist_h_ - 1), yb = std::clamp(y0 + 1, 0, hist_h_ - 1);
    const float* r0 = &history_[3 * static_cast<size_t>(ya) * hist_w_];
    const float* r1 = &history_[3 * static_cast<size_t>(yb) * hist_w_];
    const float *a = r0 + 3 * xa, *b = r0 + 3 * xb, *c0 = r1 + 3 * xa, *d = r1 + 3 * xb;
    for (int c = 0; c < 3; ++c) {
      const float top = a[c] + tx * (b[c] - a[c]);
      const float bot = c0[c] + tx * (d[c] - c0[c]);
      out[c] = top + ty * (bot - top);
    }
  }

  /// Clips the history into the box of the 3×3 neighbourhood of (x, y) in YCoCg.
  Ycc Rectify(Ycc h, int x, int y, int W, int H, const std::vector<Ycc>& ycc) const {
    float mn[3] = {1e30f, 1e30f, 1e30f}, mx[3] = {-1e30f, -1e30f, -1e30f};
    float m1[3] = {0, 0, 0}, m2[3] = {0, 0, 0};
    const int xs[3] = {std::max(x - 1, 0), x, std::min(x + 1, W - 1)};  // clamped once
    for (int dy = -1; dy <= 1; ++dy) {
      const Ycc* row = &ycc[static_cast<size_t>(std::clamp(y + dy, 0, H - 1)) * W];
      for (int dx = 0; dx < 3; ++dx) {
        AddToBox(row[xs[dx]], mn, mx, m1, m2);
      }
    }
    if (p_.clip == Clip::kVariance) NarrowToVariance(mn, mx, m1, m2, p_.gamma);
    return ClipToBox(h, mn, mx);
  }

  TaaParams p_;
  bool reference_ = false;
  std::array<float, 256> decode_{};
  // Buffers every step writes whole before reading: resized without a fill.
  using Floats = std::vector<float, DefaultInitAllocator<float>>;
  Floats history_;  ///< linear display RGB, 3 floats per pixel (StepFast: + 1 float of padding)
  int hist_w_ = 0, hist_h_ = 0;
  // Per-frame working buffers (not state: reused only to avoid reallocating every frame).
  std::vector<float> cur_;
  Floats next_;
  std::vector<Ycc> ycc_;
};

Clip ParseClip(const std::string& name) {
  if (name == "variance") return Clip::kVariance;
  if (name == "minmax") return Clip::kMinMax;
  if (name == "none") return Clip::kNone;
  throw UserError("unknown clip '" + name + "' (allowed: variance, minmax, none)");
}

}  // namespace

std::unique_ptr<TemporalState> TaaReferenceCopy(const TemporalState& taa_state) {
  const auto* t = dynamic_cast<const TaaState*>(&taa_state);
  AALAB_CHECK(t != nullptr, "TaaReferenceCopy needs a TAA state");
  auto copy = std::make_unique<TaaState>(*t);
  copy->UseReference();
  return copy;
}

std::vector<float> TaaHistory(const TemporalState& taa_state) {
  const auto* t = dynamic_cast<const TaaState*>(&taa_state);
  AALAB_CHECK(t != nullptr, "TaaHistory needs a TAA state");
  return t->History();
}

std::vector<MethodEntry> TaaMethods() {
  std::vector<MethodEntry> out;
  out.push_back(
      {"taa",
       "temporal AA: Halton(2,3) jitter, exact reprojection, YCoCg variance clip, exponential blend (needs --frames > "
       "1 to accumulate)",
       {IntParam("samples", 16, 1, 256, "Halton(2,3) jitter points cycled (indices 1..samples)"),
        FloatParam("alpha", 0.1, 0.01, 1.0, "weight of the current frame in the exponential blend"),
        ChoiceParam("clip", "variance", {"variance", "minmax", "none"},
                    "history rectification against the 3x3 neighbourhood in YCoCg"),
        FloatParam("gamma", 1.0, 0.25, 4.0, "variance box half-width in standard deviations (clip=variance)")},
       [](const ParamValues& p) {
         MethodPlan plan;
         plan.render.jitter.samples = p.Int("samples");
         TaaParams tp;
         tp.alpha = static_cast<float>(p.Number("alpha"));
         tp.gamma = static_cast<float>(p.Number("gamma"));
         tp.clip = ParseClip(p.Choice("clip"));
         plan.make_state = [tp] { return std::unique_ptr<TemporalState>(std::make_unique<TaaState>(tp)); };
         return plan;
       }});
  return out;
}

}  // namespace aalab
