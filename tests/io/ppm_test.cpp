// Binary PPM frames (io/ppm.h): the exchange format with the GPU tool.
#include "io/ppm.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <limits>
#include <vector>
#include <fstream>
#include <string>

#include "core/error.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {

namespace fs = std::filesystem;

fs::path Tmp(const std::string& name) {
  static const fs::path dir = testenv::ScratchDir("ppm");
  return dir / name;
}

void WriteBytes(const fs::path& p, const std::string& bytes) {
  std::ofstream f(p, std::ios::binary);
  f << bytes;
}

TEST(Ppm, RoundTripOddSizeKeepsRgbAndSetsAlpha) {
  Image8 img(3, 2, 4, 0);
  for (size_t i = 0; i < img.Data().size(); ++i) img.Data()[i] = static_cast<uint8_t>(i * 37);
  const fs::path p = Tmp("rt.ppm");
  WritePpm(p.string(), img);
  // Header "P6\n3 2\n255\n" (11 bytes) + 3·2·3 bytes of rgb.
  EXPECT_EQ(fs::file_size(p), 11u + 18u);
  const Image8 back = ReadPpm(p.string());
  ASSERT_EQ(back.Width(), 3);
  ASSERT_EQ(back.Height(), 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(back.At(x, y, c), img.At(x, y, c));
      EXPECT_EQ(back.At(x, y, 3), 255);
    }
  }
  fs::remove(p);
}

TEST(Ppm, HeaderCommentsAreSkipped) {
  const fs::path p = Tmp("comment.ppm");
  WriteBytes(p, std::string("P6\n# made by hand\n1 1\n255\n") + std::string("\x0a\x14\x1e", 3));
  const Image8 img = ReadPpm(p.string());
  EXPECT_EQ(img.At(0, 0, 0), 10);
  EXPECT_EQ(img.At(0, 0, 1), 20);
  EXPECT_EQ(img.At(0, 0, 2), 30);
  fs::remove(p);
}

TEST(Ppm, BadFilesAreUserErrorsNamingThePath) {
  const fs::path p = Tmp("bad.ppm");
  const std::pair<std::string, std::string> cases[] = {
      {"P3\n1 1\n255\n0 0 0\n", "not a binary PPM"},
      {"P6\n2 2\n65535\n", "maxval 65535"},
      {"P6\n2 x\n255\n", "bad PPM header"},
      {"P6\n0 2\n255\n", "out of range"},
      {std::string("P6\n2 1\n255\n") + std::string(5, '\0'), "truncated"},
  };
  for (const auto& [bytes, message] : cases) {
    WriteBytes(p, bytes);
    try {
      ReadPpm(p.string());
      FAIL() << "accepted: " << message;
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
    }
  }
  fs::remove(p);
  EXPECT_THROW(ReadPpm(p.string()), UserError);  // missing file
}

uint32_t Bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}

TEST(PreviousPositions, RoundTripKeepsEveryBitAndCentresCostNothing) {
  // 3 × 2 pixels: centres, small and large moves, off-screen, NaN (no history), -0.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> prev = {0.5f, 0.5f, 1.25f, 0.375f, -7.0f, 1e9f, nan, nan, 1.5f, 1.5f, -0.0f, 2.0000002f};
  const fs::path p = Tmp("rt.prev");
  WritePreviousPositions(p.string(), 3, 2, prev);
  // Header "AALABPREV 1 3 2\n" (16 bytes) + 3·2·2 values of 4 bytes.
  EXPECT_EQ(fs::file_size(p), 16u + 48u);
  const std::vector<float> back = ReadPreviousPositions(p.string(), 3, 2);
  ASSERT_EQ(back.size(), prev.size());
  for (size_t i = 0; i < prev.size(); ++i) EXPECT_EQ(Bits(back[i]), Bits(prev[i])) << i;
  // A position equal to its pixel centre is stored as 0: pixel (0, 0) and pixel (1, 1).
  std::ifstream f(p, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.substr(16, 8), std::string(8, '\0'));
  EXPECT_EQ(bytes.substr(16 + 4 * 8, 8), std::string(8, '\0'));
}

TEST(PreviousPositions, BadFilesAreUserErrorsNamingThePath) {
  const fs::path p = Tmp("bad.prev");
  const std::pair<std::string, std::string> cases[] = {
      {"P6\n3 2\n255\n", "not a previous-positions file"},
      {"AALABPREV 1 4 2\n" + std::string(64, '\0'), "expected 3x2"},
      {"AALABPREV 1 3 2\n" + std::string(47, '\0'), "truncated"},
  };
  for (const auto& [bytes, message] : cases) {
    WriteBytes(p, bytes);
    try {
      ReadPreviousPositions(p.string(), 3, 2);
      FAIL() << "accepted: " << message;
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
    }
  }
  fs::remove(p);
  EXPECT_THROW(ReadPreviousPositions(p.string(), 3, 2), UserError);  // missing file
}

}  // namespace
}  // namespace aalab
