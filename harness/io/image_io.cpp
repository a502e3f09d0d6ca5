#include "harness/io/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "harness/core/color.h"
#include "harness/core/error.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

std::string TempPathFor(const std::string& path) {
  const fs::path p(path);
  // Keep the extension last so OpenImageIO picks the right writer.
  return (p.parent_path() / (".tmp-" + p.stem().string() + p.extension().string())).string();
}

void CheckWritableDir(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent)) {
    throw UserError("cannot write '" + path + "': directory '" + parent.string() + "' does not exist");
  }
}

void Commit(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw UserError("cannot write '" + path + "': " + ec.message());
  }
}

void WriteRaw(const std::string& path, int w, int h, int nc, OIIO::TypeDesc type, const void* data,
              PngFilter png_filter = PngFilter::kAdaptive, const ImageText* text = nullptr) {
  CheckWritableDir(path);
  const std::string tmp = TempPathFor(path);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    throw UserError("cannot write '" + path + "': unknown image format (use .png, .jpg, .tif or .exr)");
  }
  OIIO::ImageSpec spec(w, h, nc, type);
  // OpenImageIO stamps EXR and TIFF files with the current time unless DateTime is set; an
  // empty value writes none, so the same pixels always give the same bytes (determinism).
  spec.attribute("DateTime", "");
  // libpng's row filter choice: 0x08 is PNG_FILTER_NONE (png.h); unset, libpng picks per row.
  if (png_filter == PngFilter::kNone) spec.attribute("png:filter", 0x08);
  if (text) {
    for (const auto& [key, value] : *text) spec.attribute(key, value);
  }
  if (!out->open(tmp, spec) || !out->write_image(type, data) || !out->close()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw UserError("cannot write '" + path + "': " + out->geterror());
  }
  Commit(tmp, path);
}

/// Checks the attribute sizes of an OpenEXR header against the file size; returns "" when
/// they fit (or the file is not EXR at all: OpenEXR then says so), else what is wrong.
/// OpenEXR 3.1 trusts a string attribute's size field: found by fuzzing, a 600-byte file
/// claiming a 1.8 GB attribute made the reader allocate and zero 1.8 GB before failing.
std::string CheckExrHeader(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return "";
  f.seekg(0, std::ios::end);
  const long long file_size = static_cast<long long>(f.tellg());
  f.seekg(0);
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
std::string CheckPngChunks(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return "";
  f.seekg(0, std::ios::end);
  const long long file_size = static_cast<long long>(f.tellg());
  f.seekg(0);
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

}  // namespace

LoadedImage ReadImage(const std::string& path, size_t max_pixels) {
  if (!fs::exists(path)) throw UserError("image '" + path + "' does not exist");
  if (fs::is_directory(path)) throw UserError("image '" + path + "' is a directory, not an image file");
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".tif" && ext != ".tiff" && ext != ".exr") {
    throw UserError("image '" + path + "' has an unsupported file type '" + ext +
                    "' (readable: .png, .jpg, .jpeg, .tif, .tiff, .exr)");
  }
  // Only the reader the extension names. By default OpenImageIO hands a file its reader
  // rejects to every other format plugin (DICOM, FITS, OpenVDB, video, ...): found by
  // fuzzing, a corrupt .exr then loaded ~2 GB of libraries and parsers aalab never needs.
  static const bool kOnlyTheNamedReader = OIIO::attribute("try_all_readers", 0);
  (void)kOnlyTheNamedReader;
  if (ext == ".exr") {
    if (const std::string bad = CheckExrHeader(path); !bad.empty()) {
      throw UserError("cannot read image '" + path + "': not a valid OpenEXR file: " + bad);
    }
  }
  if (ext == ".png") {
    if (const std::string bad = CheckPngChunks(path); !bad.empty()) {
      throw UserError("cannot read image '" + path + "': not a valid PNG file: " + bad);
    }
  }
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    throw UserError("cannot read image '" + path + "': " + OIIO::geterror() + " (readable: PNG, JPEG, TIFF, EXR; " +
                    "the content must match the file's extension)");
  }
  const OIIO::ImageSpec& spec = in->spec();
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  if (w <= 0 || h <= 0) throw UserError("image '" + path + "' has zero size");
  if (static_cast<size_t>(w) * static_cast<size_t>(h) > max_pixels) {
    throw UserError("image '" + path + "' is " + std::to_string(w) + "x" + std::to_string(h) +
                    ", more than the limit of " + std::to_string(max_pixels) + " pixels");
  }
  if (nc < 1 || nc > 4) {
    throw UserError("image '" + path + "' has " + std::to_string(nc) +
                    " channels (allowed: 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA)");
  }
  if (spec.depth > 1) {
    throw UserError("image '" + path + "' is a volume (" + std::to_string(spec.depth) + " slices); 2-D images only");
  }
  std::vector<float> raw(static_cast<size_t>(w) * h * nc);
  // Read in bands of at most ~256 rows (whole rows of tiles for tiled files) and stop at the
  // first band with an error. read_image() reads a narrow image in one call and OpenImageIO
  // appends a message for every row it fails to decode: found by fuzzing, a 547-byte TIFF
  // of 3x65533 pixels piled up more than 16 MB of messages and OIIO aborted the process on
  // its own assertion (SIGABRT instead of an error message).
  const bool tiled = spec.tile_width > 0;
  const int band = tiled ? std::max(1, spec.tile_height) * std::max(1, 256 / std::max(1, spec.tile_height)) : 256;
  for (int y = 0; y < h; y += band) {
    const int yend = std::min(h, y + band);
    float* dst = raw.data() + static_cast<size_t>(y) * w * nc;
    const bool ok =
        tiled ? in->read_tiles(0, 0, spec.x, spec.x + w, spec.y + y, spec.y + yend, spec.z, spec.z + 1, 0, nc,
                               OIIO::TypeDesc::FLOAT, dst)
              : in->read_scanlines(0, 0, spec.y + y, spec.y + yend, spec.z, 0, nc, OIIO::TypeDesc::FLOAT, dst);
    // Also an error when the call reported success: OIIO's multi-row TIFF reads return true
    // while appending an error for every row they failed to decode.
    if (!ok || in->has_error()) {
      // The first message only (there may be one per row), with a count of the rest.
      const std::string all = in->geterror();
      std::string why = all.substr(0, all.find('\n'));
      if (why.size() > 300) why = why.substr(0, 300) + "...";
      const auto more = std::count(all.begin(), all.end(), '\n');
      if (more > 0) why += " (and " + std::to_string(more) + " more messages)";
      throw UserError("cannot read image '" + path + "' (truncated or corrupt?) near row " + std::to_string(y) + ": " +
                      why);
    }
  }
  LoadedImage result;
  result.file_channels = nc;
  result.format = in->format_name();
  result.is_float = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                    spec.format.basetype == OIIO::TypeDesc::HALF ||
                    spec.format.basetype == OIIO::TypeDesc::DOUBLE;
  in->close();
  const int out_nc = (nc == 2 || nc == 4) ? 4 : 3;
  result.pixels = ImageF(w, h, out_nc);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float* s = &raw[(static_cast<size_t>(y) * w + x) * nc];
      for (int c = 0; c < nc; ++c) {
        if (!std::isfinite(s[c])) {
          throw UserError("image '" + path + "' has a non-finite value (NaN or Inf) at pixel (" +
                          std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                          std::to_string(c) + "; NaN/Inf pixels are rejected");
        }
      }
      float* d = result.pixels.Pixel(x, y);
      if (nc <= 2) {
        d[0] = d[1] = d[2] = s[0];
        if (nc == 2) d[3] = s[1];
      } else {
        for (int c = 0; c < nc; ++c) d[c] = s[c];
      }
    }
  }
  return result;
}

Image8 ReadImage8(const std::string& path) {
  LoadedImage img = ReadImage(path);
  if (img.is_float) {
    throw UserError("image '" + path + "' stores float data; an 8-bit display image is expected here");
  }
  Image8 out(img.pixels.Width(), img.pixels.Height(), 4, 255);
  for (int y = 0; y < out.Height(); ++y) {
    for (int x = 0; x < out.Width(); ++x) {
      for (int c = 0; c < 3; ++c) out.At(x, y, c) = QuantizeUnorm8(img.pixels.At(x, y, c));
    }
  }
  return out;
}

PngFilter ChoosePngFilter(const uint8_t* data, int w, int h, int nc) {
  // libpng's adaptive choice (smallest sum of absolute residuals per row) compresses smooth
  // frames well but noise-like ones worse than no filter at all: a 960x540 1-texel-per-pixel
  // noise frame is 1.15 MB adaptive and 0.88 MB unfiltered. Noise-like = most pixels differ
  // from their left neighbour.
  size_t differ = 0, total = 0;
  for (int y = 0; y < h; ++y) {
    const uint8_t* row = data + static_cast<size_t>(y) * w * nc;
    for (int x = 1; x < w; ++x, ++total) {
      for (int c = 0; c < nc; ++c) {
        if (row[x * nc + c] != row[(x - 1) * nc + c]) {
          ++differ;
          break;
        }
      }
    }
  }
  return total > 0 && differ * 2 > total ? PngFilter::kNone : PngFilter::kAdaptive;
}

void WriteImage8(const std::string& path, const Image8& img, bool keep_alpha) {
  AALAB_CHECK(img.Channels() == 4, "WriteImage8 expects RGBA8");
  if (keep_alpha) {
    WriteRaw(path, img.Width(), img.Height(), 4, OIIO::TypeDesc::UINT8, img.Data().data(),
             ChoosePngFilter(img.Data().data(), img.Width(), img.Height(), 4));
    return;
  }
  std::vector<uint8_t> rgb(img.PixelCount() * 3);
  for (size_t i = 0; i < img.PixelCount(); ++i) {
    for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = img.Data()[i * 4 + c];
  }
  WriteRaw(path, img.Width(), img.Height(), 3, OIIO::TypeDesc::UINT8, rgb.data(),
           ChoosePngFilter(rgb.data(), img.Width(), img.Height(), 3));
}

void WriteImage8WithText(const std::string& path, const Image8& img, const ImageText& text) {
  AALAB_CHECK(img.Channels() == 4, "WriteImage8WithText expects RGBA8");
  std::vector<uint8_t> rgb(img.PixelCount() * 3);
  for (size_t i = 0; i < img.PixelCount(); ++i) {
    for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = img.Data()[i * 4 + c];
  }
  WriteRaw(path, img.Width(), img.Height(), 3, OIIO::TypeDesc::UINT8, rgb.data(),
           ChoosePngFilter(rgb.data(), img.Width(), img.Height(), 3), &text);
}

void WriteGrey8(const std::string& path, int width, int height, const std::vector<uint8_t>& data) {
  AALAB_CHECK(width > 0 && height > 0 && data.size() == static_cast<size_t>(width) * height,
              "WriteGrey8 expects width*height bytes");
  WriteRaw(path, width, height, 1, OIIO::TypeDesc::UINT8, data.data(), ChoosePngFilter(data.data(), width, height, 1));
}

void WriteImageF(const std::string& path, const ImageF& img) {
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".exr" || ext == ".EXR") {
    WriteRaw(path, img.Width(), img.Height(), img.Channels(), OIIO::TypeDesc::FLOAT, img.Data().data());
    return;
  }
  WriteImage8(path, ToUnorm8(img));
}

void WriteTextFile(const std::string& path, const std::string& text) {
  CheckWritableDir(path);
  const std::string tmp = TempPathFor(path);
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) throw UserError("cannot write '" + path + "': cannot create a file there");
    f << text;
    f.flush();
    if (!f) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw UserError("cannot write '" + path + "': write failed");
    }
  }
  Commit(tmp, path);
}

}  // namespace aalab
