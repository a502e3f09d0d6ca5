#include "io/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
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
#include "io/image_info.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void FailWrite(const std::string& path, const std::string& why) {
  throw UserError("cannot write '" + path + "': " + why);
}

/// Encodes an image in memory with the OpenImageIO writer the extension names; every error
/// of the library is checked, and nothing touches the disk. `text` adds metadata (PNG text
/// chunks), e.g. an export's provenance.
std::string Encode(const std::string& path, int w, int h, int nc, OIIO::TypeDesc type, const void* data,
                   PngFilter png_filter, const ImageText* text) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) FailWrite(path, "unknown image format (use .png, .jpg, .tif or .exr)");
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  if (!out->set_ioproxy(&memory)) FailWrite(path, "the image library cannot encode this format in memory");
  OIIO::ImageSpec spec(w, h, nc, type);
  // OpenImageIO stamps EXR and TIFF files with the current time unless DateTime is set; an
  // empty value writes none, so the same pixels always give the same bytes (determinism).
  spec.attribute("DateTime", "");
  // Alpha as given: without this, OpenImageIO's PNG writer divides colour by alpha.
  if (nc == 2 || nc == 4) spec.attribute("oiio:UnassociatedAlpha", 1);
  // libpng's row filter choice: 0x08 is PNG_FILTER_NONE (png.h); unset, libpng picks per row.
  if (png_filter == PngFilter::kNone) spec.attribute("png:filter", 0x08);
  if (text) {
    for (const auto& [key, value] : *text) spec.attribute(key, value);
  }
  if (!out->open(path, spec) || !out->write_image(type, data) || !out->close() || bytes.empty()) {
    const std::string why = out->geterror();
    FailWrite(path, why.empty() ? "the image library failed without saying why" : why);
  }
  return std::string(bytes.begin(), bytes.end());
}

void WriteRaw(const std::string& path, int w, int h, int nc, OIIO::TypeDesc type, const void* data,
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
  WriteRaw(path, img.Width(), img.Height(), channels, OIIO::TypeDesc::UINT16, data.data());
}

void CopyFileChecked(const std::string& from, const std::string& to) {
  std::ifstream f(from, std::ios::binary);
  if (!f || !fs::is_regular_file(from)) throw UserError("cannot read '" + from + "': not a readable file");
  std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) throw UserError("cannot read '" + from + "': read error");
  WriteTextFile(to, bytes);
}

}  // namespace aalab
