// `aalab scene MODEL.glb [--out FILE]`: writes the scene file `aalab run --scenes MODEL.glb`
// uses for a glTF model (scenes/model_scene.h), to edit and run as any scene file.
#include <filesystem>
#include <fstream>
#include <memory>

#include "harness/cli/commands.h"
#include "core/error.h"
#include "scenes/model_scene.h"

namespace aalab {
namespace fs = std::filesystem;

void RegisterSceneCommand(CLI::App& app, Commands& commands) {
  auto* cmd = app.add_subcommand("scene", "write the scene file that 'run --scenes MODEL.glb' uses for a glTF model");
  auto model = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  cmd->add_option("model", *model, "a .glb or .gltf file")->required();
  cmd->add_option("--out", *out,
                  "scene file to write (default: MODEL's name with .json, in the current folder); never overwritten");
  cmd->callback([&commands, model, out] {
    commands.action = [model, out] {
      if (!IsModelPath(*model))
        throw UserError("scene: '" + *model + "' is not a glTF model (allowed: a .glb or .gltf file)");
      if (!fs::is_regular_file(*model)) throw UserError("scene: glTF file '" + *model + "' not found");
      const std::string dest = out->empty() ? fs::path(*model).stem().string() + ".json" : *out;
      if (fs::exists(dest))
        throw UserError("scene: '" + dest + "' exists; aalab does not overwrite it (name another with --out)");
      const std::string text = ModelSceneJson(*model).dump(2) + "\n";
      // Written beside its destination, then renamed: never a half-written scene file.
      const std::string tmp = dest + ".partial";
      {
        std::ofstream f(tmp, std::ios::binary);
        f << text;
        if (!f.flush()) {
          std::error_code ec;
          fs::remove(tmp, ec);
          throw UserError("scene: cannot write '" + dest + "'");
        }
      }
      fs::rename(tmp, dest);
      std::printf("wrote %s\n", dest.c_str());
      return ToInt(ExitCode::kOk);
    };
  });
}

}  // namespace aalab
