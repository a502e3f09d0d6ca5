// `aalab run --frames N` end to end: temporal metrics in report.json, the still-scene and
// moving-edge properties of the temporal error, and bad motion input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "../cli/cli_util.h"
#include "io/image_io.h"

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
  const auto r = Aalab(
      "run --scenes motion-pan,wedges --methods none,ssaa-4x4,fxaa311-p39,ssaa-jitter,taa "
      "--frames 6 --size 96x54 --ref-spp 16 --repeat 1 --quiet --out " +
      (dir / "out").string());
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
    EXPECT_EQ(row["metrics"]["temporal_perceptual"], 0.0) << m;  // exactly: a constant error
    EXPECT_EQ(row["metrics"]["temporal_csf_rmse"], 0.0) << m;
  }
  // The default viewing condition is recorded: FLIP's 67 px/deg at 60 fps.
  EXPECT_EQ(rep["settings"]["viewing"], "default");
  EXPECT_EQ(rep["settings"]["ppd"], "67");
  EXPECT_EQ(rep["settings"]["fps"], "60");
  // A moving edge: no AA crawls more than 16x SSAA, and so does FXAA (it smooths one frame,
  // not the crawl).
  const double none = Row(rep, "motion-pan", "none")["metrics"]["temporal_rmse"];
  const double ssaa = Row(rep, "motion-pan", "ssaa-4x4")["metrics"]["temporal_rmse"];
  const double fxaa = Row(rep, "motion-pan", "fxaa311-p39")["metrics"]["temporal_rmse"];
  EXPECT_GT(none, ssaa);
  EXPECT_GT(fxaa, ssaa);
  const double none_p = Row(rep, "motion-pan", "none")["metrics"]["temporal_perceptual"];
  const double ssaa_p = Row(rep, "motion-pan", "ssaa-4x4")["metrics"]["temporal_perceptual"];
  EXPECT_GT(none_p, ssaa_p);
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
  const auto shorter = Aalab(
      "run --scenes motion-pan --methods none --frames 2 --size 96x54 --ref-spp 16 --repeat 1 "
      "--quiet --out " +
      (dir / "short").string());
  ASSERT_EQ(shorter.code, 0) << shorter.output;
  const auto mixed = Aalab("compare " + report + " " + (dir / "short" / "report.json").string());
  EXPECT_EQ(mixed.code, 2) << mixed.output;
  EXPECT_NE(mixed.output.find("setting 'frames' differs: baseline 6, current 2"), std::string::npos) << mixed.output;
  fs::remove_all(dir);
}

TEST(MotionCli, ViewingConditionChangesFlipAndTheTemporalScores) {
  // Seen from further away (twice the pixels per degree) the CSFs average more of the
  // jaggies' crawl: the perceptual temporal errors of no AA fall (their only spatial filter
  // is the low-pass CSF); FLIP changes (its colour part falls, tests/metrics/viewing_test.cpp,
  // but its feature detector widens with ppd too, so the total need not fall);
  // temporal_rmse and PSNR, which have no viewing condition, stay bit-identical.
  const fs::path dir = clitest::TempDir("motion-viewing");
  const std::string common =
      "run --scenes motion-pan --methods none --frames 4 --size 96x54 --ref-spp 16 --repeat 1 --quiet ";
  const auto near = Aalab(common + "--out " + (dir / "near").string());
  const auto far = Aalab(common + "--viewing default:ppd=134 --out " + (dir / "far").string());
  ASSERT_EQ(near.code, 0) << near.output;
  ASSERT_EQ(far.code, 0) << far.output;
  auto read = [](const fs::path& p) {
    std::ifstream f(p / "report.json");
    return nlohmann::json::parse(f);
  };
  const auto a = read(dir / "near"), b = read(dir / "far");
  EXPECT_EQ(b["settings"]["viewing"], "default:ppd=134");
  EXPECT_EQ(b["settings"]["ppd"], "134");
  const nlohmann::json ma = Row(a, "motion-pan", "none")["metrics"];
  const nlohmann::json mb = Row(b, "motion-pan", "none")["metrics"];
  EXPECT_EQ(ma["temporal_rmse"], mb["temporal_rmse"]);
  EXPECT_EQ(ma["psnr_db"], mb["psnr_db"]);
  EXPECT_NE(mb["flip_mean"].get<double>(), ma["flip_mean"].get<double>());
  EXPECT_LT(mb["temporal_perceptual"].get<double>(), ma["temporal_perceptual"].get<double>());
  EXPECT_LT(mb["temporal_csf_rmse"].get<double>(), ma["temporal_csf_rmse"].get<double>());
  // The page header names the condition.
  std::ifstream page(dir / "far" / "index.html");
  const std::string html((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("Viewing condition <b>default:ppd=134</b>"), std::string::npos);
  // A bad condition: one message naming the presets, exit 1, no output folder.
  const auto bad = Aalab(common + "--viewing cinema --out " + (dir / "bad").string());
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.output.find("unknown preset 'cinema' (allowed: default, desktop-27in-4k-60cm"), std::string::npos)
      << bad.output;
  EXPECT_FALSE(fs::exists(dir / "bad"));
  fs::remove_all(dir);
}

TEST(MotionCli, FrameExrAndExportedSequences) {
  // --frame-exr writes each frame's reference as display-linear float; export-sequences lays
  // the run out as numbered frame folders with the viewing condition.
  const fs::path dir = clitest::TempDir("motion-export");
  const auto r = Aalab(
      "run --scenes motion-pan,wedges --methods none,fxaa311-p39:subpix=0.5 --frames 3 --size 48x27 "
      "--ref-spp 4 --repeat 1 --quiet --frame-exr --viewing tv-1080p-2m --out " +
      (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream f(dir / "run" / "report.json");
  const nlohmann::json rep = nlohmann::json::parse(f);
  const auto& seq = rep["scenes"][0]["sequence"];
  ASSERT_EQ(seq["reference_frames_exr"].size(), 3u);
  // The EXR holds the float reference: decoding its 8-bit PNG twin agrees to half a code value.
  const LoadedImage exr = ReadImage((dir / "run" / seq["reference_frames_exr"][2].get<std::string>()).string());
  const Image8 png = ReadImage8((dir / "run" / seq["reference_frames"][2].get<std::string>()).string());
  EXPECT_TRUE(exr.is_float);
  double worst = 0.0;
  for (int y = 0; y < png.Height(); ++y) {
    for (int x = 0; x < png.Width(); ++x) {
      for (int c = 0; c < 3; ++c) {
        const double lin = exr.pixels.At(x, y, c);
        const double enc = lin <= 0.0031308 ? 12.92 * lin : 1.055 * std::pow(lin, 1.0 / 2.4) - 0.055;
        worst = std::max(worst, std::abs(enc * 255.0 - png.At(x, y, c)));
      }
    }
  }
  EXPECT_LE(worst, 0.5 + 1e-3);
  const auto e = Aalab("export-sequences " + (dir / "run").string() + " --out " + (dir / "seq").string());
  ASSERT_EQ(e.code, 0) << e.output;
  // 2 scenes × (reference: 3 PNG + 3 EXR, 2 methods × 3 PNG) = 24 frames.
  EXPECT_NE(e.output.find("exported 2 scenes, 6 sequences, 24 frames"), std::string::npos) << e.output;
  std::ifstream jf(dir / "seq" / "sequences.json");
  const nlohmann::json idx = nlohmann::json::parse(jf);
  EXPECT_EQ(idx["viewing"]["spec"], "tv-1080p-2m");
  EXPECT_EQ(idx["viewing"]["fps"], "60");
  EXPECT_EQ(idx["scenes"][0]["methods"][1]["folder"], "motion-pan/fxaa311-p39_subpix-0.5");
  for (int t = 0; t < 3; ++t) {
    const std::string n = std::string("0000").append(std::to_string(t));
    EXPECT_TRUE(fs::exists(dir / "seq" / "motion-pan" / "reference" / (n + ".exr")));
    const Image8 a = ReadImage8((dir / "seq" / "motion-pan" / "fxaa311-p39_subpix-0.5" / (n + ".png")).string());
    const Image8 b = ReadImage8((dir / "run" / rep["rows"][1]["frames"]["images"][t].get<std::string>()).string());
    EXPECT_EQ(a.Data(), b.Data()) << t;  // the same pixels as the run's frame
  }
  // A still run has no sequences: refused, nothing written.
  const auto still = Aalab("run --scenes wedges --methods none --size 32x18 --ref-spp 4 --repeat 1 --quiet --out " +
                           (dir / "still").string());
  ASSERT_EQ(still.code, 0) << still.output;
  const auto bad = Aalab("export-sequences " + (dir / "still").string() + " --out " + (dir / "seq2").string());
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.output.find("is not a motion run"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "seq2"));
  const auto exr_still =
      Aalab("run --scenes wedges --methods none --size 32x18 --frame-exr --quiet --out " + (dir / "still2").string());
  EXPECT_EQ(exr_still.code, 1);
  EXPECT_NE(exr_still.output.find("--frame-exr"), std::string::npos) << exr_still.output;
  fs::remove_all(dir);
}

TEST(MotionCli, SameBitsAtAnyThreadCount) {
  // A moving scene (new BVH per frame, motion vectors) and TAA's state: every frame's output
  // and every pooled and temporal value identical at 1 and 2 threads.
  const fs::path dir = clitest::TempDir("motion-threads");
  nlohmann::json reps[2];
  for (int t = 1; t <= 2; ++t) {
    const std::string out = (dir / std::string("t").append(std::to_string(t))).string();
    const auto r = Aalab(
        "run --scenes motion-orbit --methods none,taa,taa-prod,taau-50 --frames 3 --size 64x36 --ref-spp 4 --repeat 1 "
        "--quiet --threads " +
        std::to_string(t) + " --out " + out);
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
    const auto r = Aalab("run --scenes motion-pan --methods none --size 32x18 --ref-spp 4 --repeat 1 --quiet " +
                         c.args + " --out " + out);
    EXPECT_NE(r.code, 0) << c.args;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << " -> " << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
    EXPECT_FALSE(fs::exists(out + ".partial")) << c.args;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
