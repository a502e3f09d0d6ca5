// PNG through libpng (io/png_codec.h), written from what OpenImageIO 2.4.7's PNG plugin does
// (src/png.imageio/pngoutput.cpp, pnginput.cpp, png_pvt.h), so that a run's files and reads
// stay what they were when OpenImageIO did this work:
//  - writing: compression level 6, Z_DEFAULT_STRATEGY, png_set_filter(0 or 0x08), an oFFs
//    chunk (0, 0, pixels), no gAMA/sRGB/iCCP/pHYs/tIME (aalab sets no colour space and an empty
//    DateTime), tEXt chunks for string attributes in attribute order (a later key replaces an
//    earlier one of the same name, ignoring case; Artist/name/DocumentName/description/
//    ImageDescription renamed Author/Title/Description), 16-bit rows big-endian, alpha as given;
//  - reading: png_set_expand (1/2/4-bit grey scaled to 8 bits, palette to RGB, tRNS to alpha),
//    16-bit kept, channels Y / Y,A / R,G,B / R,G,B,A, alpha as stored (aalab always asks OIIO
//    for unassociated alpha), gAMA/sRGB/iCCP read but never applied to the values; 8-bit code
//    k -> k * (1/255.0f), 16-bit k -> k * (1/65535.0f) (OIIO's convert_type); interlaced files
//    decoded whole on the first row asked for; messages as OIIO's ("Not a PNG file",
//    "PNG read error: ...", "Read error: hit end of file", "PNG library error").
// libpng reports errors by longjmp: each setjmp is in a small function whose locals are plain.
#include "io/png_codec.h"

#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <csetjmp>
#include <cstdio>
#include <cstring>

namespace aalab::io_detail {

namespace {

bool IEquals(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// ---- writing ------------------------------------------------------------------------------

struct WriteState {
  std::string* out = nullptr;
  std::string error;
};

void WriteBytes(png_structp png, png_bytep data, png_size_t n) {
  auto* s = static_cast<WriteState*>(png_get_io_ptr(png));
  s->out->append(reinterpret_cast<const char*>(data), n);
}
void FlushNothing(png_structp) {}
void WriteFailed(png_structp png, png_const_charp msg) {
  auto* s = static_cast<WriteState*>(png_get_error_ptr(png));
  s->error += std::string("PNG write error: ") + (msg ? msg : "");
  png_longjmp(png, 1);
}
void IgnoreWarning(png_structp, png_const_charp) {}

/// The text chunks OIIO writes for the attributes DateTime "" (none), oiio:UnassociatedAlpha
/// and png:filter (ints: none) followed by `text`.
bool TextChunks(const std::vector<std::pair<std::string, std::string>>* text,
                std::vector<std::pair<std::string, std::string>>* chunks, std::string* error) {
  // Settings OpenImageIO's writer would act on rather than store: refused (aalab sets none).
  static const char* const kSettings[] = {"DateTime",
                                          "oiio:UnassociatedAlpha",
                                          "png:filter",
                                          "oiio:ColorSpace",
                                          "oiio:Gamma",
                                          "ICCProfile",
                                          "ResolutionUnit",
                                          "XResolution",
                                          "YResolution",
                                          "PixelAspectRatio",
                                          "png:compressionLevel",
                                          "compression",
                                          "planarconfig",
                                          "oiio:dither",
                                          "oiio:ioproxy"};
  if (!text) return true;
  for (const auto& [key, value] : *text) {
    for (const char* s : kSettings) {
      if (IEquals(key, s)) {
        *error = "text key '" + key + "' is an image writer setting, not text";
        return false;
      }
    }
    if (key.empty()) continue;  // OIIO ignores an attribute without a name
    auto it = std::find_if(chunks->begin(), chunks->end(), [&](const auto& c) { return IEquals(c.first, key); });
    if (it != chunks->end()) {
      *it = {key, value};
    } else {
      chunks->push_back({key, value});
    }
  }
  for (auto& c : *chunks) {
    if (IEquals(c.first, "Artist")) c.first = "Author";
    if (IEquals(c.first, "name") || IEquals(c.first, "DocumentName")) c.first = "Title";
    if (IEquals(c.first, "description") || IEquals(c.first, "ImageDescription")) c.first = "Description";
  }
  return true;
}

/// The libpng calls, under one setjmp. `rows` holds the rows as PNG stores them.
bool WritePng(png_structp png, png_infop info, int w, int h, int nc, int bits, bool filter_none,
              std::vector<png_text>* text, const std::vector<uint8_t>* rows, size_t row_bytes) {
  if (setjmp(png_jmpbuf(png))) return false;  // NOLINT(cert-err52-cpp)
  static const int kColor[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                               PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_compression_level(png, 6);
  png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
  png_set_filter(png, 0, filter_none ? PNG_FILTER_NONE : PNG_NO_FILTERS);
#if defined(PNG_SKIP_sRGB_CHECK_PROFILE) && defined(PNG_SET_OPTION_SUPPORTED)
  png_set_option(png, PNG_SKIP_sRGB_CHECK_PROFILE, PNG_OPTION_ON);
#endif
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), bits, kColor[nc - 1],
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_oFFs(png, info, 0, 0, PNG_OFFSET_PIXEL);
  if (!text->empty()) png_set_text(png, info, text->data(), static_cast<int>(text->size()));
  png_write_info(png, info);
  png_set_packing(png);
  for (int y = 0; y < h; ++y) {
    png_write_row(png, const_cast<png_bytep>(rows->data() + static_cast<size_t>(y) * row_bytes));
  }
  png_write_end(png, info);
  return true;
}

// ---- reading ------------------------------------------------------------------------------

class PngDecoder final : public ImageDecoder {
 public:
  ~PngDecoder() override { Close(); }

  bool Open(const std::string& path, const uint8_t* data, size_t size);
  std::string FormatName() const override { return "png"; }
  const std::vector<PartSpec>& Parts() const override { return parts_; }
  bool ReadRows(int part, int y0, int y1, int cb, int ce, void* dst, bool as_uint8) override;
  bool HasError() const override { return !errors_.empty(); }
  std::string TakeErrors() override {
    std::string e;
    e.swap(errors_);
    return e;
  }
  void Close() override {
    if (png_) png_destroy_read_struct(&png_, info_ ? &info_ : nullptr, nullptr);
    png_ = nullptr;
    info_ = nullptr;
    if (file_) std::fclose(file_);
    file_ = nullptr;
  }

  void AddError(const std::string& m) {
    if (!errors_.empty() && errors_.back() != '\n') errors_ += '\n';
    errors_ += m;
  }

  // The byte source: a FILE or memory.
  FILE* file_ = nullptr;
  const uint8_t* mem_ = nullptr;
  size_t mem_size_ = 0, mem_pos_ = 0;

 private:
  bool ReadInfo();
  bool ReadOneRow(uint8_t* row);
  bool ReadWhole();

  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
  std::vector<PartSpec> parts_;
  std::string errors_;
  int next_row_ = 0;
  bool interlaced_ = false;
  size_t row_bytes_ = 0;
  std::vector<uint8_t> row_;
  std::vector<uint8_t> whole_;
  std::vector<png_bytep> row_pointers_;
};

void ReadBytes(png_structp png, png_bytep out, png_size_t n) {
  auto* d = static_cast<PngDecoder*>(png_get_io_ptr(png));
  size_t got = 0;
  if (d->file_) {
    got = std::fread(out, 1, n, d->file_);
  } else {
    got = std::min(n, d->mem_size_ - d->mem_pos_);
    std::memcpy(out, d->mem_ + d->mem_pos_, got);
    d->mem_pos_ += got;
  }
  if (got != n) {
    // OIIO's ImageInput::ioread, then png_chunk_error with the messages so far.
    d->AddError("Read error: hit end of file");
    png_chunk_error(png, "Read error: hit end of file");
  }
}

void ReadFailed(png_structp png, png_const_charp msg) {
  auto* d = static_cast<PngDecoder*>(png_get_error_ptr(png));
  d->AddError(std::string("PNG read error: ") + (msg ? msg : ""));
  png_longjmp(png, 1);
}

bool PngDecoder::ReadInfo() {
  if (setjmp(png_jmpbuf(png_))) return false;  // NOLINT(cert-err52-cpp)
  png_read_info(png_, info_);
  png_set_expand(png_);
  png_set_swap(png_);  // 16-bit samples to host order (little-endian hosts only build this)
  png_read_update_info(png_, info_);
  png_uint_32 w = 0, h = 0;
  int depth = 0, color = 0, interlace = 0;
  png_get_IHDR(png_, info_, &w, &h, &depth, &color, &interlace, nullptr, nullptr);
  PartSpec p;
  p.width = static_cast<int>(w);
  p.height = static_cast<int>(h);
  p.nchannels = png_get_channels(png_, info_);
  p.is_uint8 = depth != 16;
  p.bits = depth == 16 ? 16 : 8;
  p.x = png_get_x_offset_pixels(png_, info_);
  p.y = png_get_y_offset_pixels(png_, info_);
  static const char* const kNames[4][4] = {{"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
  for (int c = 0; c < p.nchannels && p.nchannels <= 4; ++c) p.channel_names.push_back(kNames[p.nchannels - 1][c]);
  p.channel_float.assign(static_cast<size_t>(p.nchannels), 0);
  interlaced_ = interlace != PNG_INTERLACE_NONE;
  row_bytes_ = png_get_rowbytes(png_, info_);
  parts_ = {p};
  return true;
}

bool PngDecoder::Open(const std::string& path, const uint8_t* data, size_t size) {
  uint8_t sig[8] = {};
  if (data) {
    mem_ = data;
    mem_size_ = size;
    if (size >= 8) std::memcpy(sig, data, 8);
    if (size < 8 || png_sig_cmp(sig, 0, 7) != 0) return AddError("Not a PNG file"), false;
  } else {
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) return AddError("Could not open file \"" + path + "\""), false;
    if (std::fread(sig, 1, 8, file_) != 8 || png_sig_cmp(sig, 0, 7) != 0) return AddError("Not a PNG file"), false;
    std::rewind(file_);
  }
  png_ = png_create_read_struct(PNG_LIBPNG_VER_STRING, this, ReadFailed, IgnoreWarning);
  if (!png_) return AddError("Could not create PNG read structure"), false;
  info_ = png_create_info_struct(png_);
  if (!info_) return AddError("Could not create PNG info structure"), false;
  png_set_read_fn(png_, this, ReadBytes);
  if (!ReadInfo()) {
    if (errors_.empty()) AddError("Could not read info from file");
    return false;
  }
  if (parts_[0].nchannels < 1 || parts_[0].nchannels > 4) return AddError("PNG library error"), false;
  return true;
}

bool PngDecoder::ReadOneRow(uint8_t* row) {
  if (setjmp(png_jmpbuf(png_))) return false;  // NOLINT(cert-err52-cpp)
  png_read_row(png_, row, nullptr);
  return true;
}

bool PngDecoder::ReadWhole() {
  if (setjmp(png_jmpbuf(png_))) return false;  // NOLINT(cert-err52-cpp)
  png_read_image(png_, row_pointers_.data());
  png_read_end(png_, nullptr);
  return true;
}

bool PngDecoder::ReadRows(int part, int y0, int y1, int cb, int ce, void* dst, bool as_uint8) {
  const PartSpec& p = parts_[0];
  if (part != 0 || !png_ || y0 < next_row_ || y1 > p.height || cb < 0 || ce > p.nchannels || cb >= ce ||
      (as_uint8 && !p.is_uint8)) {
    AddError("PNG rows read out of order or out of range");
    return false;
  }
  const int nc = p.nchannels, span = ce - cb;
  const size_t w = static_cast<size_t>(p.width);
  if (interlaced_ && whole_.empty()) {
    // Interlaced: the whole image at once (OIIO does the same); its size was checked by the caller.
    whole_.resize(row_bytes_ * static_cast<size_t>(p.height));
    row_pointers_.resize(static_cast<size_t>(p.height));
    for (int y = 0; y < p.height; ++y) row_pointers_[static_cast<size_t>(y)] = whole_.data() + row_bytes_ * y;
    if (!ReadWhole()) {
      AddError("PNG library error");
      return false;
    }
  }
  row_.resize(row_bytes_);
  for (int y = y0; y < y1; ++y) {
    const uint8_t* src = nullptr;
    if (interlaced_) {
      src = whole_.data() + row_bytes_ * static_cast<size_t>(y);
    } else {
      while (next_row_ <= y) {
        if (!ReadOneRow(row_.data())) {
          AddError("PNG library error");
          return false;
        }
        ++next_row_;
      }
      src = row_.data();
    }
    const size_t out_base = static_cast<size_t>(y - y0) * w * static_cast<size_t>(span);
    if (as_uint8) {
      auto* out = static_cast<uint8_t*>(dst) + out_base;
      for (size_t x = 0; x < w; ++x) {
        for (int c = 0; c < span; ++c) out[x * span + c] = src[x * nc + cb + c];
      }
    } else if (p.is_uint8) {
      auto* out = static_cast<float*>(dst) + out_base;
      for (size_t x = 0; x < w; ++x) {
        for (int c = 0; c < span; ++c) out[x * span + c] = static_cast<float>(src[x * nc + cb + c]) * (1.0f / 255.0f);
      }
    } else {
      auto* out = static_cast<float*>(dst) + out_base;
      for (size_t x = 0; x < w; ++x) {
        for (int c = 0; c < span; ++c) {
          uint16_t v = 0;
          std::memcpy(&v, src + 2 * (x * nc + cb + c), 2);
          out[x * span + c] = static_cast<float>(v) * (1.0f / 65535.0f);
        }
      }
    }
  }
  if (interlaced_) next_row_ = y1;
  return true;
}

}  // namespace

bool EncodePng(int w, int h, int nc, bool sixteen, const void* data, bool filter_none,
               const std::vector<std::pair<std::string, std::string>>* text, std::string* bytes, std::string* error) {
  if (w < 1 || h < 1) {
    *error = "Image resolution must be at least 1x1, you asked for " + std::to_string(w) + " x " + std::to_string(h);
    return false;
  }
  if (nc < 1 || nc > 4) {
    *error = "PNG only supports 1-4 channels, not " + std::to_string(nc);
    return false;
  }
  std::vector<std::pair<std::string, std::string>> chunks;
  if (!TextChunks(text, &chunks, error)) return false;
  std::vector<png_text> png_text_list(chunks.size());
  for (size_t i = 0; i < chunks.size(); ++i) {
    png_text& t = png_text_list[i];
    std::memset(&t, 0, sizeof t);
    t.compression = PNG_TEXT_COMPRESSION_NONE;
    t.key = const_cast<char*>(chunks[i].first.c_str());
    t.text = const_cast<char*>(chunks[i].second.c_str());
  }
  // The rows as PNG stores them: 16-bit samples big-endian.
  const size_t row_bytes = static_cast<size_t>(w) * nc * (sixteen ? 2 : 1);
  std::vector<uint8_t> rows(row_bytes * static_cast<size_t>(h));
  if (sixteen) {
    const auto* s = static_cast<const uint16_t*>(data);
    for (size_t i = 0; i < rows.size() / 2; ++i) {
      rows[2 * i] = static_cast<uint8_t>(s[i] >> 8);
      rows[2 * i + 1] = static_cast<uint8_t>(s[i] & 0xff);
    }
  } else {
    std::memcpy(rows.data(), data, rows.size());
  }
  WriteState state;
  std::string out;
  state.out = &out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, WriteFailed, IgnoreWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    if (png) png_destroy_write_struct(&png, nullptr);
    *error = "Could not create PNG write structure";
    return false;
  }
  png_set_write_fn(png, &state, WriteBytes, FlushNothing);
  const bool ok = WritePng(png, info, w, h, nc, sixteen ? 16 : 8, filter_none, &png_text_list, &rows, row_bytes);
  png_destroy_write_struct(&png, &info);
  if (!ok) {
    *error = state.error.empty() ? "PNG library error" : state.error;
    return false;
  }
  bytes->swap(out);
  return true;
}

std::unique_ptr<ImageDecoder> OpenPng(const std::string& path, const uint8_t* data, size_t size, std::string* error) {
  auto d = std::make_unique<PngDecoder>();
  if (!d->Open(path, data, size)) {
    *error = d->TakeErrors();
    return nullptr;
  }
  return d;
}

}  // namespace aalab::io_detail
