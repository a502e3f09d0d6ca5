/// What an image file stores (size, channels, sample type and bit depth), for inputs whose
/// format matters (an image scene's 8-bit frame, 16-bit reference, integer object ids), and
/// 16-bit integer writes.
#pragma once
#include <string>

#include "core/image.h"

namespace aalab {

/// The stored format of an image file.
struct ImageFileInfo {
  int width = 0, height = 0;
  int channels = 0;
  int bits = 0;           ///< bits per sample as stored (8, 16, 32; 16 or 32 for half/float)
  bool is_float = false;  ///< half, float or double samples
  std::string format;     ///< OpenImageIO format name ("png", "tiff", "openexr")

  /// "8-bit integer", "16-bit integer", "16-bit float", "32-bit float", ...
  std::string Describe() const;
};

/// Reads the header of an image file. Call it on a file ReadImage (image_io.h) has already
/// read successfully: this does not repeat ReadImage's checks against malformed files.
/// Throws UserError naming the path when the file cannot be opened.
ImageFileInfo ProbeImage(const std::string& path);

/// Writes the first `channels` channels (1..4) of `img` as 16-bit integers (PNG or TIFF by
/// extension): value v in [0, 1] (clamped) becomes round(v · 65535). Atomic like WriteImage8;
/// UserError when the path is not writable or the extension is not .png/.tif/.tiff.
void WriteImage16(const std::string& path, const ImageF& img, int channels);

}  // namespace aalab
