// The one image reader (io/image_io.h): every image aalab reads goes through
// ListImageChannels / ReadImageChannels. What it guarantees, and why:
//  - only regular files are opened (stat first: a FIFO would block open() for ever);
//  - only the reader the extension names is tried (see kOnlyTheNamedReader);
//  - container sizes (EXR attributes, PNG chunks) are checked before the decoders trust them;
//  - the declared size is checked against the pixel limit and against the file's size, and
//    pixels are read in bands of at most kBandBytes, so a tiny file that claims a huge image
//    fails after reading one band, never after allocating the whole image;
//  - channels are taken by name, never by position; alpha is read as stored (OpenImageIO
//    premultiplies PNG and unassociated-alpha TIFF on read unless told not to);
//  - PNG is decoded by libpng here (io/png_codec.cpp); every other format by OpenImageIO in
//    the module io/oiio_loader.h loads on first use (aalab starts without OpenImageIO).
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <sstream>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include "core/color.h"
#include "core/error.h"
#include "core/input_files.h"
#include "io/image_decoder.h"
#include "io/image_io.h"
#include "io/oiio_loader.h"
#include "io/png_codec.h"

namespace aalab {
namespace fs = std::filesystem;
using io_detail::ImageDecoder;
using io_detail::PartSpec;

namespace {

/// Pixels are decoded in bands of at most this many bytes (as float), so the memory a file
/// can make aalab take before its data has been read is bounded.
constexpr size_t kBandBytes = size_t{16} << 20;
/// Deflate (PNG's compression) stores at most 1032 bytes per byte (RFC 1951: a 258-byte match
/// in 2 bits); a PNG smaller than its filtered rows / 1032 cannot hold the size it claims.
constexpr double kDeflateMaxRatio = 1032.0;

std::string LowerExt(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string Join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

/// Checks the attribute sizes of an OpenEXR header against the file size; returns "" when
/// they fit (or the file is not EXR at all: OpenEXR then says so), else what is wrong.
/// OpenEXR 3.1 trusts a string attribute's size field: found by fuzzing, a 600-byte file
/// claiming a 1.8 GB attribute made the reader allocate and zero 1.8 GB before failing.
std::string CheckExrHeader(std::istream& f, long long file_size) {
  if (!f) return "";
  unsigned char head[8] = {};
  if (!f.read(reinterpret_cast<char*>(head), 8)) return "";
  if (head[0] != 0x76 || head[1] != 0x2f || head[2] != 0x31 || head[3] != 0x01) return "";
  const bool multipart = (head[5] & 0x10) != 0;  // version flag 0x1000: several headers
  auto read_name = [&f](std::string& out) {
    out.clear();
    for (char c; f.get(c);) {
      if (c == '\0') return true;
      if (out.size() >= 255) return false;
      out += c;
    }
    return false;
  };
  std::string name, type;
  bool header_empty = true;
  while (true) {
    if (!read_name(name)) return "its header is truncated or has an over-long attribute name";
    if (name.empty()) {
      // End of one header; a multi-part file ends its list of headers with an empty one.
      if (!multipart || header_empty) return "";
      header_empty = true;
      continue;
    }
    header_empty = false;
    if (!read_name(type)) return "attribute '" + name + "' has a truncated or over-long type name";
    unsigned char b[4] = {};
    if (!f.read(reinterpret_cast<char*>(b), 4)) return "attribute '" + name + "' is truncated";
    const int32_t size = static_cast<int32_t>(static_cast<uint32_t>(b[0]) | static_cast<uint32_t>(b[1]) << 8 |
                                              static_cast<uint32_t>(b[2]) << 16 | static_cast<uint32_t>(b[3]) << 24);
    const long long left = file_size - static_cast<long long>(f.tellg());
    if (size < 0 || size > left) {
      return "attribute '" + name + "' claims " + std::to_string(size) + " bytes but only " + std::to_string(left) +
             " remain in the file";
    }
    f.seekg(size, std::ios::cur);
  }
}

/// Checks that every PNG chunk fits in the file; returns "" when it does (or the file is not
/// a PNG at all: libpng then says so), else what is wrong. libpng allocates a chunk's
/// claimed length before reading it: found by fuzzing, a 260-byte file whose tEXt chunk
/// claimed 2 GB made aalab allocate and touch 2 GB before failing.
std::string CheckPngChunks(std::istream& f, long long file_size) {
  if (!f) return "";
  char sig[8] = {};
  if (!f.read(sig, 8) || std::string(sig, 8) != std::string("\x89PNG\r\n\x1a\n", 8)) return "";
  while (true) {
    unsigned char h[8] = {};
    if (!f.read(reinterpret_cast<char*>(h), 8)) return "";  // ends without IEND: libpng reports it
    const uint32_t length = static_cast<uint32_t>(h[0]) << 24 | static_cast<uint32_t>(h[1]) << 16 |
                            static_cast<uint32_t>(h[2]) << 8 | static_cast<uint32_t>(h[3]);
    std::string type(reinterpret_cast<const char*>(h + 4), 4);
    for (char& c : type) {
      if (!std::isalpha(static_cast<unsigned char>(c))) c = '?';
    }
    const long long left = file_size - static_cast<long long>(f.tellg());
    if (static_cast<long long>(length) + 4 > left) {
      return "chunk '" + type + "' claims " + std::to_string(length) + " bytes but only " +
             std::to_string(std::max(0LL, left - 4)) + " remain in the file (truncated?)";
    }
    if (type == "IEND") return "";
    f.seekg(static_cast<std::streamoff>(length) + 4, std::ios::cur);  // data and CRC
  }
}

/// The extension's check and the container checks of the bytes in `f` (`size` of them).
void CheckContainer(const std::string& path, const std::string& ext, std::istream& f, long long size) {
  if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".tif" && ext != ".tiff" && ext != ".exr" &&
      ext != ".hdr") {
    throw UserError("image '" + path + "' has an unsupported file type '" + ext +
                    "' (readable: .png, .jpg, .jpeg, .tif, .tiff, .exr, .hdr)");
  }
  if (ext == ".exr") {
    if (const std::string bad = CheckExrHeader(f, size); !bad.empty()) {
      throw UserError("cannot read image '" + path + "': not a valid OpenEXR file: " + bad);
    }
  }
  if (ext == ".png") {
    if (const std::string bad = CheckPngChunks(f, size); !bad.empty()) {
      throw UserError("cannot read image '" + path + "': not a valid PNG file: " + bad);
    }
  }
}

/// Everything checked before a decoder sees the file; returns the file's size in bytes.
/// stat() (not open()) first: opening a FIFO for reading blocks until a writer appears.
long long CheckInputFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT) throw UserError("image '" + path + "' does not exist");
    throw UserError("cannot read image '" + path + "': " + std::strerror(err));
  }
  if (S_ISDIR(st.st_mode)) throw UserError("image '" + path + "' is a directory, not an image file");
  if (!S_ISREG(st.st_mode)) {
    throw UserError("image '" + path + "' is not a regular file (a FIFO, device or socket); give an image file");
  }
  std::ifstream f(path, std::ios::binary);
  CheckContainer(path, LowerExt(path), f, static_cast<long long>(st.st_size));
  return static_cast<long long>(st.st_size);
}

/// One channel of a file: the part (subimage) it is in, its index there, its listed name.
struct ChannelRef {
  int part = 0;
  int index = 0;
  std::string name;
};

/// An open image file with its parts and their channels.
struct OpenedImage {
  std::unique_ptr<ImageDecoder> in;  // libpng's (PNG) or the OpenImageIO module's
  std::vector<PartSpec> parts;
  std::vector<ChannelRef> channels;
  long long file_bytes = 0;
};

/// Opens a file (`data` null) or `size` bytes in memory named `path` (its extension picks the
/// reader) after the checks above.
/// `ext` (memory only; e.g. ".png") picks the reader instead of `path`'s extension, so that
/// `path` can be a name for messages ("image 3 embedded in 'a.glb'").
OpenedImage Open(const std::string& path, const uint8_t* data = nullptr, size_t size = 0, const std::string& ext = "") {
  OpenedImage f;
  const std::string reader = ext.empty() || !data ? LowerExt(path) : ext;
  if (data) {
    std::istringstream bytes(std::string(reinterpret_cast<const char*>(data), size));
    CheckContainer(path, reader, bytes, static_cast<long long>(size));
    f.file_bytes = static_cast<long long>(size);
  } else {
    f.file_bytes = CheckInputFile(path);
    NoteInputFile(path);  // an input of the command: --out may not hold it (input_files.h)
  }
  std::string error;
  if (reader == ".png") {
    f.in = io_detail::OpenPng(path, data, size, &error);
  } else {
    // Only the reader the extension names (the module tells OpenImageIO so), alpha as stored.
    const auto& oiio = io_detail::OiioModule("image '" + path + "' (" + reader + ")");
    f.in = oiio.open(data && !ext.empty() ? "memory" + ext : path, data, size, &error);
  }
  if (!f.in) {
    throw UserError("cannot read image '" + path + "': " + error + " (readable: PNG, JPEG, TIFF, EXR; " +
                    "the content must match the file's extension)");
  }
  f.parts = f.in->Parts();
  const bool multipart = f.parts.size() > 1;
  for (int p = 0; p < static_cast<int>(f.parts.size()); ++p) {
    const PartSpec& spec = f.parts[p];
    std::string prefix;
    if (multipart) {
      std::string part = spec.subimage_name;
      if (part.empty()) part = "part" + std::to_string(p);
      prefix = part + ".";
    }
    for (int c = 0; c < spec.nchannels; ++c) {
      std::string name = c < static_cast<int>(spec.channel_names.size()) ? spec.channel_names[c] : "";
      if (name.empty()) name = "channel" + std::to_string(c);
      if (!prefix.empty() && name.rfind(prefix, 0) != 0) name = prefix + name;
      f.channels.push_back({p, c, name});
    }
  }
  return f;
}

std::vector<std::string> Names(const OpenedImage& f) {
  std::vector<std::string> names;
  for (const auto& c : f.channels) names.push_back(c.name);
  return names;
}

/// A PNG's rows can not be smaller than their deflated size; "" when the file is big enough.
std::string CheckPlausibleSize(const OpenedImage& f, const PartSpec& spec) {
  const std::string format = f.in->FormatName();
  const double bits = spec.bits;
  const double row_bytes = std::ceil(static_cast<double>(spec.width) * spec.nchannels * bits / 8.0);
  double min_bytes = 0;
  std::string why;
  if (format == "png") {
    min_bytes = static_cast<double>(spec.height) * (row_bytes + 1) / kDeflateMaxRatio;
    why = "deflate stores at most 1032 bytes per byte";
  } else if (format == "tiff" && spec.compression == "none") {
    min_bytes = static_cast<double>(spec.height) * row_bytes;
    why = "the file is uncompressed";
  }
  if (static_cast<double>(f.file_bytes) >= min_bytes) return "";
  return "its header claims " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
         " pixels, which needs at least " + std::to_string(static_cast<long long>(min_bytes)) + " bytes (" + why +
         "), but the file has " + std::to_string(f.file_bytes) + " (truncated or corrupt)";
}

/// The first message of a failed read (OpenImageIO may append one per row), at most 300
/// characters, with how many more there were.
std::string FirstReadError(ImageDecoder& in) {
  const std::string all = in.TakeErrors();
  std::string why = all.substr(0, all.find('\n'));
  if (why.size() > 300) why = why.substr(0, 300) + "...";
  const auto more = std::count(all.begin(), all.end(), '\n');
  if (more > 0) why += " (and " + std::to_string(more) + " more messages)";
  return why;
}

std::atomic<size_t>& Decoded() {
  static std::atomic<size_t> pixels{0};
  return pixels;
}

}  // namespace

/// Adds `pixels` to the command's decoded total; UserError naming `path` past the budget.
void ChargeDecodeBudget(size_t pixels, const std::string& path) {
  const size_t budget = DecodeBudgetPixels();
  const size_t before = Decoded().fetch_add(pixels);
  if (budget == 0 || before + pixels <= budget) return;
  throw UserError("image '" + path + "' (" + std::to_string(pixels) + " pixels) would take the pixels this command " +
                  "decodes to " + std::to_string(before + pixels) + ", past the budget of " + std::to_string(budget) +
                  " (" + std::to_string(budget / 1000000) + " megapixels); set " + kDecodeBudgetVariable +
                  "=MEGAPIXELS to allow more (0 = no budget)");
}

namespace {

/// ReadImageChannels on an opened file; `is_float` (optional) says whether any channel read
/// stores half/float data.
ImageF ReadChannels(OpenedImage& f, const std::string& path, const std::vector<std::string>& names, size_t max_pixels,
                    bool allow_inf, bool* is_float, bool charged = false) {
  if (names.empty()) throw UserError("cannot read image '" + path + "': no channels asked for");
  std::vector<ChannelRef> want;
  for (const auto& n : names) {
    auto it = std::find_if(f.channels.begin(), f.channels.end(), [&n](const ChannelRef& c) { return c.name == n; });
    if (it == f.channels.end()) {
      throw UserError("image '" + path + "' has no channel '" + n + "' (its channels: " + Join(Names(f)) + ")");
    }
    want.push_back(*it);
  }
  const PartSpec& spec = f.parts[want[0].part];
  for (const auto& c : want) {
    const PartSpec& s = f.parts[c.part];
    if (s.x != spec.x || s.y != spec.y || s.width != spec.width || s.height != spec.height) {
      throw UserError("image '" + path + "': channels '" + want[0].name + "' and '" + c.name +
                      "' are in parts of different sizes (" + std::to_string(spec.width) + "x" +
                      std::to_string(spec.height) + " and " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                      "); read channels of one size together");
    }
    if (s.deep) throw UserError("image '" + path + "' is a deep image; aalab reads flat images only");
  }
  const int w = spec.width, h = spec.height;
  if (w <= 0 || h <= 0) throw UserError("image '" + path + "' has zero size");
  if (static_cast<size_t>(w) * static_cast<size_t>(h) > max_pixels) {
    throw UserError("image '" + path + "' is " + std::to_string(w) + "x" + std::to_string(h) +
                    ", more than the limit of " + std::to_string(max_pixels) + " pixels");
  }
  if (spec.depth > 1) {
    throw UserError("image '" + path + "' is a volume (" + std::to_string(spec.depth) + " slices); 2-D images only");
  }
  if (!charged) ChargeDecodeBudget(static_cast<size_t>(w) * static_cast<size_t>(h), path);
  for (const auto& c : want) {
    if (const std::string bad = CheckPlausibleSize(f, f.parts[c.part]); !bad.empty()) {
      throw UserError("cannot read image '" + path + "': " + bad);
    }
  }
  if (is_float) {
    *is_float = false;
    for (const auto& c : want) *is_float = *is_float || f.parts[c.part].channel_float[c.index] != 0;
  }
  const int nc = static_cast<int>(want.size());
  // Bands of whole rows (whole rows of tiles for tiled files), at most kBandBytes each, read
  // and checked in order: a file that claims more rows than it holds fails at its first
  // missing band. OpenImageIO appends a message for every row it fails to decode: found by
  // fuzzing, one call over a 3x65533 TIFF piled up 16 MB of messages and OIIO aborted.
  int widest = 1;
  for (const auto& c : want) widest = std::max(widest, f.parts[c.part].nchannels);
  const size_t row_floats = static_cast<size_t>(w) * static_cast<size_t>(widest);
  int band = static_cast<int>(std::clamp<size_t>(kBandBytes / (row_floats * sizeof(float)), 1, 256));
  for (const auto& c : want) {
    const int th = f.parts[c.part].tile_width > 0 ? std::max(1, f.parts[c.part].tile_height) : 1;
    band = std::max(th, band / th * th);
  }
  ImageF::Storage pixels;  // every value is written below: no zero-fill
  std::vector<float> scratch;
  for (int y = 0; y < h; y += band) {
    const int yend = std::min(h, y + band);
    const size_t rows = static_cast<size_t>(yend - y);
    const size_t base = pixels.size();
    pixels.resize(base + rows * w * nc);
    // One read per part: the span of its channels that are wanted.
    for (int p = 0; p < static_cast<int>(f.parts.size()); ++p) {
      int cb = INT32_MAX, ce = -1;
      for (const auto& c : want) {
        if (c.part == p) cb = std::min(cb, c.index), ce = std::max(ce, c.index + 1);
      }
      if (ce < 0) continue;
      scratch.resize(rows * w * (ce - cb));
      if (!f.in->ReadRows(p, y, yend, cb, ce, scratch.data(), false) || f.in->HasError()) {
        // Also an error when the call reported success: OIIO's multi-row TIFF reads return true
        // while appending an error for every row they failed to decode. First message only.
        throw UserError("cannot read image '" + path + "' (truncated or corrupt?) near row " + std::to_string(y) +
                        ": " + FirstReadError(*f.in));
      }
      const int span = ce - cb;
      for (int k = 0; k < nc; ++k) {
        if (want[k].part != p) continue;
        const int src = want[k].index - cb;
        for (size_t i = 0; i < rows * w; ++i) pixels[base + i * nc + k] = scratch[i * span + src];
      }
    }
    // The first bad value in row-major order (pixel by pixel, channel by channel).
    for (size_t i = 0; i < rows * w * nc; ++i) {
      const float v = pixels[base + i];
      if (std::isfinite(v) || (allow_inf && std::isinf(v))) continue;
      const size_t px = i / nc;
      const int c = static_cast<int>(i % nc);
      throw UserError("image '" + path + "' has a non-finite value (" + (std::isnan(v) ? "NaN" : "Inf") +
                      ") at pixel (" + std::to_string(px % w) + ", " + std::to_string(y + px / w) + ") channel " +
                      std::to_string(c) + " (" + want[c].name + "); " +
                      (allow_inf ? "NaN pixels are rejected" : "NaN/Inf pixels are rejected"));
    }
  }
  f.in->Close();
  return ImageF(w, h, nc, std::move(pixels));
}

/// The channel called `name` (exact, else ignoring case) in a single-part file; "" if none.
std::string FindChannel(const std::vector<std::string>& names, const std::string& name) {
  for (const auto& n : names) {
    if (n == name) return n;
  }
  for (const auto& n : names) {
    if (n.size() == name.size() && std::equal(n.begin(), n.end(), name.begin(),
                                              [](char a, char b) { return std::tolower(a) == std::tolower(b); })) {
      return n;
    }
  }
  return "";
}

}  // namespace

std::vector<std::string> ListImageChannels(const std::string& path) {
  OpenedImage f = Open(path);
  f.in->Close();
  return Names(f);
}

ImageF ReadImageChannels(const std::string& path, const std::vector<std::string>& names, size_t max_pixels,
                         bool allow_inf) {
  OpenedImage f = Open(path);
  return ReadChannels(f, path, names, max_pixels, allow_inf, nullptr);
}

namespace {

LoadedImage ReadOpened(OpenedImage& f, const std::string& path, size_t max_pixels, bool charged = false) {
  const std::vector<std::string> all = Names(f);
  const std::string r = FindChannel(all, "R"), g = FindChannel(all, "G"), b = FindChannel(all, "B");
  const std::string a = FindChannel(all, "A");
  std::vector<std::string> names;
  bool grey = false;
  if (!r.empty() && !g.empty() && !b.empty()) {
    names = {r, g, b};
  } else if (all.size() == 1) {
    names = {all[0]};
    grey = true;
  } else if (const std::string y = FindChannel(all, "Y"); !y.empty() && all.size() == (a.empty() ? 1u : 2u)) {
    names = {y};
    grey = true;
  } else {
    throw UserError(
        "image '" + path + "' has no channels named R, G and B (its channels: " + Join(all) +
        "); colour is read from channels R, G, B (A optional), or from a grey file (one channel, or Y and A)");
  }
  if (!a.empty() && names[0] != a) names.push_back(a);
  LoadedImage result;
  result.format = f.in->FormatName();
  const ImageF read = ReadChannels(f, path, names, max_pixels, false, &result.is_float, charged);
  result.file_channels = static_cast<int>(names.size());
  const bool alpha = names.size() == (grey ? 2u : 4u);
  if (!grey) {
    result.pixels = read;
    return result;
  }
  result.pixels = ImageF(read.Width(), read.Height(), alpha ? 4 : 3);
  for (size_t i = 0; i < read.PixelCount(); ++i) {
    float* d = &result.pixels.Data()[i * result.pixels.Channels()];
    const float* s = &read.Data()[i * read.Channels()];
    d[0] = d[1] = d[2] = s[0];
    if (alpha) d[3] = s[1];
  }
  return result;
}

}  // namespace

LoadedImage ReadImage(const std::string& path, size_t max_pixels) {
  OpenedImage f = Open(path);
  return ReadOpened(f, path, max_pixels);
}

LoadedImage ReadImageFromMemory(const std::string& name, const uint8_t* data, size_t size, size_t max_pixels) {
  if (!data || size == 0) throw UserError("image '" + name + "' is empty (0 bytes)");
  OpenedImage f = Open(name, data, size);
  return ReadOpened(f, name, max_pixels);
}

namespace {

OpenedImage OpenSource(const ImageSource& src) {
  if (!src.data) return Open(src.name);
  if (src.size == 0) throw UserError("image '" + src.name + "' is empty (0 bytes)");
  return Open(src.name, src.data, src.size, src.ext);
}

/// An 8-bit single-part image of 1..4 channels read as its codes into RGBA8, in bands.
TexturePixels ReadCodes(OpenedImage& f, const std::string& path, size_t max_pixels, bool charged) {
  const PartSpec& spec = f.parts[0];
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  if (w <= 0 || h <= 0) throw UserError("image '" + path + "' has zero size");
  if (static_cast<size_t>(w) * static_cast<size_t>(h) > max_pixels) {
    throw UserError("image '" + path + "' is " + std::to_string(w) + "x" + std::to_string(h) +
                    ", more than the limit of " + std::to_string(max_pixels) + " pixels");
  }
  if (const std::string bad = CheckPlausibleSize(f, spec); !bad.empty()) {
    throw UserError("cannot read image '" + path + "': " + bad);
  }
  if (!charged) ChargeDecodeBudget(static_cast<size_t>(w) * static_cast<size_t>(h), path);
  TexturePixels t;
  t.width = w;
  t.height = h;
  t.file_channels = nc;
  t.is8 = true;
  const int th = spec.tile_width > 0 ? std::max(1, spec.tile_height) : 1;
  int band = static_cast<int>(std::clamp<size_t>(kBandBytes / (static_cast<size_t>(w) * nc), 1, 256));
  band = std::max(th, band / th * th);
  // The whole result at once when the data could plausibly hold it (no copies as it grows:
  // they doubled the transient peak); a small file claiming a huge image grows band by band
  // and fails at its first missing band, never after allocating the whole image.
  const size_t total = 4 * static_cast<size_t>(w) * static_cast<size_t>(h);
  if (total <= kBandBytes + 1032 * static_cast<size_t>(std::max(0LL, f.file_bytes))) t.rgba8.reserve(total);
  std::vector<uint8_t> rows;
  for (int y = 0; y < h; y += band) {
    const int yend = std::min(h, y + band);
    const size_t count = static_cast<size_t>(yend - y) * static_cast<size_t>(w);
    rows.resize(count * static_cast<size_t>(nc));
    if (!f.in->ReadRows(0, y, yend, 0, nc, rows.data(), true) || f.in->HasError()) {
      throw UserError("cannot read image '" + path + "' (truncated or corrupt?) near row " + std::to_string(y) + ": " +
                      FirstReadError(*f.in));
    }
    const size_t base = t.rgba8.size();
    t.rgba8.resize(base + 4 * count);
    uint8_t* d = &t.rgba8[base];
    for (size_t i = 0; i < count; ++i, d += 4) {
      const uint8_t* p = &rows[i * nc];
      d[0] = p[0];
      d[1] = nc >= 3 ? p[1] : p[0];
      d[2] = nc >= 3 ? p[2] : p[0];
      d[3] = nc == 2 || nc == 4 ? p[nc - 1] : 255;
    }
  }
  f.in->Close();
  return t;
}

}  // namespace

ImageHeader ReadImageHeader(const ImageSource& src) {
  OpenedImage f = OpenSource(src);
  const PartSpec& s = f.parts[0];
  ImageHeader h{s.width, s.height, s.nchannels, s.is_uint8};
  f.in->Close();
  return h;
}

TexturePixels ReadTexturePixels(const ImageSource& src, size_t max_pixels, bool charged) {
  OpenedImage f = OpenSource(src);
  const PartSpec& spec = f.parts[0];
  if (spec.nchannels < 1 || spec.nchannels > 4) {
    throw UserError("image '" + src.name + "' has " + std::to_string(spec.nchannels) + " channels (allowed: 1 to 4)");
  }
  if (spec.is_uint8) return ReadCodes(f, src.name, max_pixels, charged);
  const LoadedImage img = ReadOpened(f, src.name, max_pixels, charged);
  TexturePixels t;
  t.width = img.pixels.Width();
  t.height = img.pixels.Height();
  t.file_channels = img.file_channels;
  const int nc = img.pixels.Channels();  // 3 or 4 (grey expanded)
  t.rgba.resize(4 * img.pixels.PixelCount());
  for (size_t i = 0; i < img.pixels.PixelCount(); ++i) {
    const float* p = &img.pixels.Data()[i * nc];
    for (int c = 0; c < 4; ++c) t.rgba[4 * i + c] = c < nc ? p[c] : 1.0f;
  }
  return t;
}

const float* Unorm8FloatTable() {
  static const std::array<float, 256> table = [] {
    // OpenImageIO's convert_type: k * (1/255.0f) (tests/io/png_oracle_test.cpp compares).
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[static_cast<size_t>(i)] = static_cast<float>(i) * (1.0f / 255.0f);
    return t;
  }();
  return table.data();
}

size_t DecodeBudgetPixels() {
  static const size_t budget = [] {
    const char* env = std::getenv(kDecodeBudgetVariable);
    if (!env) return kDefaultDecodeBudgetPixels;
    const std::string v = env;
    if (v.empty() || v.size() > 12 || v.find_first_not_of("0123456789") != std::string::npos) {
      throw UserError(std::string(kDecodeBudgetVariable) + "='" + v +
                      "' must be a whole number of megapixels (0 = no budget)");
    }
    return static_cast<size_t>(std::stoull(v)) * 1000000;
  }();
  return budget;
}

size_t DecodedPixels() { return Decoded().load(); }

Image8 ReadImage8(const std::string& path) {
  LoadedImage img = ReadImage(path);
  if (img.is_float) {
    throw UserError("image '" + path + "' stores float data; an 8-bit display image is expected here");
  }
  const bool alpha = img.pixels.Channels() == 4;
  Image8 out(img.pixels.Width(), img.pixels.Height(), 4, 255);
  for (int y = 0; y < out.Height(); ++y) {
    for (int x = 0; x < out.Width(); ++x) {
      for (int c = 0; c < (alpha ? 4 : 3); ++c) out.At(x, y, c) = QuantizeUnorm8(img.pixels.At(x, y, c));
    }
  }
  return out;
}

}  // namespace aalab
