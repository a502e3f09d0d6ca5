// The metric registry describes every value it produces: label, unit, direction, printed
// precision, text and source, once per key. Expected values are METRICS.md's definitions
// (written by hand here, not read back from the registry).
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "metrics/metric.h"
#include "metrics/temporal.h"
#include "metrics/temporal_perceptual.h"

namespace aalab {
namespace {

TEST(MetricRegistry, EveryOutputIsDescribedOnce) {
  std::set<std::string> keys, rows;
  // Families defined by aalab itself (nothing to cite: METRICS.md is their source).
  const std::set<std::string> defined_here = {"psnr", "edge", "abs_error", "coverage_bias", "temporal"};
  for (const MetricEntry& e : MetricRegistry()) {
    EXPECT_TRUE(rows.insert(e.name).second) << "row twice: " << e.name;
    EXPECT_FALSE(e.help.empty()) << e.name;
    ASSERT_FALSE(e.outputs.empty()) << e.name;
    EXPECT_EQ(e.inputs == MetricInputs::kImage, e.compute != nullptr)
        << e.name << ": image rows compute, sequence rows not";
    EXPECT_EQ(e.source.empty(), defined_here.count(e.name) == 1) << e.name << " source '" << e.source << "'";
    for (const MetricOutput& o : e.outputs) {
      EXPECT_TRUE(keys.insert(o.key).second) << "key twice: " << o.key;
      EXPECT_EQ(o.key.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_"), std::string::npos) << o.key;
      EXPECT_FALSE(o.label.empty()) << o.key;
      EXPECT_NE(o.label, o.key) << o.key << ": a label, not the key again";
      EXPECT_GE(o.help.size(), 20u) << o.key << ": a sentence saying what it is";
      EXPECT_TRUE(o.unit.empty() || o.unit == "dB" || o.unit == "px²") << o.key << " unit " << o.unit;
      EXPECT_TRUE(o.better == Improves::kHigher || o.better == Improves::kLower || o.better == Improves::kTowardZero)
          << o.key;
      EXPECT_TRUE(o.decimals == kSignificantDigits || (o.decimals >= 0 && o.decimals <= 6)) << o.key;
      // dB values are printed with 2 decimals (and only they: the others span decades).
      EXPECT_EQ(o.unit == "dB", o.decimals == 2) << o.key;
      EXPECT_EQ(o.unit == "dB", o.key.size() > 3 && o.key.compare(o.key.size() - 3, 3, "_db") == 0) << o.key;
      EXPECT_EQ(FindMetricOutput(o.key), &o) << o.key;
      EXPECT_EQ(FindMetricEntry(o.key), &e) << o.key;
    }
  }
  EXPECT_EQ(keys.size(), 27u);  // 22 image values + 5 sequence values (METRICS.md)
  EXPECT_EQ(FindMetricOutput("psnr"), nullptr);
  EXPECT_EQ(FindMetricOutput(""), nullptr);
}

TEST(MetricRegistry, HandKnownDescriptions) {
  const MetricOutput* edge = FindMetricOutput("edge_psnr_db");
  ASSERT_NE(edge, nullptr);
  EXPECT_EQ(edge->label, "Edge PSNR");
  EXPECT_EQ(edge->unit, "dB");
  EXPECT_EQ(edge->better, Improves::kHigher);
  EXPECT_EQ(edge->decimals, 2);
  EXPECT_NE(edge->rewards.find("stair-step"), std::string::npos);
  const MetricOutput* flip = FindMetricOutput("flip_max");
  ASSERT_NE(flip, nullptr);
  EXPECT_EQ(flip->label, "FLIP max");
  EXPECT_EQ(flip->better, Improves::kLower);
  EXPECT_EQ(flip->decimals, kSignificantDigits);
  EXPECT_EQ(FindMetricEntry("flip_max")->source, "andersson2020flip");
  EXPECT_EQ(FindMetricOutput("area_bias_px2")->better, Improves::kTowardZero);  // signed: 0 is best
  EXPECT_EQ(FindMetricOutput("area_bias_px2")->unit, "px²");
  EXPECT_EQ(FindMetricOutput("area_bias_abs_rel")->better, Improves::kLower);
  EXPECT_EQ(FindMetricOutput("temporal_psnr_db")->better, Improves::kHigher);
  EXPECT_EQ(FindMetricOutput("temporal_csf_rmse")->better, Improves::kLower);
}

TEST(MetricRegistry, TemporalMetricsAreSequenceRows) {
  EXPECT_EQ(FindMetricEntry("temporal_rmse")->inputs, MetricInputs::kSequence);
  EXPECT_EQ(FindMetricEntry("temporal_perceptual")->inputs, MetricInputs::kSequence);
  EXPECT_EQ(FindMetricEntry("temporal_perceptual")->source, "andersson2020flip,watson1986temporal");
  // The accumulators' values are the rows' outputs, in order.
  EXPECT_EQ(TemporalMetricNames(),
            (std::vector<std::string>{"temporal_rmse", "temporal_psnr_db", "temporal_edge_rmse"}));
  EXPECT_EQ(PerceptualTemporalNames(), (std::vector<std::string>{"temporal_perceptual", "temporal_csf_rmse"}));
  EXPECT_EQ(OutputKeys(*FindMetricEntry("temporal_rmse")), TemporalMetricNames());
  EXPECT_EQ(OutputKeys(*FindMetricEntry("temporal_csf_rmse")), PerceptualTemporalNames());
  // The per-image list (ComputeAllMetrics) holds none of them.
  for (const std::string& k : ImageMetricKeys()) EXPECT_EQ(k.rfind("temporal_", 0), std::string::npos) << k;
  EXPECT_EQ(ImageMetricKeys().size(), 22u);
}

TEST(MetricRegistry, MarkdownTablesListEveryOutput) {
  const std::string md = MetricTablesMarkdown();
  for (const MetricEntry& e : MetricRegistry()) {
    for (const MetricOutput& o : e.outputs) {
      size_t n = 0;
      for (size_t p = md.find("| `" + o.key + "` |"); p != std::string::npos; p = md.find("| `" + o.key + "` |", p + 1))
        ++n;
      EXPECT_EQ(n, 2u) << o.key << ": once in the summary, once in the texts";
    }
  }
  EXPECT_NE(md.find("| `mse` | psnr | MSE | — | lower | significant digits | image | aalab (METRICS.md) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| `area_bias_px2` | coverage_bias | Area bias | px² | closer to 0 |"), std::string::npos) << md;
}

}  // namespace
}  // namespace aalab
