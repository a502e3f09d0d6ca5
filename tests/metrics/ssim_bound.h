// The precision bound of SSIM's float32 path (metrics/ssim_float.cpp), evaluated per pixel,
// and an accurate double SSIM map to hold the production map to: each window's statistics
// formed directly over its 121 taps with the 2-D Gaussian, the variances about the window's
// own mean (two passes), so no cancellation, even under a constant offset of 1000 (where the
// separable double reference, E[x²] − E[x]², loses ~1e-6 itself).
#pragma once
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "core/image.h"
#include "metrics/ssim.h"
#include "metrics/ssim_float.h"

namespace aalab::testssim {

struct PixelMaps {
  std::vector<double> ssim;   // accurate double SSIM map, valid region, row-major
  std::vector<double> bound;  // the float path's bound per pixel (first order × 1.25, + 1e-12)
};

// u = 2⁻²⁴; γn = n·u / (1 − n·u).
inline double Gamma(int n) {
  const double u = std::ldexp(1.0, -24);
  return n * u / (1.0 - n * u);
}

inline PixelMaps AccurateMapAndBound(const ImageF& a, const ImageF& b, int c) {
  const int nx = a.Width() - 10, ny = a.Height() - 10;
  double w1[11], wsum = 0.0;
  for (int k = 0; k < 11; ++k) wsum += w1[k] = std::exp(-((k - 5) * (k - 5)) / (2.0 * kSsimSigma * kSsimSigma));
  for (double& v : w1) v /= wsum;
  const double c1 = kSsimK1 * kSsimK1, c2 = kSsimK2 * kSsimK2;
  const int tr = ssim_float::kTileRows, tc = ssim_float::kTileCols;
  std::map<std::pair<int, int>, std::pair<double, double>> centres;  // tile → (cx, cy)
  PixelMaps out;
  out.ssim.resize(static_cast<size_t>(nx) * ny);
  out.bound.resize(out.ssim.size());
  for (int oy = 0; oy < ny; ++oy) {
    for (int ox = 0; ox < nx; ++ox) {
      const int r0 = oy / tr * tr, x0 = ox / tc * tc;
      auto it = centres.find({r0, x0});
      if (it == centres.end()) {
        const int sy = std::min(tr, ny - r0), sx = std::min(tc, nx - x0);
        it = centres
                 .emplace(std::pair{r0, x0}, std::pair<double, double>{ssim_float::TileCentre(a, c, x0, r0, sx, sy),
                                                                       ssim_float::TileCentre(b, c, x0, r0, sx, sy)})
                 .first;
      }
      const auto [cx, cy] = it->second;
      double mx = 0.0, my = 0.0;
      for (int j = 0; j < 11; ++j)
        for (int i = 0; i < 11; ++i) {
          mx += w1[i] * w1[j] * a.At(ox + i, oy + j, c);
          my += w1[i] * w1[j] * b.At(ox + i, oy + j, c);
        }
      double vx = 0.0, vy = 0.0, vxy = 0.0, qx = 0.0, qy = 0.0;
      for (int j = 0; j < 11; ++j)
        for (int i = 0; i < 11; ++i) {
          const double w = w1[i] * w1[j], x = a.At(ox + i, oy + j, c), y = b.At(ox + i, oy + j, c);
          vx += w * (x - mx) * (x - mx);
          vy += w * (y - my) * (y - my);
          vxy += w * (x - mx) * (y - my);
          qx += w * (x - cx) * (x - cx);
          qy += w * (y - cy) * (y - cy);
        }
      const double d = vx + vy + c2, m = mx * mx + my * my + c1;
      const size_t at = static_cast<size_t>(oy) * nx + ox;
      out.ssim[at] = (2.0 * mx * my + c1) * (2.0 * vxy + c2) / (m * d);
      const double g = 2.0 * (std::fabs(mx) + std::fabs(my)) / m;
      out.bound[at] =
          1.25 * (6.0 * Gamma(26) * (qx + qy) / d + g * Gamma(24) * (std::sqrt(qx) + std::sqrt(qy))) + 1e-12;
    }
  }
  return out;
}

// Worst |production − accurate| per pixel, as a multiple of the pixel's bound and absolute;
// the mean's |Δ| against the mean of the bounds.
struct Drift {
  double worst_ratio = 0.0, worst_abs = 0.0, mean_abs = 0.0, mean_bound = 0.0;
};

inline Drift MeasureDrift(const ImageF& a, const ImageF& b, int c) {
  const PixelMaps acc = AccurateMapAndBound(a, b, c);
  const std::vector<double> map = SsimMap(a, b, c);
  Drift d;
  double sum_map = 0.0, sum_acc = 0.0, sum_bound = 0.0;
  for (size_t i = 0; i < map.size(); ++i) {
    const double e = std::fabs(map[i] - acc.ssim[i]);
    d.worst_abs = std::max(d.worst_abs, e);
    d.worst_ratio = std::max(d.worst_ratio, e / acc.bound[i]);
    sum_map += map[i], sum_acc += acc.ssim[i], sum_bound += acc.bound[i];
  }
  const double n = static_cast<double>(map.size());
  d.mean_abs = std::fabs(sum_map - sum_acc) / n;
  d.mean_bound = sum_bound / n;
  return d;
}

}  // namespace aalab::testssim
