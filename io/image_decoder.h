/// The reader's view of an opened image file, shared by the two back ends of io/: the libpng
/// one (io/png_codec.cpp, linked in) and the OpenImageIO one (io/oiio_module.cpp, a module
/// loaded on first use by io/oiio_loader.cpp). Internal to io/: only standard types, so the
/// module needs nothing of aalab's libraries.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace aalab::io_detail {

/// One part (subimage) of an opened file: what OpenImageIO's ImageSpec says of it.
struct PartSpec {
  int x = 0, y = 0, z = 0;  ///< data window origin
  int width = 0, height = 0, depth = 1;
  int nchannels = 0;
  int tile_width = 0, tile_height = 0;  ///< 0: scanline file
  bool deep = false;
  bool is_uint8 = false;             ///< every channel stores 8-bit unsigned integers
  bool float_format = false;         ///< the part's main format is half/float/double
  int bits = 8;                      ///< bits per sample as stored (oiio:BitsPerSample, else the type's)
  std::string compression = "none";  ///< the "compression" attribute
  std::string subimage_name;         ///< oiio:subimagename
  std::vector<std::string> channel_names;
  std::vector<char> channel_float;  ///< per channel: half/float/double
};

/// An opened image file. Rows are relative to the part's data window.
class ImageDecoder {
 public:
  virtual ~ImageDecoder() = default;
  virtual std::string FormatName() const = 0;
  virtual const std::vector<PartSpec>& Parts() const = 0;
  /// Reads rows [y0, y1) of channels [cb, ce) of `part` into `dst`, as float (k/255 for
  /// 8-bit data) or, with `as_uint8`, as 8-bit codes (8-bit parts only). false: see Errors().
  virtual bool ReadRows(int part, int y0, int y1, int cb, int ce, void* dst, bool as_uint8) = 0;
  /// Whether a message is pending; a read may also report success while leaving one.
  virtual bool HasError() const = 0;
  /// The pending messages, one a line, cleared.
  virtual std::string TakeErrors() = 0;
  virtual void Close() = 0;
};

/// Sample types the encoders take.
enum class SampleType { kUint8, kUint16, kFloat };

/// The entry points of the OpenImageIO module (one struct, found by dlsym under
/// kOiioModuleSymbol). Every function catches its own exceptions and reports through `error`.
struct OiioModuleApi {
  int abi_version;
  /// Opens a file (`data` null) or `size` bytes in memory (`name` then is "memory.<ext>").
  std::unique_ptr<ImageDecoder> (*open)(const std::string& name, const uint8_t* data, size_t size, std::string* error);
  /// Encodes an image in memory with the writer `path`'s extension names (`filter_none`: the
  /// png:filter 0x08 attribute, as the spec has always carried it).
  bool (*encode)(const std::string& path, int w, int h, int nc, SampleType type, const void* data, bool filter_none,
                 const std::vector<std::pair<std::string, std::string>>* text, std::string* bytes, std::string* error);
  /// Draws black text on RGBA8 pixels (OpenImageIO's render_text, FreeType).
  bool (*draw_text)(uint8_t* rgba, int w, int h, int x, int y, const std::string& text, int size_px,
                    const std::string& font, std::string* error);
};

inline constexpr int kOiioModuleAbi = 1;
inline constexpr const char* kOiioModuleSymbol = "aalab_io_oiio_api";

}  // namespace aalab::io_detail
