// SMAA 1x: the production path (the filter `Smaa` that methods run).
//
// Same shader as SmaaReference in methods/smaa.cpp — same float operations in the same
// order, same fetches, same 8-bit textures — organised for a CPU. Parameters, sources and
// deviations are documented at the top of methods/smaa.cpp.
//   Pass 1, luma detection (the presets): whole rows in SSE2/AVX2 (methods/smaa_rows.cpp):
//     a padded luma row per input row in a four-row ring (the tables' values, computed:
//     UnormToFloat(k)·weight, summed (r + g) + b), then every pixel's six deltas and
//     EdgeBits, with an early exit for vectors where no pixel's left or top delta reaches the
//     threshold; a pixel the shader discards gets 0. The edge texture is one byte per pixel
//     (bit 0 = r, bit 1 = g) plus a flag per row and, for the fused pass, a list per row of
//     the columns with an edge byte.
//   Pass 1, colour detection: a vectorised byte prefilter settles most pixels: when every
//     rgb byte differs from the left and top neighbour by at most m, with m/255 + 1e-5 <
//     threshold, both deltas are below the threshold (colour deltas are within 2e-6 of the
//     exact byte arithmetic) and the shader discards the pixel. The others run EdgePixel's
//     expressions. Same edge bytes.
//   Pass 2: only candidate pixels run the shader (the one definition in smaa_shader.h,
//     reading the edge bytes through PlaneEdges: BilinearSampler's footprint, clamp and
//     weighted sums, texel values 0 or 1, for r and g). A non-candidate's first fetch (the
//     edge texture at its own centre) returns (0, 0), so its weights are 0 after one fetch.
//     Candidates: with 8-bit sub-texel fetches on frames up to 8192 pixels a side, the pixel
//     itself has an edge bit (the own-centre coordinate misses the centre by < 1/1024
//     texel, which the 8-bit fraction rounds away, so the fetch returns the own texel);
//     otherwise any edge bit in its 3×3 block (the fetch's footprint lies there).
//   Pass 3: a row is first copied (input rgb, alpha 255); only candidate pixels run
//     BlendPixel. Candidates: with 8-bit fetches (≤ 8192 px) pixels whose own.r, own.b,
//     right.a or bottom.g is non-zero (the three blend fetches hit those texels exactly);
//     otherwise any non-zero blend byte in the fetches' footprints (rows y−1..y+2, columns
//     x−1..x+2). A non-candidate sees a = 0 and returns the colour fetched at its own
//     centre, which rounds back to its input bytes (its weights put at most ~1e-7 on
//     another texel, far below the 0.5/255 that would change the 8-bit result); above 8192
//     px every pixel runs BlendPixel.
//   Passes 2 and 3 fused (8-bit fetches, frames up to 8192 px, no debug view: every preset
//     in a run): by the two candidate rules above, only listed edge pixels can have non-zero
//     weights and only pixels with own.r, own.b, right.a or bottom.g non-zero blend. Per band
//     of 32 rows: the weights of the listed pixels of row y + 1 into a scratch row (the band's
//     first row before; the row below the band is computed again, untallied), then output row
//     y = the input row (alpha 255, copied by pass 1 while the row is in cache) with only the
//     pixels that blend run through BlendColor (their a[] read from the scratch rows of y
//     and y + 1), then row y's scratch entries cleared. No blend texture, no zero-fill, no walk over pixels without an
//     edge. Taps are tallied as passes 2 and 3 count them (one fetch per pixel without an edge; four per pixel that
//     does not blend, three plus its colour fetches per pixel that does). The 8-bit stores use smaa_rows.h's Quantize8
//     (QuantizeUnorm8's value, inline).
//   InlineSampler is BilinearSampler::SampleNormalized operation for operation, inline, its
//     four channels in the lanes of one SSE2 vector (same operations per lane); PlaneEdges
//     blends the r and g bits likewise. In the fused pass the area and search fetches go
//     through MemoSampler, a direct-mapped table of earlier results keyed by the coordinates'
//     bits (a pure function of them there: fixed textures, 8-bit fractions; one table per
//     texture per thread, kept across bands and calls, emptied for another texture or
//     mode), whose hits return the same floats and count the same taps. The fused pass also
//     prefetches the colour and output lines of a row's edge pixels before their weights.
//   With 8-bit fractions the samplers take the footprint from BilinearAt8 (one rounding per
//     axis; the same texels and weights as BilinearAt). In the fused pass, a pixel with a top
//     edge whose diagonal search DiagSurelyZero settles from the edge bytes (the first step
//     of every diagonal search stops, so the search returns (0, 0)) runs the shader with the
//     diagonal search off, and that search's fetches are counted.
// Tap counts equal the reference's. tests/equivalence/smaa_fast_test.cpp compares this path with
// SmaaReference bit for bit, taps and debug views included, at 1 and 2 threads.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "methods/smaa.h"
#include "methods/row_ops.h"
#include "methods/smaa_fast.h"
#include "methods/smaa_rows.h"
#include "methods/smaa_shader.h"

namespace aalab {

namespace smaa_detail {
Image8 EdgesView(const Image8& edges);
Image8 WeightsView(const Image8& blend);
int ParseView(const std::string& view);
}  // namespace smaa_detail

namespace {

using smaa_detail::F2;
using smaa_detail::Frame;

constexpr int kGrain = 8;
using smaa_internal::EdgePlane;
using smaa_internal::InlineSampler;
using smaa_internal::kLeft;
using smaa_internal::kMaxShortcutSize;
using smaa_internal::kTop;
using smaa_internal::PlaneEdges;
using smaa_internal::Tex8;

// EdgePixel's decision from the six deltas it computes; returns the two edge bits.
struct EdgeInputs {
  float dx, dy, dr, db, dll, dtt;
};
inline uint8_t EdgeBits(const EdgeInputs& d, float thr, float lcf) {
  const bool ex = d.dx >= thr, ey = d.dy >= thr;
  const float mx = std::max(std::max(d.dx, d.dr), d.dll);
  const float my = std::max(std::max(d.dy, d.db), d.dtt);
  const float final_delta = std::max(mx, my);
  return static_cast<uint8_t>((ex && lcf * d.dx >= final_delta ? kLeft : 0) |
                              (ey && lcf * d.dy >= final_delta ? kTop : 0));
}

// The per-channel products of SmaaReference's Luma(Texel): entry k = UnormToFloat(k)·weight.
struct LumaTables {
  float r[256], g[256], b[256];
};
const LumaTables& Lumas() {
  static const LumaTables t = [] {
    LumaTables l{};
    for (int k = 0; k < 256; ++k) {
      const float u = UnormToFloat(k);
      l.r[k] = u * 0.2126f;
      l.g[k] = u * 0.7152f;
      l.b[k] = u * 0.0722f;
    }
    return l;
  }();
  return t;
}

// The largest byte difference m for which every pixel whose three channels differ from
// its left and top neighbours by at most m is certainly discarded (delta < threshold):
// both deltas are at most m/255 plus float rounding (< 2e-6: lumas are sums of products
// k/255·w with weights summing to 1, colour deltas single differences), so we require
// m/255 + 1e-5 < threshold. -1 when no difference is safe (threshold <= 1e-5).
int SafeByteDifference(float thr) {
  int safe = -1;
  for (int m = 0; m < 256; ++m) {
    if (static_cast<double>(m) / 255.0 + 1e-5 < static_cast<double>(thr)) safe = m;
  }
  return safe;
}

// Row prefilter: cand[x] = 1 unless every rgb byte of pixel x differs from the pixel on its
// left and the one above by at most `safe` (then EdgePixel discards it). Vectorisable.
void CandidateRow(const uint8_t* __restrict row, const uint8_t* __restrict top, int w, int safe,
                  uint8_t* __restrict tmp, uint8_t* __restrict cand) {
  const int n = 4 * w;
  const uint8_t s = static_cast<uint8_t>(std::max(safe, 0));
  for (int i = 0; i < n; ++i) {
    const uint8_t a = row[i], t = top[i];
    const uint8_t l = i >= 4 ? row[i - 4] : a;  // the left of column 0 is itself (clamp)
    const uint8_t dl = static_cast<uint8_t>(std::max(a, l) - std::min(a, l));
    const uint8_t dt = static_cast<uint8_t>(std::max(a, t) - std::min(a, t));
    tmp[i] = std::max(dl, dt) > s ? 1 : 0;
  }
  for (int x = 0; x < w; ++x) cand[x] = (tmp[4 * x] | tmp[4 * x + 1] | tmp[4 * x + 2]) != 0 || safe < 0;
}

// Pass 1, luma detection: each chunk of kLumaRows rows computes the luma rows it reads (its
// rows, two above, one below: 35 per 32) once, into a ring of four rows (rows y − 2 .. y + 1,
// slot = row mod 4; every float of a slot is written before it is read, so no fill), then
// every pixel's edge bits and the row's edge list. Same bits and taps as the prefilter path.
constexpr int kLumaRows = 32;
void EdgesLumaRows(const Image8& in, const SmaaParams& p, EdgePlane* plane, Image8* copy, uint64_t* taps) {
  const int w = in.Width(), h = in.Height();
  const size_t stride = static_cast<size_t>(w) + 3;
  std::vector<uint64_t> t(static_cast<size_t>((h + kLumaRows - 1) / kLumaRows), 0);
  ParallelForChunks(h, kLumaRows, [&](int y0, int y1) {
    std::unique_ptr<float[]> buf(new float[4 * stride]);
    auto row = [&](int y) { return buf.get() + static_cast<size_t>(y & 3) * stride; };
    int next = std::max(y0 - 2, 0);  // the first row not yet in the ring
    auto ensure = [&](int last) {
      for (; next <= last; ++next) smaa_internal::LumaRow(in.Row(next), w, row(next));
    };
    uint64_t n = 0;
    for (int y = y0; y < y1; ++y) {
      uint8_t any = 0;
      ensure(std::min(y + 1, h - 1));
      if (copy) CopyRowOpaque(in.Row(y), copy->Row(y), w);  // while the row is in cache
      const int kept = smaa_internal::EdgeRowLuma(row(y), row(std::max(y - 1, 0)), row(std::max(y - 2, 0)),
                                                  row(std::min(y + 1, h - 1)), w, p.threshold, p.local_contrast_factor,
                                                  plane->Row(y), &any);
      n += 3 * static_cast<uint64_t>(w) + 4 * static_cast<uint64_t>(kept);
      plane->row_any[static_cast<size_t>(y)] = any != 0;
      plane->ListRow(y, any != 0);
    }
    t[static_cast<size_t>(y0 / kLumaRows)] = n;
  });
  for (uint64_t v : t) *taps += v;
}

// Pass 1 (both detections): the prefilter settles most pixels (3 fetches, no edge); the
// others run EdgePixel's expressions with values from the tables. Taps: 3 per pixel, 4 more
// where the shader does not discard.
void EdgesFast(const Image8& in, const SmaaParams& p, EdgePlane* plane, Image8* copy, uint64_t* taps) {
  if (p.detection == SmaaParams::Detection::kLuma) return EdgesLumaRows(in, p, plane, copy, taps);
  const int w = in.Width(), h = in.Height();
  std::vector<uint64_t> t(static_cast<size_t>((h + kGrain - 1) / kGrain), 0);
  const float thr = p.threshold, lcf = p.local_contrast_factor;
  const bool luma = p.detection == SmaaParams::Detection::kLuma;
  const int safe = SafeByteDifference(thr);
  const LumaTables& lt = Lumas();
  auto L = [&lt](const uint8_t* q) { return (lt.r[q[0]] + lt.g[q[1]]) + lt.b[q[2]]; };
  auto diff = [](const uint8_t* a, const uint8_t* b) {
    const float r = std::fabs(UnormToFloat(a[0]) - UnormToFloat(b[0]));
    const float g = std::fabs(UnormToFloat(a[1]) - UnormToFloat(b[1]));
    const float bl = std::fabs(UnormToFloat(a[2]) - UnormToFloat(b[2]));
    return std::max(std::max(r, g), bl);
  };
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    std::vector<uint8_t> tmp(4 * static_cast<size_t>(w)), cand(static_cast<size_t>(w));
    uint64_t n = 0;
    for (int y = y0; y < y1; ++y) {
      const uint8_t* r0 = in.Row(y);
      const uint8_t* rt = in.Row(std::max(y - 1, 0));
      const uint8_t* rtt = in.Row(std::max(y - 2, 0));
      const uint8_t* rb = in.Row(std::min(y + 1, h - 1));
      uint8_t* out = plane->Row(y);
      std::memset(out, 0, static_cast<size_t>(w));  // pixels the prefilter settles keep 0
      CandidateRow(r0, rt, w, safe, tmp.data(), cand.data());
      uint64_t kept = 0;
      uint8_t any = 0;
      for (int x = 0; x < w; ++x) {
        if ((x & 7) == 0 && x + 8 <= w) {  // skip 8 settled pixels at a time
          uint64_t word;
          std::memcpy(&word, cand.data() + x, 8);
          if (word == 0) {
            x += 7;
            continue;
          }
        }
        if (!cand[static_cast<size_t>(x)]) continue;
        const uint8_t* C = r0 + 4 * x;
        const uint8_t* Cl = r0 + 4 * std::max(x - 1, 0);
        const uint8_t* Cll = r0 + 4 * std::max(x - 2, 0);
        const uint8_t* Cr = r0 + 4 * std::min(x + 1, w - 1);
        EdgeInputs d;
        if (luma) {
          const float Lc = L(C), Lleft = L(Cl), Ltop = L(rt + 4 * x);
          d = {std::fabs(Lc - Lleft),         std::fabs(Lc - Ltop),      std::fabs(Lc - L(Cr)),
               std::fabs(Lc - L(rb + 4 * x)), std::fabs(Lleft - L(Cll)), std::fabs(Ltop - L(rtt + 4 * x))};
        } else {
          d = {diff(C, Cl), diff(C, rt + 4 * x), diff(C, Cr), diff(C, rb + 4 * x), diff(C, Cll), diff(C, rtt + 4 * x)};
        }
        kept += (d.dx >= thr) | (d.dy >= thr);
        out[x] = EdgeBits(d, thr, lcf);
        any |= out[x];
      }
      n += 3 * static_cast<uint64_t>(w) + 4 * kept;
      plane->row_any[static_cast<size_t>(y)] = any != 0;
      plane->ListRow(y, any != 0);
      if (copy) CopyRowOpaque(r0, copy->Row(y), w);
    }
    t[static_cast<size_t>(y0 / kGrain)] = n;
  });
  for (uint64_t v : t) *taps += v;
}

// The edge plane as the RGBA8 edge texture (r, g = 0 or 255), for the debug view.
Image8 EdgeTextureOf(const EdgePlane& pl) {
  Image8 t(pl.w, pl.h, 4, 0);
  for (size_t i = 0; i < t.PixelCount(); ++i) {
    t.Data()[4 * i] = (pl.e[i] & kLeft) ? 255 : 0;
    t.Data()[4 * i + 1] = (pl.e[i] & kTop) ? 255 : 0;
  }
  return t;
}

// flags[x] = OR of plane bytes over rows y+r0 .. y+r1 and columns x+c0 .. x+c1 (clamped),
// with c0 <= 0 <= c1.
void NeighbourFlags(const uint8_t* plane, int w, int h, int y, int r0, int r1, int c0, int c1, uint8_t* __restrict col,
                    uint8_t* __restrict flags) {
  std::fill(col, col + w, 0);
  for (int dy = r0; dy <= r1; ++dy) {
    const uint8_t* __restrict row = plane + static_cast<size_t>(std::clamp(y + dy, 0, h - 1)) * w;
    for (int x = 0; x < w; ++x) col[x] |= row[x];
  }
  auto clamped = [&](int x) {
    uint8_t any = 0;
    for (int dx = c0; dx <= c1; ++dx) any |= col[std::clamp(x + dx, 0, w - 1)];
    return any;
  };
  const int lo = -c0, hi = w - c1;  // columns whose window needs no clamping: [lo, hi)
  if (lo >= hi) {
    for (int x = 0; x < w; ++x) flags[x] = clamped(x);
    return;
  }
  for (int x = 0; x < lo; ++x) flags[x] = clamped(x);
  std::fill(flags + lo, flags + hi, 0);
  for (int dx = c0; dx <= c1; ++dx) {
    for (int x = lo; x < hi; ++x) flags[x] |= col[x + dx];
  }
  for (int x = hi; x < w; ++x) flags[x] = clamped(x);
}

// True when any of rows y+r0 .. y+r1 (clamped) has its flag set.
bool AnyRow(const std::vector<uint8_t>& row_any, int y, int r0, int r1) {
  const int h = static_cast<int>(row_any.size());
  for (int dy = r0; dy <= r1; ++dy) {
    if (row_any[static_cast<size_t>(std::clamp(y + dy, 0, h - 1))]) return true;
  }
  return false;
}

// The blend texture (RGBA8, as the reference stores it), a byte plane "weights not all 0"
// and per-row flags, for pass 3. The texture and the plane are allocated uninitialised:
// the parallel weights pass clears each row before it writes it (no serial zero-fill).
struct BlendTex {
  int w = 0, h = 0;
  std::unique_ptr<uint8_t[]> px;  // 4 bytes per pixel
  std::unique_ptr<uint8_t[]> nz;  // only when the footprint test of BlendFlags reads it
  std::vector<uint8_t> row_any;
  Tex8 Tex() const { return Tex8(px.get(), w, h); }
  uint8_t* Row(int y) { return px.get() + 4 * static_cast<size_t>(y) * w; }
  const uint8_t* Row(int y) const { return px.get() + 4 * static_cast<size_t>(y) * w; }
};

void WeightsFast(const EdgePlane& edges, const SmaaParams& p, BlendTex* out, uint64_t* taps) {
  const int w = edges.w, h = edges.h;
  const Frame f(w, h);
  // With 8-bit sub-texel fetches (frames up to kMaxShortcutSize) the first fetch, at the
  // pixel's own centre, returns its own edge texel exactly; otherwise its footprint lies in
  // the 3×3 block around it.
  const bool precise = p.subtexel == SubTexel::kFixed8 && w <= kMaxShortcutSize && h <= kMaxShortcutSize;
  const Image8& area_tex = SmaaAreaTexture();
  const Image8& search_tex = SmaaSearchTexture();
  std::vector<uint64_t> t(static_cast<size_t>((h + kGrain - 1) / kGrain), 0);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    PlaneEdges reader(edges, p.subtexel);
    InlineSampler as(Tex8(area_tex), p.subtexel), ss(Tex8(search_tex), p.subtexel);
    smaa_detail::WeightsShader<PlaneEdges, InlineSampler> shader(reader, as, ss, p, f);
    std::vector<uint8_t> col(static_cast<size_t>(w)), flags(static_cast<size_t>(w));
    uint64_t skipped = 0;
    for (int y = y0; y < y1; ++y) {
      std::memset(out->Row(y), 0, 4 * static_cast<size_t>(w));
      if (out->nz) std::memset(out->nz.get() + static_cast<size_t>(y) * w, 0, static_cast<size_t>(w));
      if (!AnyRow(edges.row_any, y, -1, 1)) {
        skipped += static_cast<uint64_t>(w);  // every pixel's one fetch returns (0, 0)
        continue;
      }
      if (precise) {
        const uint8_t* er = edges.Row(y);
        for (int x = 0; x < w; ++x) flags[static_cast<size_t>(x)] = er[x];
      } else {
        NeighbourFlags(edges.e.get(), w, h, y, -1, 1, -1, 1, col.data(), flags.data());
      }
      uint8_t row_any = 0;
      for (int x = 0; x < w; ++x) {
        if (!flags[static_cast<size_t>(x)]) {
          ++skipped;
          continue;
        }
        const Float4 wt = shader.Run(x, y);
        uint8_t* o = out->Row(y) + 4 * x;
        o[0] = QuantizeUnorm8(wt.r);
        o[1] = QuantizeUnorm8(wt.g);
        o[2] = QuantizeUnorm8(wt.b);
        o[3] = QuantizeUnorm8(wt.a);
        const uint8_t nz = (o[0] | o[1] | o[2] | o[3]) != 0;
        if (out->nz) out->nz[static_cast<size_t>(y) * w + x] = nz;
        row_any |= nz;
      }
      out->row_any[static_cast<size_t>(y)] = row_any;
    }
    t[static_cast<size_t>(y0 / kGrain)] = skipped + reader.Taps() + as.Taps() + ss.Taps();
  });
  for (uint64_t v : t) *taps += v;
}

// Which pixels of row y run BlendPixel. With 8-bit sub-texel fetches on frames up to
// kMaxShortcutSize, the three blend fetches at (x+1, y), (x, y+1) and (x, y) (texel
// centres, clamped) return those texels exactly (the coordinate misses the centre by less
// than 1/512 texel, which the 8-bit fraction rounds away), so a pixel blends only if own.r,
// own.b, right.a or bottom.g is non-zero. Otherwise (exact fractions) any non-zero byte in
// the fetches' footprints (rows y-1 .. y+2, columns x-1 .. x+2) flags it.
void BlendFlags(const BlendTex& b, bool precise, int y, uint8_t* col, uint8_t* flags) {
  const int w = b.w, h = b.h;
  if (!precise) {
    NeighbourFlags(b.nz.get(), w, h, y, -1, 2, -1, 2, col, flags);
    return;
  }
  const uint8_t* own = b.Row(y);
  const uint8_t* below = b.Row(std::min(y + 1, h - 1));
  for (int x = 0; x < w - 1; ++x)
    flags[x] = (own[4 * x] | own[4 * x + 2] | own[4 * (x + 1) + 3] | below[4 * x + 1]) != 0;
  const int x = w - 1;
  flags[x] = (own[4 * x] | own[4 * x + 2] | own[4 * x + 3] | below[4 * x + 1]) != 0;
}

Image8 BlendFast(const Image8& in, const BlendTex& blend, const SmaaParams& p, uint64_t* taps) {
  const int w = in.Width(), h = in.Height();
  const Frame f(w, h);
  const bool shortcut = w <= kMaxShortcutSize && h <= kMaxShortcutSize;
  const bool precise = shortcut && p.subtexel == SubTexel::kFixed8;
  // Every pixel written: copied first (shortcut) or blended (flags all 1 otherwise), 4 bytes.
  Image8 out(w, h, 4, kUninitialized);
  std::vector<uint64_t> t(static_cast<size_t>((h + kGrain - 1) / kGrain), 0);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    InlineSampler bs(blend.Tex(), p.subtexel), cs(Tex8(in), p.subtexel);
    std::vector<uint8_t> col(static_cast<size_t>(w)), flags(static_cast<size_t>(w), 1);
    uint64_t copied = 0;
    for (int y = y0; y < y1; ++y) {
      const uint8_t* src = in.Row(y);
      uint8_t* dst = out.Row(y);
      // Every pixel first as a = 0 leaves it: its input colour, opaque (see the file block).
      if (shortcut) CopyRowOpaque(src, dst, w);
      if (shortcut && !AnyRow(blend.row_any, y, -1, 2)) {
        copied += 4 * static_cast<uint64_t>(w);  // three blend fetches, one colour fetch
        continue;
      }
      if (shortcut) BlendFlags(blend, precise, y, col.data(), flags.data());
      const uint8_t* own = blend.Row(y);
      const uint8_t* below = blend.Row(std::min(y + 1, h - 1));
      for (int x = 0; x < w; ++x) {
        if (!flags[static_cast<size_t>(x)]) {
          copied += 4;
          continue;
        }
        if (precise) {
          // The three blend fetches hit texel centres exactly (BlendFlags): their values are
          // UnormToFloat of the bytes, as BilinearBlend with fractions 0 returns them.
          const int xr = std::min(x + 1, w - 1);
          const float a[4] = {UnormToFloat(own[4 * xr + 3]), UnormToFloat(below[4 * x + 1]),
                              UnormToFloat(own[4 * x + 2]), UnormToFloat(own[4 * x])};
          copied += 3;
          smaa_detail::BlendWithWeights(a, cs, f, x, y, dst + 4 * x);
        } else {
          smaa_detail::BlendPixel(bs, cs, f, x, y, dst + 4 * x);
        }
      }
    }
    t[static_cast<size_t>(y0 / kGrain)] = copied + bs.Taps() + cs.Taps();
  });
  for (uint64_t v : t) *taps += v;
  return out;
}

}  // namespace

Image8 Smaa(const Image8& in, const SmaaParams& params, const std::string& debug_view, PostStats* stats) {
  AALAB_CHECK(in.Channels() == 4, "SMAA needs an RGBA8 frame");
  AALAB_CHECK(params.max_search_steps >= 0 && params.max_search_steps_diag >= 0, "SMAA search steps must be >= 0");
  const int view = smaa_detail::ParseView(debug_view);
  if (params.sampler != SamplerArithmetic::kGl) return SmaaReference(in, params, debug_view, stats);  // no fast path
  if (in.Empty()) return in;
  uint64_t taps = 0;
  EdgePlane edges;
  edges.w = in.Width();
  edges.h = in.Height();
  edges.e.reset(new uint8_t[in.PixelCount()]);  // rows cleared by EdgesFast
  edges.row_any.resize(static_cast<size_t>(in.Height()));
  const bool precise =
      params.subtexel == SubTexel::kFixed8 && in.Width() <= kMaxShortcutSize && in.Height() <= kMaxShortcutSize;
  const bool fused = precise && view == 0;
  if (fused) {
    edges.xs.reset(new uint16_t[in.PixelCount()]);  // rows listed by EdgesFast
    edges.n.assign(static_cast<size_t>(in.Height()), 0);
  }
  // The fused pass's output: every row the input row, alpha 255, written by pass 1 (the
  // pixels that blend are overwritten by the fused pass).
  Image8 out;
  if (fused) out = Image8(in.Width(), in.Height(), 4, kUninitialized);
  EdgesFast(in, params, &edges, fused ? &out : nullptr, &taps);
  if (fused) {
    smaa_internal::WeightsAndBlendFused(in, edges, params, &out, &taps);
    if (stats) stats->taps += taps;
    return out;
  }
  if (view == 1 && stats) stats->taps += taps;  // a debug view counts the passes it ran
  if (view == 1) return smaa_detail::EdgesView(EdgeTextureOf(edges));
  BlendTex blend;
  blend.w = in.Width();
  blend.h = in.Height();
  blend.px.reset(new uint8_t[4 * in.PixelCount()]);            // rows cleared by WeightsFast
  if (!precise) blend.nz.reset(new uint8_t[in.PixelCount()]);  // only the footprint test of BlendFlags reads it
  blend.row_any.assign(static_cast<size_t>(in.Height()), 0);
  WeightsFast(edges, params, &blend, &taps);
  if (view == 2 && stats) stats->taps += taps;
  if (view == 2) {
    Image8 tex(blend.w, blend.h, 4);
    std::memcpy(tex.Data().data(), blend.px.get(), tex.Data().size());
    return smaa_detail::WeightsView(tex);
  }
  Image8 blended = BlendFast(in, blend, params, &taps);
  if (stats) stats->taps += taps;
  return blended;
}

}  // namespace aalab
