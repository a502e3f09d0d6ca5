// Helpers for CLI tests that read and write whole files and drive a running aalab process
// (start it in the background, wait for a path it creates, then signal or wait for it).
#pragma once
#include <fcntl.h>
#include <sys/types.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

namespace aalab::clitest {

/// The whole content of the file at `p` ("" when it cannot be read).
inline std::string Bytes(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

/// Writes `text` to `p`, creating its parent folders.
inline void WriteText(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

/// Starts `aalab ARGS` in the background with SIGINT, SIGTERM and SIGHUP at their defaults,
/// stdout and stderr both to `log`; returns its pid (waitpid it).
inline pid_t SpawnAalab(const std::string& args, const std::filesystem::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) ::signal(sig, SIG_DFL);
    const std::string cmd = "exec " + std::string(AALAB_BINARY_DIR) + "/aalab " + args;
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

/// Waits up to `limit` for `p` to exist; true when it does.
inline bool WaitForPath(const std::filesystem::path& p, std::chrono::milliseconds limit = std::chrono::seconds(30)) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (!std::filesystem::exists(p) && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return std::filesystem::exists(p);
}

}  // namespace aalab::clitest
