// PSNR and the squared-error primitives every error metric builds on.
//
// Definition: MSE = mean over pixels of the mean over R, G, B of (a − b)², on sRGB-encoded
// values in [0, 1]; PSNR = 10·log10(peak² / MSE) with peak 1.0. Identical images (MSE = 0)
// have infinite PSNR, which JSON cannot hold: the value is empty (null) with the reason
// "identical". Sums are double, row by row in row-major order (fixed, thread-independent).
// Source: docs/design.md "Metrics"; OpenImageIO imagebufalgo_compare (double sums, peak).
#include <cmath>

#include "core/error.h"
#include "metrics/metric.h"

namespace aalab {

void RequireSameShape(const ImageF& a, const ImageF& b, const std::string& what) {
  if (a.Width() != b.Width() || a.Height() != b.Height()) {
    throw UserError(what + ": sizes differ (" + std::to_string(a.Width()) + "x" + std::to_string(a.Height()) + " vs " +
                    std::to_string(b.Width()) + "x" + std::to_string(b.Height()) +
                    "); images are never resampled to match");
  }
  if (a.Channels() != b.Channels()) {
    throw UserError(what + ": channel counts differ (" + std::to_string(a.Channels()) + " vs " +
                    std::to_string(b.Channels()) + ")");
  }
}

MseResult MeanSquaredError(const ImageF& a, const ImageF& b, const ImageF* mask, bool invert) {
  AALAB_CHECK(a.Width() == b.Width() && a.Height() == b.Height(), "MSE of different sizes");
  AALAB_CHECK(a.Channels() >= 3 && b.Channels() >= 3, "MSE needs RGB");
  double total = 0.0;
  size_t count = 0;
  for (int y = 0; y < a.Height(); ++y) {
    double row = 0.0;
    for (int x = 0; x < a.Width(); ++x) {
      if (mask) {
        const bool on = mask->At(x, y, 0) > 0.5f;
        if (on == invert) continue;
      }
      double px = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double d = static_cast<double>(a.At(x, y, c)) - static_cast<double>(b.At(x, y, c));
        px += d * d;
      }
      row += px / 3.0;
      ++count;
    }
    total += row;
  }
  MseResult r;
  r.pixels = count;
  r.mse = count ? total / static_cast<double>(count) : 0.0;
  return r;
}

std::optional<double> PsnrFromMse(double mse) {
  if (!(mse > 0.0)) return std::nullopt;
  return 10.0 * std::log10(1.0 / mse);
}

namespace {

std::vector<MetricValue> ComputePsnr(const MetricInput& in) {
  const MseResult r = MeanSquaredError(*in.image, *in.reference);
  MetricValue v{"psnr_db", PsnrFromMse(r.mse), ""};
  if (!v.value) v.null_reason = "identical";
  return {v, MetricValue{"mse", r.mse, ""}};
}

}  // namespace

std::vector<MetricEntry> PsnrMetrics() {
  return {{"psnr",
           "PSNR (dB, peak 1.0) and MSE on sRGB-encoded RGB over the whole image",
           {{"psnr_db", "PSNR", "dB", Improves::kHigher, 2,
             "PSNR against the reference over all pixels (sRGB-encoded RGB, peak 1).",
             "Rewards closeness to the reference pixel by pixel. Blur that halves an edge's error scores well "
             "even where it also softens texture; it does not say whether the result looks better."},
            {"mse", "MSE", "", Improves::kLower, kSignificantDigits,
             "Mean squared error over all pixels (sRGB-encoded RGB, 0..1).", ""}},
           &ComputePsnr}};
}

}  // namespace aalab
