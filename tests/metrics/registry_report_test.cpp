// A report read through the metric registry: the page's column labels, units, directions and
// printed precision, and compare's directions, for two metrics whose descriptions are known by
// hand (METRICS.md): edge_psnr_db (an image metric, dB, higher is better, 2 decimals) and
// temporal_perceptual (a sequence metric, lower is better, 4 significant digits).
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "reports/compare.h"
#include "reports/html_assets.h"
#include "reports/html_report.h"

namespace aalab {
namespace {

ResultRow Row(const std::string& spec, double edge_psnr, double perceptual) {
  ResultRow row;
  row.scene = "wedges";
  row.method = spec;
  row.spec = spec;
  row.render_width = 16;
  row.render_height = 9;
  row.render.samples_ms = {2.0, 2.5, 1.5};
  row.render.Summarize();
  row.post.samples_ms = {0, 0, 0};
  row.post.Summarize();
  row.resample = row.post;
  row.total = row.render;
  row.metrics = {
      {"edge_psnr_db", edge_psnr, ""}, {"temporal_perceptual", perceptual, ""}, {"area_bias_px2", -0.25, ""}};
  row.output_hash = spec;
  return row;
}

std::string ScriptJson(const std::string& page, const std::string& id) {
  const std::string open = "<script type=\"application/json\" id=\"" + id + "\">";
  const size_t a = page.find(open);
  if (a == std::string::npos) return "";
  return page.substr(a + open.size(), page.find("</script>", a) - a - open.size());
}

TEST(MetricRegistryReport, PageAndCompareReadTheRegistry) {
  Report r;
  r.context = {{"tool", "aalab"}, {"tool_version", "0.1.0"}};
  r.settings = {{"suite", "quick"}, {"size", "16x9"}, {"frames", "4"}};
  SceneResult s;
  s.name = "wedges";
  s.width = 16;
  s.height = 9;
  r.scenes.push_back(s);
  r.rows = {Row("none", 24.5, 0.03125), Row("ssaa-2x2", 31.256, 0.0123456)};
  const std::string page = RenderHtmlReport(r);
  const auto meta = nlohmann::json::parse(ScriptJson(page, "aalab-meta"));
  const auto& m = meta["metrics"];
  EXPECT_EQ(m["edge_psnr_db"]["label"], "Edge PSNR");
  EXPECT_EQ(m["edge_psnr_db"]["unit"], "dB");
  EXPECT_EQ(m["edge_psnr_db"]["better"], 1);
  EXPECT_EQ(m["temporal_perceptual"]["label"], "Perceptual temporal error");
  EXPECT_EQ(m["temporal_perceptual"]["unit"], "");
  EXPECT_EQ(m["temporal_perceptual"]["better"], -1);
  EXPECT_NE(m["temporal_perceptual"]["rewards"].get<std::string>().find("does not visibly change"), std::string::npos);
  EXPECT_EQ(m["area_bias_px2"]["better"], 0);  // signed bias: neither end is better, not a chart axis
  EXPECT_EQ(meta["axis"], nlohmann::json::array({"edge_psnr_db", "temporal_perceptual"}));
  // The table prints the registry's precision: 2 decimals for dB, 4 significant digits else.
  EXPECT_NE(page.find(">31.26<"), std::string::npos);
  EXPECT_NE(page.find(">0.01235<"), std::string::npos);
  EXPECT_NE(page.find("Higher is better."), std::string::npos);
  // compare and the sweep read the same directions and units.
  EXPECT_EQ(MetricDirection("edge_psnr_db"), Better::kHigher);
  EXPECT_EQ(MetricDirection("temporal_perceptual"), Better::kLower);
  EXPECT_FALSE(MetricDirection("area_bias_px2"));
  EXPECT_TRUE(IsDbMetric("edge_psnr_db"));
  EXPECT_FALSE(IsDbMetric("temporal_perceptual"));
  const std::string known = KnownMetricsText();
  EXPECT_LT(known.find("edge_psnr_db"), known.find("(higher is better)"));
  EXPECT_GT(known.find("temporal_perceptual"), known.find("(higher is better)"));
}

TEST(MetricRegistryReport, NamesFromAnotherVersionFallBackToTheirSuffix) {
  const html::MetricInfo info = html::DescribeMetric("future_psnr_db");
  EXPECT_EQ(info.label, "future_psnr_db");
  EXPECT_EQ(info.unit, "dB");
  EXPECT_EQ(info.better, 1);
  EXPECT_FALSE(MetricDirection("future_psnr_db"));  // compare judges only what it knows
  EXPECT_TRUE(IsDbMetric("future_psnr_db"));
}

}  // namespace
}  // namespace aalab
