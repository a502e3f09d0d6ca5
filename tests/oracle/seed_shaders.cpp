#include "tests/oracle/seed_shaders.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace aalab::oracle {

namespace fs = std::filesystem;

std::string SeedsDir() {
  if (const char* env = std::getenv("AALAB_SEEDS_DIR"); env && *env) return env;
  return std::string(AALAB_SOURCE_DIR) + "/../shared/seeds";
}

bool SeedsPresent() {
  std::error_code ec;
  return fs::is_directory(SeedsDir(), ec);
}

namespace {

std::vector<std::pair<std::string, std::string>> SeedTexts() {
  std::vector<std::pair<std::string, std::string>> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(SeedsDir(), ec)) {
    if (!e.is_regular_file() || e.path().extension() != ".txt") continue;
    std::ifstream in(e.path(), std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    out.emplace_back(e.path().string(), ss.str());
  }
  return out;
}

// The text between the line holding `begin` (exclusive) and the next line holding `end`
// (exclusive), from the first seed file that has both and every `must` string inside.
std::string Between(const std::string& begin, const std::string& end, const std::vector<std::string>& must,
                    const std::string& what) {
  for (const auto& [path, text] : SeedTexts()) {
    const size_t b = text.find(begin);
    if (b == std::string::npos) continue;
    const size_t start = text.find('\n', b);
    const size_t stop = start == std::string::npos ? start : text.find(end, start);
    if (stop == std::string::npos) continue;
    std::string body = text.substr(start + 1, stop - start - 1);
    bool ok = true;
    for (const auto& m : must) ok = ok && body.find(m) != std::string::npos;
    if (ok) return body;
  }
  throw std::runtime_error("no seed file in " + SeedsDir() + " holds " + what + " (looked for a line '" + begin +
                           "' followed by '" + end + "')");
}

}  // namespace

std::string Fxaa311InteractiveShader() {
  return Between("WebGL Fragment Shader FXAA-interactive.fs", "WebGL Javascript FXAA-interactive.js",
                 {"vec4 FxaaPixelShader(", "#if (FXAA_QUALITY_PRESET == 39)", "void main(", "uniform vec2 RcpFrame;",
                  "varying vec2 uv;"},
                 "the FXAA 3.11 shader FXAA-interactive.fs (seed 004)");
}

std::string Iter12Shader() {
  // From "#version 430 core" through main's closing brace (the line after "void main(){").
  for (const auto& [path, text] : SeedTexts()) {
    const size_t b = text.find("#version 430 core");
    const size_t m = b == std::string::npos ? b : text.find("void main(){", b);
    if (m == std::string::npos) continue;
    const size_t close = text.find('}', m);
    if (close == std::string::npos) continue;
    std::string body = text.substr(b, close + 1 - b);
    if (body.find("#define ITERATIONS 12") != std::string::npos && body.find("vec3 fxaa()") != std::string::npos) {
      return body + "\n";
    }
  }
  throw std::runtime_error("no seed file in " + SeedsDir() +
                           " holds the 12-iteration GLSL FXAA of seed 003 (looked for '#version 430 "
                           "core' ... '#define ITERATIONS 12' ... 'vec3 fxaa()' ... 'void main(){')");
}

}  // namespace aalab::oracle
