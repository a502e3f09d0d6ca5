// The run's scene images through the real binary: the reference's files and every distinct
// output's PNG are written beside the scores, the FLIP maps at the scene's end
// (harness/run/scene_pass.cpp). Each row's PNG holds the bytes its output_hash was taken of
// (FNV-1a 64 computed here by its own loop), rows with the same hash share one PNG and one
// FLIP map, and the folders of a 1-, 2- and 3-thread run hold the same files, byte for byte.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "io/image_io.h"

namespace aalab::clitest {
namespace {

namespace fs = std::filesystem;

std::string Fnv1aHex(const Image8::Storage& bytes) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (uint8_t b : bytes) h = (h ^ b) * 0x100000001b3ULL;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string FileBytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// Every file under `dir` (relative path → bytes), report.json and index.html left out (they
// hold the timings).
std::map<std::string, std::string> ImageFiles(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir / "images")) {
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = FileBytes(e.path());
  }
  return files;
}

TEST(SceneImages, EachRowsPngHoldsItsHashedOutputAndEqualOutputsShareOneFile) {
  const fs::path dir = TempDir("scene_images");
  // hard-dark: fxaa311-p39 leaves the 1x frame as it is (a repeated output, one file);
  // W ≠ H; two scenes, so the writes of one scene finish before the next scene's renders.
  const std::string args =
      "run --scenes hard-dark,wedges --methods none,fxaa311-p39,ssaa-2x2,scale43-fxaa-high --size 48x27 "
      "--ref-spp 4 --repeat 1 --quiet";
  std::map<int, std::map<std::string, std::string>> by_threads;
  for (int threads : {1, 2, 3}) {
    const fs::path out = dir / ("t" + std::to_string(threads));
    const CmdResult r = Aalab(args + " --threads " + std::to_string(threads) + " --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    by_threads[threads] = ImageFiles(out);
    std::ifstream f(out / "report.json");
    const auto doc = nlohmann::json::parse(f);
    ASSERT_EQ(doc["rows"].size(), 8u);
    std::map<std::string, std::string> file_of_hash;  // per scene: hash → output file
    int shared = 0;
    for (const auto& row : doc["rows"]) {
      const std::string where = row["scene"].get<std::string>() + " " + row["spec"].get<std::string>();
      const std::string hash = row["output_hash"].get<std::string>();
      const std::string png = row["images"]["output"].get<std::string>();
      const Image8 img = ReadImage8((out / png).string());
      ASSERT_EQ(img.Width(), 48) << where;
      ASSERT_EQ(img.Height(), 27) << where;
      EXPECT_EQ(Fnv1aHex(img.Data()), hash) << where;
      const std::string flip = row["images"]["flip_map"].get<std::string>();
      EXPECT_EQ(flip, png.substr(0, png.size() - 4) + ".flip.png") << where;
      const Image8 flip_img = ReadImage8((out / flip).string());
      EXPECT_EQ(flip_img.Width(), 48) << where;
      EXPECT_EQ(flip_img.Height(), 27) << where;
      const std::string key = row["scene"].get<std::string>() + "/" + hash;
      const auto [it, fresh] = file_of_hash.emplace(key, png);
      if (!fresh) {
        EXPECT_EQ(it->second, png) << where << ": a repeated output has its own file";
        ++shared;
      }
    }
    EXPECT_GT(shared, 0) << "no output repeated: the shared-file path was not exercised";
    for (const char* scene : {"hard-dark", "wedges"}) {
      for (const char* f : {"reference.png", "reference.exr", "edge_mask.png"}) {
        EXPECT_TRUE(fs::exists(out / "images" / scene / f)) << scene << " " << f;
      }
    }
    // Nothing but the rows' files and the references: one PNG and one FLIP map per distinct output.
    size_t per_scene_files = 0;
    for (const auto& [path, bytes] : by_threads[threads]) per_scene_files += bytes.empty() ? 0 : 1;
    EXPECT_EQ(per_scene_files, 2 * file_of_hash.size() + 2 * 3);
  }
  EXPECT_EQ(by_threads[1], by_threads[2]);
  EXPECT_EQ(by_threads[1], by_threads[3]);
}

}  // namespace
}  // namespace aalab::clitest
