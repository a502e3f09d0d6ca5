// The run's two report files (harness/run/runner.cpp's WriteRunReport): after the clock stops,
// report.json's document is built once and the page and report.json are rendered and written
// side by side. The files a run writes, at 1 and 2 threads, must equal the reference renders
// of the report read back: RenderHtmlReport(report), which builds its own JSON, and
// ReportToJson(report).dump(2) with a newline.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "harness/run/runner.h"
#include "reports/html_report.h"
#include "reports/report_json.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

std::string ReadBytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

TEST(RunReport, PageAndJsonWrittenSideBySideEqualTheReferenceRendersAtOneAndTwoThreads) {
  const fs::path dir = testenv::ScratchDir("run-report");
  for (int threads : {1, 2}) {
    RunSettings s;
    s.scenes = {"wedges", "circle"};
    s.methods = {"none", "fxaa311-p39", "ssaa-2x2"};
    s.width = 61;  // odd on both axes
    s.height = 37;
    s.ref_spp = 16;
    s.repeat = 1;
    s.threads = threads;
    s.quiet = true;
    s.out_dir = (dir / std::to_string(threads)).string();
    const Report ran = RunSuite(s);
    ASSERT_FALSE(ran.time_breakdown.empty());
    const std::string page = ReadBytes(dir / std::to_string(threads) / "index.html");
    const std::string json = ReadBytes(dir / std::to_string(threads) / "report.json");
    // The report the run returned and the report read back from its file: the same page and
    // the same JSON through the reference path, and the page through the shared-document path.
    const Report back = ReadReportFile((dir / std::to_string(threads) / "report.json").string());
    for (const Report* r : {&ran, &back}) {
      EXPECT_TRUE(ReportToJson(*r).dump(2) + "\n" == json) << threads << " threads: report.json differs";
      EXPECT_TRUE(RenderHtmlReport(*r) == page) << threads << " threads: index.html differs";
      EXPECT_TRUE(RenderHtmlReport(*r, ReportToJson(*r)) == page) << threads << " threads";
    }
    EXPECT_NE(page.find("id=\"time-breakdown\""), std::string::npos) << "the page shows the time breakdown";
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
