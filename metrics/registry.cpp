#include "harness/core/error.h"
#include "metrics/families.h"
#include "metrics/metric.h"

namespace aalab {

const std::vector<MetricEntry>& MetricRegistry() {
  static const std::vector<MetricEntry> table = [] {
    std::vector<MetricEntry> all;
    auto add = [&all](std::vector<MetricEntry> rows) {
      for (auto& r : rows) all.push_back(std::move(r));
    };
    // One line per family file, in listing order.
    add(PsnrMetrics());
    return all;
  }();
  return table;
}

}  // namespace aalab
