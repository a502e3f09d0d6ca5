#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <tbb/version.h>

#include "build_info.h"
#include "core/parallel.h"
#include "harness/run/context.h"
#include "harness/run/runner.h"

namespace aalab {

std::string CpuModel() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "unknown";
}

namespace {

std::string MemoryTotal() {
  std::ifstream f("/proc/meminfo");
  std::string key, unit;
  long long kb = 0;
  while (f >> key >> kb >> unit) {
    if (key == "MemTotal:") {
      std::ostringstream s;
      s.precision(3);
      s << static_cast<double>(kb) / (1024.0 * 1024.0) << " GiB";
      return s.str();
    }
  }
  return "unknown";
}

}  // namespace

std::vector<std::pair<std::string, std::string>> ContextFacts() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  std::vector<std::pair<std::string, std::string>> c;
  c.emplace_back("tool", "aalab");
  c.emplace_back("tool_version", AALAB_VERSION);
  c.emplace_back("git_commit", std::string(AALAB_GIT_COMMIT).empty() ? "unknown" : AALAB_GIT_COMMIT);
  c.emplace_back("build_type", AALAB_BUILD_TYPE);
  c.emplace_back("compiler", AALAB_COMPILER);
  c.emplace_back("float_flags", "-ffp-contract=off -fno-fast-math");
  c.emplace_back("embree_version", AALAB_EMBREE_VERSION);
  c.emplace_back("openimageio_version", AALAB_OIIO_VERSION);
  c.emplace_back("tbb_version", TBB_VERSION_STRING);
  c.emplace_back("nlohmann_json_version", std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." +
                                              std::to_string(NLOHMANN_JSON_VERSION_MINOR) + "." +
                                              std::to_string(NLOHMANN_JSON_VERSION_PATCH));
  c.emplace_back("host", host);
  c.emplace_back("cpu", CpuModel());
  c.emplace_back("hardware_threads", std::to_string(std::thread::hardware_concurrency()));
  c.emplace_back("memory", MemoryTotal());
  c.emplace_back("threads", std::to_string(ThreadCount()));
  return c;
}

}  // namespace aalab
