// FSR 2's luminance pyramid (methods/fsr2_pyramid.h) against the ORIGINAL FSR 2.2.1 pass
// ffx_fsr2_compute_luminance_pyramid_pass.glsl with ffx_spd.h (read from
// ../shared/third_party/fidelityfx-fsr2), compiled by glslangValidator and run on lavapipe
// (tests/oracle/fsr2_shader.h). Render sizes that are not multiples of 64, from one workgroup
// with 5 mips to 45 workgroups with 9 (the global-atomic tail, mips 6 to 8); flat, gradient,
// HDR and black colour; jitter and pre-exposure not 0 and 1; two frames each, the second
// starting from the first's state (the exposure's temporal smoothing). Compared bit for bit:
// the shading-change mip (luma_mip_level 4) and mip 5 (r16f), the auto-exposure texel (rg32f)
// and the atomic counter. Twice: the port with the C library's log2/exp2 (the figures are
// printed; differences must be the few-ulp transcendental ones), and the port with lavapipe's
// own log2/exp2 values substituted (every output identical). Without the sources, glslang or
// lavapipe the tests skip, and fail under CI.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "methods/fsr2_pyramid.h"
#include "methods/fsr2_tables.h"
#include "tests/oracle/fsr2_shader.h"
#include "tests/oracle/third_party_sources.h"
#include "tests/skip_or_fail.h"

namespace aalab {
namespace {

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

// A small deterministic generator (no std:: distributions: their output is library-defined).
struct Lcg {
  uint32_t s;
  float Next() {
    s = s * 1664525u + 1013904223u;
    return static_cast<float>(s >> 8) / 16777216.0f;
  }
};

enum class Content { kFlat, kGradient, kHdr, kStripes, kBlack };
const char* Name(Content c) {
  switch (c) {
    case Content::kFlat: return "flat";
    case Content::kGradient: return "gradient";
    case Content::kHdr: return "hdr";
    case Content::kStripes: return "stripes";
    case Content::kBlack: return "black";
  }
  return "?";
}

// The colour (rgba) of a w × h render; `frame` changes it between the two frames.
Fsr2Plane MakeColor(Content c, int w, int h, int frame) {
  Fsr2Plane p(w, h, 4);
  Lcg rng{static_cast<uint32_t>(w * 131 + h * 7 + frame * 977 + static_cast<int>(c))};
  const float gain = frame == 0 ? 1.0f : 1.7f;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float r = 0, g = 0, b = 0;
      const float fx = static_cast<float>(x) / static_cast<float>(w),
                  fy = static_cast<float>(y) / static_cast<float>(h);
      switch (c) {
        case Content::kFlat: r = g = b = 0.35f * gain; break;
        case Content::kGradient:  // different ramps per channel, on both axes
          r = fx * gain;
          g = fy * 0.8f * gain;
          b = (1.0f - fx) * fy * gain;
          break;
        case Content::kHdr: {  // 0 to ~2000, zeros, negatives, bright specks, a dark box
          const float n = rng.Next();
          r = fx * fx * 40.0f * gain + n;
          g = fy * 12.0f + (n > 0.97f ? 2000.0f : 0.0f);
          b = n < 0.05f ? -0.5f : n * 3.0f;
          if (x > w / 3 && x < w / 2 && y > h / 4 && y < h / 2) r = g = b = 0.0f;
          break;
        }
        case Content::kStripes:  // rows alternately ~3000 and ~0.002: log lumas of +8 and −6.2 in every
                                 // 2×2, where the order of the four additions shows in the sum
          r = g = b = (y % 2 == 0 ? 3000.0f : 0.002f) * (1.0f + 0.37f * rng.Next()) * gain;
          break;
        case Content::kBlack: break;
      }
      p.At(x, y, 0) = r;
      p.At(x, y, 1) = g;
      p.At(x, y, 2) = b;
      p.At(x, y, 3) = 1.0f;
    }
  }
  return p;
}

// A render of w × h in a max render size (and colour texture) of mw × mh.
struct Size {
  int w, h, mw, mh;
};

Fsr2Constants MakeConstants(const Size& z) {
  const int w = z.w, h = z.h;
  Fsr2Constants k;
  k.render_size[0] = w;
  k.render_size[1] = h;
  k.max_render_size[0] = k.input_color_size[0] = z.mw;
  k.max_render_size[1] = k.input_color_size[1] = z.mh;
  k.display_size[0] = w * 3 / 2;
  k.display_size[1] = h * 3 / 2;
  k.luma_mip_level = 4;  // FFX_FSR2_SHADING_CHANGE_MIP_LEVEL, as the API sets it
  k.luma_mip_size[0] = static_cast<int>(static_cast<float>(z.mw) / 32.0f);  // max render size / (2 << 4)
  k.luma_mip_size[1] = static_cast<int>(static_cast<float>(z.mh) / 32.0f);
  const Fsr2Jitter j = Fsr2JitterOffset(3, Fsr2JitterPhaseCount(w, k.display_size[0]));
  k.jitter[0] = j.x;  // (−0.375, −0.0556): a bilinear sample between four texels
  k.jitter[1] = j.y;
  k.pre_exposure = 1.25f;
  k.previous_pre_exposure = 1.25f;
  k.delta_time = 0.0167f;
  return k;
}

// lavapipe's log2/exp2 for the port: values looked up by argument, fetched from lavapipe for
// every argument the port asks for (a run that asks for new ones is repeated).
struct LavapipeMath {
  std::map<uint32_t, float> log2, exp2;
  std::set<uint32_t> missing, asked_log2, asked_exp2;
  Fsr2Transcendentals Hooks() {
    Fsr2Transcendentals t;
    t.log2 = [this](float x) {
      asked_log2.insert(Bits(x));
      return Look(log2, x, std::log2(x));
    };
    t.exp2 = [this](float x) {
      asked_exp2.insert(Bits(x));
      return Look(exp2, x, std::exp2(x));
    };
    return t;
  }
  float Look(const std::map<uint32_t, float>& m, float x, float fallback) {
    const auto it = m.find(Bits(x));
    if (it != m.end()) return it->second;
    missing.insert(Bits(x));
    return fallback;
  }
  // Fetches the missing arguments; false when there were none.
  bool Fill() {
    if (missing.empty()) return false;
    std::vector<float> args;
    for (uint32_t u : missing) {
      float f;
      std::memcpy(&f, &u, 4);
      args.push_back(f);
    }
    const std::vector<float> r = oracle::RunLavapipeLog2Exp2(args);
    for (size_t i = 0; i < args.size(); ++i) {
      log2[Bits(args[i])] = r[2 * i];
      exp2[Bits(args[i])] = r[2 * i + 1];
    }
    missing.clear();
    return true;
  }
};

struct Diff {
  int luma = 0, luma_n = 0, mip5 = 0, mip5_n = 0, exposure = 0, counter = 0;
  bool exposure_differs = false, lavg_differs = false;
  int max_half_steps = 0;   // largest distance in half-float steps among the differing mip texels
  double exposure_rel = 0;  // largest relative difference of the two exposure floats
};

int HalfSteps(float a, float b) {
  return std::abs(static_cast<int>(Fsr2HalfBits(a)) - static_cast<int>(Fsr2HalfBits(b)));
}

Diff Compare(const Fsr2PyramidState& port, const Fsr2PyramidState& shader) {
  Diff d;
  d.luma_n = static_cast<int>(port.luma_mip.v.size());
  d.mip5_n = static_cast<int>(port.mip5.v.size());
  for (size_t i = 0; i < port.luma_mip.v.size(); ++i) {
    if (Bits(port.luma_mip.v[i]) != Bits(shader.luma_mip.v[i])) {
      ++d.luma;
      d.max_half_steps = std::max(d.max_half_steps, HalfSteps(port.luma_mip.v[i], shader.luma_mip.v[i]));
    }
  }
  for (size_t i = 0; i < port.mip5.v.size(); ++i) {
    if (Bits(port.mip5.v[i]) != Bits(shader.mip5.v[i])) {
      ++d.mip5;
      d.max_half_steps = std::max(d.max_half_steps, HalfSteps(port.mip5.v[i], shader.mip5.v[i]));
    }
  }
  for (int c = 0; c < 2; ++c) {
    if (Bits(port.auto_exposure[c]) != Bits(shader.auto_exposure[c])) {
      ++d.exposure;
      (c == 0 ? d.exposure_differs : d.lavg_differs) = true;
      const double a = port.auto_exposure[c], b = shader.auto_exposure[c];
      d.exposure_rel = std::max(d.exposure_rel, std::fabs(a - b) / std::max(std::fabs(b), 1e-30));
    }
  }
  d.counter = port.atomic_counter != shader.atomic_counter;
  return d;
}

class Fsr2PyramidOracle : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string why = oracle::Fsr2ShaderAvailable();
    if (!why.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI("FSR2 oracle unavailable: " + why);
  }
};

struct Totals {
  long identical = 0, total = 0;
  long log2_args = 0, log2_differ = 0, exp2_args = 0, exp2_differ = 0;  // lavapipe against the C library
};

// Two frames of one size and content through the shader and both ports; returns the outputs
// compared (mip texels + 2 exposure floats + the counter, per frame) for each port.
void RunCase(const Size& z, Content c, Totals* libm, Totals* lavapipe) {
  const int w = z.w, h = z.h;
  const Fsr2Constants k = MakeConstants(z);
  const Fsr2SpdDispatch spd = Fsr2SpdSetup(w, h);
  Fsr2Options o;
  o.half_toward_zero = true;  // lavapipe's r16f stores
  Fsr2PyramidState shader = Fsr2PyramidReset(k), port = shader, exact = shader;
  for (int frame = 0; frame < 2; ++frame) {
    const Fsr2Plane color = MakeColor(c, z.mw, z.mh, frame);
    oracle::RunFsr2PyramidShader(k, spd, color, &shader);
    Fsr2LuminancePyramid(k, spd, color, &port, o);
    // The port again with lavapipe's log2/exp2, repeated until it asks for no new argument.
    LavapipeMath math;
    Fsr2PyramidState e;
    for (int round = 0; round < 8; ++round) {
      e = exact;
      Fsr2LuminancePyramid(k, spd, color, &e, o, math.Hooks());
      if (!math.Fill()) break;
    }
    exact = e;
    auto from_bits = [](uint32_t u) {
      float f;
      std::memcpy(&f, &u, 4);
      return f;
    };
    for (uint32_t u : math.asked_log2) {
      ++lavapipe->log2_args;
      lavapipe->log2_differ += Bits(math.log2[u]) != Bits(std::log2(from_bits(u)));
    }
    for (uint32_t u : math.asked_exp2) {
      ++lavapipe->exp2_args;
      lavapipe->exp2_differ += Bits(math.exp2[u]) != Bits(std::exp2(from_bits(u)));
    }
    const Diff dl = Compare(port, shader), de = Compare(exact, shader);
    const int n = dl.luma_n + dl.mip5_n + 3;
    std::printf(
        "  %dx%d (of %dx%d) %-8s frame %d (mips %u, %u groups): exposure %.6g, log avg %.6g | C library log2/exp2: "
        "luma mip "
        "%d/%d, mip 5 %d/%d, exposure %s, log avg %s (rel %.2g), max %d half step(s) | lavapipe's: %d/%d identical\n",
        w, h, z.mw, z.mh, Name(c), frame, spd.c.mips, spd.c.num_work_groups, shader.auto_exposure[0],
        shader.auto_exposure[1], dl.luma_n - dl.luma, dl.luma_n, dl.mip5_n - dl.mip5, dl.mip5_n,
        dl.exposure_differs ? "differs" : "same", dl.lavg_differs ? "differs" : "same", dl.exposure_rel,
        dl.max_half_steps, n - (de.luma + de.mip5 + de.exposure + de.counter), n);
    libm->total += n;
    libm->identical += n - (dl.luma + dl.mip5 + dl.exposure + dl.counter);
    lavapipe->total += n;
    lavapipe->identical += n - (de.luma + de.mip5 + de.exposure + de.counter);
    // With lavapipe's transcendentals every output is the shader's, bit for bit.
    EXPECT_EQ(de.luma + de.mip5 + de.exposure + de.counter, 0) << w << "x" << h << " " << Name(c) << " frame " << frame;
    // With the C library's: the mips at most one half step apart, the exposure within 1e-6.
    EXPECT_LE(dl.max_half_steps, 1) << w << "x" << h << " " << Name(c) << " frame " << frame;
    EXPECT_LT(dl.exposure_rel, 1e-6) << w << "x" << h << " " << Name(c) << " frame " << frame;
    EXPECT_EQ(dl.counter, 0);
    EXPECT_EQ(shader.atomic_counter, 0u);  // the tail resets it (and without a tail nobody touches it)
  }
}

void RunSizes(const std::vector<Size>& sizes) {
  Totals libm, lavapipe;
  for (const Size& z : sizes) {
    for (Content c : {Content::kFlat, Content::kGradient, Content::kHdr, Content::kStripes, Content::kBlack}) {
      RunCase(z, c, &libm, &lavapipe);
    }
  }
  std::printf("  identical outputs: %ld/%ld with the C library's log2/exp2, %ld/%ld with lavapipe's\n", libm.identical,
              libm.total, lavapipe.identical, lavapipe.total);
  std::printf("  lavapipe's log2 differs from the C library's on %ld of %ld arguments, exp2 on %ld of %ld\n",
              lavapipe.log2_differ, lavapipe.log2_args, lavapipe.exp2_differ, lavapipe.exp2_args);
}

// One workgroup (40×24: 5 mips, the exposure from mip 4) and two without the atomic (100×60:
// 6 mips, the exposure from workgroup (0,0)'s mip 5 alone).
TEST_F(Fsr2PyramidOracle, SmallRendersWithoutTheAtomicTail) { RunSizes({{40, 24, 40, 24}, {100, 60, 100, 60}}); }

// 150×90 (7 mips, 6 groups), 300×170 (8 mips, 15 groups), 530×290 (9 mips, 45 groups): the last
// workgroup reads mip 5 back and reduces on to the exposure.
TEST_F(Fsr2PyramidOracle, LargerRendersThroughTheGlobalAtomic) {
  RunSizes({{150, 90, 150, 90}, {300, 170, 300, 170}, {530, 290, 530, 290}});
}

// Dynamic resolution: a 150×90 render in a 200×120 colour texture and max render size (the
// colour's UV clamped to the render, mip views of the larger chain: mip 4 6×3, mip 5 3×1).
TEST_F(Fsr2PyramidOracle, RenderBelowTheMaxRenderSize) { RunSizes({{150, 90, 200, 120}, {100, 60, 130, 70}}); }

// The maximum-bias table of methods/fsr2_tables.cpp against all 256 numbers of the pinned
// api/ffx_fsr2_maximum_bias.h (parsed here, as text).
TEST(Fsr2TablesOracle, MaximumBiasTableIsTheApiFile) {
  const std::string rel = "fidelityfx-fsr2/api/ffx_fsr2_maximum_bias.h";
  if (!oracle::ThirdPartyHas(rel)) AALAB_SKIP_OR_FAIL_UNDER_CI("the FSR2 sources are missing: " + rel);
  const std::string text = oracle::ReadThirdParty(rel);
  size_t pos = text.find("ffxFsr2MaximumBias[]");
  ASSERT_NE(pos, std::string::npos);
  pos = text.find('{', pos);
  const size_t end = text.find('}', pos);
  std::vector<float> values;
  for (size_t i = pos + 1; i < end;) {
    const char* s = text.c_str() + i;
    char* e = nullptr;
    const float v = std::strtof(s, &e);
    if (e != s) {
      values.push_back(v);
      i += static_cast<size_t>(e - s);
    } else {
      ++i;
    }
  }
  const auto& ours = Fsr2MaximumBiasTable();
  ASSERT_EQ(values.size(), ours.size());
  for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(Bits(values[i]), Bits(ours[i])) << "entry " << i;
}

}  // namespace
}  // namespace aalab
