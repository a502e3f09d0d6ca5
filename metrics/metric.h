/// Metrics: pure functions of a method image and the reference (sRGB-encoded values in
/// [0, 1], RGB; docs/design.md "Metrics"). Sums in double, in a fixed order.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"

namespace aalab {

struct SsimReferenceSide;  // metrics/ssim.h

/// Per-pixel FLIP values, row-major (flip::ErrorValues): a std::vector<double> whose storage
/// is not zero-filled when it is sized (DefaultInitAllocator), since the producer writes every
/// value; copies and comparisons are std::vector's.
using FlipValues = std::vector<double, DefaultInitAllocator<double>>;

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
  const FlipValues* flip_values = nullptr;
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

/// Which way an output improves: higher, lower, or towards 0 (a signed bias).
enum class Improves { kHigher, kLower, kTowardZero };

/// `MetricOutput::decimals` for values printed with significant digits instead of fixed
/// decimals (the page: 4 significant digits; aalab export: enough decimals for 3 significant
/// digits of a column's largest value).
inline constexpr int kSignificantDigits = -1;

/// One value a metric produces, described for every reader (the page, compare, export,
/// sweep, METRICS.md's generated tables): what reports say about it comes from here only.
struct MetricOutput {
  std::string key;    ///< the name in report.json, e.g. "edge_psnr_db"
  std::string label;  ///< short column label, e.g. "Edge PSNR"
  std::string unit;   ///< "dB" or "" (dimensionless); "dB" values are judged with --max-drop-db
  Improves better = Improves::kLower;
  /// Printed precision: fixed decimals (dB values: 2), or kSignificantDigits.
  int decimals = kSignificantDigits;
  std::string help;     ///< one sentence: what the value is (the page's column tooltip)
  std::string rewards;  ///< what it rewards and misses (the page's axis note); may be empty
};

/// What a registry row computes from: one image against its reference (ComputeAllMetrics),
/// or a frame sequence (computed frame by frame by its own accumulator, metrics/temporal*.h).
enum class MetricInputs { kImage, kSequence };

/// One registry row: a metric family computes one or more named values.
struct MetricEntry {
  std::string name;
  std::string help;
  std::vector<MetricOutput> outputs;  ///< the values it produces, in order
  /// Computes the outputs of one image pair; null for sequence rows.
  std::vector<MetricValue> (*compute)(const MetricInput& in) = nullptr;
  /// The row needs `MetricInput::edge_mask`; ComputeAllMetrics reports its values as null
  /// ("no edge mask") when the mask is absent instead of calling `compute`.
  bool needs_edge_mask = false;
  MetricInputs inputs = MetricInputs::kImage;
  /// Where the metric comes from: BibTeX keys of reports/export_bibliography.cpp, comma
  /// separated ("" = defined here, nothing to cite). Set once per family in registry.cpp.
  std::string source = "";
};

/// Every metric, image and sequence rows, in listing order (metrics/registry.cpp).
const std::vector<MetricEntry>& MetricRegistry();

/// The output named `key` (any row), or null when no registered metric produces it.
const MetricOutput* FindMetricOutput(const std::string& key);

/// The row that produces `key`, or null.
const MetricEntry* FindMetricEntry(const std::string& key);

/// Keys of every output of the image rows (what ComputeAllMetrics returns), in order.
std::vector<std::string> ImageMetricKeys();

/// The keys of `entry`'s outputs, in order.
std::vector<std::string> OutputKeys(const MetricEntry& entry);

/// METRICS.md's generated tables (`aalab list metrics --markdown`): the summary of every
/// output (family, label, unit, better, printed precision, input, source) and what each says.
std::string MetricTablesMarkdown();

/// Mean over pixels of the RGB-mean squared error between two same-size images (double sums,
/// row-major order). `mask` (optional): only pixels where mask > 0.5 (or <= 0.5 when
/// `invert`). Returns the MSE and the pixel count used.
struct MseResult {
  double mse = 0.0;
  size_t pixels = 0;
};
MseResult MeanSquaredError(const ImageF& a, const ImageF& b, const ImageF* mask = nullptr, bool invert = false);

/// PSNR in dB for peak 1.0 from an MSE: 10·log10(1 / mse); empty when mse == 0 (identical).
std::optional<double> PsnrFromMse(double mse);

/// Checks two images have the same size and channel count; throws UserError naming both
/// sizes otherwise (never resample silently). `what` names the pair in the message.
void RequireSameShape(const ImageF& a, const ImageF& b, const std::string& what);

}  // namespace aalab
