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
// Precision: two implementations. ComputeSsimReference is the definition in double
// precision (inputs converted to double, every product and sum double, window taps in index
// order, the map summed row by row). ComputeSsim, the production path (metrics/ssim_float.cpp),
// forms the window sums in float32 over tile-centred values and the map in double; it is
// held per pixel to the bound derived there (≤ 6·γ26·(Qx + Qy)/D + G·γ24·(√Qx + √Qy), Q a
// window's second moment about its tile's centre), which the tests check on every test image.
// Measured against the double definition: report values (the mean) moved by at most 3.7e-6
// over the default run at 480x270 and 1e-7 on the bench's 1080p pair; single pixels of the
// map by up to 5.7e-4 (the default run's frames), in flat windows far from their tile's
// centre. Both paths are
// bit-identical at any thread count; SSIM(x, x) = 1 and SSIM(x, y) = SSIM(y, x) exactly.
#include "metrics/ssim.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "metrics/families.h"
#include "metrics/metric.h"
#include "metrics/ssim_float.h"

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
// Mean SSIM of channel c over the valid region; the map into map_out when not null.
double ChannelSsimReference(const ImageF& a, const ImageF& b, int c, const std::array<double, kTaps>& w,
                            double* map_out) {
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
        if (map_out) map_out[static_cast<size_t>(r) * nx + ox] = num / den;
      }
      row_sums[r] = sum;
    }
  });
  return MeanOfRowSums(row_sums, nx, ny);
}

}  // namespace

struct SsimReferenceSide {
  const ImageF* image = nullptr;  // the reference (for the cross term E_w[dx·dy]); not owned
  bool valid = false;             // false when the image is smaller than the window
  std::array<ssim_float::ReferencePlanes, 3> channel;
};

namespace {

std::vector<MetricValue> ComputeSsimMetric(const MetricInput& in) {
  AALAB_CHECK(in.image && in.reference, "ssim needs image and reference");
  const SsimResult r =
      in.ssim_reference ? ComputeSsim(*in.image, *in.ssim_reference) : ComputeSsim(*in.image, *in.reference);
  return {MetricValue{"ssim", r.ssim, r.null_reason}};
}

}  // namespace

namespace {

// The checks shared by every path; all(w) gives the three channels' mean SSIM.
template <typename All>
SsimResult ComputeSsimWith(const ImageF& a, const ImageF& b, All all) {
  RequireSameShape(a, b, "ssim");
  if (a.Channels() < 3) {
    throw UserError("ssim: needs RGB images (got " + std::to_string(a.Channels()) + " channels)");
  }
  SsimResult out;
  if (a.Width() < 2 * kSsimRadius + 1 || a.Height() < 2 * kSsimRadius + 1) {
    out.null_reason = "image smaller than the 11x11 SSIM window";
    return out;
  }
  out.per_channel = all(GaussianWindow());
  out.ssim = (out.per_channel[0] + out.per_channel[1] + out.per_channel[2]) / 3.0;
  return out;
}

}  // namespace

SsimResult ComputeSsimReference(const ImageF& a, const ImageF& b) {
  return ComputeSsimWith(a, b, [&](const auto& w) {
    std::array<double, 3> out{};
    for (int c = 0; c < 3; ++c) out[c] = ChannelSsimReference(a, b, c, w, nullptr);
    return out;
  });
}

SsimResult ComputeSsim(const ImageF& a, const ImageF& b) {
  return ComputeSsimWith(a, b, [&](const auto& w) { return ssim_float::Ssim(a, b, w, -1, nullptr); });
}

std::shared_ptr<const SsimReferenceSide> PrepareSsimReference(const ImageF& reference) {
  if (reference.Channels() < 3) {
    throw UserError("ssim: needs RGB images (got " + std::to_string(reference.Channels()) + " channels)");
  }
  auto side = std::make_shared<SsimReferenceSide>();
  side->image = &reference;
  if (reference.Width() < 2 * kSsimRadius + 1 || reference.Height() < 2 * kSsimRadius + 1) return side;
  side->valid = true;
  side->channel = ssim_float::Prepare(reference, GaussianWindow());
  return side;
}

SsimResult ComputeSsim(const ImageF& image, const SsimReferenceSide& reference) {
  return ComputeSsimWith(image, *reference.image, [&](const auto& w) {
    return ssim_float::SsimPrepared(image, *reference.image, reference.channel, w);
  });
}

namespace {

// The map of channel c by `channel(w, map)`, after ComputeSsim's checks; empty when undefined.
template <typename Channel>
std::vector<double> MapWith(const ImageF& a, const ImageF& b, int c, Channel channel) {
  if (c < 0 || c > 2) throw UserError("ssim: map channel must be 0, 1 or 2 (got " + std::to_string(c) + ")");
  std::vector<double> map;
  ComputeSsimWith(a, b, [&](const auto& w) {
    map.resize(static_cast<size_t>(a.Width() - 2 * kSsimRadius) * (a.Height() - 2 * kSsimRadius));
    channel(w, map.data());
    return std::array<double, 3>{};
  });
  return map;
}

}  // namespace

std::vector<double> SsimMap(const ImageF& a, const ImageF& b, int c) {
  return MapWith(a, b, c, [&](const auto& w, double* m) { ssim_float::Ssim(a, b, w, c, m); });
}

std::vector<double> SsimMapReference(const ImageF& a, const ImageF& b, int c) {
  return MapWith(a, b, c, [&](const auto& w, double* m) { ChannelSsimReference(a, b, c, w, m); });
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
