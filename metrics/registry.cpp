// The metric registry: one line per family file (its rows carry their outputs' labels,
// units, directions, precision and texts), the lookups every reader uses, and METRICS.md's
// generated tables.
#include <cmath>
#include <cstdio>

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
    add(TemporalMetrics(), "");
    add(PerceptualTemporalMetrics(), "andersson2020flip,watson1986temporal");
    return all;
  }();
  return table;
}

const MetricEntry* FindMetricEntry(const std::string& key) {
  for (const MetricEntry& e : MetricRegistry()) {
    for (const MetricOutput& o : e.outputs) {
      if (o.key == key) return &e;
    }
  }
  return nullptr;
}

const MetricOutput* FindMetricOutput(const std::string& key) {
  const MetricEntry* e = FindMetricEntry(key);
  if (!e) return nullptr;
  for (const MetricOutput& o : e->outputs) {
    if (o.key == key) return &o;
  }
  return nullptr;
}

std::vector<std::string> OutputKeys(const MetricEntry& entry) {
  std::vector<std::string> keys;
  for (const MetricOutput& o : entry.outputs) keys.push_back(o.key);
  return keys;
}

std::vector<std::string> ImageMetricKeys() {
  std::vector<std::string> keys;
  for (const MetricEntry& e : MetricRegistry()) {
    if (e.inputs != MetricInputs::kImage) continue;
    for (const MetricOutput& o : e.outputs) keys.push_back(o.key);
  }
  return keys;
}

namespace {

const char* DirectionText(Improves d) {
  switch (d) {
    case Improves::kHigher: return "higher";
    case Improves::kLower: return "lower";
    case Improves::kTowardZero: return "closer to 0";
  }
  return "?";
}

std::string PrecisionText(const MetricOutput& o) {
  if (o.decimals >= 0) return std::to_string(o.decimals) + " decimals";
  return "significant digits";
}

/// A table cell: '|' would end the cell.
std::string Cell(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

std::string MetricTablesMarkdown() {
  std::string md =
      "| value | family | label | unit | better | printed with | input | source |\n"
      "|---|---|---|---|---|---|---|---|\n";
  for (const MetricEntry& e : MetricRegistry()) {
    for (const MetricOutput& o : e.outputs) {
      md += "| `" + o.key + "` | " + e.name + " | " + Cell(o.label) + " | " + (o.unit.empty() ? "—" : o.unit) + " | " +
            DirectionText(o.better) + " | " + PrecisionText(o) + " | " +
            (e.inputs == MetricInputs::kImage ? "image" : "sequence (`--frames N > 1`)") + " | " +
            (e.source.empty() ? "aalab (METRICS.md)" : e.source) + " |\n";
    }
  }
  md +=
      "\nWhat the page says about each value (its column tooltip, and under the chart what the axis "
      "rewards):\n\n| value | what it is | what it rewards |\n|---|---|---|\n";
  for (const MetricEntry& e : MetricRegistry()) {
    for (const MetricOutput& o : e.outputs) {
      md += "| `" + o.key + "` | " + Cell(o.help) + " | " + (o.rewards.empty() ? "—" : Cell(o.rewards)) + " |\n";
    }
  }
  return md;
}

std::vector<MetricValue> ComputeAllMetrics(const MetricInput& in) {
  if (!in.image || !in.reference) {
    throw InternalError("ComputeAllMetrics needs both an image and a reference");
  }
  RequireSameShape(*in.image, *in.reference, "metrics: image vs reference");
  std::vector<MetricValue> out;
  for (const MetricEntry& row : MetricRegistry()) {
    if (row.inputs != MetricInputs::kImage) continue;  // sequence rows: metrics/temporal*.h
    std::vector<MetricValue> values;
    if (row.needs_edge_mask && !in.edge_mask) {
      for (const MetricOutput& o : row.outputs) {
        values.push_back(MetricValue{o.key, std::nullopt, "no edge mask"});
      }
    } else {
      values = row.compute(in);
    }
    AALAB_CHECK(values.size() == row.outputs.size(), "metric '" + row.name + "' returned the wrong number of values");
    for (size_t i = 0; i < values.size(); ++i) {
      AALAB_CHECK(values[i].name == row.outputs[i].key,
                  "metric '" + row.name + "' returned '" + values[i].name + "', expected '" + row.outputs[i].key + "'");
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
