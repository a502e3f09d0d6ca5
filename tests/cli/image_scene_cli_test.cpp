// Image scenes through the CLI, as docs/own-frames.md shows them: a run's own outputs (1x frame,
// display-linear reference EXR, edge mask) become an image scene; `run` reports renderer-side
// methods as not applicable, `sweep` prints a suggested preset, and a bad manifest exits 1
// with one message and leaves nothing behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_util.h"

namespace aalab::clitest {
namespace {
namespace fs = std::filesystem;

/// Renders circle small and writes frames/frames.json from its outputs (the docs' example).
fs::path MakeImageScene(const fs::path& dir) {
  const CmdResult r = Aalab("run --scenes circle --methods none --size 48x32 --ref-spp 16 --repeat 1 --quiet --out " +
                            (dir / "direct").string());
  EXPECT_EQ(r.code, 0) << r.output;
  const fs::path f = dir / "frames";
  fs::create_directories(f);
  fs::copy_file(dir / "direct/images/circle/none.png", f / "circle-frame.png");
  fs::copy_file(dir / "direct/images/circle/reference.exr", f / "circle-ref.exr");
  fs::copy_file(dir / "direct/images/circle/edge_mask.png", f / "circle-mask.png");
  std::ofstream(f / "frames.json") << R"({"aalab_image_scene": 1, "views": [
    {"name": "circle", "frame": "circle-frame.png", "reference": "circle-ref.exr", "edge_mask": "circle-mask.png"}]})";
  return f / "frames.json";
}

TEST(CliImageScene, RunSweepAndABadManifest) {
  const fs::path dir = TempDir("image-scene");
  const fs::path manifest = MakeImageScene(dir);

  CmdResult r = Aalab("run --scenes " + manifest.string() +
                      " --methods none,fxaa311-p12,ssaa-2x2 --repeat 1 --quiet --out " + (dir / "img").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream rf(dir / "img/report.json");
  const nlohmann::json rep = nlohmann::json::parse(rf);
  ASSERT_EQ(rep.at("rows").size(), 3u);
  EXPECT_FALSE(rep.at("rows")[0].contains("not_applicable"));
  EXPECT_NE(rep.at("rows")[2].at("not_applicable").get<std::string>().find("needs the renderer"), std::string::npos);
  EXPECT_EQ(rep.at("scenes")[0].at("kind"), "image");

  r = Aalab("sweep --scenes " + manifest.string() +
            " --method fxaa311-p12 --grid edge_threshold=0.063,0.125,0.25 --repeat 1 --quiet --out " +
            (dir / "sweep").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("suggested preset: fxaa311-p12:edge_threshold="), std::string::npos) << r.output;

  // A missing reference, an unknown field: one message, exit 1, no output folder.
  std::ofstream(manifest.parent_path() / "bad.json") << R"({"aalab_image_scene": 1, "views": [
    {"name": "circle", "frame": "circle-frame.png", "reference": "missing.exr"}]})";
  std::ofstream(manifest.parent_path() / "bad2.json") << R"({"aalab_image_scene": 1, "views": [
    {"name": "circle", "frame": "circle-frame.png", "reference": "circle-ref.exr", "exposure": 2}]})";
  for (const std::string bad : {"bad.json", "bad2.json"}) {
    r = Aalab("run --scenes " + (manifest.parent_path() / bad).string() + " --out " + (dir / "bad-out").string());
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(r.output.rfind("aalab: error: image scene '", 0), 0u) << r.output;
    EXPECT_FALSE(fs::exists(dir / "bad-out"));
    EXPECT_FALSE(fs::exists(dir / "bad-out.partial"));
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab::clitest
