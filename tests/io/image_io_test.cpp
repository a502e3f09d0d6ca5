// Image files: ReadImage's refusals (NaN/Inf with the pixel position, sizes, channel counts,
// truncation) and the writers' guarantees (atomic, byte-for-byte deterministic).
#include "io/image_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <thread>

#include "core/error.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

fs::path Dir() {
  static const fs::path d = testenv::ScratchDir("io");
  return d;
}

std::string ReadError(const fs::path& p, size_t max_pixels = size_t{1} << 28) {
  try {
    ReadImage(p.string(), max_pixels);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

std::string Bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

TEST(ImageIo, NonFinitePixelsAreRejectedWithTheirPosition) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (const auto& [value, x, y, c] :
       std::vector<std::tuple<float, int, int, int>>{{nan, 0, 0, 0}, {nan, 6, 4, 2}, {inf, 3, 1, 1}, {-inf, 2, 4, 0}}) {
    ImageF img(7, 5, 3, 0.5f);
    img.At(x, y, c) = value;
    const fs::path p = Dir() / "bad.exr";
    WriteImageF(p.string(), img);
    const std::string e = ReadError(p);
    EXPECT_NE(e.find("bad.exr"), std::string::npos) << e;
    EXPECT_NE(e.find("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " + std::to_string(c)),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("NaN/Inf pixels are rejected"), std::string::npos) << e;
  }
  // Only the first bad pixel (in row-major order) is named.
  ImageF two(4, 4, 3, 0.5f);
  two.At(3, 1, 0) = nan;
  two.At(1, 2, 0) = nan;
  WriteImageF((Dir() / "two.exr").string(), two);
  EXPECT_NE(ReadError(Dir() / "two.exr").find("pixel (3, 1)"), std::string::npos);
}

TEST(ImageIo, PixelLimitAndShapeChecks) {
  const fs::path p = Dir() / "big.png";
  WriteImage8(p.string(), Image8(300, 200, 4, 9));
  EXPECT_TRUE(ReadError(p, 60000).empty());  // exactly at the limit: allowed
  const std::string e = ReadError(p, 59999);
  EXPECT_NE(e.find("300x200"), std::string::npos) << e;
  EXPECT_NE(e.find("more than the limit of 59999 pixels"), std::string::npos) << e;
  WriteImageF((Dir() / "five.exr").string(), ImageF(2, 2, 5, 0.1f));
  // Five channels (OpenImageIO names them R, G, B, A, channel4): R, G, B, A by name, the fifth ignored.
  EXPECT_EQ(ListImageChannels((Dir() / "five.exr").string()).size(), 5u);
  EXPECT_EQ(ReadImage((Dir() / "five.exr").string()).pixels.Channels(), 4);
  // Two channels named R and G (what OpenImageIO calls an unnamed pair) are not grey+alpha:
  // refused, naming them (grey + alpha is Y, A: image_read_test.cpp).
  WriteImageF((Dir() / "two.exr").string(), ImageF(3, 1, 2, 0.25f));
  EXPECT_NE(ReadError(Dir() / "two.exr").find("has no channels named R, G and B (its channels: R, G)"),
            std::string::npos);
}

TEST(ImageIo, TruncatedEmptyAndMissingFilesNameThePath) {
  ImageF img(16, 16, 3, 0.3f);
  img.At(5, 5, 1) = 0.8f;
  for (const std::string ext : {".exr", ".tif", ".png"}) {
    const fs::path full = Dir() / ("full" + ext), cut = Dir() / ("cut" + ext);
    WriteImageF(full.string(), img);
    const std::string bytes = Bytes(full);
    // (Cutting only a PNG's IEND chunk leaves every pixel intact, and it still reads.)
    for (size_t keep : {size_t{0}, size_t{8}, bytes.size() / 2, bytes.size() - 20}) {
      std::ofstream(cut, std::ios::binary) << bytes.substr(0, keep);
      const std::string e = ReadError(cut);
      EXPECT_NE(e.find(cut.string()), std::string::npos) << ext << " keeping " << keep << " bytes: '" << e << "'";
    }
  }
  EXPECT_NE(ReadError(Dir() / "missing.png").find("does not exist"), std::string::npos);
  fs::create_directories(Dir() / "dir.png");
  EXPECT_NE(ReadError(Dir() / "dir.png").find("is a directory"), std::string::npos);
}

TEST(ImageIo, OnlyTheReaderTheExtensionNamesIsTried) {
  const fs::path png = Dir() / "real.png";
  WriteImage8(png.string(), Image8(4, 3, 4, 200));
  EXPECT_TRUE(ReadError(png).empty());
  // The same bytes under another supported extension: refused, not handed to other readers.
  fs::copy_file(png, Dir() / "fake.exr", fs::copy_options::overwrite_existing);
  const std::string e = ReadError(Dir() / "fake.exr");
  EXPECT_NE(e.find("fake.exr"), std::string::npos) << e;
  EXPECT_NE(e.find("must match the file's extension"), std::string::npos) << e;
  // Extensions outside PNG/JPEG/TIFF/EXR, and upper case accepted.
  fs::copy_file(png, Dir() / "pic.bmp", fs::copy_options::overwrite_existing);
  EXPECT_NE(ReadError(Dir() / "pic.bmp").find("unsupported file type '.bmp' (readable: .png, .jpg"), std::string::npos);
  fs::copy_file(png, Dir() / "noext", fs::copy_options::overwrite_existing);
  EXPECT_NE(ReadError(Dir() / "noext").find("unsupported file type ''"), std::string::npos);
  fs::copy_file(png, Dir() / "UPPER.PNG", fs::copy_options::overwrite_existing);
  EXPECT_TRUE(ReadError(Dir() / "UPPER.PNG").empty());
}

TEST(ImageIo, ContainerSizesAreCheckedBeforeTheDecodersTrustThem) {
  // Found by fuzzing: OpenEXR allocated (and zeroed) whatever a string attribute's size field
  // claimed, 1.8 GB for a 600-byte file, before failing on the missing bytes.
  std::string exr("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
  exr += std::string("comment\0string\0", 15) + std::string("\xf0\xff\xff\x6f", 4) + "abc";
  std::ofstream(Dir() / "claims.exr", std::ios::binary) << exr;
  const std::string e = ReadError(Dir() / "claims.exr");
  EXPECT_NE(e.find("not a valid OpenEXR file: attribute 'comment' claims 1879048176 bytes but only 3 remain"),
            std::string::npos)
      << e;
  // The same for PNG: libpng allocated a chunk's claimed length (2 GB for a 260-byte file).
  const fs::path png = Dir() / "ok.png";
  WriteImage8(png.string(), Image8(3, 2, 4, 50));
  std::string bytes = Bytes(png);
  ASSERT_EQ(bytes.substr(12, 4), "IHDR");
  std::string claims = bytes.substr(0, 33) + std::string("\x7f\xff\xff\x00tEXt", 8) + "key";
  std::ofstream(Dir() / "claims.png", std::ios::binary) << claims;
  const std::string pe = ReadError(Dir() / "claims.png");
  EXPECT_NE(pe.find("not a valid PNG file: chunk 'tEXt' claims 2147483392 bytes but only 0 remain"), std::string::npos)
      << pe;
  EXPECT_TRUE(ReadError(png).empty());
  // A valid file still reads.
  ImageF img(6, 4, 3, 0.5f);
  WriteImageF((Dir() / "valid.exr").string(), img);
  EXPECT_TRUE(ReadError(Dir() / "valid.exr").empty());
}

TEST(ImageIo, WritesAreAtomicAndDeterministic) {
  // A failed write leaves nothing behind.
  EXPECT_THROW(WriteImage8((Dir() / "nope" / "x.png").string(), Image8(2, 2, 4, 0)), UserError);
  EXPECT_THROW(WriteImage8((Dir() / "x.bmpx").string(), Image8(2, 2, 4, 0)), UserError);
  for (const auto& e : fs::directory_iterator(Dir())) {
    EXPECT_EQ(e.path().filename().string().rfind(".tmp-", 0), std::string::npos) << e.path();
  }
  // Same pixels, same bytes, also across a clock second: no timestamp in EXR or TIFF headers
  // (OpenImageIO writes DateTime unless told otherwise).
  ImageF img(5, 3, 3, 0.5f);
  img.At(1, 1, 0) = 2.0f;
  for (const std::string ext : {".exr", ".tif", ".png"}) WriteImageF((Dir() / ("a" + ext)).string(), img);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  for (const std::string ext : {".exr", ".tif", ".png"}) {
    WriteImageF((Dir() / ("b" + ext)).string(), img);
    EXPECT_EQ(Bytes(Dir() / ("a" + ext)), Bytes(Dir() / ("b" + ext))) << ext;
  }
}

}  // namespace
}  // namespace aalab
