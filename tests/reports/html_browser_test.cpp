// The HTML report in a real browser: `aalab run` on a tiny suite, then index.html loaded from
// disk (file://) in headless Chromium with the page's self-test (#selftest). Fails on any
// console message or script error, any image that does not load, and any scene × method the
// page does not show. Saves screenshots into the build folder for a human to look at.
// Skipped (visibly) only when /usr/bin/chromium is not installed, and then failed under CI
// (CI=true: tests/skip_or_fail.h).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../cli/cli_util.h"
#include "../skip_or_fail.h"
#include "browser_util.h"
#include "reports/html_method_style.h"

namespace {
namespace fs = std::filesystem;

using aalab::clitest::CmdResult;
using aalab::clitest::RunCommand;
using namespace aalab::browsertest;

TEST(HtmlBrowser, PageShowsEverythingWithoutErrors) {
  if (!fs::exists(kChromium)) {
    AALAB_SKIP_OR_FAIL_UNDER_CI(std::string(kChromium) +
                                " is not installed, so the HTML report was NOT tested in a browser. Install it with "
                                "scripts/install-deps.sh (Debian package 'chromium').");
  }
  const fs::path work = FreshWorkDir("html_browser_test");
  const fs::path out = work / "run";
  RunAalabInto(out,
               "run --scenes wedges,circle --methods none,ssaa-2x2,fxaa1-p3 --size 64x36 --ref-spp 4 --repeat 1 "
               "--debug-views");
  ASSERT_TRUE(fs::exists(out / "index.html"));
  const std::string url = "file://" + fs::absolute(out / "index.html").string();

  // 1. The self-test: every view, every row, every chart point, every gallery entry, every image.
  const fs::path dom_path = work / "dom.html", log_path = work / "chromium.log";
  const CmdResult dump = RunCommand(
      Chromium(work / "profile-selftest", "--virtual-time-budget=30000 --dump-dom " + Quote(url + "#selftest")) +
      " > " + Quote(dom_path.string()) + " 2> " + Quote(log_path.string()));
  ASSERT_EQ(dump.code, 0) << "chromium failed; log: " << log_path << "\n" << ReadFile(log_path);
  const std::string dom = ReadFile(dom_path);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("<pre id=\"selftest\">([^<]*)</pre>")))
      << "no self-test verdict in the page (script did not run?); DOM in " << dom_path;
  const std::string verdict = m[1];
  EXPECT_EQ(verdict.rfind("OK scenes=2 rows=6 points=6 galleries=6 ", 0), 0u) << verdict;
  for (const char* zero : {" failed=0", " errors=0", " problems=0"})
    EXPECT_NE(verdict.find(zero), std::string::npos) << verdict;
  EXPECT_EQ(verdict.find("images=0 "), std::string::npos) << verdict;

  // 2. Every scene and method of report.json is in the page (the tables are static HTML).
  const auto report = nlohmann::json::parse(ReadFile(out / "report.json"));
  ASSERT_EQ(report["rows"].size(), 6u);
  for (const auto& row : report["rows"]) {
    const std::string key =
        "data-scene=\"" + row["scene"].get<std::string>() + "\" data-spec=\"" + row["spec"].get<std::string>() + "\"";
    EXPECT_NE(dom.find(key), std::string::npos) << key;
  }
  for (const auto& s : report["scenes"]) {
    EXPECT_NE(dom.find("data-view=\"scene-" + s["name"].get<std::string>() + "\""), std::string::npos) << s["name"];
  }

  // 3. A healthy page logs nothing: any console message or uncaught error from it fails.
  std::istringstream log(ReadFile(log_path));
  for (std::string line; std::getline(log, line);) {
    EXPECT_EQ(line.find(":CONSOLE"), std::string::npos) << "console output: " << line;
    EXPECT_EQ(line.find("Uncaught"), std::string::npos) << line;
  }

  // 4. Screenshots of the suite overview and of a scene (charts, tables, gallery) for a human.
  for (const std::string view : {"suite", "scene-wedges"}) {
    const fs::path shot = work / ("screenshot-" + view + ".png");
    const CmdResult r = RunCommand(Chromium(work / ("profile-" + view),
                                            "--virtual-time-budget=10000 --window-size=1400,2000 "
                                            "--screenshot=" +
                                                Quote(shot.string()) + " " + Quote(url + "#" + view)) +
                                   " 2>&1");
    EXPECT_EQ(r.code, 0) << r.output;
    ASSERT_TRUE(fs::exists(shot)) << r.output;
    EXPECT_GT(fs::file_size(shot), 20000u) << shot << " looks empty";
    std::printf("screenshot: %s\n", shot.c_str());
  }
}

// Any two rows side by side (the gallery's "two rows" mode, #pairtest drives it in the page):
// A and B chosen with the selects, `f` flips between them, and the absolute-difference canvas is
// blank for two identical images and not blank for two different methods. Chromium reads the
// canvas back only with --allow-file-access-from-files (a page opened from disk may not read
// its own images' pixels); without it the page says so instead of counting.
TEST(HtmlBrowser, AnyTwoRowsSideBySideWithFlipAndDifference) {
  if (!fs::exists(kChromium)) {
    AALAB_SKIP_OR_FAIL_UNDER_CI(std::string(kChromium) +
                                " is not installed, so the A/B page was NOT tested in a browser.");
  }
  const fs::path work = FreshWorkDir("html_browser_pair_test");
  const fs::path out = work / "run";
  const std::string printed = RunAalabInto(out,
                                           "run --scenes wedges --methods none,ssaa-2x2,fxaa1-p3 --size 64x36 "
                                           "--ref-spp 4 --repeat 1");
  // The terminal states the verdict too.
  EXPECT_NE(printed.find("  wedges: edge PSNR → "), std::string::npos) << printed;
  const std::string url = "file://" + fs::absolute(out / "index.html").string() + "#pairtest";
  auto facts = [&](const std::string& name, const std::string& flags) {
    return PageFacts(work, name, url, flags, "pairtest");
  };
  const std::string png = "images/wedges/";
  const std::string read = facts("read", "--allow-file-access-from-files");
  EXPECT_NE(read.find("options=reference,none,ssaa-2x2,fxaa1-p3 "), std::string::npos) << read;
  EXPECT_NE(read.find(" same=ssaa-2x2:0 "), std::string::npos) << read;  // A = B: blank
  std::smatch m;
  ASSERT_TRUE(std::regex_search(read, m, std::regex(" pair=ssaa-2x2:fxaa1-p3:([0-9]+):([0-9]+) "))) << read;
  EXPECT_GT(std::stoi(m[1]), 0) << read;
  EXPECT_GT(std::stoi(m[2]), 0) << read;
  // The same count and largest difference as OpenImageIO's idiff on the two PNGs.
  const IdiffStats id = Idiff(out / png / "ssaa-2x2.png", out / png / "fxaa1-p3.png");
  EXPECT_EQ(std::stoi(m[2]), id.max_levels) << read;
  EXPECT_EQ(std::stoi(m[1]), id.differing) << read;
  // The split, then all of A, then all of B.
  EXPECT_NE(read.find(" before=split f1=A:" + png + "ssaa-2x2"), std::string::npos) << read;
  EXPECT_NE(read.find(" f2=B:" + png + "fxaa1-p3"), std::string::npos) << read;
  ASSERT_TRUE(std::regex_search(read, m, std::regex(" ref=([0-9]+) "))) << read;
  EXPECT_GT(std::stoi(m[1]), 0) << read;
  // Several methods' error maps on one colour bar: all three outputs picked, full scale 0.0625,
  // every map through the one filter whose matrix maps a mean error of 0.0625 to the top of the
  // table (1 / (3 × 0.0625) = 5.333333 per channel), and the bar labelled 0 .. 0.0625.
  EXPECT_NE(read.find(" heat=3:1:5.333333:0.0625:0..0.0625:none,ssaa-2x2,fxaa1-p3 "), std::string::npos) << read;
  // Crop zoom (key 1: the first window report.json names, ×32) and the pixel readout there,
  // against oiiotool's decoding of the two PNGs; key 0 back to the whole image.
  const auto report = nlohmann::json::parse(ReadFile(out / "report.json"));
  const auto& c = report["scenes"][0]["crops"][0];
  const std::array<int, 4> crop{c[0].get<int>(), c[1].get<int>(), c[2].get<int>(), c[3].get<int>()};
  EXPECT_NE(read.find(" zoom1=" + std::to_string(crop[0]) + "," + std::to_string(crop[1]) + "," +
                      std::to_string(crop[2]) + "," + std::to_string(crop[3]) + ":x32:"),
            std::string::npos)
      << read;
  ExpectReadout(read, crop, out / png / "ssaa-2x2.png", out / png / "fxaa1-p3.png", {0, 0});
  EXPECT_NE(read.find(" zoom0=0,0,64,36 "), std::string::npos) << read;
  EXPECT_NE(read.find(" errors=0"), std::string::npos) << read;
  EXPECT_EQ(read.find("exception"), std::string::npos) << read;
  // Opened from disk without the flag: the same interactions, the counts said to be unavailable.
  const std::string plain = facts("plain", "");
  EXPECT_NE(plain.find(" same=ssaa-2x2:unknown "), std::string::npos) << plain;
  EXPECT_NE(plain.find(" f2=B:" + png + "fxaa1-p3"), std::string::npos) << plain;
  EXPECT_NE(plain.find(" errors=0"), std::string::npos) << plain;
}

// The suite overview of a many-scene run: the synthetic suite (the default suite before
// issue #41; every default method, a scene without edges among them: the default suite now
// holds none), tiny. The suite chart must plot one point per method for the default quality
// axis, and say which scene its means leave out and why.
TEST(HtmlBrowser, SuiteOverviewHasOnePointPerMethod) {
  if (!fs::exists(kChromium)) AALAB_SKIP_OR_FAIL_UNDER_CI(std::string(kChromium) + " is not installed.");
  const fs::path work = fs::path(AALAB_BINARY_DIR) / "html_browser_suite_test";
  const fs::path out = work / "run";
  fs::remove_all(work);
  fs::create_directories(work);
  const CmdResult run = RunCommand(std::string(AALAB_BINARY_DIR) +
                                   "/aalab run --suite synthetic --size 48x27 --ref-spp 4 --repeat 1 --quiet --out " +
                                   Quote(out.string()) + " 2>&1");
  ASSERT_EQ(run.code, 0) << run.output;
  const auto report = nlohmann::json::parse(ReadFile(out / "report.json"));
  std::set<std::string> specs, scenes;
  for (const auto& row : report["rows"]) {
    specs.insert(row["spec"].get<std::string>());
    scenes.insert(row["scene"].get<std::string>());
  }
  ASSERT_TRUE(scenes.count("detail-texture")) << "the synthetic suite should hold the scene without edges";

  const fs::path dom_path = work / "dom.html", log_path = work / "chromium.log";
  const std::string url = "file://" + fs::absolute(out / "index.html").string() + "#suite";
  const CmdResult dump = RunCommand(Chromium(work / "profile", "--virtual-time-budget=10000 --dump-dom " + Quote(url)) +
                                    " > " + Quote(dom_path.string()) + " 2> " + Quote(log_path.string()));
  ASSERT_EQ(dump.code, 0) << "chromium failed; log: " << log_path << "\n" << ReadFile(log_path);
  const std::string dom = ReadFile(dom_path);
  const size_t begin = dom.find("id=\"view-suite\"");
  ASSERT_NE(begin, std::string::npos) << "no suite view; DOM in " << dom_path;
  const size_t end = dom.find("<section", begin);
  const std::string suite = dom.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  const size_t chart_end = suite.find("</svg>");
  ASSERT_NE(chart_end, std::string::npos) << "the suite view has no chart; DOM in " << dom_path;
  std::set<std::string> plotted;
  const std::regex point("<g class=\"pt [^\"]*\"[^>]* data-spec=\"([^\"]+)\"");
  const std::string chart = suite.substr(0, chart_end);
  for (auto it = std::sregex_iterator(chart.begin(), chart.end(), point); it != std::sregex_iterator(); ++it) {
    EXPECT_TRUE(plotted.insert((*it)[1]).second) << "two points for " << (*it)[1];
  }
  EXPECT_EQ(plotted, specs) << "the suite chart should have one point per method";
  // Every point of every chart on the page (suite and scenes, both axes) and every legend
  // swatch: the method's one colour and marker (html_method_style.h).
  const std::regex marked(
      "data-spec=\"([^\"]+)\"[^>]*>(?:<title>[^<]*</title>)?(?:<svg[^>]*>)?<path class=\"mk\"[^>]* fill=\"([^\"]+)\" "
      "stroke=\"([^\"]+)\"[^>]* data-marker=\"([a-z-]+)\"");
  int marks = 0;
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), marked); it != std::sregex_iterator(); ++it, ++marks) {
    const aalab::html::MethodStyle st = aalab::html::StyleOfMethod((*it)[1]);
    EXPECT_EQ((*it)[3].str(), st.colour) << (*it)[0];
    EXPECT_EQ((*it)[4].str(), st.marker) << (*it)[0];
  }
  EXPECT_GE(marks, static_cast<int>(2 * specs.size())) << "chart points and legend swatches; DOM in " << dom_path;
  EXPECT_EQ(suite.find("No method has a value"), std::string::npos);
  // The means leave out detail-texture (no edge pixels, so no Edge PSNR) and say so.
  const std::string note = "Suite means over " + std::to_string(scenes.size() - 1) + " of " +
                           std::to_string(scenes.size()) +
                           " scenes — left out (not every method has a value there): detail-texture: ";
  EXPECT_NE(suite.find(note), std::string::npos) << "no note naming the scene left out; DOM in " << dom_path;
}

}  // namespace
