/// Image files through OpenImageIO. Writes are atomic: a temporary file beside the target is
/// renamed into place, so a failed write never leaves a half-written result.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "harness/core/image.h"

namespace aalab {

/// Images larger than this many pixels are refused unless a caller passes its own limit
/// (2^28 = 268 million, e.g. 16384x16384; a 4-channel float image of that size is 4 GiB).
inline constexpr size_t kMaxImagePixels = size_t{1} << 28;

/// An image read from disk.
struct LoadedImage {
  ImageF pixels;          ///< values as stored, converted to float (8-bit k → k/255)
  int file_channels = 0;  ///< channels read: 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA
  bool is_float = false;  ///< the channels read store half/float data (EXR, float TIFF): scene-linear
  std::string format;     ///< OpenImageIO format name ("png", "openexr", ...)
};

/// Channel names of an image in file order. Single-part files: OIIO's channel names
/// (e.g. "R","G","B","A","Z" or Blender's "ViewLayer.Combined.R"). Multi-part EXR: every part's
/// channels, each prefixed "PART." with the part's name unless it already starts with it.
/// Throws UserError naming the path (missing, not a regular file, unknown format...).
std::vector<std::string> ListImageChannels(const std::string& path);

/// Reads exactly the channels `names` (exact names as ListImageChannels gives them, in that order)
/// into a float image with names.size() channels. Values as stored (8-bit k -> k/255, 16-bit k -> k/65535,
/// half/float as is); alpha is NEVER multiplied into colour. A name the file lacks -> UserError that
/// lists the channels the file has. Non-finite values: refused with the first bad pixel unless
/// `allow_inf` (then +Inf/-Inf are kept, NaN still refused), used for depth where a background
/// overflowed to +Inf. Only regular files are opened; the declared size is checked against `max_pixels`
/// and against the file's size before any large allocation.
ImageF ReadImageChannels(const std::string& path, const std::vector<std::string>& names,
                         size_t max_pixels = kMaxImagePixels, bool allow_inf = false);

/// Reads a PNG, JPEG, TIFF or EXR image, chosen by the extension (.png, .jpg, .jpeg, .tif,
/// .tiff, .exr; no other reader is tried), through ReadImageChannels: colour is the channels
/// named R, G, B (exact case first, else any case), alpha the channel named A when there is
/// one (channel 3, as stored: never multiplied into colour); other channels (Z, ids, AOVs) are
/// ignored. A 1-channel file, or one with a grey channel Y (and optionally A), is expanded to
/// RGB(A). Throws UserError naming the path for: another extension, content that does not
/// match it, a missing file or one that is not a regular file (FIFO, device), truncated data,
/// zero size, more than `max_pixels` pixels or more than the file's size can hold, no R, G, B
/// (the message lists the channels the file has), and NaN/Inf pixels in the channels read
/// (rejected; the message gives the first bad pixel).
LoadedImage ReadImage(const std::string& path, size_t max_pixels = kMaxImagePixels);

/// Reads an 8-bit display image as RGBA8 (alpha as stored, 255 when the file has none). Float
/// files are refused with a message pointing at the float path.
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

/// Writes a one-channel 8-bit image (`data`: width×height bytes, row-major), e.g. a metric
/// map quantised to 0..255 for the page to colour. Same errors as WriteImage8.
void WriteGrey8(const std::string& path, int width, int height, const std::vector<uint8_t>& data);

/// Writes a float image (EXR as half-free float32; PNG etc. quantised to 8 bits).
void WriteImageF(const std::string& path, const ImageF& img);

/// Writes text atomically (temporary file + rename). Throws UserError on failure.
void WriteTextFile(const std::string& path, const std::string& text);

}  // namespace aalab
