/// The one checked, atomic file writer. Free of image libraries: the GPU tool (gpu/) builds
/// it too, for its PPM frames.
#pragma once
#include <string>

namespace aalab {

/// Writes `bytes` (text or binary) atomically: to a temporary file beside `path` (a name no
/// other thread, process or host uses), every write and the close checked (ENOSPC, EIO,
/// EFBIG...), then renamed over `path`. On any error the temporary file is removed and
/// UserError names `path` and the OS error. Every file aalab writes goes through here (the
/// image writers encode in memory first, so the image library's errors are checked too).
void WriteTextFile(const std::string& path, const std::string& bytes);

}  // namespace aalab
