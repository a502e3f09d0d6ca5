// The HTML report's embedded assets (reports/html/) and metric descriptions (see html_assets.h).
#include "reports/html_assets.h"

#include <map>
#include <stdexcept>

namespace aalab::html {

namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

bool IsPsnrMetric(const std::string& name) { return name == "psnr_db" || EndsWith(name, "_psnr_db"); }

MetricInfo DescribeMetric(const std::string& name) {
  // From metrics/METRICS.md.
  static const std::map<std::string, MetricInfo> kKnown = {
      {"psnr_db", {"PSNR", "dB", +1, "PSNR against the reference over all pixels (sRGB-encoded RGB, peak 1)."}},
      {"mse", {"MSE", "", -1, "Mean squared error over all pixels (sRGB-encoded RGB, 0..1)."}},
      {"edge_psnr_db",
       {"Edge PSNR", "dB", +1, "PSNR over the geometric edge mask: the aliasing that AA should remove."}},
      {"edge_rmse", {"Edge RMSE", "", -1, "Root mean squared error over the edge mask (0..1)."}},
      {"interior_psnr_db",
       {"Interior PSNR", "dB", +1, "PSNR off the edge mask: detail that AA should not blur."}},
      {"edge_error_removed",
       {"Edge err. removed", "", +1,
        "1 − edge MSE / none's edge MSE: 1 removes all of no-AA's edge error, 0 is no better than no AA, "
        "negative is worse."}},
      {"ssim", {"SSIM", "", +1, "Structural similarity (Wang et al. 2004), mean of R, G, B."}},
      {"flip_mean", {"FLIP mean", "", -1, "LDR-FLIP per-pixel error (0..1) averaged over the image, 67 px/degree."}},
      {"flip_median_weighted",
       {"FLIP wtd. median", "", -1, "Value-weighted median of the LDR-FLIP error (as NVIDIA's FLIP tool prints)."}},
      {"flip_max", {"FLIP max", "", -1, "Largest per-pixel LDR-FLIP error."}},
      {"abs_err_p50", {"|err| p50", "", -1, "Median of the per-pixel absolute error (RGB mean, 0..1)."}},
      {"abs_err_p95", {"|err| p95", "", -1, "95th percentile of the per-pixel absolute error."}},
      {"abs_err_p99", {"|err| p99", "", -1, "99th percentile of the per-pixel absolute error."}},
      {"abs_err_max", {"|err| max", "", -1, "Largest per-pixel absolute error."}},
  };
  const auto it = kKnown.find(name);
  if (it != kKnown.end()) return it->second;
  MetricInfo info{name, "", 0, "Not described by this version of the page (see metrics/METRICS.md)."};
  if (EndsWith(name, "_db")) {
    info.unit = "dB";
    if (IsPsnrMetric(name)) info.better = +1;
  } else if (EndsWith(name, "mse") || EndsWith(name, "rmse") || EndsWith(name, "_err")) {
    info.better = -1;
  }
  return info;
}

std::string_view Asset(std::string_view name) {
  for (std::size_t i = 0; i < kEmbeddedAssetCount; ++i) {
    if (name == kEmbeddedAssets[i].name) return {kEmbeddedAssets[i].data, kEmbeddedAssets[i].size};
  }
  throw std::logic_error("HTML asset '" + std::string(name) + "' was not embedded (reports/CMakeLists.txt)");
}

std::string_view PageStyle() { return Asset("style.css"); }

std::string PageScript() {
  std::string script;
  for (std::size_t i = 0; i < kEmbeddedAssetCount; ++i) {
    const std::string_view name = kEmbeddedAssets[i].name;
    if (name.size() < 3 || name.substr(name.size() - 3) != ".js") continue;
    script += '\n';
    script.append(kEmbeddedAssets[i].data, kEmbeddedAssets[i].size);
  }
  return script;
}

}  // namespace aalab::html
