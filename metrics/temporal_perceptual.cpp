// Perceptual temporal error: the change of a method's error over a sequence, weighted by the
// eye's spatial contrast sensitivity (FLIP's achromatic CSF at the viewing condition's pixels
// per degree) and temporal sensitivity (Watson 1986, at the viewing condition's frame rate).
//
// Sources: A. B. Watson, "Temporal sensitivity", in Handbook of Perception and Human
// Performance, vol. 1, ch. 6 (Wiley 1986): the temporal impulse response of two cascades of
// 9 and 10 first-order stages, H(f) = ξ[(i2πfτ + 1)^−9 − ζ(i2πfκτ + 1)^−10], fitted to
// J. G. Robson, "Spatial and temporal contrast-sensitivity functions of the visual system",
// JOSA 56(8), 1966; τ = 4.94 ms, κ = 1.33, ζ = 0.9. Spatial CSF: LDR-FLIP (Andersson et al.
// 2020), the Y channel (metrics/flip.h). Definitions, validation and caveats: METRICS.md
// "Perceptual temporal error".
#include "metrics/temporal_perceptual.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "core/error.h"
#include "core/parallel.h"
#include "metrics/families.h"
#include "metrics/flip.h"

namespace aalab {

namespace {

constexpr double kTau = 4.94e-3, kKappa = 1.33, kZeta = 0.9;

double TemporalCsfRaw(double hz) {
  const double w = 2.0 * std::numbers::pi * hz;
  const std::complex<double> h1 = std::pow(std::complex<double>(1.0, w * kTau), -9);
  const std::complex<double> h2 = std::pow(std::complex<double>(1.0, w * kKappa * kTau), -10);
  return std::abs(h1 - kZeta * h2);
}

struct CsfPeak {
  double hz = 0.0, value = 0.0;
};

const CsfPeak& Peak() {
  static const CsfPeak peak = [] {
    CsfPeak p;
    for (int i = 0; i <= 100000; ++i) {  // 0..100 Hz on a 0.001 Hz grid
      const double f = i * 0.001;
      const double v = TemporalCsfRaw(f);
      if (v > p.value) p = {f, v};
    }
    return p;
  }();
  return peak;
}

/// CIE 1976 lightness of a relative luminance (white = 1), divided by 100.
double Lightness(double y) {
  constexpr double d = 6.0 / 29.0;
  const double f = y > d * d * d ? std::cbrt(y) : y / (3.0 * d * d) + 4.0 / 29.0;
  return (116.0 * f - 16.0) / 100.0;
}

/// S ⊛ Y of an sRGB-encoded RGB image: luminance (FLIP's RGB→XYZ row), then the separable
/// kernel along x and y with clamped borders. Row-major doubles.
std::vector<double> FilteredLuminance(const ImageF& img, const std::vector<double>& k) {
  const int W = img.Width(), H = img.Height(), r = static_cast<int>(k.size() / 2);
  std::vector<double> y(static_cast<size_t>(W) * H), tmp(y.size()), out(y.size());
  for (int j = 0; j < H; ++j) {
    for (int i = 0; i < W; ++i) {
      const flip::Color rgb = {flip::SrgbToLinear(img.At(i, j, 0)), flip::SrgbToLinear(img.At(i, j, 1)),
                               flip::SrgbToLinear(img.At(i, j, 2))};
      y[static_cast<size_t>(j) * W + i] = flip::LinearRgbToXyz(rgb)[1];
    }
  }
  ParallelFor(H, [&](int j) {
    for (int i = 0; i < W; ++i) {
      double s = 0.0;
      for (int t = -r; t <= r; ++t)
        s += k[static_cast<size_t>(t + r)] * y[static_cast<size_t>(j) * W + std::clamp(i + t, 0, W - 1)];
      tmp[static_cast<size_t>(j) * W + i] = s;
    }
  });
  ParallelFor(H, [&](int j) {
    for (int i = 0; i < W; ++i) {
      double s = 0.0;
      for (int t = -r; t <= r; ++t)
        s += k[static_cast<size_t>(t + r)] * tmp[static_cast<size_t>(std::clamp(j + t, 0, H - 1)) * W + i];
      out[static_cast<size_t>(j) * W + i] = s;
    }
  });
  return out;
}

}  // namespace

double TemporalCsfWeight(double hz) { return TemporalCsfRaw(hz) / Peak().value; }

double TemporalCsfPeakHz() { return Peak().hz; }

std::vector<int> PerceptualWindows(int frames) {
  if (frames < 2) return {};
  const int n = (frames + kPerceptualWindow - 1) / kPerceptualWindow;
  std::vector<int> w;
  for (int i = 0; i < n; ++i) w.push_back(frames / n + (i < frames % n ? 1 : 0));
  return w;
}

namespace {

/// The DFT's twiddles and the squared CSF weights of a window of m frames at `fps`.
struct WindowTable {
  size_t m = 0;
  std::vector<double> cos, sin;  ///< index (k·t) mod m
  std::vector<double> w2;        ///< index k (w2[0] unused)
};

WindowTable MakeWindowTable(size_t m, double fps) {
  WindowTable tab;
  tab.m = m;
  for (size_t i = 0; i < m; ++i) {
    const double a = -2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(m);
    tab.cos.push_back(std::cos(a));
    tab.sin.push_back(std::sin(a));
  }
  tab.w2.assign(m, 0.0);
  for (size_t k = 1; k < m; ++k) {
    const double w =
        fps > 0.0 ? TemporalCsfWeight(static_cast<double>(std::min(k, m - k)) * fps / static_cast<double>(m)) : 1.0;
    tab.w2[k] = w * w;
  }
  return tab;
}

/// The DFT runs on values[t] − values[0]: the same bins k ≥ 1 in exact arithmetic, and a
/// constant sequence (a still scene) gives exactly 0 instead of a rounding residue.
double Energy(const double* values, const WindowTable& tab) {
  const size_t m = tab.m;
  double sum = 0.0;
  for (size_t k = 1; k < m; ++k) {
    double re = 0.0, im = 0.0;
    for (size_t t = 1; t < m; ++t) {
      const size_t i = (k * t) % m;
      const double d = values[t] - values[0];
      re += d * tab.cos[i];
      im += d * tab.sin[i];
    }
    sum += tab.w2[k] * (re * re + im * im);
  }
  return sum / (static_cast<double>(m) * static_cast<double>(m));
}

}  // namespace

double WindowEnergy(const std::vector<double>& values, double fps) {
  if (values.size() < 2) return 0.0;
  return Energy(values.data(), MakeWindowTable(values.size(), fps));
}

std::vector<float> LightnessError(const ImageF& image, const ImageF& reference, const std::vector<double>& kernel) {
  RequireSameShape(image, reference, "perceptual temporal error: image vs reference");
  AALAB_CHECK(image.Channels() >= 3, "perceptual temporal error expects RGB images");
  const std::vector<double> a = FilteredLuminance(image, kernel), b = FilteredLuminance(reference, kernel);
  std::vector<float> e(a.size());
  for (size_t i = 0; i < a.size(); ++i) e[i] = static_cast<float>(Lightness(a[i]) - Lightness(b[i]));
  return e;
}

PerceptualTemporalError::PerceptualTemporalError(double ppd, double fps, int frames)
    : fps_(fps), kernel_(flip::MakeSpatialKernels(ppd).y), windows_(PerceptualWindows(frames)) {
  if (!(fps > 0.0) || !std::isfinite(fps)) throw UserError("frame rate must be finite and > 0");
}

void PerceptualTemporalError::AddFrame(const ImageF& image, const ImageF& reference) {
  std::vector<float> e = LightnessError(image, reference, kernel_);
  if (frames_ == 0) {
    width_ = image.Width();
    height_ = image.Height();
  }
  AALAB_CHECK(image.Width() == width_ && image.Height() == height_, "frames of a sequence share one size");
  if (frames_ > 0) {
    double s = 0.0;
    for (size_t i = 0; i < e.size(); ++i) {
      const double d = static_cast<double>(e[i]) - static_cast<double>(prev_error_[i]);
      s += d * d;
    }
    adjacent_sum_ += s;
    adjacent_terms_ += e.size();
  }
  prev_error_ = e;
  ++frames_;
  if (window_ < windows_.size()) {
    window_errors_.push_back(std::move(e));
    if (static_cast<int>(window_errors_.size()) == windows_[window_]) FlushWindow();
  }
}

void PerceptualTemporalError::FlushWindow() {
  const size_t m = window_errors_.size();
  const int W = width_, H = height_;
  // Per-row sums in parallel, added in row order: the same bits at any thread count.
  const WindowTable tab = MakeWindowTable(m, fps_);
  std::vector<double> rows(static_cast<size_t>(H), 0.0);
  ParallelFor(H, [&](int j) {
    std::vector<double> v(m);
    double s = 0.0;
    for (int i = 0; i < W; ++i) {
      const size_t p = static_cast<size_t>(j) * W + i;
      for (size_t t = 0; t < m; ++t) v[t] = window_errors_[t][p];
      s += Energy(v.data(), tab);
    }
    rows[static_cast<size_t>(j)] = s;
  });
  double total = 0.0;
  for (double r : rows) total += r;
  spectral_sum_ += static_cast<double>(m) * total;
  spectral_terms_ += m * static_cast<size_t>(W) * static_cast<size_t>(H);
  window_errors_.clear();
  ++window_;
}

std::vector<MetricEntry> PerceptualTemporalMetrics() {
  MetricEntry e{
      "temporal_perceptual",
      "how visible the change of the error is: CSF-blurred lightness error, its spectrum over windows of up to 32 "
      "frames weighted by Watson's temporal CSF, and its adjacent-frame RMS (--frames N > 1)",
      {{"temporal_perceptual", "Perceptual temporal error", "", Improves::kLower, kSignificantDigits,
        "How visible the change of the error over the sequence is at the viewing condition: the lightness error, "
        "blurred by FLIP's spatial CSF at the run's pixels per degree, its variation over windows of up to 32 frames "
        "weighted per temporal frequency by Watson's (1986) temporal CSF at the run's frame rate (L*/100 units).",
        "Rewards an error that does not visibly change over time: single-pixel popping the eye does not resolve at "
        "this distance, and flicker near the frame rate's limit, count less; wide shimmer, ghost trails and slow "
        "crawl over the whole window count more. Still wrong images score 0: read it with FLIP."},
       {"temporal_csf_rmse", "Temporal CSF RMSE", "", Improves::kLower, kSignificantDigits,
        "The frame-to-frame change of the CSF-blurred lightness error, RMS (L*/100 units): temporal RMSE with the "
        "spatial detail the eye does not resolve at this viewing distance removed.",
        "As the temporal RMSE, but on the eye-resolvable part of the lightness error: single-pixel popping counts "
        "less than wide shimmer."}}};
  e.inputs = MetricInputs::kSequence;
  return {e};
}

std::vector<std::string> PerceptualTemporalNames() { return OutputKeys(PerceptualTemporalMetrics().front()); }

std::vector<MetricValue> PerceptualTemporalError::Values() const {
  if (frames_ < 2 || spectral_terms_ == 0 || adjacent_terms_ == 0) {
    return {{"temporal_perceptual", std::nullopt, "needs at least 2 frames"},
            {"temporal_csf_rmse", std::nullopt, "needs at least 2 frames"}};
  }
  return {{"temporal_perceptual", std::sqrt(spectral_sum_ / static_cast<double>(spectral_terms_)), ""},
          {"temporal_csf_rmse", std::sqrt(adjacent_sum_ / static_cast<double>(adjacent_terms_)), ""}};
}

}  // namespace aalab
