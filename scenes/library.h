/// The built-in scene library (scenes/library/*.json) and suites (scenes/library/suites.json).
#pragma once
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace aalab {

/// Folder of the library: $AALAB_SCENE_DIR when set, else the source tree's scenes/library.
std::string SceneLibraryDir();

/// Names of the library scenes (file stems), sorted.
std::vector<std::string> LibrarySceneNames();

/// Names of the suites, in file order.
std::vector<std::string> SuiteNames();

/// Scene names of a suite. Throws UserError listing the suites for an unknown name.
std::vector<std::string> SuiteScenes(const std::string& suite);

/// Loads a library scene by name, or a user's scene file by path (anything containing '/' or
/// ending in .json). Unknown names list the library scenes.
Scene LoadScene(const std::string& name_or_path);

}  // namespace aalab
