// The layer rule of docs/design.md ("The layers"), read from the code: every `#include "..."`
// between the project's folders points down, and only io includes OpenImageIO.
//
// Layers, bottom to top (a folder may include its own layer and any lower one; folders of one
// layer may not include each other):
//   0 core   1 io   2 scenes, methods (with methods/cuda), metrics
//   3 reports (reads the metric registry)   4 harness/run   5 harness/cli, gpu (programs)
// bench/ and tests/ stand outside the rule (they may include anything).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace aalab {
namespace {
namespace fs = std::filesystem;

struct Layer {
  const char* prefix;  ///< path prefix, with the trailing '/'
  int rank;
};

// Longest prefix first, so core/ wins over a plain harness/.
const std::vector<Layer> kLayers = {
    {"core/", 0},    {"io/", 1},          {"scenes/", 2},      {"methods/", 2}, {"metrics/", 2},
    {"reports/", 3}, {"harness/run/", 4}, {"harness/cli/", 5}, {"gpu/", 5},
};

/// The layer a repository path belongs to, or nothing (bench/, tests/, third-party headers).
std::optional<Layer> LayerOf(const std::string& path) {
  for (const auto& l : kLayers) {
    if (path.rfind(l.prefix, 0) == 0) return l;
  }
  return std::nullopt;
}

struct Include {
  std::string file;  ///< repository path of the including file
  int line = 0;
  std::string target;  ///< the quoted include, as written
};

/// Every include arrow that breaks the rule, as "file:line includes target (layer a -> b)".
std::vector<std::string> Violations(const std::vector<Include>& includes) {
  std::vector<std::string> out;
  for (const auto& inc : includes) {
    const auto from = LayerOf(inc.file), to = LayerOf(inc.target);
    if (!from || !to || std::string(from->prefix) == to->prefix) continue;
    if (to->rank < from->rank) continue;
    out.push_back(inc.file + ":" + std::to_string(inc.line) + " includes " + inc.target + " (" + from->prefix +
                  " is layer " + std::to_string(from->rank) + ", " + to->prefix + " layer " + std::to_string(to->rank) +
                  (to->rank == from->rank ? ": siblings" : ": upward") + ")");
  }
  return out;
}

bool IsSource(const fs::path& p) {
  static const std::set<std::string> kExt = {".h", ".hpp", ".cpp", ".cu", ".cuh", ".inl"};
  return kExt.count(p.extension().string()) > 0;
}

/// Every project include of every source file under the layered folders.
std::vector<Include> ReadIncludes(const fs::path& root, std::vector<std::string>* oiio_users) {
  static const std::regex kQuoted(R"re(^\s*#\s*include\s+"([^"]+)")re");
  static const std::regex kOiio(R"re(^\s*#\s*include\s+<OpenImageIO/)re");
  std::vector<Include> out;
  for (const char* top : {"core", "io", "harness", "scenes", "methods", "metrics", "reports", "gpu"}) {
    for (const auto& e : fs::recursive_directory_iterator(root / top)) {
      if (!e.is_regular_file() || !IsSource(e.path())) continue;
      const std::string rel = fs::relative(e.path(), root).generic_string();
      std::ifstream in(e.path());
      std::string text;
      int n = 0;
      bool oiio = false;
      while (std::getline(in, text)) {
        ++n;
        std::smatch m;
        if (std::regex_search(text, m, kQuoted)) out.push_back({rel, n, m[1].str()});
        oiio = oiio || std::regex_search(text, kOiio);
      }
      if (oiio) oiio_users->push_back(rel);
    }
  }
  std::sort(oiio_users->begin(), oiio_users->end());
  return out;
}

TEST(Layers, TheCheckSeesAnUpwardAndASidewaysArrow) {
  // A planted upward include (core reading run) and a sideways one (scenes reading methods) are
  // found; downward ones, same-folder ones and files outside the layers (tests/) are not.
  const std::vector<Include> planted = {
      {"core/image.h", 3, "harness/run/runner.h"},          // upward
      {"scenes/tracer.cpp", 9, "methods/registry.h"},       // siblings
      {"harness/run/runner.cpp", 4, "core/image.h"},        // down: fine
      {"reports/verdict.cpp", 5, "metrics/registry.h"},     // down: fine
      {"methods/fxaa.cpp", 2, "methods/fxaa.h"},            // same folder: fine
      {"tests/cli/cli_util.h", 7, "harness/cli/main.cpp"},  // outside the rule
  };
  const auto v = Violations(planted);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0], "core/image.h:3 includes harness/run/runner.h (core/ is layer 0, harness/run/ layer 4: upward)");
  EXPECT_EQ(v[1], "scenes/tracer.cpp:9 includes methods/registry.h (scenes/ is layer 2, methods/ layer 2: siblings)");
}

TEST(Layers, EveryIncludeBetweenFoldersPointsDown) {
  std::vector<std::string> oiio;
  const auto includes = ReadIncludes(AALAB_SOURCE_DIR, &oiio);
  ASSERT_GT(includes.size(), 500u);  // the walk found the tree
  const auto v = Violations(includes);
  std::string all;
  for (const auto& s : v) all += "\n  " + s;
  EXPECT_TRUE(v.empty()) << v.size() << " include(s) break the layer rule of docs/design.md:" << all;
}

TEST(Layers, OnlyIoIncludesOpenImageIo) {
  std::vector<std::string> oiio;
  ReadIncludes(AALAB_SOURCE_DIR, &oiio);
  // Every image aalab decodes goes through io's reader (textures and environment maps
  // included, issue #35): no file outside io includes OpenImageIO.
  ASSERT_FALSE(oiio.empty());  // the walk sees io's own users
  std::vector<std::string> outside;
  for (const auto& f : oiio) {
    if (f.rfind("io/", 0) != 0) outside.push_back(f);
  }
  EXPECT_EQ(outside, std::vector<std::string>{}) << "only io/ may include OpenImageIO";
}

}  // namespace
}  // namespace aalab
