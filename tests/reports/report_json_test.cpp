#include "reports/report_json.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace aalab {
namespace {

Report Sample() {
  Report r;
  r.context = {{"tool", "aalab"}, {"git_commit", "abc"}};
  r.settings = {{"size", "16x9"}, {"seed", "1"}};
  SceneResult s;
  s.name = "wedges";
  s.effects = {"unlit"};
  s.width = 16;
  s.height = 9;
  s.ref_spp = 16;
  s.ref_halves_psnr_db = 40.0;
  s.ref_floor_psnr_db = 46.02;
  s.images = {{"reference_png", "images/wedges/reference.png"}};
  r.scenes.push_back(s);
  ResultRow row;
  row.scene = "wedges";
  row.method = "none";
  row.spec = "none";
  row.render.samples_ms = {3.0, 1.0, 2.0, 10.0};
  row.render.Summarize();
  row.metrics = {{"psnr_db", std::nullopt, "identical"}, {"mse", 0.0, ""}};
  row.output_hash = "00ff";
  r.rows.push_back(row);
  return r;
}

TEST(ReportJson, TimingSummary) {
  Timing t;
  t.samples_ms = {3.0, 1.0, 2.0, 10.0};
  t.Summarize();
  EXPECT_DOUBLE_EQ(t.median_ms, 2.5);  // mean of the middle two of 1, 2, 3, 10
  EXPECT_DOUBLE_EQ(t.min_ms, 1.0);
  EXPECT_DOUBLE_EQ(t.max_ms, 10.0);
}

TEST(ReportJson, HasDocumentedFieldsAndNullNotNan) {
  const auto j = ReportToJson(Sample());
  EXPECT_EQ(j["schema_version"], kSchemaVersion);
  for (const char* k : {"context", "settings", "scenes", "rows"}) EXPECT_TRUE(j.contains(k)) << k;
  const auto& row = j["rows"][0];
  for (const char* k : {"scene", "method", "spec", "params", "render_size", "samples_per_pixel", "metrics",
                        "null_reasons", "timing", "cost", "output_hash", "images"}) {
    EXPECT_TRUE(row.contains(k)) << k;
  }
  EXPECT_TRUE(row["metrics"]["psnr_db"].is_null());
  EXPECT_EQ(row["null_reasons"]["psnr_db"], "identical");
  for (const char* k : {"render", "post", "resample", "total"}) {
    for (const char* f : {"median_ms", "min_ms", "max_ms", "samples_ms"})
      EXPECT_TRUE(row["timing"][k].contains(f)) << k << f;
  }
  const auto& ref = j["scenes"][0]["reference"];
  for (const char* k : {"spp", "time_ms", "halves_psnr_db", "noise_floor_psnr_db", "primary_rays_per_px"}) {
    EXPECT_TRUE(ref.contains(k)) << k;
  }
  const std::string text = j.dump();
  EXPECT_EQ(text.find("NaN"), std::string::npos);
  EXPECT_EQ(text.find("Infinity"), std::string::npos);
}

TEST(ReportJson, RoundTrips) {
  const Report a = Sample();
  const auto j1 = ReportToJson(a);
  const Report b = ReportFromJson(nlohmann::ordered_json::parse(j1.dump()), "test");
  EXPECT_EQ(ReportToJson(b).dump(), j1.dump());
}

// A report written before FormatNumber spelled whole numbers in full ("2e+01") reads with
// today's spec, so compare and history match its rows to today's.
TEST(ReportJson, OlderScientificSpecsReadAsTodays) {
  Report a = Sample();
  a.rows[0].method = "smaa-ultra";
  a.rows[0].spec = "smaa-ultra:corner_rounding=2e+01";
  a.rows[0].params = {{"threshold", "0.05"}, {"corner_rounding", "2e+01"}, {"diag", "on"}};
  const Report b = ReportFromJson(nlohmann::ordered_json::parse(ReportToJson(a).dump()), "test");
  EXPECT_EQ(b.rows[0].spec, "smaa-ultra:corner_rounding=20");
  EXPECT_EQ(b.rows[0].params[0].second, "0.05");
  EXPECT_EQ(b.rows[0].params[1].second, "20");
  EXPECT_EQ(b.rows[0].params[2].second, "on");
}

TEST(ReportJson, NonFiniteNeverReachesJson) {
  Report r = Sample();
  r.rows[0].metrics.push_back({"bad", std::numeric_limits<double>::quiet_NaN(), ""});
  EXPECT_THROW(ReportToJson(r), InternalError);
}

TEST(ReportJson, RejectsOtherSchemasAndGarbage) {
  auto j = nlohmann::ordered_json::parse(ReportToJson(Sample()).dump());
  j["schema_version"] = 99;
  EXPECT_THROW(ReportFromJson(j, "x"), UserError);
  EXPECT_THROW(ReportFromJson(nlohmann::ordered_json::parse("{}"), "x"), UserError);
}

}  // namespace
}  // namespace aalab
