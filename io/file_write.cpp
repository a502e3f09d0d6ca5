// The checked atomic writer (io/file_write.h).
#include "io/file_write.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/cleanup.h"
#include "core/error.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

/// A temporary name beside `path` that no other thread, process or host uses.
std::string TempPathFor(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  char host[64] = {0};
  ::gethostname(host, sizeof host - 1);
  const fs::path p(path);
  return (p.parent_path() / (".tmp-" + p.stem().string() + "." + host + "." + std::to_string(::getpid()) + "." +
                             std::to_string(counter++) + p.extension().string()))
      .string();
}

[[noreturn]] void Fail(const std::string& path, const std::string& why) {
  throw UserError("cannot write '" + path + "': " + why);
}

}  // namespace

void WriteTextFile(const std::string& path, const std::string& bytes) {
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent)) {
    Fail(path, "directory '" + parent.string() + "' does not exist");
  }
  const std::string tmp = TempPathFor(path);
  TrackUnfinished(tmp);  // an interruption removes it
  auto fail = [&](int err, const std::string& what) {
    ::unlink(tmp.c_str());
    UntrackUnfinished(tmp);
    Fail(path, what + std::strerror(err));
  };
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    UntrackUnfinished(tmp);
    Fail(path, "cannot create a file there: " + std::string(std::strerror(err)));
  }
  for (size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : EIO;
      ::close(fd);
      fail(err, "");
    }
    done += static_cast<size_t>(n);
  }
  // close() reports what a file system defers (NFS, quota): checked like every write.
  if (::close(fd) != 0) fail(errno, "");
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail(errno, "");
  UntrackUnfinished(tmp);
}

}  // namespace aalab
