// Unfinished paths (core/cleanup.h).
#include "core/cleanup.h"

#include <chrono>
#include <filesystem>
#include <set>
#include <thread>

namespace aalab {
namespace {

std::recursive_mutex& Mutex() {
  static std::recursive_mutex m;
  return m;
}

std::set<std::string>& Paths() {
  static std::set<std::string> paths;
  return paths;
}

}  // namespace

void TrackUnfinished(const std::string& path) {
  std::lock_guard<std::recursive_mutex> lock(Mutex());
  Paths().insert(path);
}

void UntrackUnfinished(const std::string& path) {
  std::lock_guard<std::recursive_mutex> lock(Mutex());
  Paths().erase(path);
}

std::unique_lock<std::recursive_mutex> LockUnfinished() { return std::unique_lock<std::recursive_mutex>(Mutex()); }

int RemoveUnfinishedForExit() {
  Mutex().lock();  // never unlocked: the process exits next
  int removed = 0;
  for (const auto& p : Paths()) {
    // Worker threads may still be creating files inside a folder being removed: retry.
    for (int attempt = 0; attempt < 20; ++attempt) {
      std::error_code ec;
      std::filesystem::remove_all(p, ec);
      if (!ec && !std::filesystem::exists(std::filesystem::symlink_status(p))) {
        ++removed;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  return removed;
}

}  // namespace aalab
