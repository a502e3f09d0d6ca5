#include "io/image_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <iterator>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "core/cleanup.h"
#include "core/color.h"
#include "core/error.h"
#include "io/exr_write.h"
#include "io/image_decoder.h"
#include "io/image_info.h"
#include "io/oiio_loader.h"
#include "io/png_codec.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void FailWrite(const std::string& path, const std::string& why) {
  throw UserError("cannot write '" + path + "': " + why);
}

/// The file's extension, lower case ("" when none).
std::string LowerExt(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

/// Encodes an image in memory with the writer the extension names: PNG through libpng
/// (io/png_codec.h) and float EXR through OpenEXR (io/exr_write.h), both giving the bytes
/// OpenImageIO 2.4's writers gave; the others through the OpenImageIO module (io/oiio_loader.h). Every error is
/// checked; nothing touches the disk. `text` adds metadata (PNG text chunks), e.g. an export's provenance.
std::string Encode(const std::string& path, int w, int h, int nc, io_detail::SampleType type, const void* data,
                   PngFilter png_filter, const ImageText* text) {
  std::string bytes, why;
  bool ok = false;
  if (LowerExt(path) == ".exr" && type == io_detail::SampleType::kFloat) {
    ok = io_detail::EncodeExrFloat(w, h, nc, static_cast<const float*>(data), &bytes, &why);
  } else if (LowerExt(path) == ".png") {
    AALAB_CHECK(type != io_detail::SampleType::kFloat, "PNG stores 8- or 16-bit integers");
    ok = io_detail::EncodePng(w, h, nc, type == io_detail::SampleType::kUint16, data, png_filter == PngFilter::kNone,
                              text, &bytes, &why);
  } else {
    const auto& oiio = io_detail::OiioModule("writing '" + path + "' (" + LowerExt(path) + ")");
    ok = oiio.encode(path, w, h, nc, type, data, png_filter == PngFilter::kNone, text, &bytes, &why);
  }
  if (!ok || bytes.empty()) FailWrite(path, why.empty() ? "the image library failed without saying why" : why);
  return bytes;
}

void WriteRaw(const std::string& path, int w, int h, int nc, io_detail::SampleType type, const void* data,
              PngFilter png_filter = PngFilter::kAdaptive, const ImageText* text = nullptr) {
  WriteTextFile(path, Encode(path, w, h, nc, type, data, png_filter, text));
}

}  // namespace

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
    WriteRaw(path, img.Width(), img.Height(), 4, io_detail::SampleType::kUint8, img.Data().data(),
             ChoosePngFilter(img.Data().data(), img.Width(), img.Height(), 4));
    return;
  }
  std::vector<uint8_t> rgb(img.PixelCount() * 3);
  for (size_t i = 0; i < img.PixelCount(); ++i) {
    for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = img.Data()[i * 4 + c];
  }
  WriteRaw(path, img.Width(), img.Height(), 3, io_detail::SampleType::kUint8, rgb.data(),
           ChoosePngFilter(rgb.data(), img.Width(), img.Height(), 3));
}

void WriteImage8WithText(const std::string& path, const Image8& img, const ImageText& text) {
  AALAB_CHECK(img.Channels() == 4, "WriteImage8WithText expects RGBA8");
  std::vector<uint8_t> rgb(img.PixelCount() * 3);
  for (size_t i = 0; i < img.PixelCount(); ++i) {
    for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = img.Data()[i * 4 + c];
  }
  WriteRaw(path, img.Width(), img.Height(), 3, io_detail::SampleType::kUint8, rgb.data(),
           ChoosePngFilter(rgb.data(), img.Width(), img.Height(), 3), &text);
}

void WriteGrey8(const std::string& path, int width, int height, const std::vector<uint8_t>& data) {
  AALAB_CHECK(width > 0 && height > 0 && data.size() == static_cast<size_t>(width) * height,
              "WriteGrey8 expects width*height bytes");
  WriteRaw(path, width, height, 1, io_detail::SampleType::kUint8, data.data(),
           ChoosePngFilter(data.data(), width, height, 1));
}

void WriteImageF(const std::string& path, const ImageF& img) {
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".exr" || ext == ".EXR") {
    WriteRaw(path, img.Width(), img.Height(), img.Channels(), io_detail::SampleType::kFloat, img.Data().data());
    return;
  }
  WriteImage8(path, ToUnorm8(img));
}

void WriteImage16(const std::string& path, const ImageF& img, int channels) {
  AALAB_CHECK(channels >= 1 && channels <= 4 && channels <= img.Channels(), "WriteImage16: bad channel count");
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png" && ext != ".tif" && ext != ".tiff") {
    FailWrite(path, "16-bit images are written as .png, .tif or .tiff");
  }
  std::vector<uint16_t> data(img.PixelCount() * static_cast<size_t>(channels));
  for (size_t i = 0; i < img.PixelCount(); ++i) {
    for (int c = 0; c < channels; ++c) {
      const float v = std::clamp(img.Data()[i * img.Channels() + c], 0.0f, 1.0f);
      data[i * channels + c] = static_cast<uint16_t>(std::lround(static_cast<double>(v) * 65535.0));
    }
  }
  WriteRaw(path, img.Width(), img.Height(), channels, io_detail::SampleType::kUint16, data.data());
}

void CopyFileChecked(const std::string& from, const std::string& to) {
  std::ifstream f(from, std::ios::binary);
  if (!f || !fs::is_regular_file(from)) throw UserError("cannot read '" + from + "': not a readable file");
  std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) throw UserError("cannot read '" + from + "': read error");
  WriteTextFile(to, bytes);
}

}  // namespace aalab
