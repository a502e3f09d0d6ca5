// Determinism through the CLI: the same run at 1, 2 and 8 threads, and twice at 2, writes the
// same report (apart from timings and the thread count) and byte-identical image files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_util.h"

namespace aalab::clitest {
namespace {
namespace fs = std::filesystem;

/// The report with everything that may legitimately change between runs blanked: timing
/// (every "timing" object and every "*_ms" number) and the thread count (context.threads,
/// settings.threads).
nlohmann::json Normalised(const fs::path& report) {
  std::ifstream f(report);
  nlohmann::json doc = nlohmann::json::parse(f);
  std::function<void(nlohmann::json&)> blank = [&](nlohmann::json& j) {
    if (j.is_object()) {
      for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string& k = it.key();
        if (k == "timing" || (k.size() > 3 && k.compare(k.size() - 3, 3, "_ms") == 0)) {
          it.value() = "(timing)";
        } else {
          blank(it.value());
        }
      }
    } else if (j.is_array()) {
      for (auto& e : j) blank(e);
    }
  };
  blank(doc);
  doc["context"]["threads"] = "(threads)";
  doc["settings"]["threads"] = "(threads)";
  return doc;
}

std::map<std::string, std::string> FileBytes(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    // report.json is compared field by field (timings aside); index.html embeds the same
    // JSON, timings included, so it is not expected to be byte-identical.
    if (!e.is_regular_file() || e.path().filename() == "report.json" || e.path().filename() == "index.html") continue;
    std::ifstream f(e.path(), std::ios::binary);
    files[fs::relative(e.path(), dir).string()] =
        std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  }
  return files;
}

TEST(Determinism, ReportsAndImagesAreIdenticalAtAnyThreadCount) {
  const fs::path dir = TempDir("determinism");
  const std::string common =
      "run --scenes wedges,shadow-stipple,checker-plane "
      "--methods none,ssaa-jitter,fxaa1-p3,fxaa311-p39,scale43-fxaa-high "
      "--size 64x36 --ref-spp 16 --repeat 1 --quiet --out ";
  struct Run {
    std::string name;
    int threads;
  };
  const std::vector<Run> runs = {{"t2", 2}, {"t1", 1}, {"t8", 8}, {"t2-again", 2}};
  for (const auto& r : runs) {
    const CmdResult res = Aalab(common + (dir / r.name).string() + " --threads " + std::to_string(r.threads));
    ASSERT_EQ(res.code, 0) << r.name << "\n" << res.output;
  }
  const nlohmann::json base = Normalised(dir / "t2" / "report.json");
  const auto base_files = FileBytes(dir / "t2");
  EXPECT_EQ(base["rows"].size(), 15u);
  // Every output and FLIP map, reference (EXR and PNG) and edge mask: 3 scenes x (3 + 5 x 2),
  // and .aalab-output (the list of the files written; the same list in every run).
  EXPECT_EQ(base_files.size(), 40u);
  for (const auto& r : runs) {
    SCOPED_TRACE(r.name);
    const nlohmann::json doc = Normalised(dir / r.name / "report.json");
    EXPECT_EQ(doc, base) << "reports differ beyond timing and threads:\n" << nlohmann::json::diff(base, doc).dump(1);
    const auto files = FileBytes(dir / r.name);
    ASSERT_EQ(files.size(), base_files.size());
    for (const auto& [path, bytes] : base_files) {
      const auto it = files.find(path);
      ASSERT_NE(it, files.end()) << path;
      EXPECT_TRUE(it->second == bytes) << path << " differs from the 2-thread run";
    }
  }
  // The thread count is recorded (and is what the runs asked for).
  std::ifstream f(dir / "t8" / "report.json");
  EXPECT_EQ(nlohmann::json::parse(f)["context"]["threads"], "8");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab::clitest
