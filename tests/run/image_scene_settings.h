/// The run settings the image-scene tests share: one manifest, `none` and fxaa311-p12, one
/// timed repeat, quiet, into `out`.
#pragma once
#include <filesystem>

#include "harness/run/runner.h"

namespace aalab::testing_util {

inline RunSettings ImageSceneSettings(const std::filesystem::path& manifest, const std::filesystem::path& out) {
  RunSettings s;
  s.scenes = {manifest.string()};
  s.methods = {"none", "fxaa311-p12"};
  s.repeat = 1;
  s.quiet = true;
  s.out_dir = out.string();
  return s;
}

}  // namespace aalab::testing_util
