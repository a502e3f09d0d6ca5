// CMAA2 (methods/cmaa2.h) against the ORIGINAL CMAA2.hlsl (read from
// ../shared/third_party/cmaa2), compiled by glslang's HLSL front end and run on lavapipe
// (tests/oracle/cmaa2_shader.h), on the FXAA oracle's frames (tests/oracle/oracle_frames.h:
// synthetic frames, 1-px checkers where every pixel is a candidate, near-horizontal and
// near-vertical slopes whose Z shapes overflow the 768-item group buffer, threshold steps,
// eight library scenes at 101x67). The shader gets the port's linear colour as an RGBA32F
// texture and writes RGBA32F (no sRGB conversion), so the floats after
// DeferredColorApply2x2CS are compared bit for bit, and the bytes as the port stores them.
// The port runs with lavapipe's lane count (8 with AVX: the order its vector code reaches the
// atomics in, methods/cmaa2.cpp). Without the source, glslang or lavapipe the tests skip, and fail under CI.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "core/sampler.h"
#include "methods/cmaa2.h"
#include "tests/oracle/cmaa2_shader.h"
#include "tests/oracle/oracle_frames.h"
#include "tests/oracle/vk_compute.h"
#include "tests/skip_or_fail.h"

namespace aalab {
namespace {

using oracle::NamedFrame;

std::vector<float> Linear(const Image8& img) {
  std::vector<float> rgb(static_cast<size_t>(img.Width()) * static_cast<size_t>(img.Height()) * 3);
  for (int y = 0; y < img.Height(); ++y) {
    for (int x = 0; x < img.Width(); ++x) {
      for (int c = 0; c < 3; ++c) {
        rgb[(static_cast<size_t>(y) * static_cast<size_t>(img.Width()) + static_cast<size_t>(x)) * 3 +
            static_cast<size_t>(c)] = Cmaa2SrgbToLinear(img.Pixel(x, y)[c]);
      }
    }
  }
  return rgb;
}

struct Tally {
  long pixels = 0, changed = 0, float_differing = 0, byte_differing = 0;
  std::string examples;
  void Add(const std::vector<float>& ours, const std::vector<float>& input, const float* theirs, int w, int h,
           const std::string& name) {
    for (int i = 0; i < w * h; ++i) {
      bool fdiff = false, bdiff = false, ch = false;
      for (int c = 0; c < 3; ++c) {
        const float o = ours[static_cast<size_t>(i) * 3 + static_cast<size_t>(c)], t = theirs[i * 4 + c];
        fdiff |= std::memcmp(&o, &t, 4) != 0;
        bdiff |= StoreUnorm8(Cmaa2LinearToSrgb(o)) != StoreUnorm8(Cmaa2LinearToSrgb(t));
        ch |= std::memcmp(&o, &input[static_cast<size_t>(i) * 3 + static_cast<size_t>(c)], 4) != 0;
      }
      ++pixels;
      changed += ch ? 1 : 0;
      float_differing += fdiff ? 1 : 0;
      byte_differing += bdiff ? 1 : 0;
      if (fdiff && examples.size() < 600) {
        std::ostringstream os;
        os.precision(9);
        os << " " << name << " (" << i % w << "," << i / w << ") ours " << ours[static_cast<size_t>(i) * 3] << ","
           << ours[static_cast<size_t>(i) * 3 + 1] << "," << ours[static_cast<size_t>(i) * 3 + 2] << " shader "
           << theirs[i * 4] << "," << theirs[i * 4 + 1] << "," << theirs[i * 4 + 2] << ";";
        examples += os.str();
      }
    }
  }
};

class Cmaa2Oracle : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string why = oracle::Cmaa2ShaderAvailable();
    if (!why.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI("CMAA2 oracle unavailable: " + why);
  }
  static const std::vector<NamedFrame>& Frames() {
    static const std::vector<NamedFrame> f = oracle::OracleFrames();
    return f;
  }
};

TEST_F(Cmaa2Oracle, EveryPresetAndOptionMatchesTheShader) {
  struct Config {
    const char* name;
    int preset;
    bool sharp, color;
  };
  const Config configs[] = {{"LOW", 0, false, false},
                            {"MEDIUM", 1, false, false},
                            {"HIGH", 2, false, false},
                            {"ULTRA", 3, false, false},
                            {"HIGH extra sharpness", 2, true, false},
                            {"HIGH colour edges", 2, false, true}};
  std::printf("lavapipe device: %s\n", oracle::VkCompute::DeviceName().c_str());
  for (const Config& cfg : configs) {
    Tally t;
    Cmaa2Stats stats;
    for (const NamedFrame& f : Frames()) {
      const int w = f.img.Width(), h = f.img.Height();
      const std::vector<float> in = Linear(f.img);
      Cmaa2Params p;
      p.preset = cfg.preset;
      p.extra_sharpness = cfg.sharp;
      p.color_edges = cfg.color;
      p.lanes = oracle::VkCompute::Lanes();
      const std::vector<float> ours = Cmaa2Linear(in, w, h, p, nullptr, &stats);
      const std::vector<float> theirs = oracle::RunCmaa2Shader(in, w, h, cfg.preset, cfg.sharp, cfg.color);
      t.Add(ours, in, theirs.data(), w, h, f.name);
    }
    std::printf(
        "CMAA2 %-22s pixels %ld changed %ld (%lu candidates, %lu items, %lu Z, %lu SLM fallbacks, %lu quads > 32) "
        "floats differing %ld, bytes differing %ld\n",
        cfg.name, t.pixels, t.changed, static_cast<unsigned long>(stats.candidates),
        static_cast<unsigned long>(stats.blend_items), static_cast<unsigned long>(stats.z_shapes),
        static_cast<unsigned long>(stats.slm_fallbacks), static_cast<unsigned long>(stats.truncated_quads),
        t.float_differing, t.byte_differing);
    // Measured (docs/cmaa2.md): at most 60 pixels of 162 531 with any float different (0.037 %),
    // at most 11 with a different byte (0.007 %); each such pixel has a sample one packing
    // step (R11G11B10) apart. The bounds leave no room for a systematic error.
    if (std::getenv("AALAB_ORACLE_EXAMPLES")) std::printf("%s:%s\n", cfg.name, t.examples.c_str());
    EXPECT_LE(t.float_differing * 2000, t.pixels) << cfg.name << ":" << t.examples;
    EXPECT_LE(t.byte_differing * 10000, t.pixels) << cfg.name << ":" << t.examples;
    EXPECT_GT(t.changed * 20, t.pixels) << cfg.name << ": CMAA2 changed almost nothing";
  }
}

// How much the result depends on the order the atomics happen in (the port's lanes, and
// the order the apply pass sums a pixel's samples in): not against the shader, port only.
TEST_F(Cmaa2Oracle, OrderOfTheAtomicsChangesLastBitsOnly) {
  long pixels = 0, floats_lanes = 0, bytes_lanes = 0, floats_rev = 0, bytes_rev = 0;
  for (const NamedFrame& f : Frames()) {
    const int w = f.img.Width(), h = f.img.Height();
    const std::vector<float> in = Linear(f.img);
    Cmaa2Params a, b, r;
    a.lanes = 8;
    b.lanes = 32;
    r.lanes = 8;
    r.reverse_sum = true;
    const std::vector<float> oa = Cmaa2Linear(in, w, h, a), ob = Cmaa2Linear(in, w, h, b),
                             orv = Cmaa2Linear(in, w, h, r);
    for (int i = 0; i < w * h; ++i) {
      bool fl = false, bl = false, fr = false, br = false;
      for (int c = 0; c < 3; ++c) {
        const size_t k = static_cast<size_t>(i) * 3 + static_cast<size_t>(c);
        fl |= oa[k] != ob[k];
        fr |= oa[k] != orv[k];
        bl |= StoreUnorm8(Cmaa2LinearToSrgb(oa[k])) != StoreUnorm8(Cmaa2LinearToSrgb(ob[k]));
        br |= StoreUnorm8(Cmaa2LinearToSrgb(oa[k])) != StoreUnorm8(Cmaa2LinearToSrgb(orv[k]));
      }
      ++pixels;
      floats_lanes += fl;
      bytes_lanes += bl;
      floats_rev += fr;
      bytes_rev += br;
    }
  }
  std::printf(
      "order: %ld pixels; lanes 8 vs 32: %ld differ in floats, %ld in bytes; summed in reverse: %ld floats, %ld "
      "bytes\n",
      pixels, floats_lanes, bytes_lanes, floats_rev, bytes_rev);
  EXPECT_GT(floats_rev, 0);  // the sum is order dependent: the shader's result is not fully determined
  EXPECT_LE(bytes_lanes * 10000, pixels);
  EXPECT_LE(bytes_rev * 10000, pixels);
}

}  // namespace
}  // namespace aalab
