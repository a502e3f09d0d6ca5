#include "harness/io/image_info.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <vector>

#include "harness/core/error.h"

namespace aalab {

std::string ImageFileInfo::Describe() const {
  return std::to_string(bits) + "-bit " + (is_float ? "float" : "integer");
}

ImageFileInfo ProbeImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw UserError("cannot read image '" + path + "': " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  ImageFileInfo info;
  info.width = spec.width;
  info.height = spec.height;
  info.channels = spec.nchannels;
  info.format = in->format_name();
  const auto base = spec.format.basetype;
  info.is_float = base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::DOUBLE;
  // Files with fewer bits than their sample type (a 1-, 2- or 4-bit PNG, a 12-bit TIFF) say so
  // in oiio:BitsPerSample; OpenImageIO hands out their samples widened to the type.
  info.bits = spec.get_int_attribute("oiio:BitsPerSample", static_cast<int>(spec.format.size() * 8));
  in->close();
  return info;
}

void WriteImage16(const std::string& path, const ImageF& img, int channels) {
  namespace fs = std::filesystem;
  AALAB_CHECK(channels >= 1 && channels <= 4 && channels <= img.Channels(), "WriteImage16: bad channel count");
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png" && ext != ".tif" && ext != ".tiff") {
    throw UserError("cannot write '" + path + "': 16-bit images are written as .png, .tif or .tiff");
  }
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent)) {
    throw UserError("cannot write '" + path + "': directory '" + parent.string() + "' does not exist");
  }
  std::vector<uint16_t> data(img.PixelCount() * static_cast<size_t>(channels));
  for (size_t i = 0; i < img.PixelCount(); ++i) {
    for (int c = 0; c < channels; ++c) {
      const float v = std::clamp(img.Data()[i * img.Channels() + c], 0.0f, 1.0f);
      data[i * channels + c] = static_cast<uint16_t>(std::lround(static_cast<double>(v) * 65535.0));
    }
  }
  const std::string tmp = (parent / (".tmp-" + fs::path(path).stem().string() + ext)).string();
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw UserError("cannot write '" + path + "': no writer for this file type");
  OIIO::ImageSpec spec(img.Width(), img.Height(), channels, OIIO::TypeDesc::UINT16);
  spec.attribute("DateTime", "");  // no time stamp: the same pixels give the same bytes
  if (!out->open(tmp, spec) || !out->write_image(OIIO::TypeDesc::UINT16, data.data()) || !out->close()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw UserError("cannot write '" + path + "': " + out->geterror());
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw UserError("cannot write '" + path + "': " + ec.message());
  }
}

}  // namespace aalab
