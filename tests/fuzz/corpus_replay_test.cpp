// Corpus replay (runs in `make test`): every file of tests/fuzz/corpus/{scene,image}/ goes
// through the same entry function the libFuzzer targets call (fuzz_entries.h). The corpus
// holds the seeds and every crash `make fuzz` found, minimised, as regression cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "fuzz_entries.h"

namespace aalab::fuzz {
namespace {
namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(AALAB_SOURCE_DIR) / "tests" / "fuzz" / "corpus";

std::vector<fs::path> Files(const std::string& which) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kCorpus / which)) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<uint8_t> Bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

void Replay(const std::string& which, int (*entry)(const uint8_t*, size_t)) {
  const auto files = Files(which);
  ASSERT_FALSE(files.empty()) << "empty corpus " << which;
  for (const auto& p : files) {
    SCOPED_TRACE(p.string());
    const std::vector<uint8_t> bytes = Bytes(p);
    EXPECT_NO_THROW(EXPECT_EQ(entry(bytes.data(), bytes.size()), 0));
  }
}

TEST(FuzzCorpus, ScenesReplayWithoutFindings) { Replay("scene", FuzzScene); }

TEST(FuzzCorpus, ImagesReplayWithoutFindings) { Replay("image", FuzzImage); }

TEST(FuzzCorpus, StaysSmall) {
  // The corpus is checked in: at most 40 files and 200 KB per target.
  for (const char* which : {"scene", "image"}) {
    uintmax_t bytes = 0;
    const auto files = Files(which);
    for (const auto& p : files) bytes += fs::file_size(p);
    EXPECT_LE(files.size(), 40u) << which;
    EXPECT_LE(bytes, 200u * 1024u) << which;
  }
}

TEST(FuzzCorpus, EmptyAndTinyInputsAreHandled) {
  const uint8_t none = 0;
  EXPECT_EQ(FuzzScene(&none, 0), 0);
  EXPECT_EQ(FuzzImage(&none, 0), 0);
  for (uint8_t ext = 0; ext < 3; ++ext) EXPECT_EQ(FuzzImage(&ext, 1), 0);  // empty files
}

}  // namespace
}  // namespace aalab::fuzz
