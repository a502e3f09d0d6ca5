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
              PngFilter png_filter = PngFilter::kAdaptive) {
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
  if (!out->open(tmp, spec) || !out->write_image(type, data) || !out->close()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw UserError("cannot write '" + path + "': " + out->geterror());
  }
  Commit(tmp, path);
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
