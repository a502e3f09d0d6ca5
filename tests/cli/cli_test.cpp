// End-to-end tests of the aalab executable: exit codes, messages, and what is (not) written.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "core/color.h"
#include "io/image_io.h"
#include "methods/fxaa1.h"
#include "methods/fxaa311.h"
#include "scenes/library.h"
#include "scenes/render.h"

namespace {
namespace fs = std::filesystem;
using aalab::clitest::Aalab;
using aalab::clitest::CmdResult;
using aalab::clitest::TempDir;

/// Expects the 8-bit image file at `path` to hold exactly the RGB bytes of `want`.
void ExpectFileIs(const fs::path& path, const aalab::Image8& want) {
  ASSERT_TRUE(fs::exists(path)) << path;
  const aalab::Image8 got = aalab::ReadImage8(path.string());
  ASSERT_EQ(got.Width(), want.Width()) << path;
  ASSERT_EQ(got.Height(), want.Height()) << path;
  long differing = 0;
  for (int y = 0; y < want.Height(); ++y) {
    for (int x = 0; x < want.Width(); ++x) {
      for (int c = 0; c < 3; ++c) differing += got.At(x, y, c) != want.At(x, y, c);
    }
  }
  EXPECT_EQ(differing, 0) << path << ": channel values that differ from the library's result";
}

/// The library's render of a library scene (what `aalab render` must write).
aalab::Image8 LibraryFrame(const std::string& scene, int w, int h, int grid) {
  const aalab::Scene s = aalab::LoadScene(scene);
  const aalab::Tracer tracer(s);
  aalab::RenderSpec spec;
  if (grid > 1) {
    spec.pattern = aalab::SamplePattern::kStratified;
    spec.grid = grid;
  }
  return aalab::RenderFrame(tracer, w, h, spec, 1, nullptr);  // seed 1: aalab render's default
}

void ExpectFails(const std::string& args, const std::vector<std::string>& parts) {
  const CmdResult r = Aalab(args);
  EXPECT_NE(r.code, 0) << args << "\n" << r.output;
  for (const auto& p : parts)
    EXPECT_NE(r.output.find(p), std::string::npos) << args << "\noutput: " << r.output << "\nmissing: " << p;
}

TEST(Cli, VersionAndHelp) {
  EXPECT_EQ(Aalab("--version").code, 0);
  for (const char* sub : {"list", "render", "run", "apply"}) {
    const CmdResult r = Aalab(std::string(sub) + " --help");
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub;
  }
}

TEST(Cli, ListsNameEverything) {
  CmdResult r = Aalab("list methods");
  EXPECT_EQ(r.code, 0);
  for (const char* m : {"none", "ssaa-4x4", "ssaa-jitter", "spp=8 [1..1024]"})
    EXPECT_NE(r.output.find(m), std::string::npos) << m;
  r = Aalab("list scenes");
  EXPECT_EQ(r.code, 0);
  for (const char* s : {"wedges", "mesh", "suites:", "quick"}) EXPECT_NE(r.output.find(s), std::string::npos) << s;
  EXPECT_EQ(Aalab("list metrics").code, 0);
  ExpectFails("list colours", {"unknown list 'colours'", "scenes, methods, metrics"});
}

TEST(Cli, UnknownNamesListValidChoices) {
  const fs::path out = TempDir("bad");
  ExpectFails("run --scenes wedgez --out " + (out / "r").string(), {"unknown scene 'wedgez'", "wedges"});
  ExpectFails("run --scenes wedges --methods fxaa9 --out " + (out / "r").string(),
              {"unknown method 'fxaa9'", "ssaa-4x4"});
  ExpectFails("run --scenes wedges --methods ssaa-jitter:sp=2 --out " + (out / "r").string(),
              {"unknown parameter 'sp'", "spp=8 [1..1024]"});
  ExpectFails("run --scenes wedges --methods ssaa-jitter:spp=0 --out " + (out / "r").string(), {"out of range"});
  ExpectFails("run --suite nope --out " + (out / "r").string(), {"unknown suite 'nope'", "default", "quick"});
  ExpectFails("run --size 12 --out " + (out / "r").string(), {"--size '12'", "WxH"});
  ExpectFails("run --size 0x10 --out " + (out / "r").string(), {"--size '0x10'"});
  ExpectFails("run --ref-spp 10 --out " + (out / "r").string(), {"reference spp 10", "4, 16, 64, 256"});
  ExpectFails("run --repeat 0 --out " + (out / "r").string(), {"--repeat 0"});
  // Nothing was written by any failed run.
  EXPECT_FALSE(fs::exists(out / "r"));
  EXPECT_FALSE(fs::exists(out / "r.partial"));
}

TEST(Cli, BadSceneFileNamesFileAndField) {
  const fs::path dir = TempDir("scene");
  std::ofstream(dir / "bad.json") << R"({"name": "bad", "effects": ["unlit"], "camera": {"type": "orthographic",
      "position": [0,0,1], "look_at": [0,0,0], "height": -2}, "materials": {"w": {"shading": "unlit"}},
      "objects": [{"shape": "quad", "size": [1,1], "material": "w"}]})";
  ExpectFails("run --scenes " + (dir / "bad.json").string() + " --out " + (dir / "r").string(),
              {"bad.json", "/camera/height", "-2", "out of range"});
  EXPECT_FALSE(fs::exists(dir / "r"));
}

// AALAB_LOOP_STATS=PATH (docs/performance.md): the run's parallel-loop time, one JSON object.
// A run is mostly parallel loops: with 2 threads its loops hold work, and busy time can never
// exceed 2 × the time inside loops (two threads, each inside a chunk at most all along).
TEST(Cli, LoopStatsFileDescribesTheRunsLoops) {
  const fs::path dir = TempDir("loopstats");
  const fs::path stats = dir / "loops.json";
  const CmdResult r =
      aalab::clitest::RunCommand("AALAB_LOOP_STATS=" + stats.string() + " " + std::string(AALAB_BINARY_DIR) +
                                 "/aalab run --scenes wedges --methods none,fxaa311-p39 --size 96x54 "
                                 "--ref-spp 16 --repeat 1 --threads 2 --quiet --out " +
                                 (dir / "out").string() + " 2>&1");
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_TRUE(fs::exists(stats));
  EXPECT_FALSE(fs::exists(stats.string() + ".tmp"));
  std::ifstream f(stats);
  const auto doc = nlohmann::json::parse(f);
  EXPECT_EQ(doc["threads"].get<int>(), 2);
  EXPECT_GT(doc["loops"].get<long long>(), 0);
  EXPECT_GT(doc["in_loops_s"].get<double>(), 0.0);
  EXPECT_GT(doc["busy_s"].get<double>(), 0.0);
  EXPECT_LE(doc["busy_s"].get<double>(), 2 * doc["in_loops_s"].get<double>() + 1e-5);  // 6 decimals each
}

// A path that cannot be written is refused before the run does any work.
TEST(Cli, LoopStatsUnwritablePathIsRefusedFirst) {
  const fs::path dir = TempDir("loopstats-bad");
  const fs::path out = dir / "out";
  const CmdResult r = aalab::clitest::RunCommand("AALAB_LOOP_STATS=" + (dir / "missing" / "loops.json").string() + " " +
                                                 std::string(AALAB_BINARY_DIR) +
                                                 "/aalab run --scenes wedges --methods none --size 48x27 --ref-spp 4 "
                                                 "--repeat 1 --quiet --out " +
                                                 out.string() + " 2>&1");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("AALAB_LOOP_STATS="), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("No such file or directory"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir / "missing"));
}

TEST(Cli, RunWritesReportCoveringTheMatrix) {
  const fs::path dir = TempDir("run");
  const fs::path out = dir / "report";
  const CmdResult r = Aalab(
      "run --scenes wedges,circle --methods none,ssaa-2x2,ssaa-jitter:spp=4 --size 48x27 "
      "--ref-spp 16 --repeat 1 --quiet --out " +
      out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("report.json"), std::string::npos);
  std::ifstream f(out / "report.json");
  const auto doc = nlohmann::json::parse(f);
  EXPECT_EQ(doc["rows"].size(), 6u);
  for (const auto& row : doc["rows"]) {
    EXPECT_TRUE(fs::exists(out / row["images"]["output"].get<std::string>()));
  }
  EXPECT_EQ(doc["rows"][2]["spec"], "ssaa-jitter:spp=4");
  // Where the time went: printed and stored, every stage once, in the order first entered, and
  // the stages split the run's time with no gap (they sum to "total").
  EXPECT_NE(r.output.find("time breakdown"), std::string::npos) << r.output;
  std::vector<std::string> stages;
  double wall = 0, cpu = 0;
  for (const auto& t : doc["time_breakdown"]) {
    stages.push_back(t["stage"].get<std::string>());
    EXPECT_GE(t["wall_ms"].get<double>(), 0.0);
    EXPECT_GE(t["cpu_ms"].get<double>(), 0.0);
    if (stages.back() == "total") {
      EXPECT_NEAR(t["wall_ms"].get<double>(), wall, 1e-3);  // JSON keeps microseconds
      EXPECT_NEAR(t["cpu_ms"].get<double>(), cpu, 1e-3);
    } else {
      wall += t["wall_ms"].get<double>();
      cpu += t["cpu_ms"].get<double>();
    }
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"load_scenes", "references", "method_renders_filters", "metrics",
                                              "image_writing", "html", "total"}));
  // The page shows the same breakdown: a row per stage with its wall seconds as report.json has them.
  std::ifstream page_file(out / "index.html");
  const std::string page((std::istreambuf_iterator<char>(page_file)), std::istreambuf_iterator<char>());
  const auto table = page.find("id=\"time-breakdown\"");
  ASSERT_NE(table, std::string::npos);
  for (const auto& t : doc["time_breakdown"]) {
    char cell[64];
    std::snprintf(cell, sizeof cell, "</th><td>%.2f</td>", t["wall_ms"].get<double>() / 1e3);
    const std::string row = "<th scope=\"row\">" + t["stage"].get<std::string>() + cell;
    EXPECT_NE(page.find(row, table), std::string::npos) << row;
  }
  // Every row has its output and FLIP map; the error heatmap is drawn by the page, not stored.
  for (const auto& row : doc["rows"]) {
    EXPECT_TRUE(fs::exists(out / row["images"]["flip_map"].get<std::string>()));
    EXPECT_FALSE(row["images"].contains("error_heatmap"));
  }
  // A second run replaces the folder (it holds a report.json).
  EXPECT_EQ(
      Aalab("run --scenes wedges --methods none --size 16x9 --ref-spp 4 --repeat 1 --quiet --out " + out.string()).code,
      0);
  // A folder that is not an aalab report is never replaced.
  const fs::path foreign = dir / "foreign";
  fs::create_directories(foreign);
  std::ofstream(foreign / "notes.txt") << "mine";
  ExpectFails("run --scenes wedges --methods none --size 16x9 --ref-spp 4 --quiet --out " + foreign.string(),
              {"cannot be replaced", "was not written by aalab"});
  EXPECT_TRUE(fs::exists(foreign / "notes.txt"));
}

TEST(Cli, RenderWritesImages) {
  const fs::path dir = TempDir("render");
  EXPECT_EQ(Aalab("render --scene circle --size 32x18 --spp 4 --out " + (dir / "c.png").string()).code, 0);
  EXPECT_EQ(Aalab("render --scene circle --size 32x18 --out " + (dir / "c.exr").string()).code, 0);
  // The files hold the library's render of the same scene, size, samples and seed: the PNG
  // its 8-bit frame (2x2 stratified), the EXR its float resolve (1 sample per pixel at the
  // centre), checked through its documented relation QuantizeUnorm8(SrgbEncode(linear)) to
  // the 8-bit frame of the same samples, and against the library's float resolve value by value.
  ExpectFileIs(dir / "c.png", LibraryFrame("circle", 32, 18, 2));
  ASSERT_TRUE(fs::exists(dir / "c.exr"));
  const aalab::ImageF exr = aalab::ReadImage((dir / "c.exr").string()).pixels;
  const aalab::Image8 centre = LibraryFrame("circle", 32, 18, 1);
  const aalab::Scene circle = aalab::LoadScene("circle");
  const aalab::ImageF linear = aalab::RenderFrameLinear(aalab::Tracer(circle), 32, 18, aalab::RenderSpec{}, 1, nullptr);
  ASSERT_EQ(exr.Width(), 32);
  ASSERT_EQ(exr.Height(), 18);
  long differing = 0;
  for (int y = 0; y < 18; ++y) {
    for (int x = 0; x < 32; ++x) {
      for (int c = 0; c < 3; ++c) {
        differing += exr.At(x, y, c) != linear.At(x, y, c);
        differing += aalab::QuantizeUnorm8(aalab::SrgbEncode(exr.At(x, y, c))) != centre.At(x, y, c);
      }
    }
  }
  EXPECT_EQ(differing, 0) << "c.exr is not the library's float resolve of the 1x frame";
  ExpectFails("render --scene circle --spp 3 --out " + (dir / "x.png").string(), {"--spp 3", "square"});
  ExpectFails("render --scene circle --out " + (dir / "x.bmp").string(), {".exr or .png"});
  ExpectFails("render --scene circle --out /nonexistent-dir/x.png", {"does not exist"});
}

TEST(Cli, MetricsCommand) {
  const fs::path dir = TempDir("metrics");
  ASSERT_EQ(Aalab("render --scene circle --size 32x18 --spp 16 --out " + (dir / "ref.png").string()).code, 0);
  ASSERT_EQ(Aalab("render --scene circle --size 32x18 --out " + (dir / "none.png").string()).code, 0);
  ASSERT_EQ(Aalab("render --scene circle --size 16x9 --out " + (dir / "small.png").string()).code, 0);
  // Identical images: PSNR null with the reason, "identical": true, no NaN/Infinity.
  CmdResult r = Aalab("metrics --json --reference " + (dir / "ref.png").string() + " " + (dir / "ref.png").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_TRUE(j["identical"].get<bool>());
  EXPECT_TRUE(j["metrics"]["psnr_db"].is_null());
  EXPECT_EQ(j["null_reasons"]["psnr_db"], "identical");
  EXPECT_EQ(j["metrics"]["ssim"], 1.0);
  EXPECT_EQ(r.output.find("NaN"), std::string::npos);
  r = Aalab("metrics --reference " + (dir / "ref.png").string() + " " + (dir / "none.png").string());
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.output.find("psnr_db"), std::string::npos);
  EXPECT_NE(r.output.find("edge_psnr_db           null (no edge mask)"), std::string::npos) << r.output;
  ExpectFails("metrics --reference " + (dir / "ref.png").string() + " " + (dir / "small.png").string(),
              {"sizes differ", "32x18", "16x9", "never resampled"});
  ExpectFails("metrics --reference " + (dir / "nope.png").string() + " " + (dir / "ref.png").string(),
              {"does not exist"});
  std::ofstream(dir / "trunc.png") << "\x89PNG\r\n";
  ExpectFails("metrics --reference " + (dir / "trunc.png").string() + " " + (dir / "ref.png").string(), {"trunc.png"});
  // The viewing condition sets FLIP's pixels per degree: `default` is the plain command's 67,
  // another distance changes FLIP and nothing else.
  auto json_of = [&](const std::string& extra) {
    const CmdResult c = Aalab("metrics --json " + extra + " --reference " + (dir / "ref.png").string() + " " +
                              (dir / "none.png").string());
    EXPECT_EQ(c.code, 0) << c.output;
    return nlohmann::json::parse(c.output);
  };
  const auto plain = json_of(""), same = json_of("--viewing default"), far = json_of("--viewing default:ppd=134");
  EXPECT_EQ(plain["metrics"], same["metrics"]);
  EXPECT_NE(plain["metrics"]["flip_mean"], far["metrics"]["flip_mean"]);
  EXPECT_EQ(plain["metrics"]["psnr_db"], far["metrics"]["psnr_db"]);
  ExpectFails("metrics --viewing cinema --reference " + (dir / "ref.png").string() + " " + (dir / "none.png").string(),
              {"unknown preset 'cinema'", "tv-1080p-2m"});
}

TEST(Cli, ApplyRunsPostFiltersOnUserImages) {
  const fs::path dir = TempDir("apply");
  const std::string in = (dir / "in.png").string();
  ASSERT_EQ(Aalab("render --scene wedges --size 64x36 --out " + in).code, 0);
  // Every output is the library's filter, with the spec's parameters set by hand here, of
  // the library's render of the same scene (which the input file holds: RenderWritesImages).
  const aalab::Image8 frame = LibraryFrame("wedges", 64, 36, 1);
  ExpectFileIs(in, frame);
  CmdResult r = Aalab("apply --method fxaa1-p3 " + in + " " + (dir / "out.png").string());
  EXPECT_EQ(r.code, 0) << r.output;
  const aalab::Image8 p3 = aalab::Fxaa1(frame, aalab::Fxaa1Preset(3), "", nullptr);
  EXPECT_NE(p3, frame);  // wedges has edges: the check below compares a filtered frame
  ExpectFileIs(dir / "out.png", p3);
  r = Aalab("apply --method fxaa311-p39:subpix=0.5 " + in + " " + (dir / "out311.png").string());
  EXPECT_EQ(r.code, 0) << r.output;
  aalab::Fxaa311Params p39;
  p39.steps = aalab::Fxaa311PresetSteps(39);
  p39.subpix = 0.5f;
  ExpectFileIs(dir / "out311.png", aalab::Fxaa311(frame, p39, nullptr));
  r = Aalab("apply --method fxaa1-p3 --debug horzvert " + in + " " + (dir / "dbg.png").string());
  EXPECT_EQ(r.code, 0) << r.output;
  ExpectFileIs(dir / "dbg.png", aalab::Fxaa1(frame, aalab::Fxaa1Preset(3), "horzvert", nullptr));
  // Float input goes through the display transform, and the command says so. The EXR holds
  // the float resolve of the same centre samples, so display transform + encode gives back
  // `frame` (RenderFrameLinear's contract), and the output is fxaa-high of `frame`.
  ASSERT_EQ(Aalab("render --scene wedges --size 64x36 --out " + (dir / "in.exr").string()).code, 0);
  r = Aalab("apply --method fxaa-high " + (dir / "in.exr").string() + " " + (dir / "fromexr.png").string());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("display transform"), std::string::npos) << r.output;
  ExpectFileIs(dir / "fromexr.png", aalab::Fxaa311(frame, aalab::FxaaTutorialHighParams(), nullptr));
}

TEST(Cli, ApplyErrorsLeaveNoOutput) {
  const fs::path dir = TempDir("apply-bad");
  const std::string in = (dir / "in.png").string();
  ASSERT_EQ(Aalab("render --scene wedges --size 32x18 --out " + in).code, 0);
  const std::string out = (dir / "out.png").string();
  ExpectFails("apply --method fxaa1-p3 " + (dir / "missing.png").string() + " " + out,
              {"missing.png", "does not exist"});
  std::ofstream(dir / "trunc.png") << "\x89PNG\r\n\x1a\n";
  ExpectFails("apply --method fxaa1-p3 " + (dir / "trunc.png").string() + " " + out, {"trunc.png"});
  std::ofstream(dir / "text.png") << "not an image at all";
  ExpectFails("apply --method fxaa1-p3 " + (dir / "text.png").string() + " " + out, {"text.png"});
  ExpectFails("apply --method fxaa1-p3 " + in + " /nonexistent-dir/out.png", {"/nonexistent-dir", "does not exist"});
  ExpectFails("apply --method fxaa1-p3 " + in + " " + (dir / "out.bmp").string(), {".png, .jpg"});
  ExpectFails("apply --method ssaa-4x4 " + in + " " + out, {"not a post filter", "aalab run"});
  ExpectFails("apply --method scale43-fxaa-high " + in + " " + out, {"not a post filter", "another scale"});
  ExpectFails("apply --method fxaa1-p3 --debug sparkle " + in + " " + out, {"no debug view 'sparkle'", "horzvert"});
  ExpectFails("apply --method fxaa311-p39 --debug horzvert " + in + " " + out, {"no debug view"});
  ExpectFails("apply --method fxaa1-p3:edge_threshold=2 " + in + " " + out, {"out of range"});
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir)) {
    EXPECT_EQ(e.path().filename().string().rfind(".tmp-", 0), std::string::npos) << "left a temporary file";
  }
}

}  // namespace
