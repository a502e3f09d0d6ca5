// The one image reader: channels by name, alpha as stored, only regular files, declared
// sizes checked before large allocations. Test files are written with OpenImageIO directly
// (not through aalab's writers), so what is on disk is known independently of the reader.
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <iterator>
#include <limits>

#include "core/error.h"
#include "io/image_io.h"
#include "io/safe_path.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

fs::path Dir() {
  static const fs::path d = testenv::ScratchDir("read");
  return d;
}

/// Writes `data` (w×h×names.size() values) with the channel names given, in that order.
void WriteWithOiio(const fs::path& p, int w, int h, const std::vector<std::string>& names, OIIO::TypeDesc type,
                   const std::vector<float>& data, const std::vector<std::pair<std::string, int>>& attrs = {}) {
  OIIO::ImageSpec spec(w, h, static_cast<int>(names.size()), type);
  spec.channelnames = names;
  spec.alpha_channel = -1;
  for (size_t c = 0; c < names.size(); ++c) {
    if (names[c] == "A") spec.alpha_channel = static_cast<int>(c);
  }
  for (const auto& [k, v] : attrs) spec.attribute(k, v);
  auto out = OIIO::ImageOutput::create(p.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(p.string(), spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, data.data())) << out->geterror();
  ASSERT_TRUE(out->close());
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(ImageRead, AlphaIsNeverMultipliedIntoColour) {
  // One pixel per alpha: 0, 254, 255; colour 200/255, 100/255, 50/255 in every pixel. Read
  // raw, every colour must be k/255 exactly whatever the alpha (premultiplied, alpha 0 would
  // give black and alpha 254 would give 199.2/255).
  const std::vector<float> alphas = {0.0f, 254.0f / 255, 1.0f};
  std::vector<float> px;
  for (float a : alphas) px.insert(px.end(), {200.0f / 255, 100.0f / 255, 50.0f / 255, a});
  // PNG is unassociated by definition; TIFF marked unassociated (ExtraSamples = 2).
  WriteWithOiio(Dir() / "alpha.png", 3, 1, {"R", "G", "B", "A"}, OIIO::TypeDesc::UINT8, px,
                {{"oiio:UnassociatedAlpha", 1}});
  WriteWithOiio(Dir() / "alpha.tif", 3, 1, {"R", "G", "B", "A"}, OIIO::TypeDesc::UINT8, px,
                {{"oiio:UnassociatedAlpha", 1}});
  for (const std::string name : {"alpha.png", "alpha.tif"}) {
    const LoadedImage img = ReadImage((Dir() / name).string());
    ASSERT_EQ(img.pixels.Channels(), 4) << name;
    EXPECT_EQ(img.file_channels, 4);
    for (int x = 0; x < 3; ++x) {
      EXPECT_NEAR(img.pixels.At(x, 0, 0), 200.0 / 255, 1e-6) << name << " alpha " << alphas[x];
      EXPECT_NEAR(img.pixels.At(x, 0, 1), 100.0 / 255, 1e-6) << name;
      EXPECT_NEAR(img.pixels.At(x, 0, 2), 50.0 / 255, 1e-6) << name;
      EXPECT_NEAR(img.pixels.At(x, 0, 3), alphas[x], 1e-6) << name;
    }
    const Image8 q = ReadImage8((Dir() / name).string());
    EXPECT_EQ(q.At(0, 0, 0), 200);
    EXPECT_EQ(q.At(0, 0, 3), 0);
    EXPECT_EQ(q.At(1, 0, 3), 254);
  }
}

TEST(ImageRead, AlphaIsWrittenAsGiven) {
  // WriteImage8 with alpha: colour bytes stored as given (OpenImageIO's PNG writer would
  // divide them by alpha unless told the alpha is unassociated).
  Image8 img(2, 1, 4, 0);
  img.At(0, 0, 0) = 200, img.At(0, 0, 3) = 0;
  img.At(1, 0, 0) = 100, img.At(1, 0, 3) = 128;
  for (const std::string name : {"given.png", "given.tif"}) {
    WriteImage8((Dir() / name).string(), img, true);
    EXPECT_EQ(ReadImage8((Dir() / name).string()), img) << name;
  }
}

TEST(ImageRead, ChannelsAreTakenByNameNotPosition) {
  // Written in the order B, Z, R, G (OpenEXR stores channels sorted by name): colour must come
  // from the names. Z holds +Inf (a depth background) and is not read for colour.
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> px = {0.3f, inf, 0.1f, 0.2f, 0.3f, 5.0f, 0.1f, 0.2f};
  for (const std::string name : {"bzrg.exr"}) {
    WriteWithOiio(Dir() / name, 2, 1, {"B", "Z", "R", "G"}, OIIO::TypeDesc::FLOAT, px);
    const LoadedImage img = ReadImage((Dir() / name).string());
    ASSERT_EQ(img.pixels.Channels(), 3) << name;
    EXPECT_EQ(img.file_channels, 3);
    EXPECT_TRUE(img.is_float);
    for (int x = 0; x < 2; ++x) {
      EXPECT_EQ(img.pixels.At(x, 0, 0), 0.1f) << name;
      EXPECT_EQ(img.pixels.At(x, 0, 1), 0.2f) << name;
      EXPECT_EQ(img.pixels.At(x, 0, 2), 0.3f) << name;
    }
    // The exact channels asked for, in the order asked for; Inf only where allowed.
    const std::vector<std::string> listed = ListImageChannels((Dir() / name).string());
    EXPECT_EQ(listed.size(), 4u);
    const ImageF gz = ReadImageChannels((Dir() / name).string(), {"G", "Z"}, kMaxImagePixels, true);
    ASSERT_EQ(gz.Channels(), 2);
    EXPECT_EQ(gz.At(0, 0, 0), 0.2f);
    EXPECT_EQ(gz.At(0, 0, 1), inf);
    EXPECT_EQ(gz.At(1, 0, 1), 5.0f);
    const std::string e = ErrorOf([&] { ReadImageChannels((Dir() / name).string(), {"G", "Z"}); });
    EXPECT_NE(e.find("non-finite value (Inf) at pixel (0, 0) channel 1 (Z)"), std::string::npos) << e;
    const std::string m = ErrorOf([&] { ReadImageChannels((Dir() / name).string(), {"R", "depth"}); });
    EXPECT_NE(m.find("has no channel 'depth' (its channels: "), std::string::npos) << m;
    EXPECT_NE(m.find(name), std::string::npos) << m;
  }
  // NaN is refused even where Inf is allowed.
  WriteWithOiio(Dir() / "nanz.exr", 1, 1, {"Z"}, OIIO::TypeDesc::FLOAT, {std::nanf("")});
  EXPECT_NE(ErrorOf([&] {
              ReadImageChannels((Dir() / "nanz.exr").string(), {"Z"}, kMaxImagePixels, true);
            }).find("(NaN) at pixel (0, 0) channel 0 (Z); NaN pixels are rejected"),
            std::string::npos);
  // A renderer's usual R, G, B, A, Z: colour and alpha read, Z ignored.
  WriteWithOiio(Dir() / "rgbaz.exr", 1, 1, {"R", "G", "B", "A", "Z"}, OIIO::TypeDesc::HALF,
                {0.25f, 0.5f, 0.75f, 0.5f, inf});
  const LoadedImage rgbaz = ReadImage((Dir() / "rgbaz.exr").string());
  ASSERT_EQ(rgbaz.pixels.Channels(), 4);
  EXPECT_EQ(rgbaz.pixels.At(0, 0, 0), 0.25f);
  EXPECT_EQ(rgbaz.pixels.At(0, 0, 2), 0.75f);
  EXPECT_EQ(rgbaz.pixels.At(0, 0, 3), 0.5f);
  // Grey + alpha (Y, A): grey expanded to RGB, alpha kept as stored.
  WriteWithOiio(Dir() / "ya.png", 1, 1, {"Y", "A"}, OIIO::TypeDesc::UINT16, {0.5f, 0.0f},
                {{"oiio:UnassociatedAlpha", 1}});
  const LoadedImage ya = ReadImage((Dir() / "ya.png").string());
  ASSERT_EQ(ya.pixels.Channels(), 4);
  EXPECT_EQ(ya.file_channels, 2);
  EXPECT_NEAR(ya.pixels.At(0, 0, 1), 32768.0 / 65535, 1e-6);  // 0.5 stored as round(0.5 · 65535)
  EXPECT_EQ(ya.pixels.At(0, 0, 3), 0.0f);
  // No R, G, B: refused, naming what the file has.
  WriteWithOiio(Dir() / "xyz.exr", 1, 1, {"X", "Y", "Z"}, OIIO::TypeDesc::FLOAT, {1, 2, 3});
  const std::string e = ErrorOf([&] { ReadImage((Dir() / "xyz.exr").string()); });
  EXPECT_NE(
      e.find("image '" + (Dir() / "xyz.exr").string() + "' has no channels named R, G and B (its channels: X, Y, Z)"),
      std::string::npos)
      << e;
  WriteWithOiio(Dir() / "uvw.exr", 1, 1, {"U", "V", "W"}, OIIO::TypeDesc::FLOAT, {1, 2, 3});
  const std::string u = ErrorOf([&] { ReadImage((Dir() / "uvw.exr").string()); });
  EXPECT_NE(u.find("has no channels named R, G and B (its channels: U, V, W)"), std::string::npos) << u;
}

TEST(ImageRead, MultiPartExrListsEveryPartsChannelsWithItsName) {
  const fs::path p = Dir() / "parts.exr";
  std::vector<OIIO::ImageSpec> specs(2, OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::FLOAT));
  specs[0].attribute("oiio:subimagename", "beauty");
  specs[1] = OIIO::ImageSpec(2, 2, 1, OIIO::TypeDesc::FLOAT);
  specs[1].channelnames = {"Z"};
  specs[1].attribute("oiio:subimagename", "depth");
  auto out = OIIO::ImageOutput::create(p.string());
  ASSERT_TRUE(out && out->supports("multiimage"));
  ASSERT_TRUE(out->open(p.string(), 2, specs.data())) << out->geterror();
  const std::vector<float> rgb(12, 0.5f), z = {1, 2, 3, 4};
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
  ASSERT_TRUE(out->open(p.string(), specs[1], OIIO::ImageOutput::AppendSubimage));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, z.data()));
  ASSERT_TRUE(out->close());
  EXPECT_EQ(ListImageChannels(p.string()), (std::vector<std::string>{"beauty.R", "beauty.G", "beauty.B", "depth.Z"}));
  const ImageF read = ReadImageChannels(p.string(), {"depth.Z", "beauty.G"});
  ASSERT_EQ(read.Channels(), 2);
  EXPECT_EQ(read.At(1, 1, 0), 4.0f);
  EXPECT_EQ(read.At(1, 0, 0), 2.0f);
  EXPECT_EQ(read.At(1, 1, 1), 0.5f);
}

TEST(ImageRead, AFifoIsRefusedWithoutBlocking) {
  const fs::path fifo = Dir() / "frame.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto read = std::async(std::launch::async, [&] { return ErrorOf([&] { ReadImage(fifo.string()); }); });
  if (read.wait_for(std::chrono::seconds(20)) != std::future_status::ready) {
    // Unblock the reader (open for writing) so the test fails instead of hanging.
    const int fd = ::open(fifo.c_str(), O_WRONLY);
    if (fd >= 0) ::close(fd);
    FAIL() << "reading a FIFO blocked";
  }
  const std::string e = read.get();
  EXPECT_NE(e.find("is not a regular file (a FIFO, device or socket)"), std::string::npos) << e;
  fs::create_symlink("/dev/zero", Dir() / "zero.png");
  EXPECT_NE(ErrorOf([] { ListImageChannels((Dir() / "zero.png").string()); }).find("is not a regular file"),
            std::string::npos);
}

/// 69 bytes: signature, IHDR 16000x16000 RGB8, a 12-byte IDAT, IEND. Decoding it would need
/// 16000·16000·3 floats = 3 GB.
std::string HugePng() {
  auto be32 = [](uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                       static_cast<char>(v)};
  };
  auto chunk = [&be32](const std::string& type, const std::string& data) {
    uint32_t crc = 0xffffffffu;  // CRC-32 (ISO 3309) over type and data, as the PNG spec defines it
    for (unsigned char ch : type + data) {
      crc ^= ch;
      for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return be32(static_cast<uint32_t>(data.size())) + type + data + be32(~crc);
  };
  std::string png("\x89PNG\r\n\x1a\n", 8);
  png += chunk("IHDR", be32(16000) + be32(16000) + std::string("\x08\x02\x00\x00\x00", 5));
  png += chunk("IDAT", std::string("\x78\x9c\x63\x60\x00\x00\x00\x02\x00\x01\x00\x00", 12));
  png += chunk("IEND", "");
  return png;
}

TEST(ImageRead, ATinyFileClaimingAHugeImageFailsWithoutTakingTheMemory) {
  const std::string png = HugePng();
  ASSERT_EQ(png.size(), 69u);
  std::ofstream(Dir() / "huge.png", std::ios::binary) << png;
  rusage before{}, after{};
  ::getrusage(RUSAGE_SELF, &before);
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = ErrorOf([] { ReadImage((Dir() / "huge.png").string()); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ::getrusage(RUSAGE_SELF, &after);
  EXPECT_NE(e.find("claims 16000x16000 pixels, which needs at least"), std::string::npos) << e;
  EXPECT_NE(e.find("but the file has 69"), std::string::npos) << e;
  EXPECT_LT(seconds, 1.0);
  EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 64 * 1024)
      << "peak RSS grew by " << after.ru_maxrss - before.ru_maxrss << " KiB";
}

std::string FileBytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

TEST(ImageRead, FromMemoryGoesThroughTheSameChecks) {
  // A 3x2 RGBA PNG written by OIIO: the memory reader gives the file reader's exact values.
  const std::vector<float> px = {0.0f, 1.0f, 0.2f, 1.0f, 0.6f, 0.4f, 1.0f, 0.0f, 0.8f, 0.0f, 0.0f, 1.0f,
                                 1.0f, 1.0f, 1.0f, 0.2f, 0.0f, 0.0f, 0.0f, 1.0f, 0.4f, 0.2f, 0.6f, 0.8f};
  WriteWithOiio(Dir() / "mem.png", 3, 2, {"R", "G", "B", "A"}, OIIO::TypeDesc::UINT8, px);
  const std::string bytes = FileBytes(Dir() / "mem.png");
  const LoadedImage a = ReadImage((Dir() / "mem.png").string());
  const LoadedImage b =
      ReadImageFromMemory("embedded.png", reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  ASSERT_EQ(b.pixels.Width(), 3);
  ASSERT_EQ(b.pixels.Height(), 2);
  EXPECT_EQ(b.pixels.Data(), a.pixels.Data());
  EXPECT_EQ(b.pixels.At(1, 0, 3), 0.0f);                     // alpha as stored, never multiplied in
  EXPECT_NEAR(b.pixels.At(1, 0, 0), 153.0f / 255.0f, 1e-7);  // colour of that transparent pixel kept
  EXPECT_EQ(b.format, "png");
  // The 69-byte PNG claiming 16000x16000, held in memory: refused by the same size check.
  const std::string huge = FileBytes(Dir() / "huge.png");
  if (!huge.empty()) {
    const std::string e = ErrorOf(
        [&] { ReadImageFromMemory("texture.png", reinterpret_cast<const uint8_t*>(huge.data()), huge.size()); });
    EXPECT_NE(e.find("claims 16000x16000 pixels"), std::string::npos) << e;
  }
  // A PNG whose chunk claims more bytes than the buffer holds; a wrong extension; nothing.
  std::string cut = bytes.substr(0, 45);  // the chunk after IHDR claims more than the 4 bytes left
  EXPECT_NE(ErrorOf([&] {
              ReadImageFromMemory("t.png", reinterpret_cast<const uint8_t*>(cut.data()), cut.size());
            }).find("not a valid PNG file"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              ReadImageFromMemory("t.gif", reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
            }).find("unsupported file type '.gif'"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadImageFromMemory("t.png", nullptr, 0); }).find("is empty"), std::string::npos);
}

TEST(ImageRead, TexturesKeepTheirCodesAndGoThroughTheSameChecks) {
  // A 3x2 RGBA8 PNG (codes 0.2·255 = 51, 0.4 → 102, 0.6 → 153, 0.8 → 204), asymmetric in x
  // and y: its codes come back as stored, alpha straight, from the file and from memory.
  const std::vector<float> px = {0.0f, 1.0f, 0.2f, 1.0f, 0.6f, 0.4f, 1.0f, 0.0f, 0.8f, 0.0f, 0.0f, 1.0f,
                                 1.0f, 1.0f, 1.0f, 0.2f, 0.0f, 0.0f, 0.0f, 1.0f, 0.4f, 0.2f, 0.6f, 0.8f};
  // (Written unassociated: OpenImageIO's PNG writer would otherwise divide colour by alpha.)
  WriteWithOiio(Dir() / "tex.png", 3, 2, {"R", "G", "B", "A"}, OIIO::TypeDesc::UINT8, px,
                {{"oiio:UnassociatedAlpha", 1}});
  const std::vector<uint8_t> codes = {0,   255, 51,  255, 153, 102, 255, 0,   204, 0,  0,   255,
                                      255, 255, 255, 51,  0,   0,   0,   255, 102, 51, 153, 204};
  const std::string bytes = FileBytes(Dir() / "tex.png");
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  const ImageSource file{(Dir() / "tex.png").string(), nullptr, 0, ""};
  const ImageSource memory{"image 3 embedded in a.glb", data, bytes.size(), ".png"};
  for (const ImageSource& src : {file, memory}) {
    const ImageHeader h = ReadImageHeader(src);
    EXPECT_EQ(h.width, 3);
    EXPECT_EQ(h.height, 2);
    EXPECT_EQ(h.channels, 4);
    EXPECT_TRUE(h.is8);
    const TexturePixels t = ReadTexturePixels(src);
    EXPECT_TRUE(t.is8);
    EXPECT_EQ(t.file_channels, 4);
    EXPECT_EQ(t.rgba8, codes) << src.name;
    EXPECT_TRUE(t.rgba.empty());
  }
  // 16-bit RGB: float values as stored (k/65535), alpha 1.
  const std::vector<float> px16 = {0.25f, 0.5f, 1.0f, 0.0f, 0.75f, 0.125f};
  WriteWithOiio(Dir() / "tex16.png", 2, 1, {"R", "G", "B"}, OIIO::TypeDesc::UINT16, px16);
  const TexturePixels t16 = ReadTexturePixels({(Dir() / "tex16.png").string(), nullptr, 0, ""});
  EXPECT_FALSE(t16.is8);
  ASSERT_EQ(t16.rgba.size(), 8u);
  for (int i = 0; i < 2; ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(t16.rgba[4 * i + c], std::round(px16[3 * i + c] * 65535.0f) / 65535.0f, 1e-7) << i << c;
    }
    EXPECT_EQ(t16.rgba[4 * i + 3], 1.0f);
  }
  // The reader's checks, with the memory name in the message: the 69-byte PNG claiming
  // 16000x16000, a cut chunk, the extension picking the reader, nothing at all.
  const std::string huge = HugePng();
  const std::string e = ErrorOf([&] {
    ReadTexturePixels({"image 0 of h.glb", reinterpret_cast<const uint8_t*>(huge.data()), huge.size(), ".png"});
  });
  EXPECT_NE(e.find("image 'image 0 of h.glb'"), std::string::npos) << e;
  EXPECT_NE(e.find("claims 16000x16000 pixels"), std::string::npos) << e;
  EXPECT_NE(ErrorOf([&] {
              ReadTexturePixels({"t", data, 45, ".png"});
            }).find("not a valid PNG file"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              ReadTexturePixels({"t", data, bytes.size(), ".gif"});
            }).find("unsupported file type '.gif'"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadTexturePixels({"t", data, 0, ".png"}); }).find("is empty"), std::string::npos);
}

TEST(SafePath, PathsFromFilesStayInsideTheirFolder) {
  const fs::path base = Dir() / "base";
  fs::create_directories(base / "sub");
  EXPECT_EQ(ResolveInside(base, "sub/x.png", "f"), (base / "sub" / "x.png").lexically_normal());
  EXPECT_EQ(ResolveInside(base, "sub/../y.png", "f"), (base / "y.png").lexically_normal());
  for (const std::string& bad : {std::string("../x.png"), std::string("sub/../../x.png"), std::string("/etc/passwd"),
                                 std::string(""), std::string(".")}) {
    const std::string e = ErrorOf([&] { ResolveInside(base, bad, "field 'f' of 'r.json'"); });
    EXPECT_NE(e.find("field 'f' of 'r.json'"), std::string::npos) << bad << ": " << e;
    EXPECT_NE(e.find("must stay inside it"), std::string::npos) << bad << ": " << e;
  }
  // A symlink inside the folder that points out of it.
  fs::create_directory_symlink(Dir(), base / "out-link");
  EXPECT_NE(ErrorOf([&] { ResolveInside(base, "out-link/huge.png", "f"); }).find("through a symlink"),
            std::string::npos);
  // Relative base (".") works as the current folder.
  EXPECT_EQ(ResolveInside(".", "a.png", "f"), fs::path("a.png"));
}

TEST(SafePath, OutputNamesArePlainAndReservedNamesRefused) {
  for (const std::string& ok : {std::string("circle"), std::string("fxaa311-p39_subpix-0.5"), std::string("a.b")}) {
    EXPECT_EQ(ErrorOf([&] { CheckOutputName(ok, "n"); }), "") << ok;
  }
  for (const std::string& bad :
       {std::string(""), std::string(".."), std::string("."), std::string("a/b"), std::string("/abs"),
        std::string("a\\b"), std::string(".aalab-output"), std::string("tab\there"), std::string(201, 'x')}) {
    EXPECT_NE(ErrorOf([&] { CheckOutputName(bad, "scene name"); }).find("scene name: the name"), std::string::npos)
        << bad;
  }
  EXPECT_NE(ErrorOf([&] { CheckOutputName("reference", "spec", {"reference"}); }).find("is reserved"),
            std::string::npos);
  EXPECT_EQ(CheckOutputRelPath("images/circle/none.png", "p"), "images/circle/none.png");
  for (const std::string& bad : {std::string("images/../../x.png"), std::string("/tmp/x.png"), std::string("a//b"),
                                 std::string("images/./x.png"), std::string("")}) {
    EXPECT_NE(ErrorOf([&] { CheckOutputRelPath(bad, "p"); }), "") << bad;
  }
}

}  // namespace
}  // namespace aalab
