// Helpers shared by the scene tests.
#pragma once
#include <string>

#include "core/error.h"
#include "scenes/scene.h"

namespace aalab::testing {

/// Parses scene JSON text (origin "test.json", base dir = the library folder).
inline Scene ParseText(const std::string& json) {
  return ParseScene(json, "test.json", AALAB_SOURCE_DIR "/scenes/library");
}

/// The UserError message of parsing `json`, or "" when it parses.
inline std::string ParseError(const std::string& json) {
  try {
    ParseText(json);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

/// A minimal valid scene with `effects`, `materials` and `objects` (and optional lights) spliced in.
inline std::string MakeScene(const std::string& effects, const std::string& materials, const std::string& objects,
                             const std::string& extra = "") {
  return R"({"name": "t", "effects": )" + effects +
         R"(, "camera": {"type": "orthographic", "position": [0,0,10], "look_at": [0,0,0], "height": 4},)"
         R"( "materials": )" +
         materials + R"(, "objects": )" + objects + extra + "}";
}

}  // namespace aalab::testing
