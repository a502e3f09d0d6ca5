// glTF scenes through the real binary: a real scene renders the same bytes at 1 and 2
// threads (every method family, the reference included), reports its content; a bad glTF
// file is refused with one message and nothing is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "process_util.h"

namespace aalab::clitest {
namespace {
namespace fs = std::filesystem;

TEST(GltfCli, RealSceneIsIdenticalAtOneAndTwoThreads) {
  const fs::path dir = TempDir("gltf-threads");
  const std::string common =
      "run --scenes real-foliage,real-glossy --methods none,ssaa-2x2,msaa-4x:alpha_test=sample,fxaa311-p39,taa "
      "--size 96x54 --ref-spp 16 --repeat 1 --quiet --out ";
  for (const char* t : {"1", "2"}) {
    const CmdResult r = Aalab(common + (dir / t).string() + " --threads " + t);
    ASSERT_EQ(r.code, 0) << r.output;
  }
  int compared = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir / "1")) {
    const std::string ext = e.path().extension().string();
    if (!e.is_regular_file() || (ext != ".png" && ext != ".exr")) continue;
    const fs::path other = dir / "2" / fs::relative(e.path(), dir / "1");
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_TRUE(Bytes(e.path()) == Bytes(other)) << e.path() << " differs between 1 and 2 threads";
    ++compared;
  }
  EXPECT_GE(compared, 2 * 5);
  std::ifstream f(dir / "1" / "report.json");
  const auto doc = nlohmann::json::parse(f);
  const auto& content = doc["scenes"][0]["content"];
  EXPECT_GT(content["triangles"].get<int>(), 100);
  EXPECT_EQ(content["textures"].get<int>(), 2);  // leaf and grass
  // 256² leaf + 256² grass (8-bit PNGs, so stored as RGBA8), full chains: 2 · (256² · 4/3
  // rounded to the levels) texels of 4 bytes.
  uint64_t texels = 0;
  for (int n = 256; n >= 1; n /= 2) texels += static_cast<uint64_t>(n) * n;
  EXPECT_EQ(content["texture_bytes"].get<uint64_t>(), 2 * texels * 4);
  EXPECT_EQ(content["texture_bytes_rgba8"].get<uint64_t>(), 2 * texels * 4);
  EXPECT_GT(content["load_ms"].get<double>(), 0.0);
  fs::remove_all(dir);
}

/// The output hash of method spec `method` on `scene` in a report.
std::string OutputHash(const nlohmann::json& doc, const std::string& scene, const std::string& method) {
  for (const auto& r : doc["rows"]) {
    if (r["scene"] == scene && r["spec"] == method) return r["output_hash"].get<std::string>();
  }
  return "";
}

TEST(GltfCli, SpecularAaChangesOnlyWhereTheNormalVaries) {
  // real-grazing: flat planes, constant vertex normals, no normal map: the widening is zero
  // and gsaa renders the none frame's bytes. real-glossy: a flat floor too, so plain gsaa
  // (vertex-normal derivatives, the paper's listing) renders none's bytes; the normal map
  // varies within every pixel, so its variance term (toksvig=1) and the old derivatives of the
  // mapped normal (derivatives=mapped) differ.
  const fs::path dir = TempDir("gltf-gsaa");
  const CmdResult r = Aalab(
      "run --scenes real-grazing,real-glossy --methods none,gsaa,gsaa:toksvig=1,gsaa:derivatives=mapped "
      "--size 96x54 --ref-spp 4 "
      "--repeat 1 --quiet --out " +
      (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream f(dir / "out" / "report.json");
  const auto doc = nlohmann::json::parse(f);
  EXPECT_EQ(OutputHash(doc, "real-grazing", "gsaa"), OutputHash(doc, "real-grazing", "none"));
  EXPECT_EQ(OutputHash(doc, "real-glossy", "gsaa"), OutputHash(doc, "real-glossy", "none"));
  EXPECT_NE(OutputHash(doc, "real-glossy", "gsaa:toksvig=1"), OutputHash(doc, "real-glossy", "none"));
  EXPECT_NE(OutputHash(doc, "real-glossy", "gsaa:derivatives=mapped"), OutputHash(doc, "real-glossy", "none"));
  EXPECT_FALSE(OutputHash(doc, "real-glossy", "none").empty());
  EXPECT_FALSE(OutputHash(doc, "real-glossy", "gsaa:toksvig=1").empty());
  fs::remove_all(dir);
}

TEST(GltfCli, BadFileIsRefusedAndNothingIsWritten) {
  const fs::path dir = TempDir("gltf-bad");
  std::ofstream(dir / "broken.gltf")
      << R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 12, "uri": "gone.bin"}]})";
  std::ofstream(dir / "scene.json") << R"({"name": "bad-gltf", "effects": ["lambert", "specular"],
      "camera": {"type": "perspective", "position": [0, 0, 5], "look_at": [0, 0, 0], "fov_y": 40},
      "ambient": [1, 1, 1], "materials": {}, "objects": [{"shape": "gltf", "file": "broken.gltf"}]})";
  const CmdResult r =
      Aalab("render --scene " + (dir / "scene.json").string() + " --size 32x16 --out " + (dir / "out.png").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("/objects/0/file"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("at /buffers/0/uri"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("gone.bin' not found"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out.png"));
  const CmdResult run =
      Aalab("run --scenes " + (dir / "scene.json").string() + " --size 32x16 --out " + (dir / "run").string());
  EXPECT_EQ(run.code, 1) << run.output;
  EXPECT_FALSE(fs::exists(dir / "run" / "report.json"));
  fs::remove_all(dir);
}

TEST(GltfCli, UndeclaredEffectOfAGltfMaterialIsNamed) {
  // real/fence.glb has MASK materials: a scene that does not declare alpha_test is refused.
  const fs::path dir = TempDir("gltf-effects");
  std::ofstream(dir / "scene.json") << std::string(R"({"name": "fence", "effects": ["lambert", "specular", "textures"],
      "camera": {"type": "gltf"}, "ambient": [1, 1, 1], "materials": {},
      "objects": [{"shape": "gltf", "file": ")") +
                                           AALAB_SOURCE_DIR + R"(/scenes/library/real/fence.glb"}]})";
  const CmdResult r =
      Aalab("render --scene " + (dir / "scene.json").string() + " --size 32x16 --out " + (dir / "out.png").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("alphaMode MASK"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("alpha_test"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out.png"));
  fs::remove_all(dir);
}

TEST(GltfCli, AModelIsASceneAndSceneWritesItsFile) {
  const std::string model = "/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb";
  if (!fs::exists(model)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const fs::path dir = TempDir("gltf-model");
  // aalab scene: the scene file, with the effects the file's textured PBR material needs and
  // a camera framing the box (the file has none); never overwritten.
  const CmdResult w = Aalab("scene " + model + " --out " + (dir / "box.json").string());
  ASSERT_EQ(w.code, 0) << w.output;
  std::ifstream f(dir / "box.json");
  const auto j = nlohmann::json::parse(f);
  EXPECT_EQ(j["name"], "box-textured");
  EXPECT_EQ(j["effects"], nlohmann::json({"lambert", "shadows", "specular", "textures"}));
  EXPECT_EQ(j["camera"]["type"], "perspective");
  EXPECT_EQ(j["objects"][0]["file"], model);
  const CmdResult again = Aalab("scene " + model + " --out " + (dir / "box.json").string());
  EXPECT_EQ(again.code, 1) << again.output;
  EXPECT_NE(again.output.find("does not overwrite"), std::string::npos) << again.output;
  // run --scenes MODEL.glb: the same scene as that file, the effects printed.
  const std::string args = " --methods none --size 48x27 --ref-spp 4 --repeat 1 --quiet --out ";
  const CmdResult r1 = Aalab("run --scenes " + model + args + (dir / "a").string());
  ASSERT_EQ(r1.code, 0) << r1.output;
  EXPECT_NE(r1.output.find("effects lambert, shadows, specular, textures"), std::string::npos) << r1.output;
  const CmdResult r2 = Aalab("run --scenes " + (dir / "box.json").string() + args + (dir / "b").string());
  ASSERT_EQ(r2.code, 0) << r2.output;
  auto hash = [](const fs::path& report) {
    std::ifstream in(report);
    const auto doc = nlohmann::json::parse(in);
    return doc["rows"][0]["output_hash"].get<std::string>();
  };
  EXPECT_EQ(hash(dir / "a" / "report.json"), hash(dir / "b" / "report.json"));
  // Not a model: refused with what is allowed.
  const CmdResult bad = Aalab("scene " + (dir / "box.json").string());
  EXPECT_EQ(bad.code, 1) << bad.output;
  EXPECT_NE(bad.output.find("allowed: a .glb or .gltf file"), std::string::npos) << bad.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab::clitest
