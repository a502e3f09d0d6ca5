/// Binary PPM (P6, maxval 255) frames: the exchange format between `aalab export-frames`
/// and the GPU tool, which must not depend on image libraries. RGB on disk, RGBA8 in memory
/// (alpha 255 on reading, dropped on writing).
#pragma once
#include <string>

#include "harness/core/image.h"

namespace aalab {

/// Reads a P6 file with maxval 255 (comments after the magic allowed) into an RGBA8 frame.
/// Throws UserError naming the path for a missing file, another format, a bad header or
/// truncated pixel data.
Image8 ReadPpm(const std::string& path);

/// Writes rgb of an RGBA8 frame as P6. Written to `path`.tmp and renamed, so a failed write
/// leaves no partial file. Throws UserError when the path is not writable.
void WritePpm(const std::string& path, const Image8& img);

}  // namespace aalab
