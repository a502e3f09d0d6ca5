// Signed coverage: does a shape grow or shrink? (the AA article's radius adjustment)
//
// For every isolated flat disk (MetricInput::coverage_probes: a window holding the whole
// disk over one uniform colour), each pixel's coverage is read back from its colour in
// linear light, cov = (decode(v) − outside) / (inside − outside), on the channel with the
// largest contrast, for the method image (an 8-bit frame: inside and outside taken as their
// 8-bit values) and for the reference (float). The disk's area error is
// Σ_window (cov_method − cov_reference) in px²: positive when the method draws the disk too
// big. Values:
//   area_bias_px2       mean signed area error per disk, px²
//   area_bias_abs_rel   mean |area error| / true area over all disks (lower is better)
//   area_bias_rel_r<a>_<b>  mean signed area error / true area of the disks with radius in
//                       [a, b) px (bins 0–1, 1–2, 2–4, 4–8, 8–16, 16–64; larger radii
//                       join the last bin)
// Null when the scene has no probe (or none in the bin). Expected values, derived in
// docs/analytic-aa.md: a 1 px linear ramp centred on the outline adds π/12 ≈ 0.26 px² per
// disk; a ramp inside the outline loses πR − π/3 px². Sums in double in probe and row order.
#include <cmath>

#include "core/color.h"
#include "metrics/families.h"
#include "metrics/metric.h"

namespace aalab {

namespace {

constexpr double kBinEdges[] = {0.0, 1.0, 2.0, 4.0, 8.0, 16.0, 1e300};
constexpr const char* kBinNames[] = {"area_bias_rel_r0_1", "area_bias_rel_r1_2",  "area_bias_rel_r2_4",
                                     "area_bias_rel_r4_8", "area_bias_rel_r8_16", "area_bias_rel_r16_64"};
constexpr int kBins = 6;
constexpr float kMinContrast = 0.05f;  // linear; below it the read-back coverage is noise

/// What an 8-bit sRGB frame stores for a display-linear value, decoded back to linear.
double Through8Bit(float linear) { return SrgbDecode(QuantizeUnorm8(SrgbEncode(linear)) / 255.0f); }

/// Σ over the window of the coverage read back from `img`. The method image is an 8-bit
/// frame: its flat inside and outside colours are the quantised ones (else every interior
/// pixel would read back as slightly more or less than 1); the reference is float.
double WindowCoverage(const ImageF& img, const CoverageProbe& p, int channel, bool eight_bit) {
  const double in = eight_bit ? Through8Bit(p.inside[channel]) : p.inside[channel];
  const double out = eight_bit ? Through8Bit(p.outside[channel]) : p.outside[channel];
  double sum = 0.0;
  for (int y = p.y0; y < p.y1; ++y) {
    for (int x = p.x0; x < p.x1; ++x) sum += (SrgbDecode(img.At(x, y, channel)) - out) / (in - out);
  }
  return sum;
}

std::vector<MetricValue> Compute(const MetricInput& in) {
  std::vector<MetricValue> out;
  const char* none_reason = "no isolated flat disks (needs a flat scene with disks, e.g. sdf-circles)";
  double sum_px2 = 0, sum_abs = 0, bin_sum[kBins] = {}, n = 0;
  int bin_n[kBins] = {};
  if (in.coverage_probes) {
    for (const CoverageProbe& p : *in.coverage_probes) {
      int ch = 0;
      for (int c = 1; c < 3; ++c) {
        if (std::fabs(p.inside[c] - p.outside[c]) > std::fabs(p.inside[ch] - p.outside[ch])) ch = c;
      }
      if (std::fabs(p.inside[ch] - p.outside[ch]) < kMinContrast) continue;
      const double err = WindowCoverage(*in.image, p, ch, true) - WindowCoverage(*in.reference, p, ch, false);
      const double rel = err / p.area_px;
      sum_px2 += err;
      sum_abs += std::fabs(rel);
      n += 1;
      int b = 0;
      while (b + 1 < kBins && p.radius_px >= kBinEdges[b + 1]) ++b;
      bin_sum[b] += rel;
      bin_n[b]++;
    }
  }
  auto value = [&](const char* name, double num, double den) {
    if (den > 0) {
      out.push_back({name, num / den, ""});
    } else {
      out.push_back({name, std::nullopt,
                     in.coverage_probes && !in.coverage_probes->empty() ? "no disk with enough contrast in this group"
                                                                        : none_reason});
    }
  };
  value("area_bias_px2", sum_px2, n);
  value("area_bias_abs_rel", sum_abs, n);
  for (int b = 0; b < kBins; ++b) value(kBinNames[b], bin_sum[b], bin_n[b]);
  return out;
}

}  // namespace

std::vector<MetricEntry> CoverageBiasMetrics() {
  std::vector<MetricOutput> outputs = {
      {"area_bias_px2", "Area bias", "px²", Improves::kTowardZero, kSignificantDigits,
       "Mean signed area error per isolated flat disk (method − reference coverage summed over the disk's "
       "window): positive when shapes grow, negative when they shrink, 0 is unbiased.",
       ""},
      {"area_bias_abs_rel", "|Area bias| rel.", "", Improves::kLower, kSignificantDigits,
       "Mean |area error| / true area over all isolated flat disks.", ""}};
  constexpr const char* kBinLabels[] = {"r 0–1", "r 1–2", "r 2–4", "r 4–8", "r 8–16", "r 16–64"};
  for (int b = 0; b < kBins; ++b) {
    outputs.push_back({kBinNames[b], std::string("Area bias rel. ") + kBinLabels[b], "", Improves::kTowardZero,
                       kSignificantDigits,
                       std::string("Mean signed area error / true area of the disks with radius ") + kBinLabels[b] +
                           " px (0 is unbiased).",
                       ""});
  }
  return {{"coverage_bias",
           "signed area error of isolated flat disks (grow > 0, shrink < 0), overall and per radius bin", outputs,
           Compute, false}};
}

}  // namespace aalab
