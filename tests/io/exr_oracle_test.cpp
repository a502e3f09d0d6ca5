// Float EXR writing through OpenEXR directly (io/exr_write.cpp) against OpenImageIO 2.4's EXR
// writer with the spec aalab gave it before issue #41 (ImageSpec(w, h, nc, FLOAT), DateTime "",
// oiio:UnassociatedAlpha for 2/4 channels, png:filter for noise): the bytes must be equal, for
// 1..5 channels, sizes from 1x1 to more than one 16-line ZIP block, values random/flat/gradient
// (negative, > 1, denormal, +-Inf kept as given). The public WriteImageF path is checked too,
// and that it loads no module.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>

#include "io/exr_write.h"
#include "io/image_io.h"
#include "io/oiio_loader.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

std::string OiioEncodeExr(int w, int h, int nc, const float* data, bool filter_none) {
  auto out = OIIO::ImageOutput::create("x.exr");
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  EXPECT_TRUE(out && out->set_ioproxy(&memory));
  OIIO::ImageSpec spec(w, h, nc, OIIO::TypeDesc::FLOAT);
  spec.attribute("DateTime", "");
  if (nc == 2 || nc == 4) spec.attribute("oiio:UnassociatedAlpha", 1);
  if (filter_none) spec.attribute("png:filter", 0x08);
  EXPECT_TRUE(out->open("x.exr", spec) && out->write_image(OIIO::TypeDesc::FLOAT, data) && out->close())
      << out->geterror();
  return std::string(bytes.begin(), bytes.end());
}

TEST(ExrOracle, FloatWriterBytesEqualOpenImageIOsWriter) {
  const std::vector<std::pair<int, int>> sizes = {{1, 1}, {1, 17}, {9, 1}, {13, 5}, {40, 35}};
  for (const auto& [w, h] : sizes) {
    for (int nc = 1; nc <= 5; ++nc) {
      for (int kind = 0; kind < 3; ++kind) {
        std::mt19937 rng(static_cast<unsigned>(w * 100 + h * 10 + nc + kind));
        std::uniform_real_distribution<float> u(-2.0f, 40.0f);
        std::vector<float> v(static_cast<size_t>(w) * h * nc);
        for (size_t i = 0; i < v.size(); ++i) {
          v[i] = kind == 0 ? u(rng) : kind == 1 ? 0.25f : static_cast<float>(i % 97) / 96.0f;
        }
        if (v.size() > 3) {
          v[1] = std::numeric_limits<float>::denorm_min();
          v[2] = std::numeric_limits<float>::infinity();
        }
        std::string mine, why;
        ASSERT_TRUE(io_detail::EncodeExrFloat(w, h, nc, v.data(), &mine, &why)) << why;
        ASSERT_EQ(mine, OiioEncodeExr(w, h, nc, v.data(), false)) << w << "x" << h << " nc " << nc << " kind " << kind;
      }
    }
  }
}

TEST(ExrOracle, WriteImageFGivesOpenImageIOsBytesWithoutTheModule) {
  const fs::path dir = testenv::ScratchDir("exr-oracle");
  ImageF img(23, 19, 3, 0.0f);
  for (size_t i = 0; i < img.Data().size(); ++i) img.Data()[i] = static_cast<float>(i % 31) * 0.07f - 0.3f;
  for (const char* name : {"a.exr", "b.EXR"}) {
    WriteImageF((dir / name).string(), img);
    std::ifstream f(dir / name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_EQ(bytes, OiioEncodeExr(23, 19, 3, img.Data().data(), false)) << name;
  }
  EXPECT_FALSE(io_detail::OiioModuleLoaded());
}

}  // namespace
}  // namespace aalab
