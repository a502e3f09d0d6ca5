// The OpenImageIO module through the real aalab binary (issue #41): aalab itself does not link
// OpenImageIO; PNG work needs no module; a format that needs it, with the module missing, is
// one clear error naming the file, the format, the module and AALAB_IO_OIIO_MODULE, exit 1,
// and nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../cli/cli_util.h"

namespace {
namespace fs = std::filesystem;
using aalab::clitest::Aalab;
using aalab::clitest::RunCommand;
using aalab::clitest::TempDir;

const std::string kNoModule = "AALAB_IO_OIIO_MODULE=/nonexistent/libaalab_io_oiio.so ";

TEST(OiioModuleCli, AalabDoesNotLinkOpenImageIO) {
  const auto r = RunCommand("readelf -d " + std::string(AALAB_BINARY_DIR) + "/aalab 2>&1");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("(NEEDED)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("libpng16"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("OpenImageIO"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_regular_file(fs::path(AALAB_BINARY_DIR) / "libaalab_io_oiio.so"));
}

TEST(OiioModuleCli, PngNeedsNoModuleAndExrWithoutItIsOneClearError) {
  const fs::path dir = TempDir("oiio_module_cli");
  const auto ok = RunCommand(kNoModule + AALAB_BINARY_DIR + "/aalab render --scene circle --size 16x9 --spp 4 --out " +
                             (dir / "o.png").string() + " 2>&1");
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "o.png"));
  EXPECT_EQ(RunCommand(kNoModule + AALAB_BINARY_DIR + "/aalab --version 2>&1").code, 0);

  const std::string exr = (dir / "o.exr").string();
  const auto bad = RunCommand(kNoModule + AALAB_BINARY_DIR + "/aalab render --scene circle --size 16x9 --spp 4 --out " +
                              exr + " 2>&1");
  EXPECT_EQ(bad.code, 1) << bad.output;
  EXPECT_NE(bad.output.find("writing '" + exr + "' (.exr) needs OpenImageIO"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("libaalab_io_oiio.so"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("/nonexistent/libaalab_io_oiio.so: "), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("set AALAB_IO_OIIO_MODULE=PATH"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(exr));
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename(), "o.png") << "left behind";

  // Reading: the same message for the image read.
  ASSERT_EQ(Aalab("render --scene circle --size 16x9 --spp 4 --out " + exr).code, 0);  // module beside aalab
  const auto read = RunCommand(kNoModule + AALAB_BINARY_DIR + "/aalab metrics --reference " + exr + " " +
                               (dir / "o.png").string() + " 2>&1");
  EXPECT_NE(read.code, 0) << read.output;
  EXPECT_NE(read.output.find("image '" + exr + "' (.exr) needs OpenImageIO"), std::string::npos) << read.output;
}

}  // namespace
