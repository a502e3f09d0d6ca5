// The files a command has read (core/input_files.h).
#include "core/input_files.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <mutex>
#include <set>

#include "core/error.h"

namespace aalab {
namespace {

std::mutex& Mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

static std::vector<std::string>& Paths() {
  static std::vector<std::string> paths;
  return paths;
}

void NoteInputFile(const std::string& path) {
  static std::set<std::string> seen;
  std::lock_guard<std::mutex> lock(Mutex());
  if (seen.insert(path).second) Paths().push_back(path);
}

std::string WhatIsAt(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    return errno == ENOENT || errno == ENOTDIR ? "does not exist"
                                               : std::string("cannot be examined: ") + std::strerror(errno);
  }
  if (S_ISREG(st.st_mode)) return "";
  if (S_ISDIR(st.st_mode)) return "is a folder";
  if (S_ISFIFO(st.st_mode)) return "is a FIFO (named pipe)";
  if (S_ISCHR(st.st_mode)) return "is a character device";
  if (S_ISBLK(st.st_mode)) return "is a block device";
  if (S_ISSOCK(st.st_mode)) return "is a socket";
  return "is not a regular file";
}

void RequireRegularFile(const std::string& path, const std::string& what, const std::string& expected) {
  if (const std::string kind = WhatIsAt(path); !kind.empty()) {
    throw UserError(what + " '" + path + "' " + kind + " (" + expected + ")");
  }
}

std::vector<std::string> InputFilesRead() {
  std::lock_guard<std::mutex> lock(Mutex());
  return Paths();
}

}  // namespace aalab
