// The HTML report of runs with image scenes (docs/own-frames.md) in headless Chromium: the
// page's self-test passes with "not applicable" rows (no images, null metrics), and the suite
// overview of a run of image scenes only plots the post filters and names the methods it left
// out as not applicable. Skipped when /usr/bin/chromium is missing (failed under CI=true).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "../cli/cli_util.h"
#include "../skip_or_fail.h"

namespace {
namespace fs = std::filesystem;
using aalab::clitest::CmdResult;
using aalab::clitest::RunCommand;

constexpr const char* kChromium = "/usr/bin/chromium";

std::string ReadFile(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string Quote(const std::string& s) { return "'" + s + "'"; }

std::string Aalab(const std::string& args) { return std::string(AALAB_BINARY_DIR) + "/aalab " + args + " 2>&1"; }

/// Loads `url` in headless Chromium and returns the DOM after the scripts ran.
std::string Dom(const fs::path& work, const std::string& name, const std::string& url) {
  const fs::path dom = work / (name + ".html"), log = work / (name + ".log");
  const CmdResult r =
      RunCommand("timeout 180 " + std::string(kChromium) +
                 " --headless --no-sandbox --disable-gpu --disable-dev-shm-usage"
                 " --disable-background-networking --disable-component-update --disable-sync"
                 " --no-first-run --user-data-dir=" +
                 Quote((work / ("profile-" + name)).string()) + " --virtual-time-budget=20000 --dump-dom " +
                 Quote(url) + " > " + Quote(dom.string()) + " 2> " + Quote(log.string()));
  EXPECT_EQ(r.code, 0) << ReadFile(log);
  return ReadFile(dom);
}

TEST(HtmlBrowserImageScene, NotApplicableRowsAndSuiteMeans) {
  if (!fs::exists(kChromium)) AALAB_SKIP_OR_FAIL_UNDER_CI(std::string(kChromium) + " is not installed.");
  const fs::path work = fs::path(AALAB_BINARY_DIR) / "html_image_scene_browser_test";
  fs::remove_all(work);
  fs::create_directories(work / "frames");
  CmdResult r =
      RunCommand(Aalab("run --scenes circle --methods none --size 48x32 --ref-spp 16 --repeat 1 --quiet --out " +
                       Quote((work / "direct").string())));
  ASSERT_EQ(r.code, 0) << r.output;
  fs::copy_file(work / "direct/images/circle/none.png", work / "frames/frame.png");
  fs::copy_file(work / "direct/images/circle/reference.exr", work / "frames/ref.exr");
  std::ofstream(work / "frames/m.json") << R"({"aalab_image_scene": 1, "views": [
    {"name": "mine", "frame": "frame.png", "reference": "ref.exr"}]})";
  const std::string methods =
      " --methods none,ssaa-2x2,fxaa1-p3,fxaa311-p12 --size 48x32 --ref-spp 4 --repeat 1 --quiet";

  // A library scene and an image scene in one run: the self-test walks every row.
  r = RunCommand(Aalab("run --scenes wedges," + (work / "frames/m.json").string() + methods + " --out " +
                       Quote((work / "mixed").string())));
  ASSERT_EQ(r.code, 0) << r.output;
  std::string dom = Dom(work, "mixed", "file://" + fs::absolute(work / "mixed/index.html").string() + "#selftest");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("<pre id=\"selftest\">([^<]*)</pre>"))) << "no self-test verdict";
  const std::string verdict = m[1];
  EXPECT_EQ(verdict.rfind("OK scenes=2 rows=8 points=8 galleries=8 ", 0), 0u) << verdict;
  EXPECT_NE(verdict.find(" problems=0"), std::string::npos) << verdict;
  EXPECT_NE(dom.find("not applicable"), std::string::npos);
  EXPECT_NE(dom.find("reference gradients (no object ids or depth given)"), std::string::npos);

  // Image scenes only: ssaa-2x2 is not applicable anywhere; the suite chart plots the two post
  // filters (none's render time is unknown, 0 ms, which the log axis cannot show).
  r = RunCommand(Aalab("run --scenes " + (work / "frames/m.json").string() + methods + " --out " +
                       Quote((work / "only").string())));
  ASSERT_EQ(r.code, 0) << r.output;
  dom = Dom(work, "only", "file://" + fs::absolute(work / "only/index.html").string() + "#suite");
  const size_t begin = dom.find("id=\"view-suite\"");
  ASSERT_NE(begin, std::string::npos);
  const std::string suite = dom.substr(begin, dom.find("<section", begin) - begin);
  const size_t chart_end = suite.find("</svg>");
  ASSERT_NE(chart_end, std::string::npos) << "the suite view has no chart";
  std::set<std::string> plotted;
  const std::string chart = suite.substr(0, chart_end);
  const std::regex point("<g class=\"pt [^\"]*\"[^>]* data-spec=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(chart.begin(), chart.end(), point); it != std::sregex_iterator(); ++it) {
    plotted.insert((*it)[1]);
  }
  EXPECT_EQ(plotted, (std::set<std::string>{"fxaa1-p3", "fxaa311-p12"}));
  EXPECT_NE(suite.find("Suite means over all 1 scenes"), std::string::npos);
  EXPECT_NE(suite.find("not applicable on any scene of this run"), std::string::npos);

  // The gallery opens on a method that has an output (ssaa-2x2, the first method after none,
  // is not applicable here).
  dom = Dom(work, "only", "file://" + fs::absolute(work / "only/index.html").string() + "#scene-mine");
  std::smatch pressed;
  ASSERT_TRUE(std::regex_search(dom, pressed, std::regex("data-spec=\"([^\"]+)\" aria-pressed=\"true\"")))
      << "no selected method in the gallery";
  EXPECT_EQ(pressed[1], "fxaa1-p3");
}

}  // namespace
