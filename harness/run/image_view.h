/// Reading one view of an image-scene manifest (internal to harness/run/image_scene.cpp):
/// every field of a view, for one frame of its sequence. docs/own-frames.md is the reference.
#pragma once
#include <filesystem>
#include <string>

#include "harness/run/image_scene.h"
#include "scenes/json_fields.h"

namespace aalab {

/// Lower-case extension of a path, with the dot (".exr").
std::string LowerExt(const std::string& path);

/// Reads frame k (0-based) of the view `v` of a manifest whose folder is `base`: the 1x frame,
/// the reference, the edge mask, the supplied outputs and the motion. Throws UserError through
/// `v` (naming the manifest and the JSON path) for anything the format does not allow.
ImageView ParseView(const JsonField& v, const std::filesystem::path& base, const std::string& manifest, int k);

}  // namespace aalab
