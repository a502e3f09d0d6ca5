// SSIM's production kernels: the window sums of metrics/ssim.cpp's definition in float32 over
// tile-centred values, the map from them in double.
//
// What is computed. For each channel, the image is cut into tiles of kTileRows × kTileCols
// output pixels (a fixed tiling: it depends on the image size alone, never on the thread
// count). Each tile takes one centre per image, c = the mean of the channel over a fixed
// subsample of the tile's input block (every 4th row, every 2nd column of the outputs' rows
// and columns plus the 5-pixel halo), rounded to float; a non-finite mean gives c = 0. Inside
// the tile every value is replaced by d = x − c (float), and the five window sums
//   S1x = E_w[dx], S2x = E_w[dx²], S1y, S2y, Sxy = E_w[dx·dy]
// are formed in float32, separably (11 horizontal taps, then 11 vertical ones), each sum in
// tap order. The map is evaluated in double from them: μx = cx + S1x, σx² = S2x − S1x²,
// σxy = Sxy − S1x·S1y (the same for y), then Eq. (13) as in metrics/ssim.cpp. The map's mean is
// summed in double in a fixed pattern: a row segment in 8 lanes (outputs ox ≡ k mod 8 of its
// 16-wide blocks), the lanes in order, then its tail left to right; segments left to right;
// rows in order. A tile's three channels are walked together (one read of each input row).
//
// Why a centre, and why per tile: σ² = E[x²] − E[x]² cancels. In float32 each window sum
// carries a relative error of up to γ25 ≈ 1.5e-6 (below), so uncentred, a flat window at 0.8
// would get |Δσ²| up to ~1e-6 against C2 = 9e-4: ~1e-3 in SSIM. With centred values the
// error scales with Q = E_w[(x − c)²] = σ² + (μ − c)² instead of E[x²]. A per-window centre
// would make Q = σ², but it cannot be kept through separable sums without re-centring every
// row's sums in the vertical pass (about as many operations again as the sums, which would
// give back what float32 gains); a per-image constant leaves flat regions far from it (sky at
// 0.9, shadow at 0.05) badly conditioned. A tile of 64 × 256 pixels mostly holds one kind
// of content, so its mean is near most of its windows' means, at no cost beyond the
// subsampled mean (a sixteenth of a pass). A constant offset of the whole image (x + 1000)
// cancels exactly: d = x − c is exact when x and c are within a factor 2 (Sterbenz).
//
// The window: the double weights of ssim.cpp rounded to float (each within u = 2⁻²⁴
// relative; their exact sum is 1 − 1.4e-9, so a flat window's σ² ≈ 2·d²·1.4e-9 is far inside
// the bound below).
//
// The bound (u = 2⁻²⁴, γn = n·u/(1 − n·u); Q as above, exact weights):
//  - d = fl(x − c) and d·d carry 1 and 3 roundings; a horizontal sum of 11 products w·t adds
//    at most 11 (1 product + 10 additions), the vertical one 11 more, and the float weights
//    differ from the double Gaussian by 1 more: |ΔS2| ≤ γ26·Q (all terms ≥ 0), and
//    |ΔS1| ≤ γ24·E_w|x − c| ≤ γ24·√Q (Jensen); |ΔSxy| ≤ γ26·(Qx + Qy)/2.
//  - σ² = S2 − S1² in double (its own rounding ~1e-16): |Δσx²| ≤ γ26·Qx + 2·|S1x|·γ24·√Qx
//    ≤ 3·γ26·Qx (|S1x| ≤ √Qx); |Δσxy| ≤ 1.5·γ26·(Qx + Qy); |Δμx| ≤ γ24·√Qx.
//  - SSIM = A·B with A = (2μxμy + C1)/(μx² + μy² + C1), B = (2σxy + C2)/(σx² + σy² + C2),
//    |A|, |B| ≤ 1; |∂B/∂σx²| ≤ 1/D, |∂B/∂σxy| = 2/D with D = σx² + σy² + C2, and
//    |∂A/∂μx| ≤ 2(|μx| + |μy|)/(μx² + μy² + C1) =: G (≤ √2/√C1 ≈ 141). So per pixel
//        |ΔSSIM| ≤ 6·γ26·(Qx + Qy)/D + G·γ24·(√Qx + √Qy)        (to first order)
//    and the mean moves by at most the mean of that. tests/metrics/ssim_bound.h evaluates it
//    per pixel (× 1.25 for second-order terms) from an accurate double map and the tile
//    centres, and the tests hold every pixel of every test image to it. Where it is large:
//    flat windows far from their tile's centre (Q ≈ (μ − c)² ≫ D ≈ C2), e.g. a flat 0.02 next
//    to 0.98 in one tile, up to ~6·γ26·0.5/C2 ≈ 5e-3 at worst; measured there 2e-4 per
//    pixel; on the bench's 1080p pair ≤ 2.8e-4 per pixel and 1e-7 on the mean; over the
//    default run at 480x270 ≤ 5.7e-4 per pixel and 3.7e-6 on any report value
//    (docs/performance.md).
//  - SSIM(x, x) = 1 exactly (the x and y sums are the same floats, so 2σxy = σx² + σy² and
//    2μxμy = μx² + μy² bit for bit), and SSIM(x, y) = SSIM(y, x) exactly (every operation
//    that meets both is commutative).
//
// Determinism: separate multiplies and adds (-ffp-contract=off, no fast-math), each output's
// sums in tap order, one lane per output: the AVX-512, AVX2 and baseline clones
// (target_clones, picked at run time) give the same bits, at any thread count.
#include "metrics/ssim_float.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/parallel.h"
#include "metrics/ssim.h"

namespace aalab::ssim_float {
namespace {

constexpr int kTaps = 11;
constexpr int kR = 5;

// (Defined on the command line to check one clone alone: -DAALAB_SIMD_CLONES= for the SSE2
// baseline, as docs/performance.md's cross-check of the dispatch paths did.)
#ifndef AALAB_SIMD_CLONES
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define AALAB_SIMD_CLONES
#endif
#endif

#define AALAB_INLINE __attribute__((always_inline)) inline

// Blocks of outputs kept in registers: GCC vector types of 16 floats (one AVX-512 register,
// two AVX2 ones, four SSE2 ones: every clone does the same lane-wise operations).
typedef float V16 __attribute__((vector_size(64)));
typedef double V8 __attribute__((vector_size(64)));
constexpr int kV = 16;

AALAB_INLINE V16 Load16(const float* p) {
  V16 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
AALAB_INLINE void Store16(float* p, V16 v) { std::memcpy(p, &v, sizeof v); }

// The double window rounded to float (each tap within u relative; the 11 floats sum to
// 1 − 1.4e-9).
std::array<float, kTaps> FloatWindow(const std::array<double, kTaps>& w) {
  std::array<float, kTaps> f{};
  for (int i = 0; i < kTaps; ++i) f[i] = static_cast<float>(w[i]);
  return f;
}

// Σ_i w_i·v[ox + i] for outputs ox .. ox+31 (each lane's sum in tap order).
AALAB_INLINE void Sum32(const float* v, const float* w, float* out) {
  V16 s0 = {}, s1 = {};
  for (int i = 0; i < kTaps; ++i) {
    const float wi = w[i];
    s0 += wi * Load16(v + i);
    s1 += wi * Load16(v + kV + i);
  }
  Store16(out, s0);
  Store16(out + kV, s1);
}

AALAB_INLINE float SumScalar(const float* v, const float* w) {
  float s = 0.0f;
  for (int i = 0; i < kTaps; ++i) s += w[i] * v[i];
  return s;
}

// d[x] = src[x·stride] − centre: one channel of an interleaved row, centred (the common
// strides as constants, so the gather vectorises).
template <int kStride>
AALAB_INLINE void CentreRowFixed(const float* src, int width, float centre, float* d) {
  for (int x = 0; x < width; ++x) d[x] = src[static_cast<size_t>(x) * kStride] - centre;
}

AALAB_SIMD_CLONES
void CentreRow(const float* src, int stride, int width, float centre, float* d) {
  if (stride == 3) return CentreRowFixed<3>(src, width, centre, d);
  if (stride == 4) return CentreRowFixed<4>(src, width, centre, d);
  for (int x = 0; x < width; ++x) d[x] = src[static_cast<size_t>(x) * stride] - centre;
}

// One input row of a tile: d = x − centre, d², and their horizontal window sums.
AALAB_SIMD_CLONES
void HorizontalRow(const float* src, int stride, int width, int nx, const float* w, float centre, float* d, float* dd,
                   float* out, float* out_sq) {
  CentreRow(src, stride, width, centre, d);
  for (int x = 0; x < width; ++x) dd[x] = d[x] * d[x];
  int ox = 0;
  for (; ox + 2 * kV <= nx; ox += 2 * kV) {
    Sum32(d + ox, w, out + ox);
    Sum32(dd + ox, w, out_sq + ox);
  }
  for (; ox < nx; ++ox) {
    out[ox] = SumScalar(d + ox, w);
    out_sq[ox] = SumScalar(dd + ox, w);
  }
}

// The cross products dx·dy of a row and their horizontal window sums.
AALAB_SIMD_CLONES
void HorizontalCross(const float* da, const float* db, int width, int nx, const float* w, float* dab, float* out) {
  for (int x = 0; x < width; ++x) dab[x] = da[x] * db[x];
  int ox = 0;
  for (; ox + 2 * kV <= nx; ox += 2 * kV) Sum32(dab + ox, w, out + ox);
  for (; ox < nx; ++ox) out[ox] = SumScalar(dab + ox, w);
}

// One SSIM map value from the five centred float sums and the two centres, in double.
AALAB_INLINE double MapValue(float s1x, float s1y, float s2x, float s2y, float sxy, double cx, double cy) {
  constexpr double c1 = (kSsimK1 * 1.0) * (kSsimK1 * 1.0);
  constexpr double c2 = (kSsimK2 * 1.0) * (kSsimK2 * 1.0);
  const double ex = s1x, ey = s1y;
  const double mx = cx + ex, my = cy + ey;
  const double vx = static_cast<double>(s2x) - ex * ex;
  const double vy = static_cast<double>(s2y) - ey * ey;
  const double vxy = static_cast<double>(sxy) - ex * ey;
  const double num = (2.0 * mx * my + c1) * (2.0 * vxy + c2);
  const double den = (mx * mx + my * my + c1) * (vx + vy + c2);
  return num / den;
}

// Vertical sums of two planes (Σ_j w_j·rows[j][x], j in order).
AALAB_SIMD_CLONES
void VerticalSums2(const float* const* rows_b, const float* const* rows_bb, int nx, const float* w, float* mb_out,
                   float* mbb_out) {
  int ox = 0;
  for (; ox + kV <= nx; ox += kV) {
    V16 mb = {}, mbb = {};
    for (int j = 0; j < kTaps; ++j) {
      const float wj = w[j];
      mb += wj * Load16(rows_b[j] + ox);
      mbb += wj * Load16(rows_bb[j] + ox);
    }
    Store16(mb_out + ox, mb);
    Store16(mbb_out + ox, mbb);
  }
  for (; ox < nx; ++ox) {
    float mb = 0.0f, mbb = 0.0f;
    for (int j = 0; j < kTaps; ++j) {
      mb += w[j] * rows_b[j][ox];
      mbb += w[j] * rows_bb[j][ox];
    }
    mb_out[ox] = mb;
    mbb_out[ox] = mbb;
  }
}

// Vertical sums of x's three planes (dx, dx², dx·dy) and the map, y's sums given; returns
// the map's sum over the row segment, added in a fixed pattern (8 lanes of outputs ox ≡ k
// mod 8 over the 16-wide blocks, the lanes in order, then the tail left to right).
AALAB_SIMD_CLONES
double VerticalAndMap(const float* const* rows_a, const float* const* rows_aa, const float* const* rows_ab,
                      const float* mb, const float* mbb, int nx, const float* w, double cx, double cy, double* map) {
  int ox = 0;
  V8 acc = {};
  for (; ox + kV <= nx; ox += kV) {
    V16 ma = {}, maa = {}, mab = {};
    for (int j = 0; j < kTaps; ++j) {
      const float wj = w[j];
      ma += wj * Load16(rows_a[j] + ox);
      maa += wj * Load16(rows_aa[j] + ox);
      mab += wj * Load16(rows_ab[j] + ox);
    }
    double m[kV];
    for (int k = 0; k < kV; ++k) m[k] = MapValue(ma[k], mb[ox + k], maa[k], mbb[ox + k], mab[k], cx, cy);
    V8 lo, hi;
    std::memcpy(&lo, m, sizeof lo);
    std::memcpy(&hi, m + 8, sizeof hi);
    acc += lo;
    acc += hi;
    std::memcpy(map + ox, m, sizeof m);
  }
  double sum = 0.0;
  for (int k = 0; k < 8; ++k) sum += acc[k];
  for (; ox < nx; ++ox) {
    float ma = 0.0f, maa = 0.0f, mab = 0.0f;
    for (int j = 0; j < kTaps; ++j) {
      ma += w[j] * rows_a[j][ox];
      maa += w[j] * rows_aa[j][ox];
      mab += w[j] * rows_ab[j][ox];
    }
    map[ox] = MapValue(ma, mb[ox], maa, mbb[ox], mab, cx, cy);
    sum += map[ox];
  }
  return sum;
}

// A tile's buffers: one input row's d, d², (and for x: dx·dy), and an 11-row ring of
// horizontal sums per plane.
struct TileBuffers {
  explicit TileBuffers(int planes)
      : da(kTileCols + 2 * kR),
        daa(kTileCols + 2 * kR),
        db(kTileCols + 2 * kR),
        dab(kTileCols + 2 * kR),
        ring(static_cast<size_t>(planes) * kTaps * kTileCols),
        map(kTileCols),
        sum1(kTileCols),
        sum2(kTileCols) {}
  float* Slot(int plane, int yy) { return ring.data() + (static_cast<size_t>(plane) * kTaps + yy % kTaps) * kTileCols; }
  std::vector<float> da, daa, db, dab, ring;
  std::vector<double> map;
  std::vector<float> sum1, sum2;  // y's vertical sums of one row (the streaming path)
};

int TilesX(int nx) { return (nx + kTileCols - 1) / kTileCols; }

}  // namespace

float TileCentre(const ImageF& img, int c, int x0, int y0, int sx, int sy) {
  const int ch = img.Channels();
  double sum = 0.0;
  long count = 0;
  for (int y = y0; y < y0 + sy + 2 * kR; y += 4) {
    const float* row = img.Row(y) + static_cast<size_t>(x0) * ch + c;
    for (int x = 0; x < sx + 2 * kR; x += 2) sum += row[static_cast<size_t>(x) * ch];
    count += (sx + 2 * kR + 1) / 2;
  }
  const double mean = sum / static_cast<double>(count);
  return std::isfinite(mean) ? static_cast<float>(mean) : 0.0f;
}

namespace {

// Row sums of the three channels' maps (per channel, ny each) → the channel means.
std::array<double, 3> Means(const std::array<std::vector<double>, 3>& row_sums, int nx, int ny) {
  std::array<double, 3> out{};
  for (int c = 0; c < 3; ++c) {
    double total = 0.0;
    for (double v : row_sums[c]) total += v;
    out[c] = total / (static_cast<double>(nx) * static_cast<double>(ny));
  }
  return out;
}

size_t TileIndex(int nx, int r0, int x0) { return static_cast<size_t>(r0 / kTileRows) * TilesX(nx) + x0 / kTileCols; }

namespace {

/// One tile of the walk: output rows [r0, r1), columns [x0, x0 + sx), input span sw, and
/// each channel's centres of the two images (set by the walk's `centres` callback).
struct Tile {
  int r0, r1, x0, sx, sw;
  float cx[3], cy[3];
};

/// The walk the three passes share: tiles of kTileRows output rows in parallel, across them
/// tiles of kTileCols columns; per tile `centres(tile)` sets the centres, then every input row
/// of the tile's padded band goes, channel by channel, to `row(tile, buffers of c, c, yy, r)`
/// with r = yy − 2·kR the output row whose window that input row completes (r < r0: the
/// band's first 2·kR rows, which only fill the ring). `planes`: the ring's planes per channel.
template <typename Centres, typename Row>
void WalkTiles(int nx, int ny, int planes, const Centres& centres, const Row& row) {
  ParallelForChunks(ny, kTileRows, [&](int r0, int r1) {
    std::array<TileBuffers, 3> bufs{TileBuffers(planes), TileBuffers(planes), TileBuffers(planes)};
    for (int x0 = 0; x0 < nx; x0 += kTileCols) {
      Tile t{r0, r1, x0, std::min(kTileCols, nx - x0), 0, {}, {}};
      t.sw = t.sx + 2 * kR;
      centres(t);
      for (int yy = r0; yy < r1 + 2 * kR; ++yy) {
        for (int c = 0; c < 3; ++c) row(t, bufs[c], c, yy, yy - 2 * kR);
      }
    }
  });
}

}  // namespace

}  // namespace

// Each tile is walked once, its three channels row by row (an input row is read from memory
// once for all three); each channel's sums and map are exactly those of a channel alone.
std::array<double, 3> Ssim(const ImageF& a, const ImageF& b, const std::array<double, 11>& w, int map_channel,
                           double* map_out) {
  const int nx = a.Width() - 2 * kR, ny = a.Height() - 2 * kR;
  const auto wf = FloatWindow(w);
  std::array<std::vector<double>, 3> row_sums;
  for (auto& v : row_sums) v.assign(ny, 0.0);
  const int ca = a.Channels(), cb = b.Channels();
  WalkTiles(
      nx, ny, 5,
      [&](Tile& t) {
        for (int c = 0; c < 3; ++c) {
          t.cx[c] = TileCentre(a, c, t.x0, t.r0, t.sx, t.r1 - t.r0);
          t.cy[c] = TileCentre(b, c, t.x0, t.r0, t.sx, t.r1 - t.r0);
        }
      },
      [&](const Tile& t, TileBuffers& buf, int c, int yy, int r) {
        HorizontalRow(a.Row(yy) + static_cast<size_t>(t.x0) * ca + c, ca, t.sw, t.sx, wf.data(), t.cx[c], buf.da.data(),
                      buf.daa.data(), buf.Slot(0, yy), buf.Slot(1, yy));
        HorizontalRow(b.Row(yy) + static_cast<size_t>(t.x0) * cb + c, cb, t.sw, t.sx, wf.data(), t.cy[c], buf.db.data(),
                      buf.dab.data(), buf.Slot(3, yy), buf.Slot(4, yy));
        HorizontalCross(buf.da.data(), buf.db.data(), t.sw, t.sx, wf.data(), buf.dab.data(), buf.Slot(2, yy));
        if (r < t.r0) return;
        const float* p[5][kTaps];
        for (int plane = 0; plane < 5; ++plane)
          for (int j = 0; j < kTaps; ++j) p[plane][j] = buf.Slot(plane, r + j);
        VerticalSums2(p[3], p[4], t.sx, wf.data(), buf.sum1.data(), buf.sum2.data());
        row_sums[c][r] += VerticalAndMap(p[0], p[1], p[2], buf.sum1.data(), buf.sum2.data(), t.sx, wf.data(), t.cx[c],
                                         t.cy[c], buf.map.data());
        if (map_out && c == map_channel)
          std::copy_n(buf.map.data(), t.sx, map_out + static_cast<size_t>(r) * nx + t.x0);
      });
  return Means(row_sums, nx, ny);
}

std::array<ReferencePlanes, 3> Prepare(const ImageF& b, const std::array<double, 11>& w) {
  const int nx = b.Width() - 2 * kR, ny = b.Height() - 2 * kR;
  const auto wf = FloatWindow(w);
  std::array<ReferencePlanes, 3> side;
  for (ReferencePlanes& p : side) {
    p.s1.resize(static_cast<size_t>(nx) * ny);
    p.s2.resize(static_cast<size_t>(nx) * ny);
    p.centre.resize(static_cast<size_t>(TilesX(nx)) * ((ny + kTileRows - 1) / kTileRows));
  }
  const int cb = b.Channels();
  WalkTiles(
      nx, ny, 2,
      [&](Tile& t) {
        for (int c = 0; c < 3; ++c)
          side[c].centre[TileIndex(nx, t.r0, t.x0)] = t.cy[c] = TileCentre(b, c, t.x0, t.r0, t.sx, t.r1 - t.r0);
      },
      [&](const Tile& t, TileBuffers& buf, int c, int yy, int r) {
        HorizontalRow(b.Row(yy) + static_cast<size_t>(t.x0) * cb + c, cb, t.sw, t.sx, wf.data(), t.cy[c], buf.db.data(),
                      buf.daa.data(), buf.Slot(0, yy), buf.Slot(1, yy));
        if (r < t.r0) return;
        const float* pb[kTaps];
        const float* pbb[kTaps];
        for (int j = 0; j < kTaps; ++j) pb[j] = buf.Slot(0, r + j), pbb[j] = buf.Slot(1, r + j);
        const size_t at = static_cast<size_t>(r) * nx + t.x0;
        VerticalSums2(pb, pbb, t.sx, wf.data(), side[c].s1.data() + at, side[c].s2.data() + at);
      });
  return side;
}

std::array<double, 3> SsimPrepared(const ImageF& a, const ImageF& b, const std::array<ReferencePlanes, 3>& side,
                                   const std::array<double, 11>& w) {
  const int nx = a.Width() - 2 * kR, ny = a.Height() - 2 * kR;
  const auto wf = FloatWindow(w);
  std::array<std::vector<double>, 3> row_sums;
  for (auto& v : row_sums) v.assign(ny, 0.0);
  const int ca = a.Channels(), cb = b.Channels();
  WalkTiles(
      nx, ny, 3,
      [&](Tile& t) {
        for (int c = 0; c < 3; ++c) {
          t.cx[c] = TileCentre(a, c, t.x0, t.r0, t.sx, t.r1 - t.r0);
          t.cy[c] = side[c].centre[TileIndex(nx, t.r0, t.x0)];
        }
      },
      [&](const Tile& t, TileBuffers& buf, int c, int yy, int r) {
        HorizontalRow(a.Row(yy) + static_cast<size_t>(t.x0) * ca + c, ca, t.sw, t.sx, wf.data(), t.cx[c], buf.da.data(),
                      buf.daa.data(), buf.Slot(0, yy), buf.Slot(1, yy));
        CentreRow(b.Row(yy) + static_cast<size_t>(t.x0) * cb + c, cb, t.sw, t.cy[c], buf.db.data());
        HorizontalCross(buf.da.data(), buf.db.data(), t.sw, t.sx, wf.data(), buf.dab.data(), buf.Slot(2, yy));
        if (r < t.r0) return;
        const float* p[3][kTaps];
        for (int plane = 0; plane < 3; ++plane)
          for (int j = 0; j < kTaps; ++j) p[plane][j] = buf.Slot(plane, r + j);
        const size_t at = static_cast<size_t>(r) * nx + t.x0;
        row_sums[c][r] += VerticalAndMap(p[0], p[1], p[2], side[c].s1.data() + at, side[c].s2.data() + at, t.sx,
                                         wf.data(), t.cx[c], t.cy[c], buf.map.data());
      });
  return Means(row_sums, nx, ny);
}

}  // namespace aalab::ssim_float
