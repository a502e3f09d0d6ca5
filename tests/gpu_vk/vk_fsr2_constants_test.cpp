// aalab_vk's FSR 2 host side (gpu/vk/vk_fsr2.cpp: written from api/ffx_fsr2.cpp for the
// stand-alone tool) against aalab's own port of the same host code (methods/fsr2_tables.h,
// methods/fsr2_pyramid.h, methods/fsr2.h, itself checked against the API's values in
// tests/methods/fsr2_tables_test.cpp): cbFSR2 of every frame of the tool's sequence byte for
// byte, cbSPD and the pyramid's dispatch, the Lanczos table, the RCAS constant, the jitter and
// phase count, and the render sizes of the presets (worked out by hand: (uint32)(display /
// ratio) in float).
#include <gtest/gtest.h>

#include <cstring>

#include "gpu/vk/vk_fsr2.h"
#include "methods/fsr2.h"
#include "methods/fsr2_pyramid.h"
#include "methods/fsr2_tables.h"

namespace aalab {
namespace {

TEST(VkFsr2Constants, RenderSizesOfThePresetsAtTwoDisplaySizes) {
  struct Case {
    const char* spec;
    int w1080, h1080, w4k, h4k;
  };
  // 1920/1.5 = 1280, 1080/1.5 = 720; 1920/1.7 = 1129.41, 1080/1.7 = 635.29; /2; /3; native.
  const Case cases[] = {{"fsr2-quality", 1280, 720, 2560, 1440},
                        {"fsr2-balanced", 1129, 635, 2258, 1270},
                        {"fsr2-performance", 960, 540, 1920, 1080},
                        {"fsr2-ultra-performance", 640, 360, 1280, 720},
                        {"fsr2-native", 1920, 1080, 3840, 2160}};
  ASSERT_EQ(vk::Fsr2Presets().size(), 5u);
  for (const Case& c : cases) {
    const vk::Fsr2Preset* p = vk::FindFsr2Preset(c.spec);
    ASSERT_NE(p, nullptr) << c.spec;
    EXPECT_EQ(vk::Fsr2RenderSide(1920, p->ratio), c.w1080) << c.spec;
    EXPECT_EQ(vk::Fsr2RenderSide(1080, p->ratio), c.h1080) << c.spec;
    EXPECT_EQ(vk::Fsr2RenderSide(3840, p->ratio), c.w4k) << c.spec;
    EXPECT_EQ(vk::Fsr2RenderSide(2160, p->ratio), c.h4k) << c.spec;
  }
  EXPECT_EQ(vk::FindFsr2Preset("fsr2-ultra"), nullptr);
}

TEST(VkFsr2Constants, CbFsr2OfEveryFrameOfTheSequenceEqualsThePortsBytes) {
  static_assert(sizeof(vk::Fsr2Cb) == sizeof(Fsr2Constants), "both are cbFSR2");
  const int sizes[][4] = {{1280, 720, 1920, 1080},  {1129, 635, 1920, 1080}, {640, 360, 1920, 1080},
                          {1920, 1080, 1920, 1080}, {64, 36, 96, 54},        {2258, 1270, 3840, 2160}};
  for (const auto& s : sizes) {
    const int rw = s[0], rh = s[1], dw = s[2], dh = s[3];
    Fsr2ContextParams ctx;
    ctx.max_render_size[0] = rw;
    ctx.max_render_size[1] = rh;
    ctx.display_size[0] = dw;
    ctx.display_size[1] = dh;
    Fsr2ContextState state;
    // ffxFsr2ContextCreate zeroes the context: its first frame's previous pre-exposure is 0.
    std::memset(static_cast<void*>(&state.constants), 0, sizeof state.constants);
    const int phases = Fsr2JitterPhaseCount(rw, dw);
    EXPECT_EQ(vk::Fsr2PhaseCount(rw, dw), phases);
    for (int frame = 0; frame < 8; ++frame) {  // the tool's 8 frames; frame 0 resets
      const Fsr2Jitter j = Fsr2JitterOffset(frame, phases);
      const float jitter[2] = {vk::Fsr2HaltonF((frame % phases) + 1, 2) - 0.5f,
                               vk::Fsr2HaltonF((frame % phases) + 1, 3) - 0.5f};
      EXPECT_EQ(jitter[0], j.x);
      EXPECT_EQ(jitter[1], j.y);
      Fsr2DispatchParams p;
      p.jitter[0] = j.x;
      p.jitter[1] = j.y;
      p.motion_vector_scale[0] = p.motion_vector_scale[1] = 1.0f;  // motion vectors in render pixels
      p.render_size[0] = p.input_color_size[0] = rw;
      p.render_size[1] = p.input_color_size[1] = rh;
      p.frame_time_delta_ms = 16.6667f;
      p.pre_exposure = 1.0f;
      Fsr2NextFrameConstants(ctx, p, &state);
      const vk::Fsr2Cb mine = vk::Fsr2FrameConstants(rw, rh, dw, dh, jitter, frame);
      uint32_t a[31], b[31];
      std::memcpy(a, &mine, sizeof a);
      std::memcpy(b, &state.constants, sizeof b);
      for (int w = 0; w < 31; ++w) EXPECT_EQ(a[w], b[w]) << rw << "x" << rh << " frame " << frame << " word " << w;
      EXPECT_EQ(mine.frame_index, frame);
    }
  }
}

TEST(VkFsr2Constants, SpdLanczosAndRcasEqualThePort) {
  for (const auto& s : {std::pair{1280, 720}, std::pair{1129, 635}, std::pair{64, 36}, std::pair{3840, 2160}}) {
    const vk::Fsr2Spd mine = vk::Fsr2SpdSetup(s.first, s.second);
    const Fsr2SpdDispatch port = aalab::Fsr2SpdSetup(s.first, s.second);
    EXPECT_EQ(mine.mips, port.c.mips);
    EXPECT_EQ(mine.num_work_groups, port.c.num_work_groups);
    EXPECT_EQ(mine.work_group_offset[0], port.c.work_group_offset[0]);
    EXPECT_EQ(mine.work_group_offset[1], port.c.work_group_offset[1]);
    EXPECT_EQ(mine.render_size[0], port.c.render_size[0]);
    EXPECT_EQ(mine.render_size[1], port.c.render_size[1]);
    EXPECT_EQ(static_cast<int>(mine.groups_x), port.groups_x);
    EXPECT_EQ(static_cast<int>(mine.groups_y), port.groups_y);
  }
  // By hand: 1280x720 is 20 x 12 tiles of 64, mips floor(log2 1280) = 10.
  EXPECT_EQ(vk::Fsr2SpdSetup(1280, 720).num_work_groups, 240u);
  EXPECT_EQ(vk::Fsr2SpdSetup(1280, 720).mips, 10u);
  EXPECT_EQ(vk::Fsr2LanczosCodes(), Fsr2LanczosLutCodes());
  EXPECT_EQ(vk::Fsr2LanczosCodes()[0], 32767);  // lanczos2(0) = 1
  EXPECT_EQ(vk::Fsr2LanczosCodes()[127], 0);    // lanczos2(2) = 0 (sin(2π) rounds to a few 1e-8)
  for (float s : {0.0f, 0.5f, 0.8f, 1.0f}) EXPECT_EQ(vk::Fsr2RcasConstant(s), Fsr2RcasCon(s)) << s;
  EXPECT_EQ(vk::Fsr2RcasConstant(1.0f), 0x3f800000u);  // exp2(0) = 1
}

}  // namespace
}  // namespace aalab
