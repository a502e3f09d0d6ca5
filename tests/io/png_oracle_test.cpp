// PNG through libpng (io/png_codec.cpp) against OpenImageIO 2.4, the library that did this
// work before issue #41: the writer's bytes must equal OIIO's writer's bytes for the spec
// aalab used to give it (io/image_io.cpp's old Encode, rebuilt here), and the reader must give
// OIIO's reads (channel names, counts, values, 8-bit codes, header facts, first error line) for
// PNGs of every kind, written here with libpng directly (colour types, bit depths 1..16,
// palette with and without tRNS, interlaced, gAMA/sRGB/iCCP chunks).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <png.h>

#include <csetjmp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "core/error.h"
#include "io/image_info.h"
#include "io/image_io.h"
#include "io/oiio_loader.h"
#include "io/png_codec.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

fs::path Dir() {
  static const fs::path d = testenv::ScratchDir("png-oracle");
  return d;
}

std::string Bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

void Put(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

/// What aalab's Encode asked of OpenImageIO's PNG writer before issue #41.
std::string OiioEncode(int w, int h, int nc, bool sixteen, const void* data, bool filter_none,
                       const std::vector<std::pair<std::string, std::string>>* text) {
  auto out = OIIO::ImageOutput::create("x.png");
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  EXPECT_TRUE(out && out->set_ioproxy(&memory));
  const OIIO::TypeDesc type = sixteen ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(w, h, nc, type);
  spec.attribute("DateTime", "");
  if (nc == 2 || nc == 4) spec.attribute("oiio:UnassociatedAlpha", 1);
  if (filter_none) spec.attribute("png:filter", 0x08);
  if (text) {
    for (const auto& [key, value] : *text) spec.attribute(key, value);
  }
  EXPECT_TRUE(out->open("x.png", spec) && out->write_image(type, data) && out->close()) << out->geterror();
  return std::string(bytes.begin(), bytes.end());
}

/// Samples of one of four kinds: random, flat, a gradient over both axes, sparse (mostly 0).
std::vector<uint16_t> Samples(int kind, int w, int h, int nc, bool sixteen, unsigned seed) {
  std::mt19937 rng(seed);
  const int top = sixteen ? 65535 : 255;
  std::vector<uint16_t> v(static_cast<size_t>(w) * h * nc);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < nc; ++c) {
        uint16_t& s = v[(static_cast<size_t>(y) * w + x) * nc + c];
        switch (kind) {
          case 0: s = static_cast<uint16_t>(rng() % (top + 1)); break;
          case 1: s = static_cast<uint16_t>(top / 3 + c); break;
          case 2: s = static_cast<uint16_t>((x * 37 + y * 11 + c * 53) % (top + 1)); break;
          default: s = static_cast<uint16_t>(rng() % 13 == 0 ? rng() % (top + 1) : 0); break;
        }
      }
    }
  }
  return v;
}

TEST(PngOracle, WriterBytesEqualOpenImageIOsWriter) {
  const std::vector<std::pair<std::string, std::string>> text = {
      {"Software", "aalab 0.1.0 (commit abc)"}, {"Comment", "line one\nline two"},           {"Artist", "someone"},
      {"software", "replaced in place"},        {"ImageDescription", "renamed Description"}, {"", "skipped"}};
  const std::vector<std::pair<int, int>> sizes = {{1, 1}, {1, 7}, {7, 1}, {13, 5}, {64, 33}, {301, 3}};
  int cases = 0;
  for (const auto& [w, h] : sizes) {
    for (int nc = 1; nc <= 4; ++nc) {
      for (bool sixteen : {false, true}) {
        for (int kind = 0; kind < 4; ++kind) {
          const auto s16 = Samples(kind, w, h, nc, sixteen, static_cast<unsigned>(w * 131 + h * 7 + nc + kind));
          std::vector<uint8_t> s8(s16.begin(), s16.end());
          const void* data = sixteen ? static_cast<const void*>(s16.data()) : s8.data();
          for (bool filter_none : {false, true}) {
            for (const auto* t : {static_cast<decltype(&text)>(nullptr), &text}) {
              std::string mine, why;
              ASSERT_TRUE(io_detail::EncodePng(w, h, nc, sixteen, data, filter_none, t, &mine, &why)) << why;
              ASSERT_EQ(mine, OiioEncode(w, h, nc, sixteen, data, filter_none, t))
                  << w << "x" << h << " nc " << nc << (sixteen ? " 16-bit" : " 8-bit") << " kind " << kind
                  << " filter_none " << filter_none << " text " << (t != nullptr);
              ++cases;
            }
          }
        }
      }
    }
  }
  EXPECT_EQ(cases, 6 * 4 * 2 * 4 * 2 * 2);
}

TEST(PngOracle, PublicWritersGiveOpenImageIOsBytesAndLoadNoModule) {
  // The user's path: WriteImage8 (RGB and RGBA, noise picks png:filter 0x08), WriteGrey8,
  // WriteImage16 and WriteImage8WithText, against the oracle on the same samples.
  Image8 img(37, 21, 4, 0);
  std::mt19937 rng(7);
  for (auto& v : img.Data()) v = static_cast<uint8_t>(rng() % 256);
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 37; ++x) img.At(x, y, 3) = 255;
  }
  std::vector<uint8_t> rgb;
  for (size_t i = 0; i < img.PixelCount(); ++i) {
    for (int c = 0; c < 3; ++c) rgb.push_back(img.Data()[i * 4 + c]);
  }
  ASSERT_EQ(ChoosePngFilter(rgb.data(), 37, 21, 3), PngFilter::kNone);
  WriteImage8((Dir() / "rgb.png").string(), img);
  EXPECT_EQ(Bytes(Dir() / "rgb.png"), OiioEncode(37, 21, 3, false, rgb.data(), true, nullptr));
  WriteImage8((Dir() / "rgba.png").string(), img, true);
  EXPECT_EQ(Bytes(Dir() / "rgba.png"), OiioEncode(37, 21, 4, false, img.Data().data(), true, nullptr));
  std::vector<uint8_t> grey(37 * 21);
  for (size_t i = 0; i < grey.size(); ++i) grey[i] = static_cast<uint8_t>(i / 37 * 9);  // rows: adaptive
  WriteGrey8((Dir() / "grey.PNG").string(), 37, 21, grey);
  EXPECT_EQ(Bytes(Dir() / "grey.PNG"), OiioEncode(37, 21, 1, false, grey.data(), false, nullptr));
  ImageF f(5, 3, 4, 0.0f);
  for (size_t i = 0; i < f.Data().size(); ++i) f.Data()[i] = static_cast<float>(i) / 61.0f;
  WriteImage16((Dir() / "sixteen.png").string(), f, 2);
  std::vector<uint16_t> s16;
  for (size_t i = 0; i < f.PixelCount(); ++i) {
    for (int c = 0; c < 2; ++c) s16.push_back(static_cast<uint16_t>(std::lround(f.Data()[i * 4 + c] * 65535.0)));
  }
  EXPECT_EQ(Bytes(Dir() / "sixteen.png"), OiioEncode(5, 3, 2, true, s16.data(), false, nullptr));
  const ImageText text = {{"Software", "aalab"}, {"Comment", "a\nb"}};
  WriteImage8WithText((Dir() / "text.png").string(), img, text);
  EXPECT_EQ(Bytes(Dir() / "text.png"), OiioEncode(37, 21, 3, false, rgb.data(), true, &text));
  // A writer setting given as text is refused, not written as something else.
  try {
    WriteImage8WithText((Dir() / "bad.png").string(), img, {{"oiio:ColorSpace", "sRGB"}});
    ADD_FAILURE() << "a writer setting as text was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("text key 'oiio:ColorSpace' is an image writer setting"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(Dir() / "bad.png"));
  EXPECT_FALSE(io_detail::OiioModuleLoaded());
}

// ---- PNGs of every kind, written with libpng -------------------------------------------

struct PngKind {
  std::string name;
  int color_type;  // PNG_COLOR_TYPE_*
  int depth;       // 1, 2, 4, 8, 16
  bool trns = false;
  bool interlace = false;
  int colour_chunk = 0;  // 0 none, 1 gAMA 0.45455, 2 sRGB, 3 iCCP, 4 gAMA 1.0
};

void WriteFailedHard(png_structp png, png_const_charp msg) {
  ADD_FAILURE() << "libpng: " << msg;
  png_longjmp(png, 1);
}

void AppendBytes(png_structp png, png_bytep d, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(d), n);
}

/// A 19x11 PNG of `k`'s kind: every sample a different, known value (codes over the whole
/// range of the depth, both axes).
std::string MakePng(const PngKind& k) {
  const int w = 19, h = 11;
  const int channels = k.color_type == PNG_COLOR_TYPE_GRAY         ? 1
                       : k.color_type == PNG_COLOR_TYPE_GRAY_ALPHA ? 2
                       : k.color_type == PNG_COLOR_TYPE_RGB        ? 3
                       : k.color_type == PNG_COLOR_TYPE_RGB_ALPHA  ? 4
                                                                   : 1;  // palette index
  const int top = (1 << k.depth) - 1;
  std::vector<std::vector<uint8_t>> rows(h);
  for (int y = 0; y < h; ++y) {
    std::vector<uint32_t> samples;
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < channels; ++c) samples.push_back(static_cast<uint32_t>((x * 7 + y * 3 + c * 5) % (top + 1)));
    }
    std::vector<uint8_t>& row = rows[y];
    if (k.depth == 16) {
      for (uint32_t s : samples) {
        const uint32_t v = s * 2654435761u >> 16;  // spread over 16 bits
        row.push_back(static_cast<uint8_t>(v >> 8));
        row.push_back(static_cast<uint8_t>(v));
      }
    } else if (k.depth == 8) {
      for (uint32_t s : samples) row.push_back(static_cast<uint8_t>(s * 37 % 256));
    } else {
      row.assign((samples.size() * k.depth + 7) / 8, 0);
      for (size_t i = 0; i < samples.size(); ++i) {
        const size_t bit = i * k.depth;
        row[bit / 8] |= static_cast<uint8_t>(samples[i] << (8 - k.depth - bit % 8));
      }
    }
  }
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, WriteFailedHard, nullptr);
  png_infop info = png_create_info_struct(png);
  std::vector<png_color> palette;
  std::vector<png_byte> alpha;
  png_color_16 trans_colour{};
  std::vector<png_bytep> pointers;
  std::string icc;
  if (setjmp(png_jmpbuf(png))) {  // NOLINT(cert-err52-cpp)
    png_destroy_write_struct(&png, &info);
    return "";
  }
  png_set_write_fn(png, &out, AppendBytes, nullptr);
  png_set_IHDR(png, info, w, h, k.depth, k.color_type, k.interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (k.color_type == PNG_COLOR_TYPE_PALETTE) {
    for (int i = 0; i <= top; ++i) {
      palette.push_back({static_cast<png_byte>(i * 41 % 256), static_cast<png_byte>(255 - i * 13 % 256),
                         static_cast<png_byte>(i * 97 % 256)});
      alpha.push_back(static_cast<png_byte>(255 - i * 29 % 256));
    }
    png_set_PLTE(png, info, palette.data(), static_cast<int>(palette.size()));
    if (k.trns) png_set_tRNS(png, info, alpha.data(), static_cast<int>(alpha.size() - 1), nullptr);
  } else if (k.trns) {
    trans_colour.gray = static_cast<png_uint_16>(3 % (top + 1));
    trans_colour.red = trans_colour.green = trans_colour.blue = static_cast<png_uint_16>(k.depth == 16 ? 0 : 0);
    png_set_tRNS(png, info, nullptr, 0, &trans_colour);
  }
  if (k.colour_chunk == 1) png_set_gAMA(png, info, 0.45455);
  if (k.colour_chunk == 2) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  if (k.colour_chunk == 4) png_set_gAMA(png, info, 1.0);
  if (k.colour_chunk == 3) {
    // A minimal (not necessarily meaningful) ICC profile: readers must not apply it.
    icc.assign(132, '\0');
    icc[3] = static_cast<char>(132);
    std::memcpy(&icc[12], "mntrRGB XYZ ", 12);
    std::memcpy(&icc[36], "acsp", 4);
    const unsigned char d50[12] = {0, 0, 0xF6, 0xD6, 0, 1, 0, 0, 0, 0, 0xD3, 0x2D};  // PCS illuminant
    std::memcpy(&icc[68], d50, 12);
    png_set_iCCP(png, info, "test", 0, reinterpret_cast<png_const_bytep>(icc.data()), 132);
  }
  png_write_info(png, info);
  for (auto& r : rows) pointers.push_back(r.data());
  png_write_image(png, pointers.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return out;
}

std::vector<PngKind> AllKinds() {
  std::vector<PngKind> kinds;
  for (int d : {1, 2, 4, 8, 16}) kinds.push_back({"grey" + std::to_string(d), PNG_COLOR_TYPE_GRAY, d});
  for (int d : {1, 2, 4, 8, 16}) kinds.push_back({"grey-trns" + std::to_string(d), PNG_COLOR_TYPE_GRAY, d, true});
  for (int d : {8, 16}) {
    kinds.push_back({"greyalpha" + std::to_string(d), PNG_COLOR_TYPE_GRAY_ALPHA, d});
    kinds.push_back({"rgb" + std::to_string(d), PNG_COLOR_TYPE_RGB, d});
    kinds.push_back({"rgb-trns" + std::to_string(d), PNG_COLOR_TYPE_RGB, d, true});
    kinds.push_back({"rgba" + std::to_string(d), PNG_COLOR_TYPE_RGB_ALPHA, d});
    kinds.push_back({"rgba-interlaced" + std::to_string(d), PNG_COLOR_TYPE_RGB_ALPHA, d, false, true});
  }
  for (int d : {1, 2, 4, 8}) {
    kinds.push_back({"palette" + std::to_string(d), PNG_COLOR_TYPE_PALETTE, d});
    kinds.push_back({"palette-trns" + std::to_string(d), PNG_COLOR_TYPE_PALETTE, d, true});
  }
  kinds.push_back({"grey-interlaced2", PNG_COLOR_TYPE_GRAY, 2, false, true});
  kinds.push_back({"palette-interlaced4", PNG_COLOR_TYPE_PALETTE, 4, true, true});
  kinds.push_back({"rgb-gama", PNG_COLOR_TYPE_RGB, 8, false, false, 1});
  kinds.push_back({"rgba-srgb", PNG_COLOR_TYPE_RGB_ALPHA, 8, false, false, 2});
  kinds.push_back({"rgba-iccp16", PNG_COLOR_TYPE_RGB_ALPHA, 16, false, false, 3});
  kinds.push_back({"greyalpha-linear", PNG_COLOR_TYPE_GRAY_ALPHA, 8, false, false, 4});
  return kinds;
}

/// OIIO's read of a file: channel names and every value as float (and as UINT8 when 8-bit),
/// alpha as stored (the hint aalab gave it).
struct OiioRead {
  std::vector<std::string> names;
  std::vector<float> values;
  std::vector<uint8_t> codes;
  bool is8 = false;
  int bits = 0;
};

OiioRead ReadWithOiio(const fs::path& p) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(p.string(), &config);
  EXPECT_TRUE(in) << OIIO::geterror();
  OiioRead r;
  if (!in) return r;
  const OIIO::ImageSpec& s = in->spec();
  r.names = s.channelnames;
  r.is8 = s.format == OIIO::TypeDesc::UINT8;
  r.bits = s.get_int_attribute("oiio:BitsPerSample", static_cast<int>(s.format.size() * 8));
  r.values.resize(s.image_pixels() * s.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, r.values.data())) << in->geterror();
  if (r.is8) {
    in = OIIO::ImageInput::open(p.string(), &config);
    r.codes.resize(s.image_pixels() * s.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::UINT8, r.codes.data()));
  }
  return r;
}

TEST(PngOracle, ReaderGivesOpenImageIOsReadsForEveryKind) {
  for (const PngKind& k : AllKinds()) {
    SCOPED_TRACE(k.name);
    const std::string bytes = MakePng(k);
    ASSERT_FALSE(bytes.empty());
    const fs::path p = Dir() / (k.name + ".png");
    Put(p, bytes);
    const OiioRead want = ReadWithOiio(p);
    const int nc = static_cast<int>(want.names.size());
    ASSERT_GE(nc, 1);
    // Channel listing and exact reads by name.
    EXPECT_EQ(ListImageChannels(p.string()), want.names);
    const ImageF got = ReadImageChannels(p.string(), want.names);
    ASSERT_EQ(got.Width(), 19);
    ASSERT_EQ(got.Height(), 11);
    ASSERT_EQ(got.Data().size(), want.values.size());
    for (size_t i = 0; i < want.values.size(); ++i) ASSERT_EQ(got.Data()[i], want.values[i]) << "value " << i;
    // ReadImage from the file and from memory: grey expanded, alpha as stored.
    const LoadedImage file = ReadImage(p.string());
    const LoadedImage mem = ReadImageFromMemory(
        "mem " + k.name + ".png", reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), kMaxImagePixels);
    EXPECT_EQ(file.file_channels, nc);
    EXPECT_EQ(file.format, "png");
    EXPECT_FALSE(file.is_float);
    EXPECT_EQ(mem.pixels.Data(), file.pixels.Data());
    const int out_nc = file.pixels.Channels();
    for (size_t px = 0; px < 19 * 11; ++px) {
      for (int c = 0; c < out_nc; ++c) {
        const int src = nc <= 2 ? (c < 3 ? 0 : 1) : c;
        ASSERT_EQ(file.pixels.Data()[px * out_nc + c], want.values[px * nc + src]) << px << " " << c;
      }
    }
    // Textures: 8-bit files keep their codes; the header says what OIIO's spec said.
    const ImageHeader head = ReadImageHeader({p.string(), nullptr, 0, ""});
    EXPECT_EQ(head.channels, nc);
    EXPECT_EQ(head.is8, want.is8);
    const TexturePixels tex =
        ReadTexturePixels({"tex", reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), ".png"});
    EXPECT_EQ(tex.is8, want.is8);
    EXPECT_EQ(tex.file_channels, nc);
    if (want.is8) {
      for (size_t px = 0; px < 19 * 11; ++px) {
        for (int c = 0; c < 4; ++c) {
          const int src = c == 3 ? (nc == 2 || nc == 4 ? nc - 1 : -1) : (nc >= 3 ? c : 0);
          ASSERT_EQ(tex.rgba8[px * 4 + c], src < 0 ? 255 : want.codes[px * nc + src]) << px << " " << c;
        }
      }
    }
    const ImageFileInfo info = ProbeImage(p.string());
    EXPECT_EQ(info.bits, want.bits);
    EXPECT_EQ(info.channels, nc);
    EXPECT_EQ(info.format, "png");
    EXPECT_FALSE(info.is_float);
  }
  EXPECT_FALSE(io_detail::OiioModuleLoaded());
}

TEST(PngOracle, EightBitTableIsOpenImageIOsConversion) {
  std::array<uint8_t, 256> codes{};
  for (int i = 0; i < 256; ++i) codes[static_cast<size_t>(i)] = static_cast<uint8_t>(i);
  std::array<float, 256> want{};
  OIIO::convert_pixel_values(OIIO::TypeDesc::UINT8, codes.data(), OIIO::TypeDesc::FLOAT, want.data(), 256);
  for (int i = 0; i < 256; ++i) EXPECT_EQ(Unorm8FloatTable()[i], want[static_cast<size_t>(i)]) << i;
}

/// The first line of OIIO's message for a file it fails to open or read (aalab's message
/// quotes that first line).
std::string OiioFirstError(const fs::path& p) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(p.string(), &config);
  std::string all;
  if (!in) {
    all = OIIO::geterror();
  } else {
    std::vector<float> v(in->spec().image_pixels() * in->spec().nchannels);
    if (in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, v.data()) && !in->has_error()) return "";
    all = in->geterror();
  }
  return all.substr(0, all.find('\n'));
}

TEST(PngOracle, BrokenFilesGiveOpenImageIOsFirstMessage) {
  const std::string good = MakePng({"rgb", PNG_COLOR_TYPE_RGB, 8});
  std::string bad_crc = good;
  bad_crc[bad_crc.size() - 20] ^= 0x55;  // inside IDAT
  std::string bad_sig = good;
  bad_sig[1] = 'Q';
  std::string bad_ihdr = good;
  bad_ihdr[16 + 8] = 3;  // bit depth 3
  // No IDAT at all (a file cut inside a chunk never reaches a decoder: the chunk check refuses it).
  const size_t idat = good.find("IDAT") - 4;
  const uint32_t idat_len =
      static_cast<uint32_t>(static_cast<uint8_t>(good[idat]) << 24 | static_cast<uint8_t>(good[idat + 1]) << 16 |
                            static_cast<uint8_t>(good[idat + 2]) << 8 | static_cast<uint8_t>(good[idat + 3]));
  const std::string no_idat = good.substr(0, idat) + good.substr(idat + 12 + idat_len);
  const std::vector<std::pair<std::string, std::string>> files = {
      {"no-idat", no_idat}, {"data", bad_crc}, {"signature", bad_sig}, {"ihdr", bad_ihdr}};
  for (const auto& [name, bytes] : files) {
    SCOPED_TRACE(name);
    const fs::path p = Dir() / ("broken-" + name + ".png");
    Put(p, bytes);
    const std::string want = OiioFirstError(p);
    ASSERT_FALSE(want.empty());
    std::string got;
    try {
      ReadImage(p.string());
    } catch (const UserError& e) {
      got = e.what();
    }
    EXPECT_NE(got.find("'" + p.string() + "'"), std::string::npos) << got;
    EXPECT_NE(got.find(want), std::string::npos) << "aalab: " << got << "\nOIIO: " << want;
  }
}

}  // namespace
}  // namespace aalab
