#include "io/image_info.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <vector>

#include "core/error.h"

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

}  // namespace aalab
