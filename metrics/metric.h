/// Metrics: pure functions of a method image and the reference (sRGB-encoded values in
/// [0, 1], RGB; docs/design.md "Metrics"). Sums in double, in a fixed order.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"

namespace aalab {

struct SsimReferenceSide;  // metrics/ssim.h

/// One isolated flat disk for the signed coverage (area bias) metric: a window that holds the
/// whole disk and, outside it, one uniform colour; the disk's colour and that colour in
/// display-linear light; its exact area and radius in pixels. Built from the scene
/// (scenes/exact_reference.h DiskProbes) by the runner.
struct CoverageProbe {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< window [x0, x1) × [y0, y1)
  double radius_px = 0, area_px = 0;
  float inside[3] = {0, 0, 0}, outside[3] = {0, 0, 0};
};

/// Inputs shared by all metrics. `image` and `reference` are sRGB-encoded float RGB of the
/// same size; `edge_mask` (optional, same size, 1 channel, 0 or 1) marks geometric edges.
struct MetricInput {
  const ImageF* image = nullptr;
  const ImageF* reference = nullptr;
  const ImageF* edge_mask = nullptr;
  const ImageF* none_image = nullptr;  ///< the `none` frame, for relative metrics (optional)
  /// Optional: flip::ErrorValues(*reference, *image, flip_ppd), already computed by
  /// the caller (the runner also needs it for the FLIP heatmap). Same values either way.
  const std::vector<double>* flip_values = nullptr;
  /// Pixels per degree of the viewing condition (metrics/viewing.h) FLIP uses; 67 (FLIP's
  /// default, kFlipDefaultPpd) unless the run names another.
  double flip_ppd = 67.0;
  /// Optional: PrepareSsimReference(*reference), prepared once per scene by the caller (the
  /// reference's half of SSIM). Same values either way.
  const SsimReferenceSide* ssim_reference = nullptr;
  /// Optional: isolated flat disks for the area-bias metrics (metrics/coverage_bias.cpp).
  const std::vector<CoverageProbe>* coverage_probes = nullptr;
};

/// One named value. `value` empty means "not defined" (JSON null), with `null_reason`.
struct MetricValue {
  std::string name;
  std::optional<double> value;
  std::string null_reason;
};

/// One registry row: a metric family computes one or more named values.
struct MetricEntry {
  std::string name;
  std::string help;
  std::vector<std::string> outputs;  ///< names of the values it produces
  std::vector<MetricValue> (*compute)(const MetricInput& in);
  /// The row needs `MetricInput::edge_mask`; ComputeAllMetrics reports its values as null
  /// ("no edge mask") when the mask is absent instead of calling `compute`.
  bool needs_edge_mask = false;
  /// Where the metric comes from: BibTeX keys of reports/export_bibliography.cpp, comma
  /// separated ("" = defined here, nothing to cite). Set once per family in registry.cpp.
  std::string source = "";
};

/// Every metric, in listing order.
const std::vector<MetricEntry>& MetricRegistry();

/// Mean over pixels of the RGB-mean squared error between two same-size images (double sums,
/// row-major order). `mask` (optional): only pixels where mask > 0.5 (or <= 0.5 when
/// `invert`). Returns the MSE and the pixel count used.
struct MseResult {
  double mse = 0.0;
  size_t pixels = 0;
};
MseResult MeanSquaredError(const ImageF& a, const ImageF& b, const ImageF* mask = nullptr,
                           bool invert = false);

/// PSNR in dB for peak 1.0 from an MSE: 10·log10(1 / mse); empty when mse == 0 (identical).
std::optional<double> PsnrFromMse(double mse);

/// Checks two images have the same size and channel count; throws UserError naming both
/// sizes otherwise (never resample silently). `what` names the pair in the message.
void RequireSameShape(const ImageF& a, const ImageF& b, const std::string& what);

}  // namespace aalab
