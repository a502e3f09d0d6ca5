// `aalab run --frames N` end to end: temporal metrics in report.json, the still-scene and
// moving-edge properties of the temporal error, and bad motion input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "../cli/cli_util.h"

namespace aalab {
namespace {

using clitest::Aalab;
namespace fs = std::filesystem;

nlohmann::json Row(const nlohmann::json& report, const std::string& scene, const std::string& spec) {
  for (const auto& r : report["rows"]) {
    if (r["scene"] == scene && r["spec"] == spec) return r;
  }
  ADD_FAILURE() << "no row " << scene << " " << spec;
  return {};
}

TEST(MotionCli, TemporalErrorOfStillAndMovingEdges) {
  const fs::path dir = clitest::TempDir("motion-run");
  const auto r = Aalab("run --scenes motion-pan,wedges --methods none,ssaa-4x4,fxaa311-p39,ssaa-jitter,taa "
                       "--frames 6 --size 96x54 --ref-spp 16 --repeat 1 --quiet --out " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream f(dir / "out" / "report.json");
  const nlohmann::json rep = nlohmann::json::parse(f);
  EXPECT_EQ(rep["settings"]["frames"], "6");
  // A still scene: every deterministic spatial method repeats itself exactly: zero
  // temporal error (and an infinite temporal PSNR, written as null).
  for (const std::string m : {"none", "ssaa-4x4", "fxaa311-p39", "ssaa-jitter"}) {
    const auto row = Row(rep, "wedges", m);
    EXPECT_EQ(row["metrics"]["temporal_rmse"], 0.0) << m;
    EXPECT_TRUE(row["metrics"]["temporal_psnr_db"].is_null()) << m;
  }
  // A moving edge: no AA crawls more than 16x SSAA, and so does FXAA (it smooths one frame,
  // not the crawl).
  const double none = Row(rep, "motion-pan", "none")["metrics"]["temporal_rmse"];
  const double ssaa = Row(rep, "motion-pan", "ssaa-4x4")["metrics"]["temporal_rmse"];
  const double fxaa = Row(rep, "motion-pan", "fxaa311-p39")["metrics"]["temporal_rmse"];
  EXPECT_GT(none, ssaa);
  EXPECT_GT(fxaa, ssaa);
  // Per-frame series and frame images for the player.
  const auto taa = Row(rep, "motion-pan", "taa");
  EXPECT_EQ(taa["frames"]["images"].size(), 6u);
  EXPECT_EQ(taa["frames"]["series"]["temporal_rmse"].size(), 6u);
  EXPECT_TRUE(taa["frames"]["series"]["temporal_rmse"][0].is_null());
  for (const auto& img : taa["frames"]["images"]) EXPECT_TRUE(fs::exists(dir / "out" / img.get<std::string>()));
  const auto& seq = rep["scenes"][0]["sequence"];
  EXPECT_EQ(seq["frames"], 6);
  EXPECT_EQ(seq["moves"], true);
  EXPECT_EQ(seq["reference_frames"].size(), 6u);
  // The page has a player per scene (reports/html/player.js draws it from the JSON).
  std::ifstream page(dir / "out" / "index.html");
  const std::string html((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("class=\"player-host\" data-scene=\"motion-pan\""), std::string::npos);
  EXPECT_NE(html.find("aalab-stop"), std::string::npos);  // the player script is embedded
  // compare: a motion report compares its temporal error by default, and only with a
  // report of the same sequence length.
  const std::string report = (dir / "out" / "report.json").string();
  const auto same = Aalab("compare " + report + " " + report);
  EXPECT_EQ(same.code, 0) << same.output;
  EXPECT_NE(same.output.find("temporal_rmse"), std::string::npos) << same.output;
  const auto shorter = Aalab("run --scenes motion-pan --methods none --frames 2 --size 96x54 --ref-spp 16 --repeat 1 "
                             "--quiet --out " + (dir / "short").string());
  ASSERT_EQ(shorter.code, 0) << shorter.output;
  const auto mixed = Aalab("compare " + report + " " + (dir / "short" / "report.json").string());
  EXPECT_EQ(mixed.code, 2) << mixed.output;
  EXPECT_NE(mixed.output.find("setting 'frames' differs: baseline 6, current 2"), std::string::npos) << mixed.output;
  fs::remove_all(dir);
}

TEST(MotionCli, SameBitsAtAnyThreadCount) {
  // A moving scene (new BVH per frame, motion vectors) and TAA's state: every frame's output
  // and every pooled and temporal value identical at 1 and 2 threads.
  const fs::path dir = clitest::TempDir("motion-threads");
  nlohmann::json reps[2];
  for (int t = 1; t <= 2; ++t) {
    const std::string out = (dir / ("t" + std::to_string(t))).string();
    const auto r = Aalab("run --scenes motion-orbit --methods none,taa --frames 3 --size 64x36 --ref-spp 4 --repeat 1 "
                         "--quiet --threads " + std::to_string(t) + " --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream f(fs::path(out) / "report.json");
    reps[t - 1] = nlohmann::json::parse(f);
  }
  ASSERT_EQ(reps[0]["rows"].size(), reps[1]["rows"].size());
  for (size_t i = 0; i < reps[0]["rows"].size(); ++i) {
    const auto& a = reps[0]["rows"][i];
    const auto& b = reps[1]["rows"][i];
    EXPECT_EQ(a["output_hash"], b["output_hash"]) << a["spec"];
    EXPECT_EQ(a["metrics"], b["metrics"]) << a["spec"];
    EXPECT_EQ(a["frames"]["series"], b["frames"]["series"]) << a["spec"];
  }
  fs::remove_all(dir);
}

TEST(MotionCli, BadFramesLeaveNothingBehind) {
  const fs::path dir = clitest::TempDir("motion-bad");
  const std::string out = (dir / "out").string();
  struct Case {
    std::string args, expect;
  };
  for (const Case& c : std::vector<Case>{{"--frames 0", "--frames 0 is out of range (1..100000)"},
                                         {"--frames 100001", "out of range"},
                                         {"--frames 65", "/animation/frames = 64"},
                                         {"--frames x", "--frames"}}) {
    const auto r = Aalab("run --scenes motion-pan --methods none --size 32x18 --ref-spp 4 --repeat 1 --quiet " + c.args +
                         " --out " + out);
    EXPECT_NE(r.code, 0) << c.args;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << " -> " << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
    EXPECT_FALSE(fs::exists(out + ".partial")) << c.args;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
