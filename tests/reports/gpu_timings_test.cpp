// GPU timings (reports/gpu_timings.h): reading aalab_gpu's JSON and merging it into rows.
// The file below is written by hand; the expected blocks follow from it directly.
#include "reports/gpu_timings.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "reports/report_json.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {

namespace fs = std::filesystem;

const char* kFile = R"({
  "schema": "aalab-gpu-timings", "schema_version": 1, "generated_utc": "2026-11-22T20:29:30Z",
  "device": {"name": "Test GPU"}, "driver": "580.1", "cuda_runtime": "13.0",
  "results": [
    {"scene": "wedges", "size": "1920x1080", "method": "copy", "kernels": "copy",
     "median_ms": 0.02, "min_ms": 0.01, "max_ms": 0.03, "ratio_to_copy": 1},
    {"scene": "wedges", "size": "1920x1080", "method": "fxaa1-p3", "kernels": "fxaa1",
     "median_ms": 0.05, "min_ms": 0.04, "max_ms": 0.09, "ratio_to_copy": 2.5,
     "fidelity": {"identical_share": 0.999, "max_diff": 1}},
    {"scene": "wedges", "size": "3840x2160", "method": "copy", "kernels": "copy",
     "median_ms": 0.08, "min_ms": 0.07, "max_ms": 0.09, "ratio_to_copy": 1},
    {"scene": "wedges", "size": "3840x2160", "method": "fxaa1-p3", "kernels": "fxaa1",
     "median_ms": 0.2, "min_ms": 0.19, "max_ms": 0.3, "ratio_to_copy": 2.5},
    {"scene": "circle", "size": "1920x1080", "method": "fxaa1-p3", "kernels": "fxaa1",
     "median_ms": 0.06, "min_ms": 0.05, "max_ms": 0.07, "ratio_to_copy": 3},
    {"scene": "wedges", "size": "1920x1080", "method": "fxaa311-p39", "kernels": "fxaa311",
     "fidelity": {"identical_share": 0.99, "max_diff": 30}}
  ]})";

fs::path WriteTmp(const std::string& name, const std::string& text) {
  static const fs::path dir = testenv::ScratchDir("gpu-timings");
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

ResultRow Row(const std::string& scene, const std::string& spec) {
  ResultRow r;
  r.scene = scene;
  r.method = spec.substr(0, spec.find(':'));
  r.spec = spec;
  return r;
}

TEST(GpuTimings, MergeMatchesSceneAndSpecAndCarriesEverySize) {
  const GpuTimingsFile g = ReadGpuTimingsFile(WriteTmp("ok.json", kFile).string());
  EXPECT_EQ(g.device, "Test GPU");
  EXPECT_EQ(g.results.size(), 6u);
  EXPECT_EQ(g.Scenes(), (std::vector<std::string>{"wedges", "circle"}));
  Report r;
  r.rows = {Row("wedges", "fxaa1-p3"), Row("wedges", "fxaa1-p3:subpix_cap=0.5"), Row("wedges", "none"),
            Row("wedges", "fxaa311-p39"), Row("circle", "fxaa1-p3")};
  EXPECT_EQ(MergeGpuTimings(r, g), 2);
  ASSERT_TRUE(r.rows[0].gpu.has_value());
  const GpuTiming& t = *r.rows[0].gpu;
  EXPECT_EQ(t.device, "Test GPU");
  EXPECT_EQ(t.driver, "580.1");
  EXPECT_EQ(t.kernels, "fxaa1");
  ASSERT_EQ(t.sizes.size(), 2u);
  EXPECT_EQ(t.sizes[0].size, "1920x1080");
  EXPECT_DOUBLE_EQ(t.sizes[0].median_ms, 0.05);
  EXPECT_DOUBLE_EQ(t.sizes[0].copy_ms, 0.02);  // the copy line of the same scene and size
  EXPECT_DOUBLE_EQ(t.sizes[0].ratio_to_copy, 2.5);
  EXPECT_DOUBLE_EQ(*t.sizes[0].identical_share, 0.999);
  EXPECT_EQ(*t.sizes[0].max_diff, 1);
  EXPECT_EQ(t.sizes[1].size, "3840x2160");
  EXPECT_DOUBLE_EQ(t.sizes[1].copy_ms, 0.08);
  EXPECT_FALSE(t.sizes[1].identical_share.has_value());
  // An overridden spec, a method without a twin and an untimed result get no block; another
  // scene's timings stay with that scene.
  EXPECT_FALSE(r.rows[1].gpu.has_value());
  EXPECT_FALSE(r.rows[2].gpu.has_value());
  EXPECT_FALSE(r.rows[3].gpu.has_value());
  ASSERT_TRUE(r.rows[4].gpu.has_value());
  EXPECT_DOUBLE_EQ(r.rows[4].gpu->sizes.at(0).median_ms, 0.06);
  EXPECT_DOUBLE_EQ(r.rows[4].gpu->sizes.at(0).copy_ms, 0.0);  // no copy line for circle
  EXPECT_NE(r.context.at("gpu_timings").find("Test GPU"), std::string::npos);
}

TEST(GpuTimings, BlockSurvivesTheReportJsonRoundTrip) {
  Report r;
  r.rows = {Row("wedges", "fxaa1-p3"), Row("wedges", "none")};
  MergeGpuTimings(r, ReadGpuTimingsFile(WriteTmp("rt.json", kFile).string()));
  const auto doc = ReportToJson(r);
  EXPECT_FALSE(doc.at("rows").at(1).contains("gpu"));  // absent, not null, without timings
  EXPECT_DOUBLE_EQ(doc.at("rows").at(0).at("gpu").at("sizes").at("3840x2160").at("median_ms").get<double>(), 0.2);
  const Report back = ReportFromJson(doc, "test");
  ASSERT_TRUE(back.rows[0].gpu.has_value());
  EXPECT_EQ(back.rows[0].gpu->sizes.size(), 2u);
  EXPECT_DOUBLE_EQ(back.rows[0].gpu->sizes[1].ratio_to_copy, 2.5);
  EXPECT_FALSE(back.rows[0].gpu->sizes[1].max_diff.has_value());
  EXPECT_EQ(*back.rows[0].gpu->sizes[0].max_diff, 1);
  EXPECT_FALSE(back.rows[1].gpu.has_value());
}

TEST(GpuTimings, BadFilesAreUserErrors) {
  std::string other = kFile;
  other.replace(other.find("aalab-gpu-timings"), 17, "something-else");
  EXPECT_THROW(ReadGpuTimingsFile(WriteTmp("schema.json", other).string()), UserError);
  std::string version = kFile;
  version.replace(version.find("\"schema_version\": 1"), 19, "\"schema_version\": 2");
  EXPECT_THROW(ReadGpuTimingsFile(WriteTmp("version.json", version).string()), UserError);
  std::string order = kFile;
  order.replace(order.find("\"min_ms\": 0.04"), 14, "\"min_ms\": 0.06");  // min > median
  EXPECT_THROW(ReadGpuTimingsFile(WriteTmp("order.json", order).string()), UserError);
  EXPECT_THROW(ReadGpuTimingsFile(WriteTmp("json.json", "{").string()), UserError);
  EXPECT_THROW(ReadGpuTimingsFile("/nonexistent/gpu.json"), UserError);
}

// One aalab_gpu file per size (1080p first, 4K later, as two H100 runs write them), merged one
// after the other: the row carries both sizes, each with its own time; a later file of the same
// setup replaces only the size it re-measures; another kernel list replaces the block.
TEST(GpuTimings, FilesOfOneSetupAddTheirSizesToTheRow) {
  const auto file = [](const std::string& when, const std::string& size, double ms, const std::string& kernels) {
    return std::string(R"({"schema": "aalab-gpu-timings", "schema_version": 1, "generated_utc": ")") + when +
           R"(", "device": {"name": "Test GPU"}, "driver": "580.1", "cuda_runtime": "13.0", "results": [
             {"scene": "wedges", "size": ")" +
           size + R"(", "method": "fxaa1-p3", "kernels": ")" + kernels + R"(", "median_ms": )" + std::to_string(ms) +
           R"(, "min_ms": 0.01, "max_ms": 9, "ratio_to_copy": 2}]})";
  };
  Report r;
  r.rows = {Row("wedges", "fxaa1-p3")};
  EXPECT_EQ(MergeGpuTimings(r, ReadGpuTimingsFile(WriteTmp("a.json", file("T1", "1920x1080", 0.05, "fxaa1")).string())),
            1);
  EXPECT_EQ(MergeGpuTimings(r, ReadGpuTimingsFile(WriteTmp("b.json", file("T2", "3840x2160", 0.2, "fxaa1")).string())),
            1);
  ASSERT_TRUE(r.rows[0].gpu.has_value());
  ASSERT_EQ(r.rows[0].gpu->sizes.size(), 2u);
  EXPECT_EQ(r.rows[0].gpu->sizes[0].size, "1920x1080");
  EXPECT_DOUBLE_EQ(r.rows[0].gpu->sizes[0].median_ms, 0.05);
  EXPECT_EQ(r.rows[0].gpu->sizes[0].measured_utc, "T1");
  EXPECT_EQ(r.rows[0].gpu->sizes[1].size, "3840x2160");
  EXPECT_DOUBLE_EQ(r.rows[0].gpu->sizes[1].median_ms, 0.2);
  EXPECT_EQ(r.rows[0].gpu->sizes[1].measured_utc, "T2");
  EXPECT_EQ(r.rows[0].gpu->measured_utc, "T1; T2");
  EXPECT_NE(r.context.at("gpu_timings").find("measured T1; "), std::string::npos);
  EXPECT_NE(r.context.at("gpu_timings").find("measured T2"), std::string::npos);
  // The per-size times survive report.json.
  const Report back = ReportFromJson(ReportToJson(r), "test");
  EXPECT_EQ(back.rows[0].gpu->sizes[1].measured_utc, "T2");

  // 1080p measured again: it replaces the 1080p entry; 4K stays; T1 no longer on the row.
  MergeGpuTimings(r, ReadGpuTimingsFile(WriteTmp("c.json", file("T3", "1920x1080", 0.07, "fxaa1")).string()));
  ASSERT_EQ(r.rows[0].gpu->sizes.size(), 2u);
  EXPECT_DOUBLE_EQ(r.rows[0].gpu->sizes[0].median_ms, 0.07);
  EXPECT_DOUBLE_EQ(r.rows[0].gpu->sizes[1].median_ms, 0.2);
  EXPECT_EQ(r.rows[0].gpu->measured_utc, "T3; T2");

  // Another kernel list is another setup: its block replaces the row's.
  MergeGpuTimings(r, ReadGpuTimingsFile(WriteTmp("d.json", file("T4", "3840x2160", 0.3, "fxaa1_v2")).string()));
  ASSERT_EQ(r.rows[0].gpu->sizes.size(), 1u);
  EXPECT_EQ(r.rows[0].gpu->kernels, "fxaa1_v2");
  EXPECT_DOUBLE_EQ(r.rows[0].gpu->sizes[0].median_ms, 0.3);
  EXPECT_EQ(r.rows[0].gpu->measured_utc, "T4");
}

}  // namespace
}  // namespace aalab
