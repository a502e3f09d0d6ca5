/// Image files through OpenImageIO. Writes are atomic: a temporary file beside the target is
/// renamed into place, so a failed write never leaves a half-written result.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "harness/core/image.h"

namespace aalab {

/// An image read from disk.
struct LoadedImage {
  ImageF pixels;          ///< values as stored, converted to float (8-bit k → k/255)
  int file_channels = 0;  ///< channels in the file (1, 2, 3 or 4)
  bool is_float = false;  ///< the file stores half/float data (EXR, float TIFF): scene-linear
  std::string format;     ///< OpenImageIO format name ("png", "openexr", ...)
};

/// Reads a PNG, JPEG, TIFF or EXR image, chosen by the extension (.png, .jpg, .jpeg, .tif,
/// .tiff, .exr; no other reader is tried). Throws UserError naming the path for: another
/// extension, content that does not match it, missing or unreadable file,
/// truncated data, zero size, more than `max_pixels` pixels, unsupported channel count
/// (allowed 1–4; grey is expanded to RGB, the alpha of 2/4-channel images is kept as
/// channel 3), and NaN/Inf pixels (rejected; the message gives the first bad pixel).
LoadedImage ReadImage(const std::string& path, size_t max_pixels = 1ull << 28);

/// Reads an 8-bit display image as RGBA8 (alpha 255 when the file has none). Float files are
/// refused with a message pointing at the float path.
Image8 ReadImage8(const std::string& path);

/// libpng's row filters for a PNG: kAdaptive lets libpng pick per row, kNone stores rows
/// unfiltered (smaller for noise-like images).
enum class PngFilter { kAdaptive, kNone };

/// kNone when more than half of the pixels differ from their left neighbour (noise-like),
/// else kAdaptive. `data` is w×h pixels of nc interleaved 8-bit channels.
PngFilter ChoosePngFilter(const uint8_t* data, int w, int h, int nc);

/// Writes an RGBA8 frame as RGB (PNG/JPEG/TIFF by extension); alpha is dropped unless
/// `keep_alpha`. A PNG's row filter is ChoosePngFilter's (lossless either way). Throws
/// UserError when the path is not writable or the extension unknown.
void WriteImage8(const std::string& path, const Image8& img, bool keep_alpha = false);

/// Text metadata of an image file: (key, value) pairs, e.g. ("Software", "aalab 0.1.0").
using ImageText = std::vector<std::pair<std::string, std::string>>;

/// WriteImage8 (alpha dropped) with text metadata: PNG tEXt chunks, the other formats' string
/// attributes. `aalab export` stamps its figures' provenance this way.
void WriteImage8WithText(const std::string& path, const Image8& img, const ImageText& text);

/// Writes a one-channel 8-bit image (`data`: width×height bytes, row-major), e.g. a metric
/// map quantised to 0..255 for the page to colour. Same errors as WriteImage8.
void WriteGrey8(const std::string& path, int width, int height, const std::vector<uint8_t>& data);

/// Writes a float image (EXR as half-free float32; PNG etc. quantised to 8 bits).
void WriteImageF(const std::string& path, const ImageF& img);

/// Writes text atomically (temporary file + rename). Throws UserError on failure.
void WriteTextFile(const std::string& path, const std::string& text);

}  // namespace aalab
