#include "io/image_info.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/error.h"
#include "io/image_decoder.h"
#include "io/oiio_loader.h"
#include "io/png_codec.h"

namespace aalab {

std::string ImageFileInfo::Describe() const {
  return std::to_string(bits) + "-bit " + (is_float ? "float" : "integer");
}

ImageFileInfo ProbeImage(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string why;
  std::unique_ptr<io_detail::ImageDecoder> in =
      ext == ".png" ? io_detail::OpenPng(path, nullptr, 0, &why)
                    : io_detail::OiioModule("image '" + path + "' (" + ext + ")").open(path, nullptr, 0, &why);
  if (!in) throw UserError("cannot read image '" + path + "': " + why);
  const io_detail::PartSpec& spec = in->Parts()[0];
  ImageFileInfo info;
  info.width = spec.width;
  info.height = spec.height;
  info.channels = spec.nchannels;
  info.format = in->FormatName();
  info.is_float = spec.float_format;
  // Files with fewer bits than their sample type (a 12-bit TIFF) say so in oiio:BitsPerSample;
  // their samples are handed out widened to the type. (A 1-, 2- or 4-bit PNG reads as 8-bit.)
  info.bits = spec.bits;
  in->Close();
  return info;
}

}  // namespace aalab
