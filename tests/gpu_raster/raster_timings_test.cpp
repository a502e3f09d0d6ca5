// The raster timings file (reports/raster_timings.h): reading aalab_raster's JSON, merging it
// into rows (ratio to the same scene's `none` at the same size), and the row block's round
// trip through report.json. The file is written by hand; the expected values follow from it.
#include "reports/raster_timings.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "reports/report_json.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {

namespace fs = std::filesystem;

const char* kFile = R"({
  "schema": "aalab-raster-timings", "schema_version": 1, "tool": "aalab_raster",
  "device": "Test GL", "vendor": "V", "gl_version": "4.5 test", "egl_platform": "EGL_EXT_platform_device",
  "target_format": "rgba16f", "msaa_resolve": "shader", "warmup": 1, "repeat": 3, "not_drawn": [],
  "rows": [
    {"scene": "wedges", "width": 1920, "height": 1080, "method": "none", "samples": 1, "triangles": 18,
     "total": {"median_ms": 0.5, "min_ms": 0.4, "max_ms": 0.6}, "draw": {"median_ms": 0.3, "min_ms": 0, "max_ms": 0},
     "resolve": {"median_ms": 0, "min_ms": 0, "max_ms": 0}, "encode": {"median_ms": 0.2, "min_ms": 0, "max_ms": 0}},
    {"scene": "wedges", "width": 1920, "height": 1080, "method": "msaa-4x", "samples": 4, "triangles": 18,
     "total": {"median_ms": 1.5, "min_ms": 1.25, "max_ms": 2}, "draw": {"median_ms": 0.75, "min_ms": 0, "max_ms": 0},
     "resolve": {"median_ms": 0.5, "min_ms": 0, "max_ms": 0}, "encode": {"median_ms": 0.25, "min_ms": 0, "max_ms": 0}},
    {"scene": "wedges", "width": 3840, "height": 2160, "method": "msaa-4x", "samples": 4, "triangles": 18,
     "total": {"median_ms": 6, "min_ms": 5, "max_ms": 7}, "draw": {"median_ms": 3, "min_ms": 0, "max_ms": 0},
     "resolve": {"median_ms": 2, "min_ms": 0, "max_ms": 0}, "encode": {"median_ms": 1, "min_ms": 0, "max_ms": 0}}
  ]})";

fs::path WriteTmp(const std::string& name, const std::string& text) {
  static const fs::path dir = testenv::ScratchDir("raster-timings");
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

ResultRow Row(const std::string& scene, const std::string& spec) {
  ResultRow r;
  r.scene = scene;
  r.method = spec;
  r.spec = spec;
  return r;
}

TEST(RasterTimings, MergeSetsBlocksWithRatioToTheOneXFrame) {
  const fs::path p = WriteTmp("ok.json", kFile);
  EXPECT_TRUE(IsRasterTimingsFile(p.string()));
  const RasterTimingsFile f = ReadRasterTimingsFile(p.string());
  ASSERT_EQ(f.results.size(), 3u);
  EXPECT_EQ(f.results[2].size, "3840x2160");
  Report r;
  r.rows = {Row("wedges", "none"), Row("wedges", "msaa-4x"), Row("wedges", "fxaa-high"), Row("mesh", "msaa-4x")};
  EXPECT_EQ(MergeRasterTimings(r, f), 2);
  ASSERT_TRUE(r.rows[1].gpu_raster.has_value());
  const RasterTiming& t = *r.rows[1].gpu_raster;
  EXPECT_EQ(t.device, "Test GL");
  EXPECT_EQ(t.samples, 4);
  ASSERT_EQ(t.sizes.size(), 2u);
  EXPECT_DOUBLE_EQ(t.sizes[0].ratio_to_1x, 3.0);  // 1.5 / 0.5
  EXPECT_DOUBLE_EQ(t.sizes[0].resolve_ms, 0.5);
  EXPECT_DOUBLE_EQ(t.sizes[1].ratio_to_1x, 0.0);  // no `none` timed at 4K
  EXPECT_FALSE(r.rows[2].gpu_raster.has_value());
  EXPECT_FALSE(r.rows[3].gpu_raster.has_value());
  EXPECT_NE(r.context.at("gpu_raster_timings").find("Test GL"), std::string::npos);
  // Round trip through the row block's JSON.
  const RasterTiming back = RasterTimingFrom(RasterTimingJson(t));
  ASSERT_EQ(back.sizes.size(), 2u);
  EXPECT_EQ(back.sizes[1].size, "3840x2160");
  EXPECT_DOUBLE_EQ(back.sizes[1].median_ms, 6.0);
  EXPECT_EQ(back.msaa_resolve, "shader");
}

TEST(RasterTimings, BadFilesAreRefusedWithTheirPath) {
  std::string s = kFile;
  s.replace(s.find("\"schema_version\": 1"), 19, "\"schema_version\": 7");
  EXPECT_THROW(ReadRasterTimingsFile(WriteTmp("v7.json", s).string()), UserError);
  s = kFile;
  s.replace(s.find("\"median_ms\": 1.5"), 16, "\"median_ms\": 2.5");  // above its max of 2
  try {
    ReadRasterTimingsFile(WriteTmp("order.json", s).string());
    FAIL() << "no error";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("order.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("min <= median <= max"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(IsRasterTimingsFile(WriteTmp("cuda.json", R"({"schema": "aalab-gpu-timings"})").string()));
  EXPECT_THROW(ReadRasterTimingsFile(WriteTmp("junk.json", "{").string()), UserError);
}

// scale43's raster row is the render part of scale43 and scale43-fxaa-high: both rows get
// the block with part "render" and the render size; other methods time their own spec
// (aaa included), whole.
TEST(RasterTimings, Scale43IsTheRenderPartOfBothScaleRows) {
  bool render_only = true;
  EXPECT_EQ(RasterSpecsOf("aaa", &render_only), std::vector<std::string>{"aaa"});
  EXPECT_FALSE(render_only);
  EXPECT_EQ(RasterSpecsOf("scale43", &render_only), (std::vector<std::string>{"scale43", "scale43-fxaa-high"}));
  EXPECT_TRUE(render_only);
  std::string s = kFile;
  const std::string scale_row =
      R"({"scene": "wedges", "width": 1920, "height": 1080, "method": "scale43", "samples": 1, "render_width": 2560,
     "render_height": 1440, "triangles": 18, "total": {"median_ms": 0.875, "min_ms": 0.75, "max_ms": 1},
     "draw": {"median_ms": 0.5, "min_ms": 0, "max_ms": 0}, "resolve": {"median_ms": 0, "min_ms": 0, "max_ms": 0},
     "encode": {"median_ms": 0.375, "min_ms": 0, "max_ms": 0}},
    )";
  s.insert(s.find("{\"scene\": \"wedges\", \"width\": 1920, \"height\": 1080, \"method\": \"msaa-4x\""), scale_row);
  const RasterTimingsFile f = ReadRasterTimingsFile(WriteTmp("scale.json", s).string());
  Report r;
  r.rows = {Row("wedges", "none"), Row("wedges", "scale43-fxaa-high"), Row("wedges", "scale43"),
            Row("wedges", "scale43-easu"), Row("wedges", "msaa-4x")};
  EXPECT_EQ(MergeRasterTimings(r, f), 4);
  EXPECT_FALSE(r.rows[3].gpu_raster.has_value());  // EASU renders at 3/4: not this target
  for (int i : {1, 2}) {
    ASSERT_TRUE(r.rows[i].gpu_raster.has_value()) << i;
    const RasterTiming& t = *r.rows[i].gpu_raster;
    EXPECT_EQ(t.part, "render");
    ASSERT_EQ(t.sizes.size(), 1u);
    EXPECT_EQ(t.sizes[0].render_size, "2560x1440");
    EXPECT_DOUBLE_EQ(t.sizes[0].ratio_to_1x, 1.75);  // 0.875 / 0.5
    const RasterTiming back = RasterTimingFrom(RasterTimingJson(t));
    EXPECT_EQ(back.part, "render");
    EXPECT_EQ(back.sizes[0].render_size, "2560x1440");
  }
  EXPECT_EQ(r.rows[4].gpu_raster->part, "");
  EXPECT_FALSE(RasterTimingJson(*r.rows[4].gpu_raster).contains("part"));
  EXPECT_FALSE(RasterTimingJson(*r.rows[4].gpu_raster)["sizes"]["1920x1080"].contains("render_size"));
}

}  // namespace
}  // namespace aalab
