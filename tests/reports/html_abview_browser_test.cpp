// The shared A/B view (reports/html/abview.js) on the compare page and on the sweep page, in
// headless Chromium: the page's own exercise (#abtest) picks A = B (blank difference), then two
// different images (counts as OpenImageIO's idiff says), flips twice with `f`, zooms to crop 1
// with key 1 (the window report.json names), moves a real pointer over the pixel of that crop
// where A and B differ most (the readout must equal oiiotool's decoding of both PNGs there),
// zooms to crop 2 with key 2 and back with 0. The run page's twin is in html_browser_test.cpp.
// Skipped (visibly) only when /usr/bin/chromium is not installed; failed under CI=true.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "../cli/cli_util.h"
#include "../skip_or_fail.h"
#include "browser_util.h"

namespace {
namespace fs = std::filesystem;
using namespace aalab::browsertest;
using aalab::clitest::CmdResult;
using aalab::clitest::RunCommand;

/// The crop windows report.json (or sweep.json) names for `scene`.
std::vector<std::array<int, 4>> CropsOf(const fs::path& json, const std::string& scene) {
  const auto j = nlohmann::json::parse(ReadFile(json));
  std::vector<std::array<int, 4>> out;
  for (const auto& s : j["scenes"]) {
    if (s["name"] != scene) continue;
    for (const auto& c : s["crops"])
      out.push_back({c[0].get<int>(), c[1].get<int>(), c[2].get<int>(), c[3].get<int>()});
  }
  return out;
}

std::string Window(const std::array<int, 4>& c) {
  return std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) + "," + std::to_string(c[3]);
}

TEST(HtmlBrowserAbView, ComparePageAnyTwoFlipCropZoomAndPixelReadout) {
  if (!fs::exists(kChromium)) AALAB_SKIP_OR_FAIL_UNDER_CI(std::string(kChromium) + " is not installed.");
  const fs::path work = FreshWorkDir("html_abview_compare_test");
  const std::string common = "run --scenes wedges --size 64x36 --ref-spp 4 --repeat 1 --methods none,ssaa-2x2,";
  RunAalabInto(work / "base", common + "fxaa311-p39");
  RunAalabInto(work / "cur", common + "fxaa311-p39:subpix=0");  // a deliberate change, gated through --map
  const fs::path page = work / "cmp.html";
  const CmdResult cmp = RunCommand(
      std::string(AALAB_BINARY_DIR) + "/aalab compare " + Quote((work / "base/report.json").string()) + " " +
      Quote((work / "cur/report.json").string()) +
      " --map fxaa311-p39=fxaa311-p39:subpix=0 --max-time-increase off --html " + Quote(page.string()) + " 2>&1");
  // subpix=0 loses edge PSNR: a regression (time off: its noise would add changed rows at random)
  ASSERT_EQ(cmp.code, 1) << cmp.output;
  const auto crops = CropsOf(work / "cur/report.json", "wedges");
  ASSERT_GE(crops.size(), 2u);
  const std::string url = "file://" + fs::absolute(page).string() + "#abtest";
  const std::string read = PageFacts(work, "read", url, "--allow-file-access-from-files", "abtest");
  // One view (the one changed row): its baseline and current outputs and the reference.
  EXPECT_NE(read.find("options=b0|c0|ref "), std::string::npos) << read;
  EXPECT_NE(read.find(" same=b0:0 "), std::string::npos) << read;
  const fs::path base_png = work / "cmp_files/row1-baseline-output.png",
                 cur_png = work / "cmp_files/row1-current-output.png";
  const IdiffStats id = Idiff(base_png, cur_png);
  ASSERT_GT(id.differing, 0);
  EXPECT_NE(read.find(" pair=b0:c0:" + std::to_string(id.differing) + ":" + std::to_string(id.max_levels) + " "),
            std::string::npos)
      << read;
  EXPECT_NE(read.find(" before=split f1=A:cmp_files/row1-baseline-output.png f2=B:cmp_files/row1-current-output.png "),
            std::string::npos)
      << read;
  // Key 1: crop 1's window, magnified ×32 (a 9×9 window: 480 / 9, at most 32).
  EXPECT_NE(read.find(" zoom1=" + Window(crops[0]) + ":x32:"), std::string::npos) << read;
  ExpectReadout(read, crops[0], base_png, cur_png, {0, 0});
  EXPECT_NE(read.find(" zoom2=" + Window(crops[1]) + ":cmp_files/row1-baseline-output.png "), std::string::npos)
      << read;
  EXPECT_NE(read.find(" zoom0=0,0,64,36 "), std::string::npos) << read;
  EXPECT_NE(read.find(" hosts=1 errors=0"), std::string::npos) << read;
  // From disk without the flag: the same interactions; counts and values said to be unavailable.
  const std::string plain = PageFacts(work, "plain", url, "", "abtest");
  EXPECT_NE(plain.find(" same=b0:unknown "), std::string::npos) << plain;
  EXPECT_NE(plain.find(" f2=B:cmp_files/row1-current-output.png "), std::string::npos) << plain;
  const std::string centre =
      std::to_string(crops[0][0] + crops[0][2] / 2) + "," + std::to_string(crops[0][1] + crops[0][3] / 2);
  EXPECT_NE(plain.find(" px=" + centre + ":a=unknown:b=unknown:d=unknown "), std::string::npos) << plain;
  EXPECT_NE(plain.find(" errors=0"), std::string::npos) << plain;
}

TEST(HtmlBrowserAbView, SweepPageAnyTwoPointsFlipCropZoomAndPixelReadout) {
  if (!fs::exists(kChromium)) AALAB_SKIP_OR_FAIL_UNDER_CI(std::string(kChromium) + " is not installed.");
  const fs::path work = FreshWorkDir("html_abview_sweep_test");
  RunAalabInto(work / "sweep",
               "sweep --scenes wedges,circle --method fxaa311-p39 --grid subpix=0,0.75,1 --size 64x36 "
               "--ref-spp 4 --repeat 1");
  const auto crops = CropsOf(work / "sweep/sweep.json", "wedges");
  ASSERT_GE(crops.size(), 2u);
  const std::string url = "file://" + fs::absolute(work / "sweep/index.html").string() + "#abtest";
  const std::string read = PageFacts(work, "read", url, "--allow-file-access-from-files", "abtest");
  // The columns of the crop table: the reference, the default (subpix=0.75), the suggestion, ...
  EXPECT_EQ(read.rfind("options=reference|default|", 0), 0u) << read;
  EXPECT_NE(read.find(" same=reference:0 "), std::string::npos) << read;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(read, m, std::regex(" f1=A:(crops/[^ ]+-w0\\.png) f2=B:(crops/[^ ]+-w0\\.png) ")))
      << read;
  const fs::path a_png = work / "sweep" / m[1].str(), b_png = work / "sweep" / m[2].str();
  EXPECT_EQ(m[1].str(), "crops/s0-wedges/reference-w0.png") << read;
  const IdiffStats id = Idiff(a_png, b_png);
  ASSERT_GT(id.differing, 0);
  EXPECT_NE(
      read.find(" pair=reference:default:" + std::to_string(id.differing) + ":" + std::to_string(id.max_levels) + " "),
      std::string::npos)
      << read;
  // No whole frame on the sweep page: the view opens on crop 1, key 2 shows window 2's files, 0 stays.
  EXPECT_NE(read.find(" zoom1=" + Window(crops[0]) + ":x32:" + std::to_string(id.differing) + " "), std::string::npos)
      << read;
  ExpectReadout(read, crops[0], a_png, b_png, {crops[0][0], crops[0][1]});
  EXPECT_NE(read.find(" zoom2=" + Window(crops[1]) + ":crops/s0-wedges/reference-w1.png "), std::string::npos) << read;
  EXPECT_NE(read.find(" zoom0=" + Window(crops[1]) + " "), std::string::npos) << read;
  EXPECT_NE(read.find(" hosts=2 errors=0"), std::string::npos) << read;  // one view per scene
}

}  // namespace
