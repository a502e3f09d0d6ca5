/// Image files. Reads: one reader (image_read.cpp). PNG is read and written through libpng and
/// float EXR written through OpenEXR (the bytes and values OpenImageIO 2.4 gave); every other
/// format through OpenImageIO, in a module loaded on first use (io/oiio_loader.h; a missing
/// module is a UserError naming the file and its format). Writes are atomic and checked: a
/// temporary file beside the target is renamed into place, so a failed write never leaves a
/// half-written result and always says so.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "io/file_write.h"  // WriteTextFile

namespace aalab {

/// Images larger than this many pixels are refused unless a caller passes its own limit
/// (2^28 = 268 million, e.g. 16384x16384; a 4-channel float image of that size is 4 GiB).
inline constexpr size_t kMaxImagePixels = size_t{1} << 28;

/// The decode budget: the pixels one command (one process) decodes through the reader, summed
/// over every image it reads (frames, captures, references, masks, textures, environment
/// maps), may not pass this many. It bounds what a hostile set of small valid files (a
/// 216 KB PNG may hold 8192x8192 pixels) can make a run decode and hold. Default 2^32 pixels
/// (4295 megapixels: e.g. 2,000 frames of 1920x1080 with 4 images each, 4 GiB of 8-bit RGBA,
/// 64 GiB at 4-channel float); the environment variable AALAB_DECODE_BUDGET_MP=N sets N
/// megapixels (0 = no budget). Past the budget: UserError naming the image, the total and the
/// variable. Docs: docs/cli.md, "Bounded inputs".
inline constexpr size_t kDefaultDecodeBudgetPixels = size_t{1} << 32;
inline constexpr const char* kDecodeBudgetVariable = "AALAB_DECODE_BUDGET_MP";
/// The budget in pixels (0 = none), read once from AALAB_DECODE_BUDGET_MP (UserError when it
/// is not a whole number).
size_t DecodeBudgetPixels();
/// Pixels decoded so far by this process.
size_t DecodedPixels();
/// Charges `pixels` to the budget now, for a loader that decodes several images in parallel
/// and wants the same refusal at any thread count: it charges each image in its own order
/// first, then reads with ReadTexturePixels(src, max, true). UserError naming `name` past it.
void ChargeDecodeBudget(size_t pixels, const std::string& name);

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

/// Reads a PNG, JPEG, TIFF, EXR or Radiance HDR image, chosen by the extension (.png, .jpg,
/// .jpeg, .tif, .tiff, .exr, .hdr; no other reader is tried), through ReadImageChannels: colour is the channels
/// named R, G, B (exact case first, else any case), alpha the channel named A when there is
/// one (channel 3, as stored: never multiplied into colour); other channels (Z, ids, AOVs) are
/// ignored. A 1-channel file, or one with a grey channel Y (and optionally A), is expanded to
/// RGB(A). Throws UserError naming the path for: another extension, content that does not
/// match it, a missing file or one that is not a regular file (FIFO, device), truncated data,
/// zero size, more than `max_pixels` pixels or more than the file's size can hold, no R, G, B
/// (the message lists the channels the file has), and NaN/Inf pixels in the channels read
/// (rejected; the message gives the first bad pixel).
LoadedImage ReadImage(const std::string& path, size_t max_pixels = kMaxImagePixels);

/// ReadImage for an image held in memory: a glTF's embedded texture, a GLB buffer view, a
/// data: URI already decoded from base64. THE entry point for loaders that have bytes rather
/// than a file (glTF textures, environment maps packed in a container): the same checks as a
/// file — the reader chosen by `name`'s extension only (give "<uri>.png" for a mimeType
/// image/png), the PNG chunk and EXR attribute sizes checked against `size`, the declared
/// size against `max_pixels` and against `size` (a 70-byte PNG claiming 16384x16384 is
/// refused before any allocation), pixels decoded in bounded bands, NaN/Inf refused — and
/// the pixels charged to the same decode budget. `name` is used in messages only (nothing is
/// opened by it). Loaders that have a FILE call ReadImage(path, max_pixels) (or
/// ReadImageChannels) instead; both note the file as an input (core/input_files.h).
/// Result: float values as stored (8-bit k -> k/255), colour R,G,B (+A as stored, never
/// premultiplied), grey expanded to RGB; `is_float` says whether the data was half/float.
LoadedImage ReadImageFromMemory(const std::string& name, const uint8_t* data, size_t size,
                                size_t max_pixels = kMaxImagePixels);

/// Where an image's bytes are, for a loader that may have a file or memory (glTF images):
/// `data` null: the file `name`, its extension picking the reader; else `size` bytes at
/// `data`, the reader picked by `ext` (".png", ".jpg", ...), `name` used in messages only
/// (e.g. "image 3 embedded in 'a.glb'").
struct ImageSource {
  std::string name;
  const uint8_t* data = nullptr;
  size_t size = 0;
  std::string ext;
};

/// What an image's header declares (its first part), read before any pixel is decoded.
struct ImageHeader {
  int width = 0, height = 0, channels = 0;
  bool is8 = false;  ///< 8-bit integer channels (ReadTexturePixels keeps their codes)
};

/// Opens `src` with every check of ReadImage (regular file, the named reader only, container
/// sizes) and reads its header only. UserError naming `src.name` when it cannot be opened.
ImageHeader ReadImageHeader(const ImageSource& src);

/// An image read for a texture: 8-bit files keep their codes (a GPU stores RGBA8 as is),
/// the others are float. Alpha is straight, as stored (glTF's alpha is unassociated):
/// never multiplied into colour.
struct TexturePixels {
  int width = 0, height = 0;
  int file_channels = 0;       ///< 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA
  bool is8 = false;            ///< `rgba8` holds the texels, else `rgba`
  std::vector<uint8_t> rgba8;  ///< 4 codes a texel, as stored; grey replicated, alpha 255 when absent
  std::vector<float> rgba;     ///< 4 floats a texel, as stored (16-bit k -> k/65535); alpha 1 when absent
};

/// Reads `src` (1 to 4 channels) for a texture with the reader's checks: the declared size
/// against `max_pixels` and the file's size, the decode budget charged before any
/// allocation (unless `charged`), pixels read in bounded bands, NaN/Inf refused (float files). UserError naming
/// `src.name` otherwise, and for more than 4 channels.
/// With `charged`, the caller has charged the image's pixels already (ChargeDecodeBudget).
TexturePixels ReadTexturePixels(const ImageSource& src, size_t max_pixels = kMaxImagePixels, bool charged = false);

/// The float OpenImageIO's UINT8 -> FLOAT conversion gives each 8-bit code (what ReadImage
/// returns for an 8-bit file), 256 entries.
const float* Unorm8FloatTable();

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

/// Copies the regular file `from` to `to` through WriteTextFile.
void CopyFileChecked(const std::string& from, const std::string& to);

}  // namespace aalab
