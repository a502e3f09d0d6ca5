// OpenEXR writing (io/exr_write.h), written from what OpenImageIO 2.4.7's EXR writer
// (src/openexr.imageio/exroutput.cpp) does with ImageSpec(w, h, nc, FLOAT) and the attributes
// DateTime "" (-> capDate ""), oiio:UnassociatedAlpha and png:filter (not stored): a display
// and data window of the image, one FLOAT channel per channel, ZIP compression at
// zipCompressionLevel 4, INCREASING_Y, written through Imf::OutputFile to a memory stream.
// Every `aalab run` writes reference.exr: with this, a run that reads no EXR/TIFF/JPEG never
// loads OpenImageIO. tests/io/exr_oracle_test.cpp compares the bytes with OIIO's writer's.
#include "io/exr_write.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <vector>

namespace aalab::io_detail {
namespace {

/// An Imf::OStream into a string (OpenEXR seeks back to fill in the line offsets).
class MemoryOStream final : public Imf::OStream {
 public:
  explicit MemoryOStream(std::string* out) : Imf::OStream("memory"), out_(out) {}
  void write(const char c[], int n) override {
    const size_t end = pos_ + static_cast<size_t>(n);
    if (out_->size() < end) out_->resize(end);
    std::memcpy(out_->data() + pos_, c, static_cast<size_t>(n));
    pos_ = end;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }

 private:
  std::string* out_;
  size_t pos_ = 0;
};

/// OIIO's ImageSpec::default_channel_names.
std::vector<std::string> ChannelNames(int nc) {
  if (nc == 1) return {"Y"};
  std::vector<std::string> names;
  static const char* const kFirst[] = {"R", "G", "B", "A"};
  for (int c = 0; c < nc; ++c) names.push_back(c < 4 ? kFirst[c] : "channel" + std::to_string(c));
  return names;
}

}  // namespace

bool EncodeExrFloat(int w, int h, int nc, const float* data, std::string* bytes, std::string* error) {
  if (w < 1 || h < 1 || nc < 1) {
    *error = "Image resolution must be at least 1x1, you asked for " + std::to_string(w) + " x " + std::to_string(h);
    return false;
  }
  try {
    const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(w - 1, h - 1));
    Imf::Header header(window, window);
    const std::vector<std::string> names = ChannelNames(nc);
    for (const auto& n : names) header.channels().insert(n.c_str(), Imf::Channel(Imf::FLOAT, 1, 1, false));
    header.compression() = Imf::ZIP_COMPRESSION;
    header.zipCompressionLevel() = 4;
    header.lineOrder() = Imf::INCREASING_Y;
    header.insert("capDate", Imf::StringAttribute(""));
    std::string out;
    {
      MemoryOStream stream(&out);
      Imf::OutputFile file(stream, header);
      Imf::FrameBuffer fb;
      const size_t pixel = sizeof(float) * static_cast<size_t>(nc);
      char* base = reinterpret_cast<char*>(const_cast<float*>(data));
      for (int c = 0; c < nc; ++c) {
        fb.insert(names[static_cast<size_t>(c)].c_str(),
                  Imf::Slice(Imf::FLOAT, base + sizeof(float) * c, pixel, pixel * static_cast<size_t>(w)));
      }
      file.setFrameBuffer(fb);
      file.writePixels(h);
    }  // the file's destructor writes the line offsets
    bytes->swap(out);
    return true;
  } catch (const std::exception& e) {
    *error = std::string("Failed OpenEXR write: ") + e.what();
    return false;
  }
}

}  // namespace aalab::io_detail
