#include "harness/io/image_io.h"

#include <OpenImageIO/imageio.h>

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

void WriteRaw(const std::string& path, int w, int h, int nc, OIIO::TypeDesc type, const void* data) {
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
  if (!out->open(tmp, spec) || !out->write_image(type, data) || !out->close()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw UserError("cannot write '" + path + "': " + out->geterror());
  }
  Commit(tmp, path);
}

}  // namespace

LoadedImage ReadImage(const std::string& path, size_t max_pixels) {
  if (!fs::exists(path)) throw UserError("image '" + path + "' does not exist");
  if (fs::is_directory(path)) throw UserError("image '" + path + "' is a directory, not an image file");
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    throw UserError("cannot read image '" + path + "': " + OIIO::geterror() +
                    " (readable: PNG, JPEG, TIFF, EXR)");
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
  std::vector<float> raw(static_cast<size_t>(w) * h * nc);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, raw.data())) {
    throw UserError("cannot read image '" + path + "' (truncated or corrupt?): " + in->geterror());
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

void WriteImage8(const std::string& path, const Image8& img, bool keep_alpha) {
  AALAB_CHECK(img.Channels() == 4, "WriteImage8 expects RGBA8");
  if (keep_alpha) {
    WriteRaw(path, img.Width(), img.Height(), 4, OIIO::TypeDesc::UINT8, img.Data().data());
    return;
  }
  std::vector<uint8_t> rgb(img.PixelCount() * 3);
  for (size_t i = 0; i < img.PixelCount(); ++i) {
    for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = img.Data()[i * 4 + c];
  }
  WriteRaw(path, img.Width(), img.Height(), 3, OIIO::TypeDesc::UINT8, rgb.data());
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
