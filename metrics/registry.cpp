#include <cmath>

#include "core/error.h"
#include "metrics/families.h"
#include "metrics/metric.h"
#include "metrics/metrics.h"

namespace aalab {

const std::vector<MetricEntry>& MetricRegistry() {
  static const std::vector<MetricEntry> table = [] {
    std::vector<MetricEntry> all;
    auto add = [&all](std::vector<MetricEntry> rows, const char* source) {
      for (auto& r : rows) {
        r.source = source;
        all.push_back(std::move(r));
      }
    };
    // One line per family file, in listing order, with the family's source: BibTeX keys of
    // reports/export_bibliography.cpp (what `aalab export` cites; "" = defined by aalab).
    add(PsnrMetrics(), "");
    add(EdgeErrorMetrics(), "");
    add(SsimMetrics(), "wang2004ssim");
    add(FlipMetrics(), "andersson2020flip");
    add(AbsErrorMetrics(), "");
    add(CoverageBiasMetrics(), "");
    return all;
  }();
  return table;
}

std::vector<MetricValue> ComputeAllMetrics(const MetricInput& in) {
  if (!in.image || !in.reference) {
    throw InternalError("ComputeAllMetrics needs both an image and a reference");
  }
  RequireSameShape(*in.image, *in.reference, "metrics: image vs reference");
  std::vector<MetricValue> out;
  for (const MetricEntry& row : MetricRegistry()) {
    std::vector<MetricValue> values;
    if (row.needs_edge_mask && !in.edge_mask) {
      for (const std::string& name : row.outputs) {
        values.push_back(MetricValue{name, std::nullopt, "no edge mask"});
      }
    } else {
      values = row.compute(in);
    }
    AALAB_CHECK(values.size() == row.outputs.size(), "metric '" + row.name +
                                                         "' returned the wrong number of values");
    for (size_t i = 0; i < values.size(); ++i) {
      AALAB_CHECK(values[i].name == row.outputs[i],
                  "metric '" + row.name + "' returned '" + values[i].name + "', expected '" +
                      row.outputs[i] + "'");
      if (values[i].value && !std::isfinite(*values[i].value)) {
        values[i].value.reset();
        values[i].null_reason = "non-finite result (input has NaN/Inf pixels)";
      }
      out.push_back(std::move(values[i]));
    }
  }
  return out;
}

}  // namespace aalab
