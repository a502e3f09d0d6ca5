// aalab_vk's FSR 2 frame (gpu/vk/vk_fsr2.cpp: its resources, bindings, constants and pass
// order) against the FSR 2 oracle's chain (tests/oracle/fsr2_shader.h: the same original GLSL
// passes, each run on its own with the inputs and outputs the oracle gives it), on lavapipe:
// the first frame after a reset of the tool's own sequence, 96×54 display, quality (64×36
// render). The oracle chain: luminance pyramid (from the API's reset state), reconstruct,
// depth clip, lock, accumulate with APPLY_SHARPENING, RCAS (sharpness 0.8), every history
// input cleared (zeros) as the tool's first frame finds them; the exposure is the pyramid's
// auto exposure. Where they may differ: the oracle's modules are made precise (no fused
// multiply-adds) and the tool's are not, the tool's dilated depth is r32f (the API's) where
// the oracle's is r16f (the GLSL's), and the tool's output is rgba16f (rounded by lavapipe)
// where the oracle reads RCAS's floats. Skips without lavapipe, glslang or the sources;
// fails under CI.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "gpu/vk/vk_fsr2.h"
#include "gpu/vk/vk_runner.h"
#include "methods/fsr2.h"
#include "methods/fsr2_pyramid.h"
#include "methods/fsr2_tables.h"
#include "tests/cli/cli_util.h"
#include "tests/oracle/fsr2_shader.h"
#include "tests/skip_or_fail.h"

namespace aalab {
namespace {

namespace fs = std::filesystem;

// A 96×54 frame with structure on both axes: a gradient (red across, green down), three dark
// boxes at uneven places, a bright diagonal line.
vk::Frame Display() {
  vk::Frame f{96, 54, std::vector<uint8_t>(96 * 54 * 4, 255)};
  for (int y = 0; y < 54; ++y) {
    for (int x = 0; x < 96; ++x) {
      uint8_t* p = &f.rgba[(static_cast<size_t>(y) * 96 + static_cast<size_t>(x)) * 4];
      p[0] = static_cast<uint8_t>(40 + 2 * x);
      p[1] = static_cast<uint8_t>(60 + 3 * y);
      p[2] = 90;
      const bool box = (x >= 10 && x < 27 && y >= 7 && y < 19) || (x >= 55 && x < 61 && y >= 30 && y < 50) ||
                       (x >= 70 && x < 90 && y >= 4 && y < 9);
      if (box) p[0] = p[1] = p[2] = 20;
      if (std::abs((x - 30) - 2 * (y - 20)) <= 1 && x > 30 && x < 60) p[0] = p[1] = p[2] = 250;
    }
  }
  return f;
}

Fsr2Plane FromHalves(const std::vector<uint16_t>& h, int w, int hh, int c) {
  Fsr2Plane p(w, hh, c);
  for (size_t i = 0; i < p.v.size(); ++i) p.v[i] = vk::Fsr2HalfToFloat(h[i]);
  return p;
}

TEST(VkFsr2Oracle, FirstFrameAfterResetMatchesTheOracleChain) {
  const std::string missing = oracle::Fsr2ShaderAvailable();  // also points Vulkan at lavapipe
  if (!missing.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI("FSR 2 oracle unavailable: " + missing);
  const fs::path dir = clitest::TempDir("vk-fsr2-oracle");
  const clitest::CmdResult sh =
      clitest::RunCommand(std::string(AALAB_SOURCE_DIR) + "/scripts/vk_shaders.sh " + (dir / "spv").string() + " 2>&1");
  ASSERT_EQ(sh.code, 0) << sh.output;

  const vk::Frame display = Display();
  const int rw = 64, rh = 36, dw = 96, dh = 54;
  vk::MethodResult tool;
  {
    vk::Device device("llvmpipe");
    tool = vk::RunFsr2(device, (dir / "spv").string(), "fsr2-quality", display, 0, 1);
  }
  ASSERT_EQ(tool.output_half.size(), static_cast<size_t>(dw) * dh * 4);

  // The oracle chain on the same frame 0.
  const int phases = Fsr2JitterPhaseCount(rw, dw);
  float jitter[2];
  vk::Fsr2SequenceJitter(0, phases, jitter);
  const vk::Fsr2InputFrame in = vk::Fsr2MakeInput(display, 0, rw, rh, jitter);
  const Fsr2Plane color = FromHalves(in.color, rw, rh, 4), motion = FromHalves(in.motion, rw, rh, 2);
  Fsr2Plane depth(rw, rh, 1);
  depth.v = in.depth;
  Fsr2Constants k;
  const vk::Fsr2Cb cb = vk::Fsr2FrameConstants(rw, rh, dw, dh, jitter, 0);
  static_assert(sizeof k == sizeof cb, "both are cbFSR2");
  std::memcpy(static_cast<void*>(&k), &cb, sizeof k);
  Fsr2Options o;
  o.apply_sharpening = true;

  Fsr2PyramidState pyramid = Fsr2PyramidReset(k);
  oracle::RunFsr2PyramidShader(k, aalab::Fsr2SpdSetup(rw, rh), color, &pyramid);
  const float exposure = pyramid.auto_exposure[0];
  Fsr2ReconstructOut rec;
  rec.prev_depth.assign(static_cast<size_t>(rw) * rh, 0u);
  oracle::RunFsr2ReconstructShader(k, o, color, depth, motion, exposure, &rec);
  const Fsr2Plane previous_motion(rw, rh, 2);
  Fsr2DepthClipIn dc;
  dc.prev_depth = &rec.prev_depth;
  dc.dilated_motion = &rec.dilated_motion;
  dc.dilated_depth = &rec.dilated_depth;
  dc.previous_dilated_motion = &previous_motion;
  dc.motion = &motion;
  dc.color = &color;
  dc.depth = &depth;
  dc.exposure = exposure;
  Fsr2DepthClipOut clip;
  oracle::RunFsr2DepthClipShader(k, o, dc, &clip);
  Fsr2Plane new_locks(dw, dh, 1);
  oracle::RunFsr2LockShader(k, o, rec.lock_luma, &new_locks, &rec.prev_depth);
  const Fsr2Plane history(dw, dh, 4), lock_status(dw, dh, 2), luma_history(dw, dh, 4);
  Fsr2Plane lut(128, 1, 1);
  const auto lut_floats = Fsr2LanczosLut();
  lut.v.assign(lut_floats.begin(), lut_floats.end());
  const auto codes = Fsr2LanczosLutCodes();
  Fsr2AccumulateIn ai;
  ai.exposure = exposure;
  ai.dilated_reactive_masks = &clip.reactive_masks;
  ai.dilated_motion = &rec.dilated_motion;
  ai.history = &history;
  ai.lock_status = &lock_status;
  ai.prepared_color = &clip.prepared_color;
  ai.lanczos_lut = &lut;
  ai.luma_mip = &pyramid.luma_mip;
  ai.luma_history = &luma_history;
  ai.new_locks = &new_locks;
  Fsr2AccumulateOut acc;
  oracle::RunFsr2AccumulateShader(k, o, ai, std::vector<int16_t>(codes.begin(), codes.end()), &acc);
  const std::vector<float> rcas = oracle::RunFsr2RcasShader(k, acc.internal_upscaled, exposure, Fsr2RcasCon(0.8f));

  // Compare rgb: the tool's half against the oracle's float, in steps of the half's spacing.
  long same = 0, within1 = 0, total = 0;
  double worst = 0;
  for (size_t i = 0; i < static_cast<size_t>(dw) * dh; ++i) {
    for (size_t c = 0; c < 3; ++c) {
      const float t = vk::Fsr2HalfToFloat(tool.output_half[i * 4 + c]), r = rcas[i * 3 + c];
      ASSERT_TRUE(std::isfinite(t)) << i;
      const float ulp = std::ldexp(1.0f, std::max(-24, std::ilogb(std::max(std::fabs(r), 0x1p-14f)) - 10));
      const double steps = std::fabs(static_cast<double>(t) - r) / ulp;
      same += steps < 1.0;
      within1 += steps <= 2.0;
      worst = std::max(worst, steps);
      ++total;
    }
  }
  std::printf(
      "FSR 2 first frame, tool vs oracle chain: %ld/%ld rgb values within a half step, %ld within 2, worst "
      "%.1f steps\n",
      same, total, within1, worst);
  EXPECT_GE(same * 100, total * 99);
  EXPECT_EQ(within1, total);
}

}  // namespace
}  // namespace aalab
