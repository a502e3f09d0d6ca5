// The perceptual temporal error against values worked out by hand: Parseval, uniform
// flicker at a known frequency, slow drift, the spatial CSF's effect on one-pixel popping,
// and Watson's temporal CSF against the flicker psychophysics it was fitted to.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/parallel.h"
#include "metrics/temporal_perceptual.h"

namespace aalab {
namespace {

ImageF Filled(int w, int h, float v) {
  ImageF img(w, h, 3);
  for (float& x : img.Data()) x = v;
  return img;
}

double Value(const PerceptualTemporalError& p, const std::string& name) {
  for (const auto& v : p.Values()) {
    if (v.name == name) return v.value.value();
  }
  throw std::runtime_error("no value " + name);
}

/// CIE L*/100 of a grey given sRGB-encoded, computed here from the standards' formulas.
double LightnessOfGrey(double encoded) {
  const double lin = encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
  return (116.0 * std::cbrt(lin) - 16.0) / 100.0;  // lin > (6/29)³ for every grey used here
}

TEST(TemporalCsf, ShapeOfTheFlickerSensitivity) {
  // Watson's fit to Robson (1966) and the classic flicker data (de Lange 1958, Kelly 1961):
  // band-pass, most sensitive near 8 Hz, about a quarter of the peak at 1 Hz, a tenth near
  // 30 Hz and nearly blind at 60 Hz.
  EXPECT_GT(TemporalCsfPeakHz(), 7.0);
  EXPECT_LT(TemporalCsfPeakHz(), 10.0);
  EXPECT_NEAR(TemporalCsfWeight(TemporalCsfPeakHz()), 1.0, 1e-12);
  EXPECT_GT(TemporalCsfWeight(1.0), 0.15);
  EXPECT_LT(TemporalCsfWeight(1.0), 0.4);
  EXPECT_GT(TemporalCsfWeight(30.0), 0.05);
  EXPECT_LT(TemporalCsfWeight(30.0), 0.2);
  EXPECT_LT(TemporalCsfWeight(60.0), 0.01);
}

// Watson (1986), eq. for the temporal impulse response's spectrum with the parameters of his
// fit to Robson (1966): τ = 4.94 ms, κ = 1.33, ζ = 0.9, stages 9 and 10. Worked here in polar
// form, independently of the code's complex powers: (1 + ia)^−n has modulus (1 + a²)^(−n/2)
// and argument −n·atan(a). The weights at 1..60 Hz, normalised by the peak (found here by a
// golden-section search), must match TemporalCsfWeight: a swapped exponent, κ on the wrong
// stage or a different τ moves them by far more than the tolerance.
double WatsonModulus(double hz) {
  const double tau = 4.94e-3, kappa = 1.33, zeta = 0.9, w = 2.0 * std::numbers::pi * hz;
  const double a1 = w * tau, a2 = w * kappa * tau;
  const double m1 = std::pow(1.0 + a1 * a1, -4.5), p1 = -9.0 * std::atan(a1);
  const double m2 = zeta * std::pow(1.0 + a2 * a2, -5.0), p2 = -10.0 * std::atan(a2);
  return std::hypot(m1 * std::cos(p1) - m2 * std::cos(p2), m1 * std::sin(p1) - m2 * std::sin(p2));
}

TEST(TemporalCsf, MatchesWatsonsFitWorkedInPolarForm) {
  double lo = 1.0, hi = 30.0;  // golden-section search for the peak of a unimodal band-pass
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int i = 0; i < 200; ++i) {
    const double c = hi - g * (hi - lo), d = lo + g * (hi - lo);
    if (WatsonModulus(c) > WatsonModulus(d)) {
      hi = d;
    } else {
      lo = c;
    }
  }
  const double peak_hz = (lo + hi) / 2.0, peak = WatsonModulus(peak_hz);
  EXPECT_NEAR(TemporalCsfPeakHz(), peak_hz, 0.001);  // the code's 0.001 Hz grid
  for (double hz : {0.5, 1.0, 2.0, 4.0, 8.0, 12.0, 16.0, 24.0, 30.0, 45.0, 60.0}) {
    // The code normalises by the grid's maximum, at most 0.0005 Hz from the true peak: a
    // relative error of order 1e-8 there (the derivative vanishes at the peak).
    EXPECT_NEAR(TemporalCsfWeight(hz), WatsonModulus(hz) / peak, 1e-6) << hz << " Hz";
  }
}

TEST(PerceptualTemporal, WindowEnergyWithoutWeightsIsTheVariance) {
  // Parseval: (1/M²)·Σ_{k≥1} |Ê_k|² = population variance. {1, 3, 2, 6}: mean 3,
  // variance (4 + 0 + 1 + 9)/4 = 3.5.
  EXPECT_NEAR(WindowEnergy({1, 3, 2, 6}, 0.0), 3.5, 1e-12);
  EXPECT_EQ(WindowEnergy({0.25, 0.25, 0.25}, 60.0), 0.0);  // constant: exactly 0
  EXPECT_EQ(PerceptualWindows(16), std::vector<int>({16}));
  EXPECT_EQ(PerceptualWindows(33), std::vector<int>({17, 16}));
  EXPECT_EQ(PerceptualWindows(64), std::vector<int>({32, 32}));
  EXPECT_TRUE(PerceptualWindows(1).empty());
}

TEST(PerceptualTemporal, UniformFlickerAtHalfTheFrameRate) {
  // Reference grey 0.5 every frame; the method alternates 0.6 / 0.4 (sRGB-encoded). Uniform
  // images: the unit-sum CSF kernel leaves them as they are, so e_t = c + d·(−1)^t with
  // d = (L(0.6) − L(0.4))/2 ≈ 0.1 and all of the variance d² at k = M/2, f = fps/2:
  // temporal_perceptual = |d|·w(fps/2), temporal_csf_rmse = 2|d|.
  const double d = (LightnessOfGrey(0.6) - LightnessOfGrey(0.4)) / 2.0;
  for (double fps : {60.0, 16.0}) {
    PerceptualTemporalError p(67.0, fps, 16);
    const ImageF ref = Filled(9, 7, 0.5f);
    for (int t = 0; t < 16; ++t) p.AddFrame(Filled(9, 7, t % 2 ? 0.4f : 0.6f), ref);
    EXPECT_NEAR(Value(p, "temporal_csf_rmse"), 2.0 * d, 1e-6) << fps;
    EXPECT_NEAR(Value(p, "temporal_perceptual"), d * TemporalCsfWeight(fps / 2.0), 1e-6) << fps;
  }
  // At 60 fps the eye barely follows 30 Hz flicker (weight ≈ 0.1); at 16 fps the same
  // alternation is 8 Hz, near the peak.
  EXPECT_LT(TemporalCsfWeight(30.0), 0.2 * TemporalCsfWeight(8.0));
}

TEST(PerceptualTemporal, SlowDriftCountsWhereAdjacentDifferencesMissIt) {
  // The error grows by s per frame over 16 frames (a slow crawl): the adjacent-frame RMS is
  // s; the window's standard deviation is s·sqrt((M² − 1)/12) = 4.61·s, and almost all of the
  // ramp's energy sits in the lowest bins (3.75 and 7.5 Hz at 60 fps, weights 0.68 and
  // 0.99), so the perceptual value is several times the adjacent one.
  PerceptualTemporalError p(67.0, 60.0, 16);
  const ImageF ref = Filled(5, 5, 0.5f);
  for (int t = 0; t < 16; ++t) p.AddFrame(Filled(5, 5, 0.5f + 0.002f * t), ref);
  const double adjacent = Value(p, "temporal_csf_rmse"), whole = Value(p, "temporal_perceptual");
  EXPECT_GT(whole, 3.0 * adjacent);
  EXPECT_LT(whole, 4.62 * adjacent);
}

TEST(PerceptualTemporal, OnePixelPoppingIsDiscountedByTheSpatialCsf) {
  // A single pixel pops by a small step every other frame on a grey field. Linearised (small
  // step), the CSF spreads its lightness error over the kernel: the RMS over the image falls
  // by sqrt(Σ_ij k_i²k_j²) = Σ_i k_i² ≈ 1/(2√π·σ) for σ in pixels (1.034 at 67 px/deg,
  // 2.068 at 134): 0.273 and 0.136. A 9×9 block popping by the same step keeps most of it.
  auto adjacent = [](double ppd, int size) {
    PerceptualTemporalError p(ppd, 60.0, 4);
    const ImageF ref = Filled(31, 31, 0.5f);
    for (int t = 0; t < 4; ++t) {
      ImageF f = Filled(31, 31, 0.5f);
      if (t % 2) {
        for (int y = 15 - size / 2; y <= 15 + size / 2; ++y)
          for (int x = 15 - size / 2; x <= 15 + size / 2; ++x)
            for (int c = 0; c < 3; ++c) f.At(x, y, c) = 0.51f;
      }
      p.AddFrame(f, ref);
    }
    return Value(p, "temporal_csf_rmse");
  };
  // Unfiltered lightness step of the one pixel, as an RMS over the 31² pixels.
  const double step = (LightnessOfGrey(0.51) - LightnessOfGrey(0.5)) / 31.0;
  const double pi = 3.14159265358979;
  EXPECT_NEAR(adjacent(67.0, 1) / step, 1.0 / (2.0 * std::sqrt(pi) * 1.03385), 0.01);
  EXPECT_NEAR(adjacent(134.0, 1) / step, 1.0 / (2.0 * std::sqrt(pi) * 2.0677), 0.005);
  EXPECT_GT(adjacent(67.0, 9) / (step * 9.0), 0.8);
}

TEST(PerceptualTemporal, NullBeforeTwoFramesAndSameBitsAtAnyThreadCount) {
  PerceptualTemporalError one(67.0, 60.0, 1);
  one.AddFrame(Filled(4, 4, 0.2f), Filled(4, 4, 0.3f));
  for (const auto& v : one.Values()) EXPECT_FALSE(v.value.has_value()) << v.name;
  auto run = [](int threads) {
    SetThreadCount(threads);
    PerceptualTemporalError p(50.0, 60.0, 5);
    for (int t = 0; t < 5; ++t) {
      ImageF f(23, 17, 3), r(23, 17, 3);
      for (size_t i = 0; i < f.Data().size(); ++i) {
        f.Data()[i] = static_cast<float>((i * 7 + t * 13) % 31) / 31.0f;
        r.Data()[i] = static_cast<float>((i * 5) % 29) / 29.0f;
      }
      p.AddFrame(f, r);
    }
    return p.Values();
  };
  const auto a = run(1), b = run(2);
  SetThreadCount(0);
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(*a[i].value, *b[i].value) << a[i].name;
}

}  // namespace
}  // namespace aalab
