// Scratch folders for tests: `<temp>/aalab-<name>-<pid>`, created empty and removed, with
// everything in it, when the test process exits normally. ctest runs each test in a process
// of its own, so a run leaves nothing behind in the temp folder (a test killed by its
// timeout or a signal still can).
#pragma once
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace aalab::testenv {

/// The folders to remove at exit (a function-local static: destroyed after main returns).
class ScratchRegistry {
 public:
  ~ScratchRegistry() {
    for (const auto& d : dirs_) {
      std::error_code ec;
      std::filesystem::remove_all(d, ec);  // best effort: a test's result does not depend on it
    }
  }
  void Add(const std::filesystem::path& d) {
    if (std::find(dirs_.begin(), dirs_.end(), d) == dirs_.end()) dirs_.push_back(d);
  }
  static ScratchRegistry& Instance() {
    static ScratchRegistry r;
    return r;
  }

 private:
  std::vector<std::filesystem::path> dirs_;
};

/// A fresh, empty folder `<temp>/aalab-<name>-<pid>` (emptied when it exists), removed when
/// the process exits.
inline std::filesystem::path ScratchDir(const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("aalab-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  ScratchRegistry::Instance().Add(d);
  return d;
}

}  // namespace aalab::testenv
