// The output folder rule (harness/run/out_folder.h).
#include "harness/run/out_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/cleanup.h"
#include "core/error.h"
#include "io/image_io.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

constexpr const char* kLockFile = ".aalab-lock";

std::string Q(const fs::path& p) {
  std::string q = "'";  // (not "'" + ...: GCC 12 warns a false -Wrestrict on that)
  q += p.string();
  q += "'";
  return q;
}

/// The first line of the marker, then "kind KIND", then one relative file path per line.
std::string MarkerHeader() { return "aalab output folder 1"; }

/// Relative paths of every file (and symlink) under `dir`, folders left out.
std::set<std::string> FilesUnder(const fs::path& dir) {
  std::set<std::string> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_directory(ec) && !it->is_symlink(ec)) continue;
    files.insert(fs::relative(it->path(), dir, ec).generic_string());
  }
  if (ec) throw UserError("cannot list the folder " + Q(dir) + ": " + ec.message());
  return files;
}

/// Collects every string of a JSON document that names a file under images/.
void ImagePathsIn(const nlohmann::json& j, std::set<std::string>* out) {
  if (j.is_object() || j.is_array()) {
    for (const auto& v : j) ImagePathsIn(v, out);
  } else if (j.is_string()) {
    const auto& s = j.get_ref<const std::string&>();
    if (s.rfind("images/", 0) == 0) out->insert(s);
  }
}

/// A run folder written by an aalab build from before the marker: report.json is an aalab
/// report and every file in the folder is report.json, index.html or an image the report
/// names. Anything else (a user's file anywhere in it) and it is not recognised.
bool IsLegacyRunFolder(const fs::path& dir, const std::set<std::string>& files) {
  if (!files.count("report.json") || !fs::is_regular_file(dir / "report.json")) return false;
  std::ifstream f(dir / "report.json");
  const nlohmann::json j = nlohmann::json::parse(f, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("schema_version") || !j.contains("rows")) return false;
  std::set<std::string> named = {"report.json", "index.html"};
  ImagePathsIn(j, &named);
  return std::all_of(files.begin(), files.end(), [&](const std::string& file) { return named.count(file) > 0; });
}

/// A `history report` folder of a build from before the marker: only index.html, which is
/// aalab's history page.
bool IsLegacyHistoryFolder(const fs::path& dir, const std::set<std::string>& files) {
  if (files != std::set<std::string>{"index.html"} || !fs::is_regular_file(dir / "index.html")) return false;
  std::ifstream f(dir / "index.html", std::ios::binary);
  std::string head(8192, '\0');
  f.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(f.gcount()));
  return head.find("<h1>aalab history</h1>") != std::string::npos;
}

/// "" when `dir` (an existing folder) may be replaced by an output of `kind`, else why not.
std::string WhyNotReplaceable(const fs::path& dir, const std::string& kind) {
  const std::set<std::string> files = FilesUnder(dir);
  if (files.empty()) return "";
  const fs::path marker = dir / kOutputMarker;
  std::ifstream f(marker);
  std::string header, kind_line;
  if (!fs::exists(marker) && kind == "run" && IsLegacyRunFolder(dir, files)) return "";
  if (!fs::exists(marker) && kind == "history" && IsLegacyHistoryFolder(dir, files)) return "";
  if (!f || !std::getline(f, header) || header != MarkerHeader() || !std::getline(f, kind_line)) {
    return "it is not empty and was not written by aalab (it has no " + std::string(kOutputMarker) +
           ", the list of files aalab wrote, and is not a run folder of an older aalab build holding only its report, "
           "page and the images the report names)";
  }
  if (kind_line != "kind " + kind) {
    return "it holds an aalab output of another kind (" + kind_line.substr(std::min<size_t>(5, kind_line.size())) +
           ", this command writes a " + kind + " output)";
  }
  std::set<std::string> listed;
  for (std::string line; std::getline(f, line);) listed.insert(line);
  for (const auto& file : files) {
    // (.aalab-lock is not exempt: aalab removes its lock at commit, so one in a finished
    // folder is a user's file and is never deleted silently.)
    if (file != kOutputMarker && !listed.count(file)) {
      return "it holds '" + file + "', which aalab did not write (aalab replaces the whole folder: move the file out)";
    }
  }
  return "";
}

/// Undoes /proc/self/mountinfo's octal escapes ("\040" for a space).
std::string Unescape(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\' && i + 3 < s.size()) {
      const std::string oct = s.substr(i + 1, 3);
      if (oct.size() == 3 && oct.find_first_not_of("01234567") == std::string::npos) {
        out += static_cast<char>(std::stoi(oct, nullptr, 8));
        i += 3;
        continue;
      }
    }
    out += s[i];
  }
  return out;
}

/// Whether `dir` (normalised, symlinks resolved) is a mount point: listed in
/// /proc/self/mountinfo (a bind mount of a folder of the same file system included), or on
/// another device than its parent. Such a folder cannot be renamed (EBUSY) nor be the target
/// of a rename from its parent's file system (EXDEV).
bool IsMountPoint(const fs::path& dir) {
  struct stat a {
  }, b{};
  if (::stat(dir.c_str(), &a) == 0 && ::stat(dir.parent_path().c_str(), &b) == 0 && a.st_dev != b.st_dev) return true;
  std::ifstream f("/proc/self/mountinfo");
  for (std::string line; std::getline(f, line);) {
    std::istringstream ss(line);
    std::string id, parent, devno, root, mount_point;
    if (ss >> id >> parent >> devno >> root >> mount_point && Unescape(mount_point) == dir.string()) return true;
  }
  return false;
}

bool Contains(const fs::path& outer, const fs::path& inner) {
  auto o = outer.begin(), i = inner.begin();
  for (; o != outer.end(); ++o, ++i) {
    if (i == inner.end() || *o != *i) return false;
  }
  return true;
}

}  // namespace

fs::path NormaliseOutPath(const std::string& dir, const std::string& option) {
  if (dir.empty()) throw UserError(option + " must not be empty");
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(dir), ec);
  if (ec) throw UserError(option + " '" + dir + "': " + ec.message());
  p = p.lexically_normal();
  while (!p.has_filename() && p.has_relative_path()) p = p.parent_path();  // "dir/" -> "dir"
  if (!p.has_relative_path()) throw UserError(option + " '" + dir + "' is the root folder; give a folder of its own");
  return p;
}

OutFolder::OutFolder(const std::string& dir, const std::string& kind, const std::vector<std::string>& inputs)
    : kind_(kind) {
  dir_ = NormaliseOutPath(dir);
  partial_ = dir_.string() + ".partial";
  const std::string shown = dir == dir_.string() ? Q(dir) : Q(dir) + " (" + dir_.string() + ")";
  for (const auto& in : inputs) {
    std::error_code ec;
    if (in.empty()) continue;
    const fs::path p = fs::weakly_canonical(fs::absolute(in), ec);
    if (ec) continue;
    if (p == dir_ || Contains(dir_, p) || p == partial_ || Contains(partial_, p)) {
      throw UserError("--out " + shown + (p == dir_ ? " is" : " contains") + " the input '" + in +
                      "'; the output folder is replaced as a whole, so it must not hold anything the command reads: "
                      "choose an --out outside the inputs");
    }
  }
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir_, ec))) {
    if (!fs::is_directory(dir_, ec)) throw UserError("--out " + shown + " exists and is not a folder");
    // The finished output replaces DIR by a rename, which a mount point refuses: said now,
    // before the work, not after it (no work lost).
    if (IsMountPoint(dir_)) {
      throw UserError("--out " + shown +
                      " is a mount point (a bind mount or another file system): aalab builds the output beside it "
                      "in DIR.partial and renames it into place at the end, which a mount point refuses. Give a "
                      "folder inside it instead (e.g. --out " +
                      (dir_ / "results").string() + ")");
    }
    if (const std::string why = WhyNotReplaceable(dir_, kind); !why.empty()) {
      throw UserError("--out " + shown + " cannot be replaced: " + why +
                      ". Choose another --out (or empty the folder yourself)");
    }
  }
  if (!fs::is_directory(dir_.parent_path(), ec)) {
    throw UserError("--out " + shown + ": the folder '" + dir_.parent_path().string() + "' does not exist");
  }
  // DIR.partial is the lock: created atomically, with a locked file in it.
  for (int attempt = 0; attempt < 3; ++attempt) {
    if (::mkdir(partial_.c_str(), 0755) == 0) {
      TrackUnfinished(partial_.string());
      const std::string lock = (partial_ / kLockFile).string();
      lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
      if (lock_fd_ < 0 || ::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
        // Another command removed a stale DIR.partial and made its own in between: it wins.
        const int err = errno;
        if (lock_fd_ >= 0) ::close(lock_fd_), lock_fd_ = -1;
        UntrackUnfinished(partial_.string());
        throw UserError("--out " + shown + ": cannot lock '" + lock + "': " + std::strerror(err));
      }
      const std::string pid = std::to_string(::getpid()) + "\n";
      if (::write(lock_fd_, pid.data(), pid.size()) < 0) {
        // Only informative (which process holds the folder); the lock is the flock.
      }
      return;
    }
    const int err = errno;
    if (err != EEXIST) {
      throw UserError("--out " + shown + ": cannot create '" + partial_.string() + "': " + std::strerror(err));
    }
    // A DIR.partial exists: another command's (locked), a killed one's (ours, lock free) or
    // the user's (no lock file): only the second is removed.
    const std::string lock = (partial_ / kLockFile).string();
    const int fd = ::open(lock.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) {
      throw UserError("--out " + shown + ": '" + partial_.string() + "' exists and was not made by aalab (no " +
                      kLockFile + " in it); move it away or choose another --out");
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      std::ifstream f(lock);
      std::string pid;
      std::getline(f, pid);
      ::close(fd);
      throw UserError("--out " + shown + " is being written by another aalab command right now (process " +
                      (pid.empty() ? "?" : pid) + ", holding '" + partial_.string() +
                      "'); wait for it to finish or choose another --out");
    }
    fs::remove_all(partial_, ec);  // a killed command's leftover; we hold its lock meanwhile
    ::close(fd);
    if (ec)
      throw UserError("--out " + shown + ": cannot remove the leftover '" + partial_.string() + "': " + ec.message());
  }
  throw UserError("--out " + shown + ": another command keeps creating '" + partial_.string() + "'");
}

void OutFolder::KeepPartial() {
  // Finished work that could not be put in place is kept: no longer tracked for clean-up, and
  // without its lock file, so a later command refuses (never removes) it as not aalab's.
  committed_ = true;
  UntrackUnfinished(partial_.string());
  ::unlink((partial_ / kLockFile).c_str());
}

OutFolder::~OutFolder() {
  std::error_code ec;
  if (!committed_) {
    auto lock = LockUnfinished();
    fs::remove_all(partial_, ec);
    UntrackUnfinished(partial_.string());
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

void OutFolder::Commit() {
  // The list of what aalab wrote: checked before this folder is ever replaced.
  std::set<std::string> files = FilesUnder(partial_);
  files.erase(kLockFile);
  std::string marker = MarkerHeader() + "\nkind " + kind_ + "\n";
  for (const auto& f : files) marker += f + "\n";
  WriteTextFile((partial_ / kOutputMarker).string(), marker);
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir_, ec))) {
    // Files may have appeared during a long run: checked again just before the replacement.
    if (const std::string why = WhyNotReplaceable(dir_, kind_); !why.empty()) {
      KeepPartial();
      throw UserError("--out '" + dir_.string() + "' cannot be replaced: " + why +
                      ". The finished output is kept in '" + partial_.string() + "': move it where you want it");
    }
  }
  auto lock = LockUnfinished();  // an interruption waits until the renames are done
  const fs::path old = dir_.string() + ".old-" + std::to_string(::getpid());
  const bool had_old = fs::exists(fs::symlink_status(dir_, ec));
  if (had_old && ::rename(dir_.c_str(), old.c_str()) != 0) {
    const int err = errno;
    KeepPartial();
    throw UserError("cannot replace '" + dir_.string() + "': " + std::strerror(err) +
                    ". The finished output is kept in '" + partial_.string() + "': move it where you want it");
  }
  if (::rename(partial_.c_str(), dir_.c_str()) != 0) {
    const int err = errno;
    if (had_old) ::rename(old.c_str(), dir_.c_str());
    KeepPartial();
    throw UserError("cannot move '" + partial_.string() + "' to '" + dir_.string() + "': " + std::strerror(err) +
                    ". The finished output is kept in '" + partial_.string() + "': move it where you want it");
  }
  committed_ = true;
  UntrackUnfinished(partial_.string());
  ::unlink((dir_ / kLockFile).c_str());
  if (had_old) {
    TrackUnfinished(old.string());
    fs::remove_all(old, ec);
    UntrackUnfinished(old.string());
  }
}

std::string CheckOutFile(const std::string& path, const std::vector<std::string>& inputs) {
  const fs::path out = NormaliseOutPath(path, "output");
  std::error_code ec;
  if (fs::is_directory(out, ec)) throw UserError("output '" + path + "' is a folder; give a file name");
  for (const auto& in : inputs) {
    if (fs::exists(in, ec) && fs::weakly_canonical(fs::absolute(in), ec) == out) {
      throw UserError("output '" + path + "' is the input '" + in + "'; write the result to another file");
    }
  }
  return out.string();
}

std::string SpecFileName(const std::string& spec) {
  std::string s = spec;
  for (char& c : s) {
    if (c == ':' || c == ',') c = '_';
    if (c == '=') c = '-';
  }
  return s;
}

}  // namespace aalab
