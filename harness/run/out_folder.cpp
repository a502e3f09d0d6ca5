// The output folder guard (harness/run/out_folder.h).
#include "harness/run/out_folder.h"

#include "harness/core/error.h"

namespace aalab {
namespace fs = std::filesystem;

OutFolder::OutFolder(const std::string& dir, const std::string& marker) : dir_(dir), partial_(dir + ".partial") {
  if (dir.empty()) throw UserError("--out must not be empty");
  if (fs::exists(dir_)) {
    if (!fs::is_directory(dir_)) throw UserError("--out '" + dir + "' exists and is not a folder");
    if (!fs::is_empty(dir_) && !fs::exists(dir_ / marker)) {
      throw UserError("--out '" + dir + "' is a non-empty folder without a " + marker + "; refusing to replace it");
    }
  }
}

OutFolder::~OutFolder() {
  std::error_code ec;
  if (begun_ && !committed_) fs::remove_all(partial_, ec);
}

const fs::path& OutFolder::Begin() {
  fs::remove_all(partial_);
  fs::create_directories(partial_);
  begun_ = true;
  return partial_;
}

void OutFolder::Commit() {
  fs::remove_all(dir_);
  fs::rename(partial_, dir_);
  committed_ = true;
}

}  // namespace aalab
