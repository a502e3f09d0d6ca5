// FSR 1 (methods/fsr1.h) against the ORIGINAL ffx_fsr1.h + ffx_a.h (read from
// ../shared/third_party/fidelityfx-fsr1) run as a GL compute shader on llvmpipe
// (tests/oracle/fsr1_shader.h): EASU at the upscale factors 4/3, 1.5, 1.7 and 2, and RCAS at
// sharpness 0, 0.2 and 1, on the FXAA oracle's synthetic, adversarial and rendered frames
// (tests/oracle/oracle_frames.h) and on the EASU outputs. The shader's floats come back
// before any store (RGBA32F image): the test expects every float bit for bit and so every
// stored byte (with the wrapper's result declared precise: tests/oracle/fsr1_shader.h).
// Without the sources the tests skip with a message, and fail under CI.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "core/sampler.h"
#include "methods/fsr1.h"
#include "tests/oracle/fsr1_shader.h"
#include "tests/oracle/gl_oracle.h"
#include "tests/oracle/oracle_frames.h"
#include "tests/oracle/third_party_sources.h"
#include "tests/skip_or_fail.h"

namespace aalab {
namespace {

using oracle::NamedFrame;

struct Tally {
  long pixels = 0, float_differing = 0, byte_differing = 0;
  int max_byte_diff = 0;
  double max_float_diff = 0;
  std::string examples;
};

// Compares our floats (pixel(x, y)) with the shader's rgba floats, bit for bit and as stored.
template <class Pixel>
void Tallies(Tally& t, const std::vector<float>& gl, int w, int h, const std::string& name, Pixel pixel) {
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::array<float, 3> ours = pixel(x, y);
      const float* theirs = &gl[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 4];
      bool fdiff = false;
      int bdiff = 0;
      for (int c = 0; c < 3; ++c) {
        if (std::memcmp(&ours[static_cast<size_t>(c)], &theirs[c], 4) != 0) fdiff = true;
        t.max_float_diff =
            std::max(t.max_float_diff, std::fabs(static_cast<double>(ours[static_cast<size_t>(c)]) - theirs[c]));
        bdiff = std::max(bdiff, std::abs(StoreUnorm8(ours[static_cast<size_t>(c)]) - StoreUnorm8(theirs[c])));
      }
      ++t.pixels;
      if (fdiff && t.examples.size() < 500) {
        std::ostringstream os;
        os.precision(9);
        os << " " << name << " (" << x << "," << y << ") ours " << ours[0] << "," << ours[1] << "," << ours[2]
           << " shader " << theirs[0] << "," << theirs[1] << "," << theirs[2] << ";";
        t.examples += os.str();
      }
      t.float_differing += fdiff ? 1 : 0;
      t.byte_differing += bdiff ? 1 : 0;
      t.max_byte_diff = std::max(t.max_byte_diff, bdiff);
    }
  }
}

void Print(const std::string& what, const Tally& t) {
  std::printf("[oracle] %-26s %ld px, floats identical %.4f%%, bytes identical %.4f%%, max diff %d levels (%.3g)\n",
              what.c_str(), t.pixels,
              100.0 * static_cast<double>(t.pixels - t.float_differing) / static_cast<double>(t.pixels),
              100.0 * static_cast<double>(t.pixels - t.byte_differing) / static_cast<double>(t.pixels), t.max_byte_diff,
              t.max_float_diff);
}

void Report(const std::string& what, const Tally& t) {
  Print(what, t);
  EXPECT_EQ(t.byte_differing, 0) << what << ": " << t.byte_differing << " of " << t.pixels
                                 << " pixels differ as stored";
  EXPECT_EQ(t.float_differing, 0) << what << ": " << t.float_differing << " of " << t.pixels
                                  << " pixels differ in a float bit:" << t.examples;
}

class Fsr1Oracle : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!oracle::ThirdPartyHas("fidelityfx-fsr1/ffx_fsr1.h") || !oracle::ThirdPartyHas("fidelityfx-fsr1/ffx_a.h")) {
      AALAB_SKIP_OR_FAIL_UNDER_CI(
          "the FSR 1 oracle needs the original ffx_a.h and ffx_fsr1.h in " + oracle::ThirdPartyDir() +
          "/fidelityfx-fsr1 (../shared/third_party beside the clone, or set AALAB_THIRD_PARTY_DIR)");
    }
    const std::string err = oracle::StartGl(oracle::GlMode{});
    ASSERT_EQ(err, "") << "the FSR 1 oracle cannot start OpenGL: " << err;
  }
};

const std::vector<NamedFrame>& Frames() {
  static const std::vector<NamedFrame> f = oracle::OracleFrames();
  return f;
}

std::array<std::array<uint32_t, 4>, 4> AsArrays(const Fsr1EasuConst& k) { return {k.con0, k.con1, k.con2, k.con3}; }

int Scaled(int n, double up) { return static_cast<int>(std::lround(n * up)); }

Tally EasuTally(double up, bool precise) {
  Tally t;
  for (const auto& f : Frames()) {
    const int ow = Scaled(f.img.Width(), up), oh = Scaled(f.img.Height(), up);
    const Fsr1EasuConst con = Fsr1EasuCon(static_cast<float>(f.img.Width()), static_cast<float>(f.img.Height()),
                                          static_cast<float>(ow), static_cast<float>(oh));
    const Fsr1Planes planes = Fsr1PlanesOf(f.img, SamplerArithmetic::kGl);
    const std::vector<float> gl = oracle::RunFsr1EasuShader(f.img, ow, oh, AsArrays(con), precise);
    Tallies(t, gl, ow, oh, f.name, [&](int x, int y) { return Fsr1EasuPixel(planes, con, x, y); });
  }
  return t;
}

TEST_F(Fsr1Oracle, EasuIsTheShader) {
  for (double up : {4.0 / 3.0, 1.5, 1.7, 2.0}) {
    char what[64];
    std::snprintf(what, sizeof what, "easu upscale %.4g", up);
    Report(what, EasuTally(up, true));
  }
}

// The same text without `precise` (Mesa free to rewrite float expressions, as any GLSL
// compiler may): the port is then not always llvmpipe's bits, but never more than one 8-bit
// level away (measured: docs/fsr1.md).
TEST_F(Fsr1Oracle, CompilerRewritesMoveAtMostOneLevel) {
  for (double up : {4.0 / 3.0, 2.0}) {
    const Tally t = EasuTally(up, false);
    char what[64];
    std::snprintf(what, sizeof what, "easu %.4g (not precise)", up);
    Print(what, t);
    EXPECT_LE(t.max_byte_diff, 1) << what;
    EXPECT_LT(t.byte_differing * 100, t.pixels) << what;  // under 1 % of pixels
  }
  Tally t;
  for (const auto& f : Frames()) {
    const Fsr1Planes planes = Fsr1PlanesOf(f.img, SamplerArithmetic::kGl);
    const uint32_t con = Fsr1RcasCon(0.2f);
    const std::vector<float> gl = oracle::RunFsr1RcasShader(f.img, con, false);
    Tallies(t, gl, f.img.Width(), f.img.Height(), f.name,
            [&](int x, int y) { return Fsr1RcasPixel(planes, con, x, y); });
  }
  Print("rcas 0.2 (not precise)", t);
  EXPECT_LE(t.max_byte_diff, 1);
}

TEST_F(Fsr1Oracle, RcasIsTheShader) {
  for (float stops : {0.0f, 0.2f, 1.0f}) {
    Tally t;
    for (const auto& f : Frames()) {
      // On the frame itself, and on its EASU 4/3 upscale (RCAS's input in FSR 1).
      const Image8 up = Fsr1Easu(f.img, Scaled(f.img.Width(), 4.0 / 3.0), Scaled(f.img.Height(), 4.0 / 3.0), nullptr);
      for (const Image8* img : {&f.img, &up}) {
        const Fsr1Planes planes = Fsr1PlanesOf(*img, SamplerArithmetic::kGl);
        const uint32_t con = Fsr1RcasCon(stops);
        const std::vector<float> gl = oracle::RunFsr1RcasShader(*img, con);
        Tallies(t, gl, img->Width(), img->Height(), f.name,
                [&](int x, int y) { return Fsr1RcasPixel(planes, con, x, y); });
      }
    }
    char what[64];
    std::snprintf(what, sizeof what, "rcas sharpness %.3g", static_cast<double>(stops));
    Report(what, t);
  }
}

}  // namespace
}  // namespace aalab
