// SMAA 1x passes 2 and 3 fused, for the production path (methods/smaa_fast.cpp: the rules
// and the proofs are in its top block, "Passes 2 and 3 fused"). Same bits and taps as
// SmaaReference (tests/equivalence/smaa_fast_test.cpp).
#include <algorithm>
#include <cstring>
#include <vector>

#include "core/parallel.h"
#include "methods/smaa_fast.h"

namespace aalab::smaa_internal {

namespace {

using smaa_detail::Frame;

// Passes 2 and 3 fused, for 8-bit sub-texel fetches on frames up to kMaxShortcutSize (where
// a pixel's weights can be non-zero only if it has an edge bit, and a pixel blends only if
// own.r, own.b, right.a or bottom.g is non-zero: WeightsFast and BlendFlags). A band of
// kBand rows computes the weights of its rows' listed edge pixels (and of the row below it,
// again, untallied: the next band's first row) into two scratch rows, row by row; once the
// weights of rows y and y + 1 are final, row y of the output is the input row (alpha 255)
// with only the pixels that blend run through BlendColor. No full-frame blend texture, no
// zero-fill, no walk over pixels without edges. Taps as the two passes count them: pass 2
// one fetch per pixel without an edge, pass 3 four per pixel that does not blend and three
// plus its colour fetches per pixel that does.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_SMAA_BAND __attribute__((target_clones("avx2", "default"), flatten))
#else
#define AALAB_SMAA_BAND
#endif
constexpr int kBand = 32;

struct FusedJob {
  const Image8* in;
  Image8* out;
  const EdgePlane* edges;
  const SmaaParams* p;
};

// The weights of row y's edge pixels into wr (4 bytes per pixel; the other bytes stay 0).
// `plain` is the shader with the diagonal search off: it runs the pixels without a top edge
// (which never reach the diagonal search) and those for which DiagSurelyZero settles the
// search as (0, 0) (then the shader takes the orthogonal branch, as `plain` does; the
// search's fetches are counted); `full` runs the others.
template <class Shader>
[[gnu::always_inline]] inline void WeightsRow(Shader& full, Shader& plain, PlaneEdges& reader, bool diag,
                                              const EdgePlane& edges, int y, uint8_t* wr) {
  const uint16_t* xs = edges.List(y);
  const uint8_t* er = edges.Row(y);
  const int n = edges.n[static_cast<size_t>(y)];
  for (int i = 0; i < n; ++i) {
    const int x = xs[i];
    int dt = 0;
    const bool settled = !diag || !(er[x] & kTop) || DiagSurelyZero(edges, x, y, &dt);
    reader.CountTaps(dt);
    const Float4 wt = settled ? plain.Run(x, y) : full.Run(x, y);
    uint8_t* o = wr + 4 * x;
    o[0] = smaa_internal::Quantize8(wt.r);
    o[1] = smaa_internal::Quantize8(wt.g);
    o[2] = smaa_internal::Quantize8(wt.b);
    o[3] = smaa_internal::Quantize8(wt.a);
  }
}

// Pass 1 finished the whole frame before this pass, so the input and output rows a blending
// pixel reads and writes are long out of cache: for the listed edge pixels of row y (those
// that can make pixels of rows y − 1 and y blend), one prefetch per 64-byte line of the
// colour rows y − 1 .. y + 1 and the output rows y − 1 and y, issued before row y's weights
// are computed, so that the lines arrive while the searches run. Prefetches change no value.
[[gnu::always_inline]] inline void PrefetchBlendRows(const FusedJob& job, const EdgePlane& edges, int y) {
  const int n = edges.n[static_cast<size_t>(y)];
  if (n == 0) return;
  const int h = edges.h;
  const uint16_t* xs = edges.List(y);
  const uint8_t* r0 = job.in->Row(std::max(y - 1, 0));
  const uint8_t* r1 = job.in->Row(y);
  const uint8_t* r2 = job.in->Row(std::min(y + 1, h - 1));
  const uint8_t* o0 = job.out->Row(std::max(y - 1, 0));
  const uint8_t* o1 = job.out->Row(y);
  uintptr_t last = 0;
  for (int i = 0; i < n; ++i) {
    const size_t off = 4 * static_cast<size_t>(xs[i]);
    const uintptr_t line = reinterpret_cast<uintptr_t>(r1 + off) >> 6;
    if (line == last) continue;
    last = line;
    __builtin_prefetch(r0 + off);
    __builtin_prefetch(r1 + off);
    __builtin_prefetch(r2 + off);
    __builtin_prefetch(o0 + off, 1);
    __builtin_prefetch(o1 + off, 1);
  }
}

AALAB_SMAA_BAND void FusedBand(const FusedJob& job, int y0, int y1, uint64_t* taps) {
  const Image8& in = *job.in;
  const EdgePlane& edges = *job.edges;
  const int w = in.Width(), h = in.Height();
  const Frame f(w, h);
  PlaneEdges reader(edges, job.p->subtexel);
  InlineSampler as(Tex8(SmaaAreaTexture()), job.p->subtexel), ss(Tex8(SmaaSearchTexture()), job.p->subtexel);
  InlineSampler cs(Tex8(in), job.p->subtexel);
  // The area and search fetches repeat within a frame and across frames: one table each per
  // thread, kept between bands and calls (MemoTable).
  thread_local MemoTable<11> area_memo, search_memo;
  MemoSampler<11> am(as, area_memo), sm(ss, search_memo);
  smaa_detail::WeightsShader<PlaneEdges, MemoSampler<11>> shader(reader, am, sm, *job.p, f);
  // The same shader with the diagonal search off; diag = whether the preset has it and
  // DiagSurelyZero applies (max_search_steps_diag >= 1).
  SmaaParams plain_params = *job.p;
  plain_params.diag = false;
  const bool diag = job.p->diag && job.p->max_search_steps_diag >= 1;
  if (job.p->diag && !diag) plain_params.diag = true;  // no shortcut: both run the full shader
  smaa_detail::WeightsShader<PlaneEdges, MemoSampler<11>> plain(reader, am, sm, plain_params, f);
  std::vector<uint8_t> rows(8 * static_cast<size_t>(w), 0), mark(static_cast<size_t>(w), 0);
  std::vector<uint16_t> cand(static_cast<size_t>(w));
  uint8_t* cur = rows.data();
  uint8_t* nxt = cur + 4 * static_cast<size_t>(w);
  uint64_t n = 0;
  WeightsRow(shader, plain, reader, diag, edges, y0, cur);
  for (int y = y0; y < y1; ++y) {
    if (y + 1 < h) PrefetchBlendRows(job, edges, y + 1);
    const uint64_t before = reader.Taps() + as.Taps() + ss.Taps();
    if (y + 1 < h) WeightsRow(shader, plain, reader, diag, edges, y + 1, nxt);
    if (y + 1 < h && y + 1 < y1) n += reader.Taps() + as.Taps() + ss.Taps() - before;  // row y + 1's own taps
    if (y == y0) n += before;  // row y0's (computed before the loop)
    const uint8_t* below = y + 1 < h ? nxt : cur;
    const int ny = edges.n[static_cast<size_t>(y)], nb = edges.n[static_cast<size_t>(std::min(y + 1, h - 1))];
    n += static_cast<uint64_t>(w - ny);  // pass 2: one fetch per pixel without an edge
    // Pass 3's candidates: own.r or own.b (x), right.a (x − 1; x itself at the clamped last
    // column), bottom.g (x).
    int nc = 0;
    auto add = [&](int x) {
      if (!mark[static_cast<size_t>(x)])
        mark[static_cast<size_t>(x)] = 1, cand[static_cast<size_t>(nc++)] = static_cast<uint16_t>(x);
    };
    const uint16_t* xs = edges.List(y);
    for (int i = 0; i < ny; ++i) {
      const int x = xs[i];
      const uint8_t* o = cur + 4 * x;
      if (o[3] && x > 0) add(x - 1);
      if (o[0] | o[2] | (o[3] && x == w - 1)) add(x);
    }
    const uint16_t* xb = edges.List(std::min(y + 1, h - 1));
    for (int i = 0; i < nb; ++i) {
      if (below[4 * xb[i] + 1]) add(xb[i]);
    }
    uint8_t* dst = job.out->Row(y);  // the input row, alpha 255 (pass 1)
    const uint64_t colour_before = cs.Taps();
    for (int i = 0; i < nc; ++i) {
      const int x = cand[static_cast<size_t>(i)];
      mark[static_cast<size_t>(x)] = 0;
      const int xr = std::min(x + 1, w - 1);
      const float a[4] = {UnormToFloat(cur[4 * xr + 3]), UnormToFloat(below[4 * x + 1]), UnormToFloat(cur[4 * x + 2]),
                          UnormToFloat(cur[4 * x])};
      const Float4 c = smaa_detail::BlendColor(a, cs, f, x, y);  // StoreBlended, inline
      uint8_t* o = dst + 4 * x;
      o[0] = smaa_internal::Quantize8(c.r);
      o[1] = smaa_internal::Quantize8(c.g);
      o[2] = smaa_internal::Quantize8(c.b);
      o[3] = 255;
    }
    n += 4 * static_cast<uint64_t>(w) - static_cast<uint64_t>(nc) + (cs.Taps() - colour_before);
    for (int i = 0; i < ny; ++i) std::memset(cur + 4 * xs[i], 0, 4);  // row y's weights are done
    std::swap(cur, nxt);
  }
  *taps = n;
}

}  // namespace

// Passes 2 and 3 through FusedBand, bands in parallel.
void WeightsAndBlendFused(const Image8& in, const EdgePlane& edges, const SmaaParams& p, Image8* out, uint64_t* taps) {
  const int h = in.Height();
  const FusedJob job{&in, out, &edges, &p};
  std::vector<uint64_t> t(static_cast<size_t>((h + kBand - 1) / kBand), 0);
  ParallelForChunks(h, kBand, [&](int y0, int y1) { FusedBand(job, y0, y1, &t[static_cast<size_t>(y0 / kBand)]); });
  for (uint64_t v : t) *taps += v;
}

}  // namespace aalab::smaa_internal
