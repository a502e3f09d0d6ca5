// Corpus replay (runs in `make test`): every file of tests/fuzz/corpus/{scene,image}/ goes
// through the same entry function the libFuzzer targets call (fuzz_entries.h). The corpus
// holds the seeds and every crash `make fuzz` found, minimised, as regression cases.
// A file's name says what must become of it: `lib-*` / `ok-*` must be accepted (parse or
// read, post-conditions hold), `bad-*` must be refused with a UserError (crash regressions
// are `bad-regress-*` or `ok-regress-*`). Any other name fails the replay, so a seed that
// silently stops parsing, or bad input that starts to pass, is caught.
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

const char* Name(Outcome o) { return o == Outcome::kAccepted ? "accepted" : "refused"; }

void Replay(const std::string& which, Outcome (*entry)(const uint8_t*, size_t)) {
  const auto files = Files(which);
  ASSERT_FALSE(files.empty()) << "empty corpus " << which;
  int accepted = 0, refused = 0;
  for (const auto& p : files) {
    SCOPED_TRACE(p.string());
    const std::string name = p.filename().string();
    const bool ok = name.rfind("lib-", 0) == 0 || name.rfind("ok-", 0) == 0;
    const bool bad = name.rfind("bad-", 0) == 0;
    ASSERT_TRUE(ok || bad) << name << ": a corpus file's name must start with lib- or ok- (must be accepted) or "
                           << "bad- (must be refused)";
    const Outcome want = ok ? Outcome::kAccepted : Outcome::kRefused;
    const std::vector<uint8_t> bytes = Bytes(p);
    Outcome got = Outcome::kRefused;
    EXPECT_NO_THROW(got = entry(bytes.data(), bytes.size()));
    EXPECT_EQ(Name(got), std::string(Name(want))) << name;
    (want == Outcome::kAccepted ? accepted : refused) += 1;
  }
  // Both kinds present: a corpus of only good or only bad files checks half the contract.
  EXPECT_GT(accepted, 0) << which;
  EXPECT_GT(refused, 0) << which;
}

TEST(FuzzCorpus, ScenesReplayWithoutFindings) { Replay("scene", CheckSceneBytes); }

TEST(FuzzCorpus, ImagesReplayWithoutFindings) { Replay("image", CheckImageBytes); }

TEST(FuzzCorpus, EveryLibrarySceneIsAccepted) {
  // The library as it is now (the corpus copies may be older): each file through the entry.
  int n = 0;
  for (const auto& e : fs::directory_iterator(fs::path(AALAB_SOURCE_DIR) / "scenes" / "library")) {
    if (!e.is_regular_file() || e.path().extension() != ".json" || e.path().filename() == "suites.json") continue;
    SCOPED_TRACE(e.path().string());
    const std::vector<uint8_t> bytes = Bytes(e.path());
    EXPECT_EQ(CheckSceneBytes(bytes.data(), bytes.size()), Outcome::kAccepted);
    ++n;
  }
  EXPECT_GT(n, 10);
}

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

TEST(FuzzCorpus, EmptyAndTinyInputsAreRefused) {
  const uint8_t none = 0;
  EXPECT_EQ(CheckSceneBytes(&none, 0), Outcome::kRefused);
  EXPECT_EQ(CheckImageBytes(&none, 0), Outcome::kRefused);
  for (uint8_t ext = 0; ext < 3; ++ext) EXPECT_EQ(CheckImageBytes(&ext, 1), Outcome::kRefused);  // empty files
  EXPECT_EQ(FuzzScene(&none, 0), 0);  // libFuzzer's entries always return 0
  EXPECT_EQ(FuzzImage(&none, 0), 0);
}

}  // namespace
}  // namespace aalab::fuzz
