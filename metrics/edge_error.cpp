// Edge / interior error: where does a method's error sit, on geometric edges (aliasing, what
// anti-aliasing is meant to fix) or off them (detail lost to blur, what it should not touch)?
//
// Inputs: `image`, `reference` (sRGB-encoded RGB in [0, 1]), `edge_mask` (1 channel, same
// size; a pixel is "on the mask" when its value > 0.5, as MeanSquaredError reads it) and,
// for edge_error_removed only, `none_image` (the method `none`: the aliased 1x frame).
//
// Values (MSE = mean over the selected pixels of the mean over R, G, B of (a − b)², double
// sums in row-major order; PSNR = 10·log10(1 / MSE), peak 1.0, as metrics/psnr.cpp):
//   edge_psnr_db        PSNR over mask pixels (dB).
//   edge_rmse           sqrt(MSE) over mask pixels (same units as the sRGB values, 0..1).
//   interior_psnr_db    PSNR over the pixels off the mask (dB): blur shows up here.
//   edge_error_removed  1 − MSE_edge(image) / MSE_edge(none_image): 1 = all edge error gone,
//                       0 = as bad as no AA, < 0 = worse than no AA. Dimensionless.
// Null reasons (exact strings, also in METRICS.md): "no edge mask" (mask absent), "empty
// image", "empty mask" (no pixel > 0.5), "mask covers every pixel" (interior has no pixel),
// "identical" (MSE = 0, PSNR infinite), "no none frame" (none_image absent), "none has no
// edge error" (MSE_edge(none) = 0, ratio undefined).
// Parameters: none. Source: docs/design.md "Metrics"; the split into edge and interior error is
// this project's definition, not a published metric.
#include <cmath>
#include <string>

#include "core/error.h"
#include "metrics/families.h"
#include "metrics/metric.h"

namespace aalab {
namespace {

const char* const kNames[] = {"edge_psnr_db", "edge_rmse", "interior_psnr_db", "edge_error_removed"};

std::vector<MetricValue> AllNull(const std::string& reason) {
  std::vector<MetricValue> out;
  for (const char* n : kNames) out.push_back(MetricValue{n, std::nullopt, reason});
  return out;
}

MetricValue Psnr(const std::string& name, const MseResult& r, const std::string& empty_reason) {
  if (r.pixels == 0) return MetricValue{name, std::nullopt, empty_reason};
  const std::optional<double> db = PsnrFromMse(r.mse);
  return MetricValue{name, db, db ? "" : "identical"};
}

void RequireMask(const ImageF& mask, const ImageF& reference) {
  if (mask.Width() != reference.Width() || mask.Height() != reference.Height()) {
    throw UserError("edge mask: size " + std::to_string(mask.Width()) + "x" + std::to_string(mask.Height()) +
                    " differs from the reference " + std::to_string(reference.Width()) + "x" +
                    std::to_string(reference.Height()) + "; masks are never resampled");
  }
  if (mask.Channels() != 1) {
    throw UserError("edge mask: has " + std::to_string(mask.Channels()) +
                    " channels; a mask has exactly 1 (0 or 1 per pixel)");
  }
}

std::vector<MetricValue> ComputeEdgeError(const MetricInput& in) {
  AALAB_CHECK(in.image && in.reference, "edge error needs image and reference");
  if (!in.edge_mask) return AllNull("no edge mask");
  RequireSameShape(*in.image, *in.reference, "edge error: image vs reference");
  RequireMask(*in.edge_mask, *in.reference);
  if (in.reference->Empty()) return AllNull("empty image");

  const MseResult edge = MeanSquaredError(*in.image, *in.reference, in.edge_mask, false);
  const MseResult interior = MeanSquaredError(*in.image, *in.reference, in.edge_mask, true);

  std::vector<MetricValue> out;
  out.push_back(Psnr("edge_psnr_db", edge, "empty mask"));
  if (edge.pixels == 0) {
    out.push_back(MetricValue{"edge_rmse", std::nullopt, "empty mask"});
  } else {
    out.push_back(MetricValue{"edge_rmse", std::sqrt(edge.mse), ""});
  }
  out.push_back(Psnr("interior_psnr_db", interior, "mask covers every pixel"));

  MetricValue removed{"edge_error_removed", std::nullopt, ""};
  if (edge.pixels == 0) {
    removed.null_reason = "empty mask";
  } else if (!in.none_image) {
    removed.null_reason = "no none frame";
  } else {
    RequireSameShape(*in.none_image, *in.reference, "edge error: none frame vs reference");
    const MseResult none = MeanSquaredError(*in.none_image, *in.reference, in.edge_mask, false);
    if (!(none.mse > 0.0)) {
      removed.null_reason = "none has no edge error";
    } else {
      removed.value = 1.0 - edge.mse / none.mse;
    }
  }
  out.push_back(removed);
  return out;
}

}  // namespace

std::vector<MetricEntry> EdgeErrorMetrics() {
  MetricEntry e{"edge",
                "PSNR/RMSE on edge-mask pixels, PSNR off the mask, share of the no-AA edge "
                "error removed",
                {{"edge_psnr_db", "Edge PSNR", "dB", Improves::kHigher, 2,
                  "PSNR over the geometric edge mask: the aliasing that AA should remove.",
                  "Rewards removing the stair-step error on geometric edges. A blur that smears every edge "
                  "scores well here, and blur of detail off the edges is not counted at all."},
                 {"edge_rmse", "Edge RMSE", "", Improves::kLower, kSignificantDigits,
                  "Root mean squared error over the edge mask (0..1).", ""},
                 {"interior_psnr_db", "Interior PSNR", "dB", Improves::kHigher, 2,
                  "PSNR off the edge mask: detail that AA should not blur.",
                  "Rewards leaving everything off the edges alone: drops when a filter blurs texture or text."},
                 {"edge_error_removed", "Edge err. removed", "", Improves::kHigher, kSignificantDigits,
                  "1 − edge MSE / none's edge MSE: 1 removes all of no-AA's edge error, 0 is no better than no AA, "
                  "negative is worse.",
                  ""}},
                &ComputeEdgeError};
  e.needs_edge_mask = true;
  return {e};
}

}  // namespace aalab
