/// The standard output of a shell command, for the bench's outside tools (git, scikit-image,
/// NVIDIA's FLIP tool). Header-only so that the stand-alone bench targets share it without
/// linking bench_common (which needs Google Benchmark).
#pragma once
#include <cstdio>
#include <string>

namespace aalab::bench {

/// Runs `cmd` through popen and returns what it printed on stdout ("" when it cannot start).
inline std::string RunCapture(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

}  // namespace aalab::bench
