// The OpenImageIO back end of io/ (io/image_decoder.h's OiioModuleApi), built as the MODULE
// library aalab_io_oiio and loaded by io/oiio_loader.cpp the first time a command reads or
// writes a format other than PNG (EXR, TIFF, JPEG, HDR) or draws text. Linking OpenImageIO
// into aalab itself cost every process ~0.5 s of start-up (260 shared libraries, 157k symbol
// relocations); PNG, the format of every file a run writes, goes through libpng directly
// (io/png_codec.cpp). Nothing here throws across the module's boundary: errors are strings.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <exception>

#include "io/image_decoder.h"

namespace aalab::io_detail {
namespace {

bool IsFloatType(OIIO::TypeDesc t) {
  return t.basetype == OIIO::TypeDesc::FLOAT || t.basetype == OIIO::TypeDesc::HALF ||
         t.basetype == OIIO::TypeDesc::DOUBLE;
}

PartSpec ToPart(const OIIO::ImageSpec& s) {
  PartSpec p;
  p.x = s.x, p.y = s.y, p.z = s.z;
  p.width = s.width, p.height = s.height, p.depth = s.depth;
  p.nchannels = s.nchannels;
  p.tile_width = s.tile_width, p.tile_height = s.tile_height;
  p.deep = s.deep;
  p.is_uint8 = s.format == OIIO::TypeDesc::UINT8;
  p.float_format = IsFloatType(s.format);
  // Files with fewer bits than their sample type (a 12-bit TIFF) say so in oiio:BitsPerSample.
  p.bits = s.get_int_attribute("oiio:BitsPerSample", static_cast<int>(s.format.size() * 8));
  p.compression = s.get_string_attribute("compression", "none");
  p.subimage_name = s.get_string_attribute("oiio:subimagename");
  for (int c = 0; c < s.nchannels; ++c) {
    p.channel_names.push_back(c < static_cast<int>(s.channelnames.size()) ? s.channelnames[c] : "");
    p.channel_float.push_back(IsFloatType(s.channelformat(c)) ? 1 : 0);
  }
  return p;
}

class OiioDecoder final : public ImageDecoder {
 public:
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;  // outlives `in`
  std::unique_ptr<OIIO::ImageInput> in;
  std::vector<PartSpec> parts;
  std::string format;

  std::string FormatName() const override { return format; }
  const std::vector<PartSpec>& Parts() const override { return parts; }
  bool ReadRows(int part, int y0, int y1, int cb, int ce, void* dst, bool as_uint8) override {
    const PartSpec& s = parts[static_cast<size_t>(part)];
    const OIIO::TypeDesc type = as_uint8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    if (s.tile_width > 0) {
      return in->read_tiles(part, 0, s.x, s.x + s.width, s.y + y0, s.y + y1, s.z, s.z + 1, cb, ce, type, dst);
    }
    return in->read_scanlines(part, 0, s.y + y0, s.y + y1, s.z, cb, ce, type, dst);
  }
  bool HasError() const override { return in->has_error(); }
  std::string TakeErrors() override { return in->geterror(); }
  void Close() override { in->close(); }
};

std::unique_ptr<ImageDecoder> Open(const std::string& name, const uint8_t* data, size_t size, std::string* error) {
  try {
    auto f = std::make_unique<OiioDecoder>();
    if (data) f->memory = std::make_unique<OIIO::Filesystem::IOMemReader>(data, size);
    // Only the reader the extension names. By default OpenImageIO hands a file its reader
    // rejects to every other format plugin (DICOM, FITS, OpenVDB, video, ...): found by
    // fuzzing, a corrupt .exr then loaded ~2 GB of libraries and parsers aalab never needs.
    static const bool kOnlyTheNamedReader = OIIO::attribute("try_all_readers", 0);
    (void)kOnlyTheNamedReader;
    // Values as stored: without this hint OpenImageIO 2.4 multiplies the alpha of TIFF files
    // with unassociated alpha into their colour channels on read.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    if (f->memory) {
      // OIIO 2.4's readers take the proxy from the open() config (they reset it otherwise).
      void* proxy = f->memory.get();
      config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    }
    f->in = OIIO::ImageInput::open(name, &config, f->memory.get());
    if (!f->in) {
      *error = OIIO::geterror();
      return nullptr;
    }
    f->format = f->in->format_name();
    f->parts.push_back(ToPart(f->in->spec()));
    // Several parts only for multi-part EXR (a TIFF's further pages are not parts of one image).
    if (f->format == "openexr") {
      for (int s = 1; s < 1024 && f->in->seek_subimage(s, 0); ++s) f->parts.push_back(ToPart(f->in->spec()));
      f->in->seek_subimage(0, 0);
      (void)f->in->geterror();  // seeking past the last part leaves a message
    }
    return f;
  } catch (const std::exception& e) {
    *error = e.what();
    return nullptr;
  }
}

bool Encode(const std::string& path, int w, int h, int nc, SampleType sample, const void* data, bool filter_none,
            const std::vector<std::pair<std::string, std::string>>* text, std::string* bytes, std::string* error) {
  try {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
      *error = "unknown image format (use .png, .jpg, .tif or .exr)";
      return false;
    }
    std::vector<unsigned char> buffer;
    OIIO::Filesystem::IOVecOutput memory(buffer);
    if (!out->set_ioproxy(&memory)) {
      *error = "the image library cannot encode this format in memory";
      return false;
    }
    const OIIO::TypeDesc type = sample == SampleType::kUint8    ? OIIO::TypeDesc::UINT8
                                : sample == SampleType::kUint16 ? OIIO::TypeDesc::UINT16
                                                                : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(w, h, nc, type);
    // OpenImageIO stamps EXR and TIFF files with the current time unless DateTime is set; an
    // empty value writes none, so the same pixels always give the same bytes (determinism).
    spec.attribute("DateTime", "");
    // Alpha as given (a TIFF with 2 or 4 channels would otherwise be divided by alpha).
    if (nc == 2 || nc == 4) spec.attribute("oiio:UnassociatedAlpha", 1);
    // As the PNG writer's spec had it (the other writers store no png: attribute).
    if (filter_none) spec.attribute("png:filter", 0x08);
    if (text) {
      for (const auto& [key, value] : *text) spec.attribute(key, value);
    }
    if (!out->open(path, spec) || !out->write_image(type, data) || !out->close() || buffer.empty()) {
      const std::string why = out->geterror();
      *error = why.empty() ? "the image library failed without saying why" : why;
      return false;
    }
    bytes->assign(buffer.begin(), buffer.end());
    return true;
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
}

bool DrawText(uint8_t* rgba, int w, int h, int x, int y, const std::string& text, int size_px, const std::string& font,
              std::string* error) {
  try {
    OIIO::ImageSpec spec(w, h, 4, OIIO::TypeDesc::UINT8);
    OIIO::ImageBuf buf(spec, rgba);
    const float black[] = {0, 0, 0, 1};
    if (!OIIO::ImageBufAlgo::render_text(buf, x, y, text, size_px, font, black)) {
      *error = buf.geterror();
      return false;
    }
    return true;
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
}

const OiioModuleApi kApi = {kOiioModuleAbi, Open, Encode, DrawText};

}  // namespace
}  // namespace aalab::io_detail

extern "C" __attribute__((visibility("default"))) const aalab::io_detail::OiioModuleApi* aalab_io_oiio_api() {
  return &aalab::io_detail::kApi;
}
