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

namespace {
namespace fs = std::filesystem;

constexpr const char* kChromium = "/usr/bin/chromium";
using aalab::clitest::CmdResult;
using aalab::clitest::RunCommand;



std::string ReadFile(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string Quote(const std::string& s) { return "'" + s + "'"; }  // paths here have no quotes

/// Headless Chromium with no network services, a throw-away profile and console logging to stderr.
std::string Chromium(const fs::path& profile, const std::string& args) {
  return std::string("timeout 180 ") + kChromium +
         " --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --disable-background-networking"
         " --disable-component-update --disable-sync --no-first-run --hide-scrollbars --user-data-dir=" +
         Quote(profile.string()) + " --enable-logging=stderr --v=0 " + args;
}

TEST(HtmlBrowser, PageShowsEverythingWithoutErrors) {
  if (!fs::exists(kChromium)) {
    AALAB_SKIP_OR_FAIL_UNDER_CI(std::string(kChromium) +
                                " is not installed, so the HTML report was NOT tested in a browser. Install it with "
                                "scripts/install-deps.sh (Debian package 'chromium').");
  }
  const fs::path work = fs::path(AALAB_BINARY_DIR) / "html_browser_test";
  const fs::path out = work / "run";
  fs::remove_all(work);
  fs::create_directories(work);
  const CmdResult run = RunCommand(std::string(AALAB_BINARY_DIR) + "/aalab run --scenes wedges,circle --methods "
                            "none,ssaa-2x2,fxaa1-p3 --size 64x36 --ref-spp 4 --repeat 1 --debug-views --quiet --out " +
                            Quote(out.string()) + " 2>&1");
  ASSERT_EQ(run.code, 0) << run.output;
  ASSERT_TRUE(fs::exists(out / "index.html"));
  const std::string url = "file://" + fs::absolute(out / "index.html").string();

  // 1. The self-test: every view, every row, every chart point, every gallery entry, every image.
  const fs::path dom_path = work / "dom.html", log_path = work / "chromium.log";
  const CmdResult dump = RunCommand(Chromium(work / "profile-selftest", "--virtual-time-budget=30000 --dump-dom " +
                                                                     Quote(url + "#selftest")) +
                             " > " + Quote(dom_path.string()) + " 2> " + Quote(log_path.string()));
  ASSERT_EQ(dump.code, 0) << "chromium failed; log: " << log_path << "\n" << ReadFile(log_path);
  const std::string dom = ReadFile(dom_path);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("<pre id=\"selftest\">([^<]*)</pre>")))
      << "no self-test verdict in the page (script did not run?); DOM in " << dom_path;
  const std::string verdict = m[1];
  EXPECT_EQ(verdict.rfind("OK scenes=2 rows=6 points=6 galleries=6 ", 0), 0u) << verdict;
  for (const char* zero : {" failed=0", " errors=0", " problems=0"}) EXPECT_NE(verdict.find(zero), std::string::npos) << verdict;
  EXPECT_EQ(verdict.find("images=0 "), std::string::npos) << verdict;

  // 2. Every scene and method of report.json is in the page (the tables are static HTML).
  const auto report = nlohmann::json::parse(ReadFile(out / "report.json"));
  ASSERT_EQ(report["rows"].size(), 6u);
  for (const auto& row : report["rows"]) {
    const std::string key = "data-scene=\"" + row["scene"].get<std::string>() + "\" data-spec=\"" +
                            row["spec"].get<std::string>() + "\"";
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
    const CmdResult r = RunCommand(Chromium(work / ("profile-" + view), "--virtual-time-budget=10000 --window-size=1400,2000 "
                                                                 "--screenshot=" + Quote(shot.string()) + " " +
                                                                 Quote(url + "#" + view)) +
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
    AALAB_SKIP_OR_FAIL_UNDER_CI(std::string(kChromium) + " is not installed, so the A/B page was NOT tested in a browser.");
  }
  const fs::path work = fs::path(AALAB_BINARY_DIR) / "html_browser_pair_test";
  const fs::path out = work / "run";
  fs::remove_all(work);
  fs::create_directories(work);
  const CmdResult run = RunCommand(std::string(AALAB_BINARY_DIR) + "/aalab run --scenes wedges --methods "
                                   "none,ssaa-2x2,fxaa1-p3 --size 64x36 --ref-spp 4 --repeat 1 --quiet --out " +
                                   Quote(out.string()) + " 2>&1");
  ASSERT_EQ(run.code, 0) << run.output;
  // The terminal states the verdict too.
  EXPECT_NE(run.output.find("  wedges: edge PSNR → "), std::string::npos) << run.output;
  const std::string url = "file://" + fs::absolute(out / "index.html").string() + "#pairtest";
  auto facts = [&](const std::string& name, const std::string& flags) {
    const fs::path dom = work / (name + ".html"), log = work / (name + ".log");
    const CmdResult r = RunCommand(Chromium(work / ("profile-" + name), flags + " --virtual-time-budget=20000 "
                                                                        "--window-size=1400,1600 --dump-dom " + Quote(url)) +
                                   " > " + Quote(dom.string()) + " 2> " + Quote(log.string()));
    EXPECT_EQ(r.code, 0) << ReadFile(log);
    std::smatch m;
    const std::string text = ReadFile(dom);
    if (!std::regex_search(text, m, std::regex("<pre id=\"pairtest\">([^<]*)</pre>"))) return std::string("no pairtest");
    return std::string(m[1]);
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
  const CmdResult idiff = RunCommand("idiff -a " + Quote((out / png / "ssaa-2x2.png").string()) + " " +
                                     Quote((out / png / "fxaa1-p3.png").string()) + " 2>&1");
  std::smatch im;
  ASSERT_TRUE(std::regex_search(idiff.output, im, std::regex("Max error += ([0-9.]+)"))) << idiff.output;
  EXPECT_EQ(std::stoi(m[2]), static_cast<int>(std::lround(std::stod(im[1]) * 255))) << read << "\n" << idiff.output;
  ASSERT_TRUE(std::regex_search(idiff.output, im, std::regex("([0-9]+) pixels \\([0-9.]+%\\) over"))) << idiff.output;
  EXPECT_EQ(m[1].str(), im[1].str()) << read << "\n" << idiff.output;
  // The split, then all of A, then all of B.
  EXPECT_NE(read.find(" before=split f1=A:" + png + "ssaa-2x2"), std::string::npos) << read;
  EXPECT_NE(read.find(" f2=B:" + png + "fxaa1-p3"), std::string::npos) << read;
  ASSERT_TRUE(std::regex_search(read, m, std::regex(" ref=([0-9]+) "))) << read;
  EXPECT_GT(std::stoi(m[1]), 0) << read;
  EXPECT_NE(read.find(" errors=0"), std::string::npos) << read;
  EXPECT_EQ(read.find("exception"), std::string::npos) << read;
  // Opened from disk without the flag: the same interactions, the counts said to be unavailable.
  const std::string plain = facts("plain", "");
  EXPECT_NE(plain.find(" same=ssaa-2x2:unknown "), std::string::npos) << plain;
  EXPECT_NE(plain.find(" f2=B:" + png + "fxaa1-p3"), std::string::npos) << plain;
  EXPECT_NE(plain.find(" errors=0"), std::string::npos) << plain;
}

// The first screen of `make run`: the default suite (every default method, a scene without
// edges among them), tiny. The suite chart must plot one point per method for the default
// quality axis, and say which scene its means leave out and why.
TEST(HtmlBrowser, DefaultSuiteOverviewHasOnePointPerMethod) {
  if (!fs::exists(kChromium)) AALAB_SKIP_OR_FAIL_UNDER_CI(std::string(kChromium) + " is not installed.");
  const fs::path work = fs::path(AALAB_BINARY_DIR) / "html_browser_suite_test";
  const fs::path out = work / "run";
  fs::remove_all(work);
  fs::create_directories(work);
  const CmdResult run = RunCommand(std::string(AALAB_BINARY_DIR) +
                                   "/aalab run --suite default --size 48x27 --ref-spp 4 --repeat 1 --quiet --out " +
                                   Quote(out.string()) + " 2>&1");
  ASSERT_EQ(run.code, 0) << run.output;
  const auto report = nlohmann::json::parse(ReadFile(out / "report.json"));
  std::set<std::string> specs, scenes;
  for (const auto& row : report["rows"]) {
    specs.insert(row["spec"].get<std::string>());
    scenes.insert(row["scene"].get<std::string>());
  }
  ASSERT_TRUE(scenes.count("detail-texture")) << "the default suite should hold the scene without edges";

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
  EXPECT_EQ(suite.find("No method has a value"), std::string::npos);
  // The means leave out detail-texture (no edge pixels, so no Edge PSNR) and say so.
  const std::string note = "Suite means over " + std::to_string(scenes.size() - 1) + " of " + std::to_string(scenes.size()) +
                           " scenes — left out (not every method has a value there): detail-texture: ";
  EXPECT_NE(suite.find(note), std::string::npos) << "no note naming the scene left out; DOM in " << dom_path;
}

}  // namespace
