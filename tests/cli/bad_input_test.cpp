// Bad input through the CLI: every case exits with code 1 (never a crash, never "internal
// error"), prints one message naming the file/option and the problem (with the limit where
// there is one), and leaves no report, no partial folder and no output file behind.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "cli_util.h"
#include "io/image_io.h"

namespace aalab::clitest {
namespace {
namespace fs = std::filesystem;

void ExpectUserError(const std::string& args, const std::vector<std::string>& parts) {
  const CmdResult r = Aalab(args);
  EXPECT_EQ(r.code, 1) << args << "\n" << r.output;
  EXPECT_EQ(r.signal, 0) << args << " crashed:\n" << r.output;
  EXPECT_EQ(r.output.find("internal error"), std::string::npos) << args << "\n" << r.output;
  EXPECT_NE(r.output.find("aalab: error: "), std::string::npos) << args << "\n" << r.output;
  for (const auto& p : parts) {
    EXPECT_NE(r.output.find(p), std::string::npos) << args << "\noutput: " << r.output << "\nmissing: " << p;
  }
}

/// Nothing but the inputs the test put there: no report, no DIR.partial, no temporaries.
void ExpectOnly(const fs::path& dir, const std::vector<std::string>& inputs) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    EXPECT_NE(std::find(inputs.begin(), inputs.end(), name), inputs.end()) << "left behind: " << e.path();
  }
}

const char* kScene = R"({"name": "t", "effects": ["unlit"],
  "camera": {"type": "orthographic", "position": [0,0,10], "look_at": [0,0,0], "height": HEIGHT},
  "materials": {"w": {"shading": "unlit"}},
  "objects": [{"shape": "quad", "size": [SIZE, 1], "material": "w"}]})";

std::string Scene(const std::string& height, const std::string& size) {
  std::string s = kScene;
  s.replace(s.find("HEIGHT"), 6, height);
  s.replace(s.find("SIZE"), 4, size);
  return s;
}

TEST(CliBadInput, AbsurdFrameSizesAreRefusedWithTheLimit) {
  const fs::path dir = TempDir("size");
  // (Every --size form is tested in-process in tests/run/limits_test.cpp; here the CLI contract.)
  for (const std::string size : {"100000x100000", "16384x16384", "0x0", "1e3x5", "99999999999999x1"}) {
    ExpectUserError("run --scenes wedges --methods none --size '" + size + "' --out " + (dir / "r").string(),
                    {"--size '" + size + "'", "16384", "64 Mpx"});
  }
  ExpectUserError("render --scene wedges --size 100000x100000 --out " + (dir / "x.png").string(),
                  {"--size '100000x100000'", "16384", "64 Mpx"});
  ExpectUserError("run --scenes wedges --ref-spp 65536 --out " + (dir / "r").string(),
                  {"reference spp 65536", "2..64"});
  ExpectUserError("run --scenes wedges --repeat 100000 --out " + (dir / "r").string(), {"--repeat 100000", "1..1000"});
  ExpectUserError("render --scene wedges --spp 1000000 --out " + (dir / "x.png").string(), {"--spp 1000000", "4096"});
  ExpectUserError("run --scenes wedges --threads -1 --out " + (dir / "r").string(), {"--threads -1", "0 = all"});
  ExpectUserError("run --scenes wedges --threads 100000 --out " + (dir / "r").string(), {"--threads 100000", "4096"});
  ExpectOnly(dir, {});
  fs::remove_all(dir);
}

TEST(CliBadInput, MalformedSceneFilesNameTheFileAndTheProblem) {
  const fs::path dir = TempDir("scenes");
  struct Case {
    std::string file, text;
    std::vector<std::string> parts;
  };
  const std::string deep = std::string(300000, '[') + std::string(300000, ']');
  const std::vector<Case> cases = {
      {"syntax.json", "{\"name\": \"t\", \"effects\": [\"unlit\"],", {"syntax.json", "not valid JSON"}},
      {"nan.json", Scene("NaN", "1"), {"nan.json", "not valid JSON"}},
      {"infinity.json", Scene("Infinity", "1"), {"infinity.json", "not valid JSON"}},
      {"overflow.json", Scene("4", "1e999"), {"overflow.json", "1e999", "must be finite"}},
      {"nanstring.json", Scene("\"nan\"", "1"), {"nanstring.json", "/camera/height", "expected a number", "\"nan\""}},
      {"negative.json", Scene("4", "-3"), {"negative.json", "/objects/0/size/0", "-3", "out of range"}},
      {"huge.json", Scene("1e300", "1"), {"huge.json", "/camera/height", "1e+300", "<= 1e+09"}},
      {"tiny.json", Scene("1e-300", "1"), {"tiny.json", "/camera/height", "rounds to 0"}},
      {"deep.json", Scene(deep, "1"), {"deep.json", "/camera/height", "expected a number", "[[[[...]]]]"}},
      {"mesh.json",
       "{\"name\": \"t\", \"effects\": [\"unlit\"], \"camera\": {\"type\": \"orthographic\", \"position\": [0,0,10], "
       "\"look_at\": [0,0,0], \"height\": 4}, \"materials\": {\"w\": {\"shading\": \"unlit\"}}, \"objects\": "
       "[{\"shape\": \"mesh\", \"file\": \"missing.obj\", \"material\": \"w\"}]}",
       {"mesh.json", "/objects/0/file", "missing.obj", "does not exist"}},
  };
  std::vector<std::string> inputs;
  for (const auto& c : cases) {
    std::ofstream(dir / c.file) << c.text;
    inputs.push_back(c.file);
  }
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string scene = (dir / c.file).string();
    ExpectUserError("run --scenes wedges," + scene +
                        " --methods none --size 16x9 --ref-spp 4 --repeat 1 --quiet --out " + (dir / "report").string(),
                    c.parts);
  }
  for (const char* file : {"overflow.json", "deep.json"}) {
    ExpectUserError("render --scene " + (dir / file).string() + " --size 16x9 --out " + (dir / "out.png").string(),
                    {file});
  }
  ExpectOnly(dir, inputs);
  fs::remove_all(dir);
}

/// A PNG that is only a header: IHDR declaring width x height RGB8, then no pixel data.
void WritePngHeader(const fs::path& path, uint32_t width, uint32_t height) {
  auto crc32 = [](const std::string& bytes) {
    uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) {
      c ^= b;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
  };
  auto be32 = [](uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                       static_cast<char>(v)};
  };
  const std::string ihdr = "IHDR" + be32(width) + be32(height) + std::string("\x08\x02\x00\x00\x00", 5);
  // libpng reads the header up to the first IDAT chunk: give it one (the start of a zlib
  // stream; the pixel data itself is missing).
  const std::string idat = std::string("IDAT") + std::string("\x78\x9c", 2);
  std::ofstream f(path, std::ios::binary);
  f << std::string("\x89PNG\r\n\x1a\n", 8) << be32(13) << ihdr << be32(crc32(ihdr)) << be32(2) << idat
    << be32(crc32(idat)) << be32(0) << "IEND" << be32(crc32("IEND"));
}

TEST(CliBadInput, BrokenImagesAreRejectedWithPositionOrLimit) {
  const fs::path dir = TempDir("images");
  const std::string good = (dir / "good.png").string();
  ASSERT_EQ(Aalab("render --scene wedges --size 32x18 --out " + good).code, 0);
  // Float images holding NaN / Inf, written by the build's own writer.
  ImageF nan_img(7, 5, 3, 0.25f);
  nan_img.At(4, 2, 1) = std::numeric_limits<float>::quiet_NaN();
  WriteImageF((dir / "nan.exr").string(), nan_img);
  ImageF inf_img(7, 5, 3, 0.25f);
  inf_img.At(0, 3, 2) = -std::numeric_limits<float>::infinity();
  WriteImageF((dir / "inf.exr").string(), inf_img);
  ImageF five(3, 2, 5, 0.5f);
  WriteImageF((dir / "five.exr").string(), five);
  // Truncated files of every format the build writes.
  ImageF ok(16, 16, 3, 0.5f);
  ok.At(3, 3, 0) = 0.9f;
  WriteImageF((dir / "full.exr").string(), ok);
  WriteImage8((dir / "full.tif").string(), ToUnorm8(ok));
  for (const char* name : {"full.exr", "full.tif", "good.png"}) {
    std::ifstream in(dir / name, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string ext = fs::path(name).extension().string();
    std::ofstream(dir / ("trunc" + ext), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  std::ofstream(dir / "zero.png");  // 0 bytes
  fs::create_directories(dir / "folder.png");
  // Headers that claim more pixels than the limit (2^28 = 268435456), with no pixel data:
  // refused before any allocation.
  WritePngHeader(dir / "huge.png", 20000, 20000);
  WritePngHeader(dir / "wide.png", 1000000, 300);  // libpng's own width limit is 1e6
  const std::vector<std::string> inputs = {"good.png",   "nan.exr",   "inf.exr",   "five.exr",  "full.exr",
                                           "full.tif",   "trunc.exr", "trunc.tif", "trunc.png", "zero.png",
                                           "folder.png", "huge.png",  "wide.png"};

  struct Case {
    std::string file;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {"nan.exr", {"nan.exr", "non-finite value (NaN)", "pixel (4, 2) channel 1", "rejected"}},
      {"inf.exr", {"inf.exr", "non-finite value (Inf)", "pixel (0, 3) channel 2"}},
      // (five.exr: channels R, G, B, A and a fifth are read by name since issue #24.)
      {"trunc.exr", {"trunc.exr"}},
      {"trunc.tif", {"trunc.tif"}},
      {"trunc.png", {"trunc.png"}},
      {"zero.png", {"zero.png"}},
      {"folder.png", {"folder.png", "directory"}},
      {"missing.png", {"missing.png", "does not exist"}},
      {"huge.png", {"huge.png", "20000x20000", "limit of 268435456 pixels"}},
      {"wide.png", {"wide.png", "1000000x300", "limit of 268435456 pixels"}},
  };
  const std::string out = (dir / "out.png").string();
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string in = (dir / c.file).string();
    ExpectUserError("apply --method fxaa1-p3 " + in + " " + out, c.parts);
  }
  // The same reader behind every command that takes images, in either position.
  ExpectUserError("apply --method fxaa311-p39 " + (dir / "nan.exr").string() + " " + out, cases[0].parts);
  ExpectUserError("metrics --reference " + good + " " + (dir / "nan.exr").string(), cases[0].parts);
  ExpectUserError("metrics --reference " + (dir / "huge.png").string() + " " + good, cases[8].parts);
  ExpectUserError("metrics --reference " + good + " " + good + " --mask " + (dir / "trunc.tif").string(),
                  {"trunc.tif"});
  ExpectOnly(dir, inputs);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab::clitest
