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
// A band that holds more than 1/kEdgeShare of the frame's edge pixels is cut into column
// pieces, run as separate jobs: on edge-dense frames a few bands near a horizon hold most of
// the work (checker-plane at 1080p, ultra: one band 25 % of the pass, 9 pieces here), which
// whole bands cannot share between two threads. The weights and the blend of a pixel do not
// depend on the split; a piece also computes, untallied, the weights of column x1 (the right
// neighbour its last column's blend reads), as a band does for the row below it. The split
// is fixed by the edge lists alone (FusedJobs), never by the thread count.
constexpr int kEdgeShare = 32;
constexpr int kMinPieceCols = 128;

struct FusedJob {
  const Image8* in;
  Image8* out;
  const EdgePlane* edges;
  const SmaaParams* p;
};

// The index range [*b, *e) of row y's edge list holding the columns [x0, x1) (lists ascend).
inline void ListRange(const EdgePlane& edges, int y, int x0, int x1, int* b, int* e) {
  const uint16_t* xs = edges.List(y);
  const uint16_t* end = xs + edges.n[static_cast<size_t>(y)];
  const uint16_t* lo = std::lower_bound(xs, end, x0);
  *b = static_cast<int>(lo - xs);
  *e = static_cast<int>(std::lower_bound(lo, end, x1) - xs);
}

// The weights of row y's edge pixels i0 .. i1 − 1 (of its list) into wr (4 bytes per pixel;
// the other bytes stay 0). `plain` is the shader with the diagonal search off: it runs the
// pixels without a top edge (which never reach the diagonal search) and those for which
// DiagSurelyZero settles the search as (0, 0) (then the shader takes the orthogonal branch, as
// `plain` does; the search's fetches are counted); `full` runs the others.
template <class Shader>
[[gnu::always_inline]] inline void WeightsRow(Shader& full, Shader& plain, PlaneEdges& reader, bool diag,
                                              const EdgePlane& edges, int y, int i0, int i1, uint8_t* wr) {
  const uint16_t* xs = edges.List(y);
  const uint8_t* er = edges.Row(y);
  for (int i = i0; i < i1; ++i) {
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
// Only the list entries i0 .. i1 − 1 (the piece's columns).
[[gnu::always_inline]] inline void PrefetchBlendRows(const FusedJob& job, const EdgePlane& edges, int y, int i0,
                                                     int i1) {
  if (i0 >= i1) return;
  const int h = edges.h;
  const uint16_t* xs = edges.List(y);
  const uint8_t* r0 = job.in->Row(std::max(y - 1, 0));
  const uint8_t* r1 = job.in->Row(y);
  const uint8_t* r2 = job.in->Row(std::min(y + 1, h - 1));
  const uint8_t* o0 = job.out->Row(std::max(y - 1, 0));
  const uint8_t* o1 = job.out->Row(y);
  uintptr_t last = 0;
  for (int i = i0; i < i1; ++i) {
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

// Rows y0 .. y1 − 1, columns x0 .. x1 − 1 of passes 2 and 3.
AALAB_SMAA_BAND void FusedBand(const FusedJob& job, int y0, int y1, int x0, int x1, uint64_t* taps) {
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
  // Two weight rows and the candidate marks, per thread, kept between pieces: the piece's
  // columns x0 .. x1 (x1 for the right neighbour's weights) are cleared here and every byte a
  // piece writes in them is cleared again before it ends, or here by the next piece.
  thread_local std::vector<uint8_t> rows, mark;
  thread_local std::vector<uint16_t> cand;
  if (rows.size() < 8 * static_cast<size_t>(w))
    rows.resize(8 * static_cast<size_t>(w)), mark.resize(static_cast<size_t>(w)), cand.resize(static_cast<size_t>(w));
  const int xe = std::min(x1 + 1, w);  // weight columns x0 .. xe − 1
  uint8_t* cur = rows.data();
  uint8_t* nxt = cur + 4 * static_cast<size_t>(w);
  std::memset(cur + 4 * x0, 0, 4 * static_cast<size_t>(xe - x0));
  std::memset(nxt + 4 * x0, 0, 4 * static_cast<size_t>(xe - x0));
  std::memset(mark.data() + x0, 0, static_cast<size_t>(x1 - x0));
  auto taps_now = [&] { return reader.Taps() + as.Taps() + ss.Taps(); };
  uint64_t n = 0;
  // Row y's weights of the piece's columns (tallied when `tally`), then those of column x1
  // when listed (never tallied: its own piece tallies them).
  auto weights = [&](int y, uint8_t* wr, bool tally) {
    int b, e;
    ListRange(edges, y, x0, xe, &b, &e);
    const int own = e > b && edges.List(y)[e - 1] == x1 ? e - 1 : e;
    const uint64_t before = taps_now();
    WeightsRow(shader, plain, reader, diag, edges, y, b, own, wr);
    if (tally) n += taps_now() - before;
    WeightsRow(shader, plain, reader, diag, edges, y, own, e, wr);
  };
  weights(y0, cur, true);
  for (int y = y0; y < y1; ++y) {
    if (y + 1 < h) {
      int pb, pe;
      ListRange(edges, y + 1, x0, xe, &pb, &pe);
      PrefetchBlendRows(job, edges, y + 1, pb, pe);
      weights(y + 1, nxt, y + 1 < y1);  // row y + 1's own taps only inside the band
    }
    const uint8_t* below = y + 1 < h ? nxt : cur;
    int b, e, bb, be;
    ListRange(edges, y, x0, xe, &b, &e);  // entries b .. e − 1, x1's included
    const uint16_t* xs = edges.List(y);
    const int own = e > b && xs[e - 1] == x1 ? e - 1 : e;
    n += static_cast<uint64_t>(x1 - x0 - (own - b));  // pass 2: one fetch per pixel without an edge
    // Pass 3's candidates in x0 .. x1 − 1: own.r or own.b (x), right.a (x − 1; x itself at
    // the clamped last column), bottom.g (x).
    int nc = 0;
    auto add = [&](int x) {
      if (!mark[static_cast<size_t>(x)])
        mark[static_cast<size_t>(x)] = 1, cand[static_cast<size_t>(nc++)] = static_cast<uint16_t>(x);
    };
    for (int i = b; i < e; ++i) {
      const int x = xs[i];
      const uint8_t* o = cur + 4 * x;
      if (o[3] && x > x0) add(x - 1);
      if (x < x1 && (o[0] | o[2] | (o[3] && x == w - 1))) add(x);
    }
    ListRange(edges, std::min(y + 1, h - 1), x0, x1, &bb, &be);
    const uint16_t* xb = edges.List(std::min(y + 1, h - 1));
    for (int i = bb; i < be; ++i) {
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
    n += 4 * static_cast<uint64_t>(x1 - x0) - static_cast<uint64_t>(nc) + (cs.Taps() - colour_before);
    for (int i = b; i < e; ++i) std::memset(cur + 4 * xs[i], 0, 4);  // row y's weights are done
    std::swap(cur, nxt);
  }
  *taps = n;
}

// One job of the fused pass: rows y0 .. y1 − 1, columns x0 .. x1 − 1.
struct Piece {
  int y0, y1, x0, x1;
};

// The fused pass's jobs, in band order: a band of e edge pixels out of the frame's total
// becomes 1 + e · kEdgeShare / total pieces of equal width (at most w / kMinPieceCols).
std::vector<Piece> FusedJobs(const EdgePlane& edges) {
  const int w = edges.w, h = edges.h;
  uint64_t total = 0;
  for (int y = 0; y < h; ++y) total += static_cast<uint64_t>(edges.n[static_cast<size_t>(y)]);
  const int max_pieces = std::max(1, w / kMinPieceCols);
  std::vector<Piece> jobs;
  for (int y0 = 0; y0 < h; y0 += kBand) {
    const int y1 = std::min(y0 + kBand, h);
    uint64_t e = 0;
    for (int y = y0; y < y1; ++y) e += static_cast<uint64_t>(edges.n[static_cast<size_t>(y)]);
    const uint64_t want = total == 0 ? 1 : 1 + e * kEdgeShare / total;
    const int pieces = static_cast<int>(std::min<uint64_t>(want, static_cast<uint64_t>(max_pieces)));
    const int cols = (w + pieces - 1) / pieces;
    for (int x0 = 0; x0 < w; x0 += cols) jobs.push_back({y0, y1, x0, std::min(x0 + cols, w)});
  }
  return jobs;
}

}  // namespace

// Passes 2 and 3 through FusedBand, the jobs of FusedJobs in parallel.
void WeightsAndBlendFused(const Image8& in, const EdgePlane& edges, const SmaaParams& p, Image8* out, uint64_t* taps) {
  const FusedJob job{&in, out, &edges, &p};
  const std::vector<Piece> jobs = FusedJobs(edges);
  std::vector<uint64_t> t(jobs.size(), 0);
  ParallelFor(static_cast<int>(jobs.size()), [&](int j) {
    const Piece& q = jobs[static_cast<size_t>(j)];
    FusedBand(job, q.y0, q.y1, q.x0, q.x1, &t[static_cast<size_t>(j)]);
  });
  for (uint64_t v : t) *taps += v;
}

}  // namespace aalab::smaa_internal
