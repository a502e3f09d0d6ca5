// SSIM: structural similarity index.
//
// Source: Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image Quality Assessment:
// From Error Visibility to Structural Similarity", IEEE TIP 13(4), 2004. Per-pixel index,
// Eq. (13): SSIM = ((2 μx μy + C1)(2 σxy + C2)) / ((μx² + μy² + C1)(σx² + σy² + C2)),
// C1 = (K1 L)², C2 = (K2 L)²; local statistics weighted by a circular-symmetric Gaussian
// window, σ = 1.5, 11×11, normalised to unit sum (Eqs. 14–16); mean over the map (MSSIM,
// Eq. 17).
//
// Parameters (fixed, the paper's): σ = 1.5, window 11×11 (radius 5), K1 = 0.01, K2 = 0.03,
// L = 1 (data range of sRGB-encoded values in [0, 1]).
//
// Choices (stated so users can cross-check):
//  - Colour: SSIM is computed on each of R, G, B separately, on sRGB-encoded values (no
//    linearisation, no luma), and the value `ssim` is the mean of the three channel means.
//  - Statistics are population (biased) moments: σx² = E_w[x²] − E_w[x]², no N/(N−1).
//  - The window is separable: 1-D weights w(i) = exp(−i²/(2σ²)), i = −5..5, divided by
//    their sum; the 2-D window is w(i)·w(j) (exactly the normalised 2-D Gaussian).
//  - Border: only the "valid" region is averaged, i.e. pixels whose 11×11 window lies inside
//    the image (x in [5, W−6], y in [5, H−6]); no padding is ever read. This equals
//    scikit-image 0.19 `structural_similarity(a, b, channel_axis=2, gaussian_weights=True,
//    sigma=1.5, use_sample_covariance=False, data_range=1)`: it filters with mode='reflect'
//    and truncate=3.5 (radius 5) but then crops 5 pixels on each side before averaging, so
//    its padded values never reach the mean either. Checked against scikit-image 0.19.3 on
//    float64 inputs (agreement ≈ 1e-15; see METRICS.md). Pass float64 arrays when
//    cross-checking: with float32 inputs scikit-image filters in float32 (≈ 1e-7 off).
//  - Images smaller than 11 in either dimension: SSIM is undefined here (null, reason
//    "image smaller than the 11x11 SSIM window"); scikit-image raises an error.
//
// Precision: inputs are float32 converted to double; every product and sum is double, in a
// fixed order (window taps in index order; the map summed row by row, each row left to
// right, rows in order), so the value is bit-identical at any thread count. x == y gives
// numerator == denominator bit for bit, so SSIM(x, x) = 1 exactly.
#include "metrics/ssim.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "metrics/families.h"
#include "metrics/metric.h"

namespace aalab {
namespace {

// The SSIM map's mean from its per-row sums, added in row order (the same order at any
// thread count, so the same bits).
double MeanOfRowSums(const std::vector<double>& row_sums, int nx, int ny) {
  double total = 0.0;
  for (double s : row_sums) total += s;
  return total / (static_cast<double>(nx) * static_cast<double>(ny));
}

constexpr int kTaps = 2 * kSsimRadius + 1;

std::array<double, kTaps> GaussianWindow() {
  std::array<double, kTaps> w{};
  double sum = 0.0;
  for (int i = 0; i < kTaps; ++i) {
    const double d = i - kSsimRadius;
    w[i] = std::exp(-(d * d) / (2.0 * kSsimSigma * kSsimSigma));
    sum += w[i];
  }
  for (double& v : w) v /= sum;
  return w;
}

// Mean SSIM of channel c over the valid region.
double ChannelSsimReference(const ImageF& a, const ImageF& b, int c, const std::array<double, kTaps>& w) {
  const int width = a.Width(), height = a.Height();
  const int nx = width - 2 * kSsimRadius;   // valid columns: x = 5 .. W-6
  const int ny = height - 2 * kSsimRadius;  // valid rows:    y = 5 .. H-6
  const size_t plane = static_cast<size_t>(height) * nx;
  // Horizontal pass on every row, valid columns only: weighted sums of a, b, a², b², ab.
  std::vector<double> ha(plane), hb(plane), haa(plane), hbb(plane), hab(plane);
  ParallelForChunks(height, 8, [&](int y0, int y1) {
    std::vector<double> ra(width), rb(width);
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < width; ++x) {
        ra[x] = static_cast<double>(a.At(x, y, c));
        rb[x] = static_cast<double>(b.At(x, y, c));
      }
      const size_t row = static_cast<size_t>(y) * nx;
      for (int ox = 0; ox < nx; ++ox) {
        double sa = 0.0, sb = 0.0, saa = 0.0, sbb = 0.0, sab = 0.0;
        for (int i = 0; i < kTaps; ++i) {
          const double va = ra[ox + i], vb = rb[ox + i];  // x = ox + 5, tap offset i − 5
          sa += w[i] * va;
          sb += w[i] * vb;
          saa += w[i] * (va * va);
          sbb += w[i] * (vb * vb);
          sab += w[i] * (va * vb);
        }
        ha[row + ox] = sa;
        hb[row + ox] = sb;
        haa[row + ox] = saa;
        hbb[row + ox] = sbb;
        hab[row + ox] = sab;
      }
    }
  });
  // Vertical pass on valid rows, then the SSIM map, summed per row.
  const double c1 = (kSsimK1 * 1.0) * (kSsimK1 * 1.0);
  const double c2 = (kSsimK2 * 1.0) * (kSsimK2 * 1.0);
  std::vector<double> row_sums(ny, 0.0);
  ParallelForChunks(ny, 8, [&](int r0, int r1) {
    std::vector<double> ma(nx), mb(nx), maa(nx), mbb(nx), mab(nx);
    for (int r = r0; r < r1; ++r) {  // output row y = r + 5 uses input rows r .. r + 10
      std::fill(ma.begin(), ma.end(), 0.0);
      std::fill(mb.begin(), mb.end(), 0.0);
      std::fill(maa.begin(), maa.end(), 0.0);
      std::fill(mbb.begin(), mbb.end(), 0.0);
      std::fill(mab.begin(), mab.end(), 0.0);
      for (int j = 0; j < kTaps; ++j) {
        const size_t src = static_cast<size_t>(r + j) * nx;
        const double wj = w[j];
        for (int ox = 0; ox < nx; ++ox) {
          ma[ox] += wj * ha[src + ox];
          mb[ox] += wj * hb[src + ox];
          maa[ox] += wj * haa[src + ox];
          mbb[ox] += wj * hbb[src + ox];
          mab[ox] += wj * hab[src + ox];
        }
      }
      double sum = 0.0;
      for (int ox = 0; ox < nx; ++ox) {
        const double mx = ma[ox], my = mb[ox];
        const double vx = maa[ox] - mx * mx;
        const double vy = mbb[ox] - my * my;
        const double vxy = mab[ox] - mx * my;
        const double num = (2.0 * mx * my + c1) * (2.0 * vxy + c2);
        const double den = (mx * mx + my * my + c1) * (vx + vy + c2);
        sum += num / den;
      }
      row_sums[r] = sum;
    }
  });
  return MeanOfRowSums(row_sums, nx, ny);
}

// The production ChannelSsim: the same sums as ChannelSsimReference, term for term and in
// the same order for every output value, laid out so the compiler can vectorise across
// pixels (never within one sum, which would reorder it):
//  - the products a², b², ab of a row are formed once per input pixel (the reference forms
//    them again for each of the 11 taps; the values are the same doubles);
//  - horizontal sums run tap-outer, pixel-inner: acc[x] = 0, then acc[x] += w[i]·v[x+i] for
//    i = 0..10, which is exactly the reference's left-to-right sum for each x;
//  - each SSIM map row is evaluated into an array, then summed left to right in a scalar
//    loop (the reference's order).
// The kernels are compiled for AVX-512, AVX2 and the baseline (target_clones, picked at run
// time): separate multiplies and adds (-ffp-contract=off), so every clone gives the same bits.
// Tests compare ComputeSsim with ComputeSsimReference bit for bit.

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define AALAB_SIMD_CLONES
#endif

// Sums are kept in registers for a block of kLanes neighbouring outputs; each output's sum
// still runs over the taps in index order.
constexpr int kLanes = 32;   // horizontal: 2 sums × 4 registers of 8 doubles
constexpr int kVLanes = 16;  // vertical: 5 sums × 2 registers

AALAB_SIMD_CLONES
void HorizontalRow(const float* src, int stride, int width, int nx, const double* w, double* ra, double* raa,
                   double* out, double* out_sq) {
  for (int x = 0; x < width; ++x) {
    ra[x] = static_cast<double>(src[static_cast<size_t>(x) * stride]);
    raa[x] = ra[x] * ra[x];
  }
  int ox = 0;
  for (; ox + kLanes <= nx; ox += kLanes) {
    double s[kLanes] = {}, q[kLanes] = {};
    for (int i = 0; i < kTaps; ++i) {
      const double wi = w[i];
      for (int k = 0; k < kLanes; ++k) {
        s[k] += wi * ra[ox + k + i];
        q[k] += wi * raa[ox + k + i];
      }
    }
    for (int k = 0; k < kLanes; ++k) {
      out[ox + k] = s[k];
      out_sq[ox + k] = q[k];
    }
  }
  for (; ox < nx; ++ox) {
    double s = 0.0, q = 0.0;
    for (int i = 0; i < kTaps; ++i) {
      s += w[i] * ra[ox + i];
      q += w[i] * raa[ox + i];
    }
    out[ox] = s;
    out_sq[ox] = q;
  }
}

AALAB_SIMD_CLONES
void HorizontalCross(const double* ra, const double* rb, int width, int nx, const double* w, double* rab, double* out) {
  for (int x = 0; x < width; ++x) rab[x] = ra[x] * rb[x];
  int ox = 0;
  for (; ox + kLanes <= nx; ox += kLanes) {
    double s[kLanes] = {};
    for (int i = 0; i < kTaps; ++i) {
      const double wi = w[i];
      for (int k = 0; k < kLanes; ++k) s[k] += wi * rab[ox + k + i];
    }
    for (int k = 0; k < kLanes; ++k) out[ox + k] = s[k];
  }
  for (; ox < nx; ++ox) {
    double s = 0.0;
    for (int i = 0; i < kTaps; ++i) s += w[i] * rab[ox + i];
    out[ox] = s;
  }
}

// One SSIM map value from the five window sums (the reference's expressions).
inline double MapValue(double mx, double my, double sxx, double syy, double sxy, double c1, double c2) {
  const double vx = sxx - mx * mx;
  const double vy = syy - my * my;
  const double vxy = sxy - mx * my;
  const double num = (2.0 * mx * my + c1) * (2.0 * vxy + c2);
  const double den = (mx * mx + my * my + c1) * (vx + vy + c2);
  return num / den;
}

AALAB_SIMD_CLONES
void VerticalAndMap(const double* const* rows_a, const double* const* rows_b, const double* const* rows_aa,
                    const double* const* rows_bb, const double* const* rows_ab, int nx, const double* w, double c1,
                    double c2, double* map) {
  int ox = 0;
  for (; ox + kVLanes <= nx; ox += kVLanes) {
    double ma[kVLanes] = {}, mb[kVLanes] = {}, maa[kVLanes] = {}, mbb[kVLanes] = {}, mab[kVLanes] = {};
    for (int j = 0; j < kTaps; ++j) {
      const double wj = w[j];
      for (int k = 0; k < kVLanes; ++k) {
        ma[k] += wj * rows_a[j][ox + k];
        mb[k] += wj * rows_b[j][ox + k];
        maa[k] += wj * rows_aa[j][ox + k];
        mbb[k] += wj * rows_bb[j][ox + k];
        mab[k] += wj * rows_ab[j][ox + k];
      }
    }
    for (int k = 0; k < kVLanes; ++k) map[ox + k] = MapValue(ma[k], mb[k], maa[k], mbb[k], mab[k], c1, c2);
  }
  for (; ox < nx; ++ox) {
    double ma = 0.0, mb = 0.0, maa = 0.0, mbb = 0.0, mab = 0.0;
    for (int j = 0; j < kTaps; ++j) {
      ma += w[j] * rows_a[j][ox];
      mb += w[j] * rows_b[j][ox];
      maa += w[j] * rows_aa[j][ox];
      mbb += w[j] * rows_bb[j][ox];
      mab += w[j] * rows_ab[j][ox];
    }
    map[ox] = MapValue(ma, mb, maa, mbb, mab, c1, c2);
  }
}

// Blocking: chunks of kChunkRows output rows (in parallel), each walked in strips of
// kStripCols output columns; a strip keeps the horizontal sums of its last 11 input rows in
// a ring (5 planes × 11 rows × kStripCols doubles ≈ 113 KB, in L2), so no full-size plane is
// ever written. Row sums of the map continue across strips left to right, as in the
// reference.
constexpr int kChunkRows = 64;
constexpr int kStripCols = 256;

double ChannelSsim(const ImageF& a, const ImageF& b, int c, const std::array<double, kTaps>& w) {
  const int width = a.Width(), height = a.Height();
  const int nx = width - 2 * kSsimRadius;
  const int ny = height - 2 * kSsimRadius;
  (void)height;
  const double c1 = (kSsimK1 * 1.0) * (kSsimK1 * 1.0);
  const double c2 = (kSsimK2 * 1.0) * (kSsimK2 * 1.0);
  std::vector<double> row_sums(ny, 0.0);
  const int ca = a.Channels(), cb = b.Channels();
  ParallelForChunks(ny, kChunkRows, [&](int r0, int r1) {
    const int strip_in = kStripCols + 2 * kSsimRadius;
    std::vector<double> ra(strip_in), rb(strip_in), raa(strip_in), rbb(strip_in), rab(strip_in);
    std::vector<double> ring(static_cast<size_t>(5) * kTaps * kStripCols);
    std::vector<double> map(kStripCols);
    for (int r = r0; r < r1; ++r) row_sums[r] = 0.0;
    for (int x0 = 0; x0 < nx; x0 += kStripCols) {
      const int sx = std::min(kStripCols, nx - x0);
      auto slot = [&](int plane, int yy) {
        return ring.data() + (static_cast<size_t>(plane) * kTaps + yy % kTaps) * kStripCols;
      };
      for (int yy = r0; yy < r1 + 2 * kSsimRadius; ++yy) {  // input rows of this chunk
        HorizontalRow(a.Row(yy) + static_cast<size_t>(x0) * ca + c, ca, sx + 2 * kSsimRadius, sx, w.data(), ra.data(),
                      raa.data(), slot(0, yy), slot(2, yy));
        HorizontalRow(b.Row(yy) + static_cast<size_t>(x0) * cb + c, cb, sx + 2 * kSsimRadius, sx, w.data(), rb.data(),
                      rbb.data(), slot(1, yy), slot(3, yy));
        HorizontalCross(ra.data(), rb.data(), sx + 2 * kSsimRadius, sx, w.data(), rab.data(), slot(4, yy));
        const int r = yy - 2 * kSsimRadius;  // output row complete once its 11th input row is in
        if (r < r0) continue;
        const double* pa[kTaps];
        const double* pb[kTaps];
        const double* paa[kTaps];
        const double* pbb[kTaps];
        const double* pab[kTaps];
        for (int j = 0; j < kTaps; ++j) {
          pa[j] = slot(0, r + j);
          pb[j] = slot(1, r + j);
          paa[j] = slot(2, r + j);
          pbb[j] = slot(3, r + j);
          pab[j] = slot(4, r + j);
        }
        VerticalAndMap(pa, pb, paa, pbb, pab, sx, w.data(), c1, c2, map.data());
        double sum = row_sums[r];
        for (int ox = 0; ox < sx; ++ox) sum += map[ox];
        row_sums[r] = sum;
      }
    }
  });
  return MeanOfRowSums(row_sums, nx, ny);
}

// The prepared path (PrepareSsimReference / ComputeSsim(image, side)): the reference's two
// window means E_w[y] and E_w[y²] are the same for every method of a scene, so they are
// formed once, with the kernels above (the same sums in the same order), and kept as full
// planes over the valid region; a method's score then forms only E_w[x], E_w[x²] and
// E_w[xy] (3 of the 5 horizontal and vertical window sums) and the map.

// Vertical window sums of two planes, for the reference side.
constexpr int kV2Lanes = 32;

AALAB_SIMD_CLONES
void VerticalSums2(const double* const* rows_b, const double* const* rows_bb, int nx, const double* w, double* mb_out,
                   double* mbb_out) {
  int ox = 0;
  for (; ox + kV2Lanes <= nx; ox += kV2Lanes) {
    double mb[kV2Lanes] = {}, mbb[kV2Lanes] = {};
    for (int j = 0; j < kTaps; ++j) {
      const double wj = w[j];
      for (int k = 0; k < kV2Lanes; ++k) {
        mb[k] += wj * rows_b[j][ox + k];
        mbb[k] += wj * rows_bb[j][ox + k];
      }
    }
    for (int k = 0; k < kV2Lanes; ++k) {
      mb_out[ox + k] = mb[k];
      mbb_out[ox + k] = mbb[k];
    }
  }
  for (; ox < nx; ++ox) {
    double mb = 0.0, mbb = 0.0;
    for (int j = 0; j < kTaps; ++j) {
      mb += w[j] * rows_b[j][ox];
      mbb += w[j] * rows_bb[j][ox];
    }
    mb_out[ox] = mb;
    mbb_out[ox] = mbb;
  }
}

// VerticalAndMap with the reference's vertical sums given (mb, mbb: one row of the planes).
AALAB_SIMD_CLONES
void VerticalAndMapPrepared(const double* const* rows_a, const double* const* rows_aa, const double* const* rows_ab,
                            const double* mb, const double* mbb, int nx, const double* w, double c1, double c2,
                            double* map) {
  int ox = 0;
  for (; ox + kVLanes <= nx; ox += kVLanes) {
    double ma[kVLanes] = {}, maa[kVLanes] = {}, mab[kVLanes] = {};
    for (int j = 0; j < kTaps; ++j) {
      const double wj = w[j];
      for (int k = 0; k < kVLanes; ++k) {
        ma[k] += wj * rows_a[j][ox + k];
        maa[k] += wj * rows_aa[j][ox + k];
        mab[k] += wj * rows_ab[j][ox + k];
      }
    }
    for (int k = 0; k < kVLanes; ++k) map[ox + k] = MapValue(ma[k], mb[ox + k], maa[k], mbb[ox + k], mab[k], c1, c2);
  }
  for (; ox < nx; ++ox) {
    double ma = 0.0, maa = 0.0, mab = 0.0;
    for (int j = 0; j < kTaps; ++j) {
      ma += w[j] * rows_a[j][ox];
      maa += w[j] * rows_aa[j][ox];
      mab += w[j] * rows_ab[j][ox];
    }
    map[ox] = MapValue(ma, mb[ox], maa, mbb[ox], mab, c1, c2);
  }
}

}  // namespace

struct SsimReferenceSide {
  const ImageF* image = nullptr;                     // the reference (for the cross term E_w[xy]); not owned
  int nx = 0, ny = 0;                                // valid region; 0 when the image is smaller than the window
  std::array<std::vector<double>, 3> mean, mean_sq;  // E_w[y], E_w[y²] per channel, nx × ny row-major
};

namespace {

// Fills side->mean[c], side->mean_sq[c] (same blocking as ChannelSsim).
void PrepareChannel(SsimReferenceSide* side, int c, const std::array<double, kTaps>& w) {
  const ImageF& b = *side->image;
  const int nx = side->nx, ny = side->ny;
  const int cb = b.Channels();
  side->mean[c].resize(static_cast<size_t>(nx) * ny);
  side->mean_sq[c].resize(static_cast<size_t>(nx) * ny);
  ParallelForChunks(ny, kChunkRows, [&](int r0, int r1) {
    const int strip_in = kStripCols + 2 * kSsimRadius;
    std::vector<double> rb(strip_in), rbb(strip_in);
    std::vector<double> ring(static_cast<size_t>(2) * kTaps * kStripCols);
    for (int x0 = 0; x0 < nx; x0 += kStripCols) {
      const int sx = std::min(kStripCols, nx - x0);
      auto slot = [&](int plane, int yy) {
        return ring.data() + (static_cast<size_t>(plane) * kTaps + yy % kTaps) * kStripCols;
      };
      for (int yy = r0; yy < r1 + 2 * kSsimRadius; ++yy) {
        HorizontalRow(b.Row(yy) + static_cast<size_t>(x0) * cb + c, cb, sx + 2 * kSsimRadius, sx, w.data(), rb.data(),
                      rbb.data(), slot(0, yy), slot(1, yy));
        const int r = yy - 2 * kSsimRadius;
        if (r < r0) continue;
        const double* pb[kTaps];
        const double* pbb[kTaps];
        for (int j = 0; j < kTaps; ++j) {
          pb[j] = slot(0, r + j);
          pbb[j] = slot(1, r + j);
        }
        const size_t at = static_cast<size_t>(r) * nx + x0;
        VerticalSums2(pb, pbb, sx, w.data(), side->mean[c].data() + at, side->mean_sq[c].data() + at);
      }
    }
  });
}

// ChannelSsim against a prepared reference: E_w[x], E_w[x²], E_w[xy] in a 3-plane ring, the
// reference's sums read from its planes; the map and its row sums as ChannelSsim.
double ChannelSsimPrepared(const ImageF& a, const SsimReferenceSide& side, int c, const std::array<double, kTaps>& w) {
  const ImageF& b = *side.image;
  const int nx = side.nx, ny = side.ny;
  const double c1 = (kSsimK1 * 1.0) * (kSsimK1 * 1.0);
  const double c2 = (kSsimK2 * 1.0) * (kSsimK2 * 1.0);
  std::vector<double> row_sums(ny, 0.0);
  const int ca = a.Channels(), cb = b.Channels();
  ParallelForChunks(ny, kChunkRows, [&](int r0, int r1) {
    const int strip_in = kStripCols + 2 * kSsimRadius;
    std::vector<double> ra(strip_in), rb(strip_in), raa(strip_in), rab(strip_in);
    std::vector<double> ring(static_cast<size_t>(3) * kTaps * kStripCols);
    std::vector<double> map(kStripCols);
    for (int x0 = 0; x0 < nx; x0 += kStripCols) {
      const int sx = std::min(kStripCols, nx - x0);
      const int sw = sx + 2 * kSsimRadius;
      auto slot = [&](int plane, int yy) {
        return ring.data() + (static_cast<size_t>(plane) * kTaps + yy % kTaps) * kStripCols;
      };
      for (int yy = r0; yy < r1 + 2 * kSsimRadius; ++yy) {
        HorizontalRow(a.Row(yy) + static_cast<size_t>(x0) * ca + c, ca, sw, sx, w.data(), ra.data(), raa.data(),
                      slot(0, yy), slot(1, yy));
        const float* brow = b.Row(yy) + static_cast<size_t>(x0) * cb + c;
        for (int x = 0; x < sw; ++x) rb[x] = static_cast<double>(brow[static_cast<size_t>(x) * cb]);
        HorizontalCross(ra.data(), rb.data(), sw, sx, w.data(), rab.data(), slot(2, yy));
        const int r = yy - 2 * kSsimRadius;
        if (r < r0) continue;
        const double* pa[kTaps];
        const double* paa[kTaps];
        const double* pab[kTaps];
        for (int j = 0; j < kTaps; ++j) {
          pa[j] = slot(0, r + j);
          paa[j] = slot(1, r + j);
          pab[j] = slot(2, r + j);
        }
        const size_t at = static_cast<size_t>(r) * nx + x0;
        VerticalAndMapPrepared(pa, paa, pab, side.mean[c].data() + at, side.mean_sq[c].data() + at, sx, w.data(), c1,
                               c2, map.data());
        double sum = row_sums[r];
        for (int ox = 0; ox < sx; ++ox) sum += map[ox];
        row_sums[r] = sum;
      }
    }
  });
  return MeanOfRowSums(row_sums, nx, ny);
}

std::vector<MetricValue> ComputeSsimMetric(const MetricInput& in) {
  AALAB_CHECK(in.image && in.reference, "ssim needs image and reference");
  const SsimResult r =
      in.ssim_reference ? ComputeSsim(*in.image, *in.ssim_reference) : ComputeSsim(*in.image, *in.reference);
  return {MetricValue{"ssim", r.ssim, r.null_reason}};
}

}  // namespace

namespace {

// The checks and the per-channel loop shared by every path; channel(c, w) is one
// channel's mean SSIM.
template <typename Channel>
SsimResult ComputeSsimWith(const ImageF& a, const ImageF& b, Channel channel) {
  RequireSameShape(a, b, "ssim");
  if (a.Channels() < 3) {
    throw UserError("ssim: needs RGB images (got " + std::to_string(a.Channels()) + " channels)");
  }
  SsimResult out;
  if (a.Width() < 2 * kSsimRadius + 1 || a.Height() < 2 * kSsimRadius + 1) {
    out.null_reason = "image smaller than the 11x11 SSIM window";
    return out;
  }
  const auto w = GaussianWindow();
  for (int c = 0; c < 3; ++c) out.per_channel[c] = channel(c, w);
  out.ssim = (out.per_channel[0] + out.per_channel[1] + out.per_channel[2]) / 3.0;
  return out;
}

}  // namespace

SsimResult ComputeSsimReference(const ImageF& a, const ImageF& b) {
  return ComputeSsimWith(a, b, [&](int c, const auto& w) { return ChannelSsimReference(a, b, c, w); });
}

SsimResult ComputeSsim(const ImageF& a, const ImageF& b) {
  return ComputeSsimWith(a, b, [&](int c, const auto& w) { return ChannelSsim(a, b, c, w); });
}

std::shared_ptr<const SsimReferenceSide> PrepareSsimReference(const ImageF& reference) {
  if (reference.Channels() < 3) {
    throw UserError("ssim: needs RGB images (got " + std::to_string(reference.Channels()) + " channels)");
  }
  auto side = std::make_shared<SsimReferenceSide>();
  side->image = &reference;
  if (reference.Width() < 2 * kSsimRadius + 1 || reference.Height() < 2 * kSsimRadius + 1) return side;
  side->nx = reference.Width() - 2 * kSsimRadius;
  side->ny = reference.Height() - 2 * kSsimRadius;
  const auto w = GaussianWindow();
  for (int c = 0; c < 3; ++c) PrepareChannel(side.get(), c, w);
  return side;
}

SsimResult ComputeSsim(const ImageF& image, const SsimReferenceSide& reference) {
  return ComputeSsimWith(image, *reference.image,
                         [&](int c, const auto& w) { return ChannelSsimPrepared(image, reference, c, w); });
}

std::vector<MetricEntry> SsimMetrics() {
  return {{"ssim",
           "SSIM (Wang 2004; 11x11 Gaussian σ=1.5, K1=0.01, K2=0.03), mean over R,G,B on "
           "sRGB values, valid region",
           {{"ssim", "SSIM", "", Improves::kHigher, kSignificantDigits,
             "Structural similarity (Wang et al. 2004), mean of R, G, B.",
             "Rewards matching local structure (mean, contrast, correlation) in 11×11 windows; blur lowers it "
             "less than a one-pixel shift."}},
           &ComputeSsimMetric}};
}

}  // namespace aalab
