#include "tests/oracle/third_party_sources.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace aalab::oracle {

std::string ThirdPartyDir() {
  if (const char* env = std::getenv("AALAB_THIRD_PARTY_DIR"); env && *env) return env;
  return std::string(AALAB_SOURCE_DIR) + "/../shared/third_party";
}

bool ThirdPartyHas(const std::string& relative) {
  std::error_code ec;
  return std::filesystem::is_regular_file(ThirdPartyDir() + "/" + relative, ec);
}

std::string ReadThirdParty(const std::string& relative) {
  const std::string path = ThirdPartyDir() + "/" + relative;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the original source " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace aalab::oracle
