// Absolute-error statistics: how the error is distributed over pixels, not just its mean.
//
// Per-pixel error e = (|Δr| + |Δg| + |Δb|) / 3 on sRGB-encoded values in [0, 1] (the mean over
// channels, consistent with the RGB-mean squared error of PSNR; a pure one-channel error of d
// therefore counts d/3). Units: fraction of the full 8-bit code range (multiply by 255 for
// code values).
// Values: abs_err_p50, abs_err_p95, abs_err_p99 (nearest-rank percentiles: sort the N pixel
// errors ascending, take the one of 1-based rank ceil(p·N/100)), abs_err_max (rank N).
// Identical images give 0 everywhere (values, not null). Null only for an empty image.
// Parameters: none. Source: docs/design.md "Metrics"; percentiles by the classic nearest-rank
// method (no interpolation: every reported percentile is an observed pixel error).
// Precision: differences and the per-pixel mean in double; ranks in exact integer
// arithmetic; order statistics (selected as a sort would place them) make the result
// independent of pixel order and thread count.
#include "metrics/error_stats.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "metrics/families.h"
#include "metrics/metric.h"

namespace aalab {

std::vector<double> AbsErrorValues(const ImageF& a, const ImageF& b) {
  RequireSameShape(a, b, "abs error");
  if (a.Channels() < 3) {
    throw UserError("abs error: needs RGB images (got " + std::to_string(a.Channels()) + " channels)");
  }
  std::vector<double> out;
  out.reserve(a.PixelCount());
  for (int y = 0; y < a.Height(); ++y) {
    for (int x = 0; x < a.Width(); ++x) {
      double s = 0.0;
      for (int c = 0; c < 3; ++c) {
        s += std::abs(static_cast<double>(a.At(x, y, c)) - static_cast<double>(b.At(x, y, c)));
      }
      out.push_back(s / 3.0);
    }
  }
  return out;
}

ImageF AbsErrorMap(const ImageF& a, const ImageF& b) {
  const std::vector<double> v = AbsErrorValues(a, b);
  ImageF map(a.Width(), a.Height(), 1, 0.0f);
  for (size_t i = 0; i < v.size(); ++i) map.Data()[i] = static_cast<float>(v[i]);
  return map;
}

double NearestRankPercentile(const std::vector<double>& sorted, int percent) {
  AALAB_CHECK(!sorted.empty(), "percentile of no values");
  AALAB_CHECK(percent >= 0 && percent <= 100, "percentile outside [0, 100]");
  const size_t n = sorted.size();
  size_t rank = (static_cast<size_t>(percent) * n + 99) / 100;  // ceil(percent·n/100)
  if (rank < 1) rank = 1;
  return sorted[rank - 1];
}

namespace {

std::vector<MetricValue> ComputeAbsError(const MetricInput& in) {
  AALAB_CHECK(in.image && in.reference, "abs error needs image and reference");
  std::vector<double> v = AbsErrorValues(*in.image, *in.reference);
  if (v.empty()) {
    return {MetricValue{"abs_err_p50", std::nullopt, "empty image"},
            MetricValue{"abs_err_p95", std::nullopt, "empty image"},
            MetricValue{"abs_err_p99", std::nullopt, "empty image"},
            MetricValue{"abs_err_max", std::nullopt, "empty image"}};
  }
  // Selection instead of a full sort (a 960x540 sort was ~4 % of a run's serial time): after
  // nth_element at index k, v[k] is the value a sort would put there and everything before it
  // is not larger, so the next lower rank is selected within [0, k). Same values as sorting.
  const size_t n = v.size();
  auto rank_index = [n](int percent) {
    const size_t rank = (static_cast<size_t>(percent) * n + 99) / 100;  // as NearestRankPercentile
    return (rank < 1 ? size_t{1} : rank) - 1;
  };
  const double max = *std::max_element(v.begin(), v.end());
  double p[3] = {0, 0, 0};
  const int percents[3] = {99, 95, 50};
  size_t end = n;
  for (int i = 0; i < 3; ++i) {
    const size_t k = rank_index(percents[i]);
    if (k < end)
      std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k),
                       v.begin() + static_cast<std::ptrdiff_t>(end));
    p[i] = v[k];
    end = k;
  }
  return {MetricValue{"abs_err_p50", p[2], ""}, MetricValue{"abs_err_p95", p[1], ""},
          MetricValue{"abs_err_p99", p[0], ""}, MetricValue{"abs_err_max", max, ""}};
}

}  // namespace

std::vector<MetricEntry> AbsErrorMetrics() {
  return {{"abs_error",
           "Per-pixel |error| (mean over R,G,B, sRGB values): nearest-rank p50/p95/p99 and max",
           {{"abs_err_p50", "|err| p50", "", Improves::kLower, kSignificantDigits,
             "Median of the per-pixel absolute error (RGB mean, 0..1).", ""},
            {"abs_err_p95", "|err| p95", "", Improves::kLower, kSignificantDigits,
             "95th percentile of the per-pixel absolute error.", ""},
            {"abs_err_p99", "|err| p99", "", Improves::kLower, kSignificantDigits,
             "99th percentile of the per-pixel absolute error.", ""},
            {"abs_err_max", "|err| max", "", Improves::kLower, kSignificantDigits, "Largest per-pixel absolute error.",
             ""}},
           &ComputeAbsError}};
}

}  // namespace aalab
