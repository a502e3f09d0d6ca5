// The repository's own .clang-format, checked: every C++ and CUDA file under the project's
// folders is formatted as clang-format 14 (Debian 12's, scripts/debian-packages.txt) formats
// it. `make format` rewrites the tree; this test is how CI checks it (a changed line that is
// not formatted fails `make test`). Another clang-format major version formats some
// constructs differently, so the check runs only with version 14: elsewhere it skips (and
// fails under CI, which installs 14).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/skip_or_fail.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

struct Run {
  int status = -1;
  std::string output;
};

Run Shell(const std::string& command) {
  Run r;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  r.status = pclose(p);
  return r;
}

/// The clang-format 14 binary, or "" when there is none.
std::string ClangFormat14() {
  for (const char* name : {"clang-format-14", "clang-format"}) {
    const Run v = Shell(std::string(name) + " --version");
    if (v.status == 0 && v.output.find("version 14.") != std::string::npos) return name;
  }
  return "";
}

/// The project's C++ and CUDA sources (the folders of docs/design.md plus bench/ and tests/).
std::vector<std::string> Sources(const fs::path& root) {
  std::vector<std::string> files;
  for (const char* dir :
       {"core", "io", "scenes", "methods", "metrics", "reports", "harness", "gpu", "bench", "tests"}) {
    if (!fs::exists(root / dir)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root / dir)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".cpp" || ext == ".h" || ext == ".cu" || ext == ".cuh")) {
        files.push_back(e.path().string());
      }
    }
  }
  return files;
}

/// The files of `files` that `clang_format` would change (--dry-run --Werror): one call per
/// batch of 64 files, and file by file only inside a batch that fails.
std::vector<std::string> Unformatted(const std::string& clang_format, const std::vector<std::string>& files) {
  auto check = [&](size_t from, size_t to) {
    std::string cmd = clang_format + " --style=file --dry-run --Werror";
    for (size_t i = from; i < to; ++i) cmd += " '" + files[i] + "'";
    return Shell(cmd).status == 0;
  };
  std::vector<std::string> bad;
  for (size_t from = 0; from < files.size(); from += 64) {
    const size_t to = std::min(files.size(), from + 64);
    if (check(from, to)) continue;
    for (size_t i = from; i < to; ++i) {
      if (!check(i, i + 1)) bad.push_back(files[i]);
    }
  }
  return bad;
}

TEST(Format, EverySourceFileIsAsClangFormat14FormatsIt) {
  const std::string cf = ClangFormat14();
  if (cf.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI("clang-format 14 not found (apt-get install clang-format on Debian 12)");
  const auto files = Sources(AALAB_SOURCE_DIR);
  ASSERT_GT(files.size(), 300u);  // the tree, not an empty folder
  const auto bad = Unformatted(cf, files);
  std::string list;
  for (const auto& f : bad) list += "\n  " + f;
  EXPECT_TRUE(bad.empty()) << bad.size() << " file(s) not formatted; run `make format` (clang-format 14):" << list;
}

// The check can fail: a file written against the style (4-space indent, a brace on its own
// line, a 130-column line) in a folder holding the repository's .clang-format is reported,
// and the same code formatted is not.
TEST(Format, TheCheckReportsAFileWrittenAgainstTheStyle) {
  const std::string cf = ClangFormat14();
  if (cf.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI("clang-format 14 not found (apt-get install clang-format on Debian 12)");
  const fs::path dir = fs::temp_directory_path() / ("aalab_format_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::copy_file(fs::path(AALAB_SOURCE_DIR) / ".clang-format", dir / ".clang-format",
                fs::copy_options::overwrite_existing);
  const fs::path bad = dir / "bad.cpp", good = dir / "good.cpp";
  std::ofstream(bad) << "int f(int x)\n{\n    return x + 1;\n}\nint g() { return f(1) + f(2) + f(3) + f(4) + f(5) + "
                        "f(6) + f(7) + f(8) + f(9) + f(10) + f(11) + f(12) + f(13) + f(14) + f(15); }\n";
  std::ofstream(good) << "int f(int x) { return x + 1; }\n";
  EXPECT_EQ(Unformatted(cf, {bad.string(), good.string()}), std::vector<std::string>{bad.string()});
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
