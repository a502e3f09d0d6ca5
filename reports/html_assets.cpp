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
  struct Known {
    std::string label, unit;
    int better;
    std::string help;
  };
  static const std::map<std::string, Known> kKnown = {
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
      {"flip_mean",
       {"FLIP mean", "", -1,
        "LDR-FLIP per-pixel error (0..1) averaged over the image, at the run's viewing condition (pixels per degree "
        "in the header; default 67)."}},
      {"flip_median_weighted",
       {"FLIP wtd. median", "", -1, "Value-weighted median of the LDR-FLIP error (as NVIDIA's FLIP tool prints)."}},
      {"flip_max", {"FLIP max", "", -1, "Largest per-pixel LDR-FLIP error."}},
      {"abs_err_p50", {"|err| p50", "", -1, "Median of the per-pixel absolute error (RGB mean, 0..1)."}},
      {"abs_err_p95", {"|err| p95", "", -1, "95th percentile of the per-pixel absolute error."}},
      {"abs_err_p99", {"|err| p99", "", -1, "99th percentile of the per-pixel absolute error."}},
      {"abs_err_max", {"|err| max", "", -1, "Largest per-pixel absolute error."}},
      {"temporal_rmse",
       {"Temporal RMSE", "", -1,
        "RMS over pixels and frame pairs of the change of the error image (method − reference) from frame to frame: "
        "flicker and crawl the reference does not have (0..1, --frames > 1)."}},
      {"temporal_psnr_db", {"Temporal PSNR", "dB", +1, "10·log10(1 / temporal MSE): the temporal RMSE as a PSNR."}},
      {"temporal_edge_rmse",
       {"Temporal edge RMSE", "", -1, "The temporal RMSE over the edge masks of both frames of each pair."}},
      {"temporal_perceptual",
       {"Perceptual temporal error", "", -1,
        "How visible the change of the error over the sequence is at the viewing condition: the lightness error, "
        "blurred by FLIP's spatial CSF at the run's pixels per degree, its variation over windows of up to 32 frames "
        "weighted per temporal frequency by Watson's (1986) temporal CSF at the run's frame rate (L*/100 units)."}},
      {"temporal_csf_rmse",
       {"Temporal CSF RMSE", "", -1,
        "The frame-to-frame change of the CSF-blurred lightness error, RMS (L*/100 units): temporal RMSE with the "
        "spatial detail the eye does not resolve at this viewing distance removed."}},
  };
  // What each axis rewards (metrics/METRICS.md "What each metric rewards").
  static const std::map<std::string, std::string> kRewards = {
      {"psnr_db", "Rewards closeness to the reference pixel by pixel. Blur that halves an edge's error scores well "
                  "even where it also softens texture; it does not say whether the result looks better."},
      {"edge_psnr_db", "Rewards removing the stair-step error on geometric edges. A blur that smears every edge "
                       "scores well here, and blur of detail off the edges is not counted at all."},
      {"interior_psnr_db", "Rewards leaving everything off the edges alone: drops when a filter blurs texture "
                           "or text."},
      {"ssim", "Rewards matching local structure (mean, contrast, correlation) in 11×11 windows; blur lowers it "
               "less than a one-pixel shift."},
      {"flip_mean", "Rewards what a viewer sees when flipping between the result and the reference at this "
                    "viewing distance: both jaggies and lost sharpness count, fine detail below the eye's "
                    "resolution does not. A method that trades aliasing for blur can score worse than no AA."},
      {"temporal_rmse", "Rewards a steady error: any frame-to-frame change the reference does not have counts "
                        "the same at every spatial scale, so single-pixel popping weighs as much as wide "
                        "shimmer, and a steadily wrong (blurred or aliased but still) image scores 0."},
      {"temporal_perceptual",
       "Rewards an error that does not visibly change over time: single-pixel popping the eye does not resolve "
       "at this distance, and flicker near the frame rate's limit, count less; wide shimmer, ghost trails and "
       "slow crawl over the whole window count more. Still wrong images score 0: read it with FLIP."},
      {"temporal_csf_rmse", "As the temporal RMSE, but on the eye-resolvable part of the lightness error: "
                            "single-pixel popping counts less than wide shimmer."},
  };
  auto rewards = [](const std::string& n) {
    const auto r = kRewards.find(n);
    return r == kRewards.end() ? std::string() : r->second;
  };
  const auto it = kKnown.find(name);
  if (it != kKnown.end()) return {it->second.label, it->second.unit, it->second.better, it->second.help, rewards(name)};
  MetricInfo info{name, "", 0, "Not described by this version of the page (see metrics/METRICS.md).", ""};
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

std::string PageStyle() { return std::string(Asset("style.css")) + "\n" + std::string(Asset("abview.css")); }

std::string AbViewAssets() {
  return "<style>\n" + std::string(Asset("abview.css")) + "</style>\n<script>\n" + std::string(Asset("abview.js")) +
         "\nAAB.autoMount();\n</script>\n";
}

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
