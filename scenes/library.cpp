#include "scenes/library.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/params.h"
#include "scenes/model_scene.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

nlohmann::ordered_json ReadSuites() {
  const fs::path p = fs::path(SceneLibraryDir()) / "suites.json";
  std::ifstream f(p);
  if (!f) throw UserError("suite file '" + p.string() + "' cannot be read");
  std::stringstream ss;
  ss << f.rdbuf();
  try {
    return nlohmann::ordered_json::parse(ss.str());
  } catch (const nlohmann::json::exception& e) {
    throw UserError("suite file '" + p.string() + "' is not valid JSON: " + e.what());
  }
}

}  // namespace

std::string SceneLibraryDir() {
  if (const char* env = std::getenv("AALAB_SCENE_DIR"); env && *env) return env;
  return AALAB_SCENE_LIBRARY_DIR;
}

std::vector<std::string> LibrarySceneNames() {
  std::vector<std::string> names;
  const fs::path dir(SceneLibraryDir());
  if (!fs::is_directory(dir)) throw UserError("scene library folder '" + dir.string() + "' not found");
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".json" && entry.path().stem() != "suites") {
      names.push_back(entry.path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> SuiteNames() {
  std::vector<std::string> names;
  const auto doc = ReadSuites();
  for (auto it = doc.begin(); it != doc.end(); ++it) names.push_back(it.key());
  return names;
}

std::vector<std::string> SuiteScenes(const std::string& suite) {
  const auto doc = ReadSuites();
  if (!doc.contains(suite)) {
    throw UserError("unknown suite '" + suite + "' (valid: " + JoinNames(SuiteNames()) + ")");
  }
  const auto& entry = doc.at(suite);
  if (entry.is_object() && entry.contains("scenes") && entry.at("scenes") == "all") return LibrarySceneNames();
  if (!entry.is_object() || !entry.contains("scenes") || !entry.at("scenes").is_array()) {
    throw UserError("suite '" + suite + "' in '" + SceneLibraryDir() +
                    "/suites.json' needs \"scenes\": an array of scene names or \"all\"");
  }
  std::vector<std::string> names;
  for (const auto& n : entry.at("scenes")) {
    if (!n.is_string()) {
      throw UserError("suite '" + suite + "' in '" + SceneLibraryDir() +
                      "/suites.json': scene names must be strings, got " + std::string(n.type_name()));
    }
    names.push_back(n.get<std::string>());
  }
  return names;
}

Scene LoadScene(const std::string& name) {
  if (IsModelPath(name)) return LoadModelScene(name);  // a .glb / .gltf given as a scene
  const bool is_path =
      name.find('/') != std::string::npos || (name.size() > 5 && name.substr(name.size() - 5) == ".json");
  if (is_path) return LoadSceneFile(name);
  const auto names = LibrarySceneNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    throw UserError("unknown scene '" + name + "' (library scenes: " + JoinNames(names) +
                    "; or give a path to a scene file)");
  }
  return LoadSceneFile((fs::path(SceneLibraryDir()) / (name + ".json")).string());
}

}  // namespace aalab
