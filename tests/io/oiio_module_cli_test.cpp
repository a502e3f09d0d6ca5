// The OpenImageIO module through the real aalab binary (issue #41): aalab itself does not link
// OpenImageIO; PNG and float EXR writes need no module; a format that needs it (here an EXR
// read), with the module missing, is one clear error naming the file, the format, the module
// and AALAB_IO_OIIO_MODULE, exit 1.
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

TEST(OiioModuleCli, PngAndExrWritesNeedNoModuleAndAnExrReadWithoutItIsOneClearError) {
  const fs::path dir = TempDir("oiio_module_cli");
  const std::string aalab = kNoModule + AALAB_BINARY_DIR + "/aalab ";
  EXPECT_EQ(RunCommand(aalab + "--version 2>&1").code, 0);
  // PNG through libpng, float EXR through OpenEXR: no module needed.
  const std::string png = (dir / "o.png").string(), exr = (dir / "o.exr").string();
  for (const auto& out : {png, exr}) {
    const auto r = RunCommand(aalab + "render --scene circle --size 16x9 --spp 4 --out " + out + " 2>&1");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::is_regular_file(out)) << out;
  }
  // Reading EXR goes through OpenImageIO: one message naming the image, its format, the
  // module, where it was looked for and the variable.
  const auto read = RunCommand(aalab + "metrics --reference " + exr + " " + png + " 2>&1");
  EXPECT_EQ(read.code, 1) << read.output;
  EXPECT_NE(read.output.find("image '" + exr + "' (.exr) needs OpenImageIO, which aalab loads from its module " +
                             "libaalab_io_oiio.so"),
            std::string::npos)
      << read.output;
  EXPECT_NE(read.output.find("(/nonexistent/libaalab_io_oiio.so: "), std::string::npos) << read.output;
  EXPECT_NE(read.output.find("set AALAB_IO_OIIO_MODULE=PATH"), std::string::npos) << read.output;
  // With the module (found beside aalab) the same command reads the EXR.
  const auto ok = Aalab("metrics --reference " + exr + " " + png);
  EXPECT_EQ(ok.code, 0) << ok.output;
}

}  // namespace
