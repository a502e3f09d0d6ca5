// Helpers for the tests that load aalab's pages in headless Chromium (tests/reports/
// html_*browser_test.cpp): the browser's command line, a page's facts (what its in-page test
// wrote into a <pre>), and a PNG's pixel as OpenImageIO's oiiotool decodes it.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "../cli/cli_util.h"

namespace aalab::browsertest {

namespace fs = std::filesystem;

inline constexpr const char* kChromium = "/usr/bin/chromium";

inline std::string ReadFile(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline std::string Quote(const std::string& s) { return "'" + s + "'"; }  // paths here have no quotes

/// Headless Chromium with no network services, a throw-away profile and console logging to stderr.
inline std::string Chromium(const fs::path& profile, const std::string& args) {
  return std::string("timeout 180 ") + kChromium +
         " --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --disable-background-networking"
         " --disable-component-update --disable-sync --no-first-run --hide-scrollbars --user-data-dir=" +
         Quote(profile.string()) + " --enable-logging=stderr --v=0 " + args;
}

/// A fresh folder `name` in the build folder (kept after the test for a human to look at).
inline fs::path FreshWorkDir(const std::string& name) {
  const fs::path work = fs::path(AALAB_BINARY_DIR) / name;
  fs::remove_all(work);
  fs::create_directories(work);
  return work;
}

/// Runs `aalab ARGS --out OUT` (quiet) and returns what it printed; a non-zero exit fails the test.
inline std::string RunAalabInto(const fs::path& out, const std::string& args) {
  const clitest::CmdResult r = clitest::RunCommand(std::string(AALAB_BINARY_DIR) + "/aalab " + args +
                                                   " --quiet --out " + Quote(out.string()) + " 2>&1");
  EXPECT_EQ(r.code, 0) << r.output;
  return r.output;
}

/// Loads `url` with Chromium `flags` and returns the text of `<pre id="PRE">` the page's test
/// wrote, or "no PRE" (DOM and log kept as WORK/NAME.html and .log).
inline std::string PageFacts(const fs::path& work, const std::string& name, const std::string& url,
                             const std::string& flags, const std::string& pre) {
  const fs::path dom = work / (name + ".html"), log = work / (name + ".log");
  const clitest::CmdResult r = clitest::RunCommand(
      Chromium(work / ("profile-" + name),
               flags + " --virtual-time-budget=20000 --window-size=1400,1600 --dump-dom " + Quote(url)) +
      " > " + Quote(dom.string()) + " 2> " + Quote(log.string()));
  EXPECT_EQ(r.code, 0) << ReadFile(log);
  std::smatch m;
  const std::string text = ReadFile(dom);
  if (!std::regex_search(text, m, std::regex("<pre id=\"" + pre + "\">([^<]*)</pre>"))) return "no " + pre;
  return m[1];
}

/// Pixel (x, y) of an 8-bit PNG as "r,g,b", decoded by `oiiotool --dumpdata` (OpenImageIO),
/// independently of the browser; "" when oiiotool does not print it.
inline std::string PngPixel(const fs::path& png, int x, int y) {
  const clitest::CmdResult r = clitest::RunCommand("oiiotool --dumpdata " + Quote(png.string()) + " 2>&1");
  std::smatch m;
  const std::regex line("Pixel \\(" + std::to_string(x) + ", " + std::to_string(y) + "\\): ([0-9]+) ([0-9]+) ([0-9]+)");
  if (!std::regex_search(r.output, m, line)) return "";
  return m[1].str() + "," + m[2].str() + "," + m[3].str();
}

/// What OpenImageIO's `idiff -a` says of two images: the count of pixels that differ at all
/// and the largest difference in 8-bit levels; {-1, -1} when its output does not say.
struct IdiffStats {
  int differing = -1, max_levels = -1;
};
inline IdiffStats Idiff(const fs::path& a, const fs::path& b) {
  const clitest::CmdResult r = clitest::RunCommand("idiff -a " + Quote(a.string()) + " " + Quote(b.string()) + " 2>&1");
  IdiffStats s;
  std::smatch m;
  if (std::regex_search(r.output, m, std::regex("Max error += ([0-9.]+)"))) {
    s.max_levels = static_cast<int>(std::lround(std::stod(m[1]) * 255));
  }
  if (std::regex_search(r.output, m, std::regex("([0-9]+) pixels \\([0-9.]+%\\) over"))) s.differing = std::stoi(m[1]);
  return s;
}

/// Checks the pixel readout fact "px=X,Y:a=R,G,B:b=R,G,B:d=R,G,B" of abview.js: (X, Y) inside
/// `window` ({x, y, w, h}), A and B the pixels oiiotool reads from `a_png` and `b_png` (whose
/// top-left corner lies at `origin` in frame pixels: {0, 0} for a whole frame, the window's
/// corner for a crop file), and d their per-channel absolute difference.
inline void ExpectReadout(const std::string& facts, const std::array<int, 4>& window, const fs::path& a_png,
                          const fs::path& b_png, const std::array<int, 2>& origin) {
  std::smatch m;
  ASSERT_TRUE(std::regex_search(facts, m, std::regex(" px=([0-9]+),([0-9]+):a=([0-9,]+):b=([0-9,]+):d=([0-9,]+) ")))
      << facts;
  const int x = std::stoi(m[1]), y = std::stoi(m[2]);
  EXPECT_TRUE(x >= window[0] && x < window[0] + window[2] && y >= window[1] && y < window[1] + window[3]) << facts;
  const std::string a = PngPixel(a_png, x - origin[0], y - origin[1]),
                    b = PngPixel(b_png, x - origin[0], y - origin[1]);
  EXPECT_EQ(m[3].str(), a) << facts << " vs " << a_png;
  EXPECT_EQ(m[4].str(), b) << facts << " vs " << b_png;
  int va[3], vb[3];
  ASSERT_EQ(std::sscanf(a.c_str(), "%d,%d,%d", &va[0], &va[1], &va[2]), 3) << a;
  ASSERT_EQ(std::sscanf(b.c_str(), "%d,%d,%d", &vb[0], &vb[1], &vb[2]), 3) << b;
  const std::string d = std::to_string(std::abs(va[0] - vb[0])) + "," + std::to_string(std::abs(va[1] - vb[1])) + "," +
                        std::to_string(std::abs(va[2] - vb[2]));
  EXPECT_EQ(m[5].str(), d) << facts;
}

}  // namespace aalab::browsertest
