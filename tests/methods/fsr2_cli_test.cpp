// The fsr2-* rows through the real `aalab` binary: a motion run whose rows render at the
// mode's size (160×90 output: 1.5× renders round(160/1.5) × round(90/1.5) = 107 × 60, 1×
// the full size), whose FSR 2 native row is nearer the reference than `none`, and whose bits do
// not depend on the thread count; on a captured sequence (an image scene with motion vectors
// and jitter) fsr2-native runs and the upscaling modes are refused as taau-* are ("needs the
// renderer"); a parameter out of range exits 1 with one message and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "io/image_io.h"
#include "tests/cli/cli_util.h"

namespace aalab::clitest {
namespace {
namespace fs = std::filesystem;

nlohmann::json Report(const fs::path& dir) {
  std::ifstream f(dir / "report.json");
  return nlohmann::json::parse(f);
}

const nlohmann::json& Row(const nlohmann::json& rep, const std::string& spec) {
  for (const auto& r : rep.at("rows")) {
    if (r.at("spec") == spec) return r;
  }
  throw std::runtime_error("no row " + spec);
}

double Metric(const nlohmann::json& row, const std::string& name) { return row.at("metrics").at(name).get<double>(); }

TEST(Fsr2Cli, MotionRunRendersAtTheModeSizeAndBeatsNone) {
  const fs::path dir = TempDir("fsr2-motion");
  nlohmann::json reps[2];
  for (int t = 1; t <= 2; ++t) {
    const fs::path out = dir / ("t" + std::to_string(t));
    const CmdResult r = Aalab(
        "run --scenes motion-pan --methods none,fsr2-quality,fsr2-native --frames 6 --size 160x90 --ref-spp 4 "
        "--repeat 1 --quiet --threads " +
        std::to_string(t) + " --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    reps[t - 1] = Report(out);
  }
  const nlohmann::json& rep = reps[0];
  EXPECT_EQ(Row(rep, "fsr2-quality").at("render_size"), nlohmann::json::array({107, 60}));
  EXPECT_EQ(Row(rep, "fsr2-native").at("render_size"), nlohmann::json::array({160, 90}));
  EXPECT_FALSE(Row(rep, "fsr2-quality").contains("not_applicable"));
  // Measured (pooled over the 6 frames, frame 0 included): none 25.83 dB, fsr2-native 28.35 dB.
  EXPECT_GT(Metric(Row(rep, "fsr2-native"), "psnr_db"), Metric(Row(rep, "none"), "psnr_db") + 2.0);
  for (const std::string spec : {"fsr2-quality", "fsr2-native"}) {
    EXPECT_EQ(Row(reps[0], spec).at("output_hash"), Row(reps[1], spec).at("output_hash")) << spec;
    EXPECT_EQ(Row(reps[0], spec).at("metrics"), Row(reps[1], spec).at("metrics")) << spec;
  }
  EXPECT_TRUE(fs::exists(dir / "t1/images/motion-pan/fsr2-quality.f5.png"));
  if (!HasFailure()) fs::remove_all(dir);
}

TEST(Fsr2Cli, CapturedSequenceRunsNativeAndRefusesUpscaling) {
  const fs::path dir = TempDir("fsr2-captured");
  // A still capture: wedges' 1x frames and references of a 3-frame run, zero motion, zero jitter.
  CmdResult r =
      Aalab("run --scenes wedges --methods none --frames 3 --size 48x27 --ref-spp 4 --repeat 1 --quiet --out " +
            (dir / "src").string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (int t = 0; t < 3; ++t) WriteImageF((dir / ("mv_" + std::to_string(t) + ".exr")).string(), ImageF(48, 27, 2));
  const std::string src = "src/images/wedges";  // relative to the manifest's folder
  std::ofstream(dir / "seq.json") << R"({"aalab_image_scene": 1, "views": [{"name": "capture",
    "sequence": {"frames": 3, "first": 0}, "frame": ")" +
                                         src + R"(/none.f%d.png", "reference": ")" + src +
                                         R"(/reference.f%d.png",
    "jitter": [[0, 0], [0, 0], [0, 0]],
    "motion_vectors": {"path": ")" + std::string("mv_%d.exr") +
                                         R"(", "direction": "to_previous"}}]})";
  r = Aalab("run --scenes " + (dir / "seq.json").string() +
            " --methods none,fsr2-native,fsr2-quality,taau-67 --repeat 1 --quiet --out " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json rep = Report(dir / "out");
  EXPECT_FALSE(Row(rep, "fsr2-native").contains("not_applicable"));
  EXPECT_EQ(Row(rep, "fsr2-native").at("render_size"), nlohmann::json::array({48, 27}));
  for (const std::string spec : {"fsr2-quality", "taau-67"}) {
    const std::string why = Row(rep, spec).at("not_applicable").get<std::string>();
    EXPECT_NE(why.find("needs the renderer"), std::string::npos) << why;
    EXPECT_NE(why.find("at scale 0.66"), std::string::npos) << why;
  }
  if (!HasFailure()) fs::remove_all(dir);
}

TEST(Fsr2Cli, AParameterOutOfRangeIsRefused) {
  const fs::path dir = TempDir("fsr2-bad");
  const CmdResult r =
      Aalab("run --scenes motion-pan --methods fsr2-quality:sharpness=2 --frames 2 --size 32x18 --out " +
            (dir / "out").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("method 'fsr2-quality': parameter 'sharpness' = '2' is out of range"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  EXPECT_FALSE(fs::exists(dir / "out.partial"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab::clitest
