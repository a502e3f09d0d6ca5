// FXAA 3.11 and the 12-iteration GLSL FXAA against the ORIGINAL shaders run on llvmpipe
// (tests/oracle/gl_oracle.h): every fxaa311-p* preset, the tutorial levels that map onto
// FXAA 3.11's presets, and fxaa-iter12, on rendered library frames and adversarial frames,
// must give the same bytes. Needs ../shared/seeds and
// Mesa's EGL + llvmpipe (fails with a message without them). Without the seeds the tests skip
// with a message, and fail under CI (CI=true: tests/skip_or_fail.h).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <sstream>

#include "methods/fxaa311.h"
#include "methods/registry.h"
#include "tests/oracle/gl_oracle.h"
#include "tests/oracle/oracle_frames.h"
#include "tests/oracle/seed_shaders.h"
#include "tests/skip_or_fail.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {

using oracle::NamedFrame;

struct Diff {
  long pixels = 0, differing = 0;
  int max_diff = 0;
  std::string first;
};

Diff Compare(const Image8& ours, const Image8& gl, const std::string& name) {
  Diff d;
  d.pixels = static_cast<long>(ours.Width()) * ours.Height();
  for (int y = 0; y < ours.Height(); ++y) {
    for (int x = 0; x < ours.Width(); ++x) {
      int m = 0;
      for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(ours.Pixel(x, y)[c] - gl.Pixel(x, y)[c]));
      if (m == 0) continue;
      if (d.differing < 3) {
        std::ostringstream os;
        os << " " << name << " (" << x << "," << y << ") ours " << int(ours.Pixel(x, y)[0]) << ","
           << int(ours.Pixel(x, y)[1]) << "," << int(ours.Pixel(x, y)[2]) << " gl " << int(gl.Pixel(x, y)[0]) << ","
           << int(gl.Pixel(x, y)[1]) << "," << int(gl.Pixel(x, y)[2]) << ";";
        d.first += os.str();
      }
      ++d.differing;
      d.max_diff = std::max(d.max_diff, m);
    }
  }
  return d;
}

class FxaaOracle : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!oracle::SeedsPresent()) {
      AALAB_SKIP_OR_FAIL_UNDER_CI("FXAA oracle needs the source documents with the original shaders: " +
                                  oracle::SeedsDir() + " (../shared/seeds beside the clone, or set AALAB_SEEDS_DIR)");
    }
    const std::string err = oracle::StartGl(oracle::GlMode{});
    ASSERT_EQ(err, "") << "the FXAA oracle cannot start OpenGL: " << err;
  }
};

const std::vector<NamedFrame>& Frames() {
  static const std::vector<NamedFrame> f = oracle::OracleFrames();
  return f;
}

// Runs `ours` and `theirs` on every frame; expects identical bytes, reports the share.
template <typename Ours, typename Theirs>
void ExpectIdentical(const std::string& what, Ours ours, Theirs theirs) {
  long pixels = 0, differing = 0;
  int max_diff = 0;
  std::string examples;
  for (const auto& f : Frames()) {
    const Diff d = Compare(ours(f.img), theirs(f.img), f.name);
    pixels += d.pixels;
    differing += d.differing;
    max_diff = std::max(max_diff, d.max_diff);
    if (examples.size() < 600) examples += d.first;
  }
  std::printf("[oracle] %-22s %ld px, identical %.4f%%, max diff %d\n", what.c_str(), pixels,
              100.0 * static_cast<double>(pixels - differing) / static_cast<double>(pixels), max_diff);
  EXPECT_EQ(differing, 0) << what << ": " << differing << " of " << pixels << " pixels differ (max " << max_diff
                          << " levels):" << examples;
}

void ExpectPresetIdentical(const std::string& what, const Fxaa311Params& p, int preset) {
  ExpectIdentical(
      what, [&](const Image8& img) { return Fxaa311(img, p, nullptr); },
      [&](const Image8& img) {
        return oracle::RunFxaa311Shader(Fxaa311LumaFrame(img, p.luma), preset, false, p.subpix, p.edge_threshold,
                                        p.edge_threshold_min);
      });
}

TEST_F(FxaaOracle, EveryQualityPresetIsTheShader) {
  for (int id : Fxaa311PresetIds()) {
    Fxaa311Params p;
    p.steps = Fxaa311PresetSteps(id);
    ExpectPresetIdentical("fxaa311-p" + std::to_string(id), p, id);
  }
}

TEST_F(FxaaOracle, TutorialLevelsAreTheShaderWithTheirPresets) {
  // low = preset 22's steps, medium = preset 27's, high = preset 39's (methods/fxaa311.cpp).
  const std::pair<const char*, int> levels[] = {{"low", 22}, {"medium", 27}, {"high", 39}};
  for (const auto& [level, preset] : levels) {
    Fxaa311Params p = FxaaTutorialHighParams();
    p.steps = FxaaTutorialSteps(level);
    ASSERT_EQ(p.steps, Fxaa311PresetSteps(preset)) << level;
    ExpectPresetIdentical(std::string("fxaa-") + level, p, preset);
  }
}

TEST_F(FxaaOracle, Iter12IsSeed003Glsl) {
  const Fxaa311Params p = *MakeMethod("fxaa-iter12").Config<Fxaa311Params>();  // the registry row's parameters
  ExpectIdentical(
      "fxaa-iter12", [&](const Image8& img) { return Fxaa311(img, p, nullptr); },
      [&](const Image8& img) { return oracle::RunIter12Shader(img); });
}

// The extraction finds the shaders by their markers and says what it looked for when a
// seeds folder lacks them (here: a folder with one unrelated text file).
TEST(FxaaOracleSeeds, MissingShaderTextFailsWithItsMarkers) {
  const std::string dir = testenv::ScratchDir("no-shader-seeds").string();
  std::ofstream(dir + "/000_unrelated.txt") << "no shader here\n#version 430 core\n";
  const char* old = std::getenv("AALAB_SEEDS_DIR");
  const std::string saved = old ? old : "";
  setenv("AALAB_SEEDS_DIR", dir.c_str(), 1);
  std::string e1, e2;
  try {
    oracle::Fxaa311InteractiveShader();
  } catch (const std::runtime_error& e) {
    e1 = e.what();
  }
  try {
    oracle::Iter12Shader();
  } catch (const std::runtime_error& e) {
    e2 = e.what();
  }
  if (old) {
    setenv("AALAB_SEEDS_DIR", saved.c_str(), 1);
  } else {
    unsetenv("AALAB_SEEDS_DIR");
  }
  EXPECT_NE(e1.find("WebGL Fragment Shader FXAA-interactive.fs"), std::string::npos) << e1;
  EXPECT_NE(e1.find(dir), std::string::npos) << e1;
  EXPECT_NE(e2.find("#define ITERATIONS 12"), std::string::npos) << e2;
}

// With the real seeds: the extracted texts are the complete shaders (start to end markers).
TEST(FxaaOracleSeeds, ExtractedShadersAreComplete) {
  if (!oracle::SeedsPresent()) AALAB_SKIP_OR_FAIL_UNDER_CI("needs " + oracle::SeedsDir() + " (../shared/seeds)");
  const std::string fs = oracle::Fxaa311InteractiveShader();
  EXPECT_EQ(fs.rfind("precision highp float;", 0), 0u);
  EXPECT_NE(fs.find("return vec4(texture2D(tex, posM).xyz, lumaM);"), std::string::npos);
  const std::string it = oracle::Iter12Shader();
  EXPECT_EQ(it.rfind("#version 430 core", 0), 0u);
  EXPECT_NE(it.find("FragColor = vec4(fxaa(),1);"), std::string::npos);
}

}  // namespace
}  // namespace aalab
