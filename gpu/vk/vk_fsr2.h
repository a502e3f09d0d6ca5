/// FSR 2 (FidelityFX FSR 2.2.1) as its original GLSL passes through Vulkan, a whole frame at a
/// time over a warm sequence of frames (docs/gpu.md "Original shaders through Vulkan"). The
/// per-frame constants (cbFSR2, cbSPD, cbRCAS), the resources and the dispatches are the host
/// side of ffx_fsr2.cpp (ffxFsr2ContextDispatch), written here from that file: gpu/vk is
/// stand-alone and does not include methods/ (aalab's port, methods/fsr2_tables.h, computes the
/// same constants for the CPU path).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gpu/vk/vk_methods.h"
#include "gpu/vk/vk_runner.h"

namespace aalab::vk {

/// A row of aalab_vk's FSR 2 methods: display size = the frame's, render size = display / ratio.
struct Fsr2Preset {
  std::string spec;  ///< fsr2-native, fsr2-quality, fsr2-balanced, fsr2-performance, fsr2-ultra-performance
  float ratio;       ///< 1, 1.5, 1.7, 2, 3 (ffxFsr2GetUpscaleRatioFromQualityMode; native 1)
};
const std::vector<Fsr2Preset>& Fsr2Presets();
/// The preset named `spec`, or nullptr.
const Fsr2Preset* FindFsr2Preset(const std::string& spec);

/// ffxFsr2GetRenderResolutionFromQualityMode's side: (uint32_t)((float)display / ratio).
int Fsr2RenderSide(int display, float ratio);
/// ffxFsr2GetJitterPhaseCount: int32_t(8 · (display / render)²) (pow in float).
int Fsr2PhaseCount(int render_width, int display_width);
/// halton(index, base) of ffx_fsr2.cpp, float for float.
float Fsr2HaltonF(int index, int base);

/// cbFSR2 as the shaders declare it (std140: 124 bytes).
struct Fsr2Cb {
  int32_t render_size[2], max_render_size[2], display_size[2], input_color_size[2], luma_mip_size[2];
  int32_t luma_mip_level, frame_index;
  float device_to_view_depth[4], jitter[2], motion_vector_scale[2], downscale_factor[2], jitter_cancellation[2];
  float pre_exposure, previous_pre_exposure, tan_half_fov, jitter_sequence_length, delta_time, dynamic_res_change,
      view_space_to_meters;
};
static_assert(sizeof(Fsr2Cb) == 124, "cbFSR2 is 124 bytes in std140");

/// cbFSR2 of one frame as ffxFsr2ContextDispatch fills it for aalab_vk's sequence: context
/// flags none (no inverted or infinite depth, low-resolution motion vectors, no jitter
/// cancellation), max render size = render size, camera near 0.1, far 100, vertical fov 60°,
/// motion vectors in render pixels (app scale 1), pre-exposure 1 (the previous one 0 on the
/// reset frame: a fresh context is zeroed), Δt 16.67 ms, jitter `jitter`, frame index `frame`
/// (0 = reset), the luma mip level 4 of a max-render/2 chain.
Fsr2Cb Fsr2FrameConstants(int rw, int rh, int dw, int dh, const float jitter[2], int frame);

/// cbSPD and the pyramid's dispatch (SpdSetup over (0, 0, rw, rh), mips from the larger side).
struct Fsr2Spd {
  uint32_t mips, num_work_groups, work_group_offset[2], render_size[2];
  uint32_t groups_x, groups_y;
};
Fsr2Spd Fsr2SpdSetup(int rw, int rh);

/// The 128 r16 snorm codes of FSR2_LanczosLutData: round(lanczos2(2i/127) · 32767).
std::array<int16_t, 128> Fsr2LanczosCodes();

/// FsrRcasCon(sharpness remapped as the API does: −2·s + 2)'s con.x: the bits of exp2(−(2 − 2s)).
uint32_t Fsr2RcasConstant(float sharpness);

/// The six passes of the default pipeline in dispatch order (the JSON's pass names) and the
/// SPIR-V module of each (scripts/vk_shaders.sh's file names without .spv).
const std::vector<std::string>& Fsr2PassNames();
std::vector<std::string> Fsr2Modules();

/// One render-size frame of the sequence, as uploaded: colour rgba16f (4 halves a pixel),
/// depth r32f, motion rg16f (render pixels, previous position − current).
struct Fsr2InputFrame {
  std::vector<uint16_t> color, motion;
  std::vector<float> depth;
};
/// Frame k (0..7) of the synthetic sequence made from `display` at render size rw × rh with
/// `jitter` (docs/gpu.md; gpu/vk/vk_fsr2_host.cpp).
Fsr2InputFrame Fsr2MakeInput(const Frame& display, int k, int rw, int rh, const float jitter[2]);
/// The colour of the sequence's frame k at display-pixel position (px, py), unjittered.
void Fsr2SceneColor(const Frame& display, int k, float px, float py, float rgb[3]);
/// The jitter of the sequence's frame `slot`: ffxFsr2GetJitterOffset(slot, phases).
void Fsr2SequenceJitter(int slot, int phases, float out[2]);
/// IEEE binary16 bits to float.
float Fsr2HalfToFloat(uint16_t h);

/// Runs preset `spec` at `display`'s size: the synthetic sequence (docs/gpu.md) built from
/// `display` (the scene's 1x frame), `warmup` frames untimed (the first one resets), then
/// `repeat` frames timed one by one (timings.ms[r][k]: pass k of frame r; whole[r]: the frame).
/// The output is the last frame's upscaled, sharpened image (RGBA16F) as 8-bit; `check` gets
/// its float facts.
MethodResult RunFsr2(Device& device, const std::string& spirv_dir, const std::string& spec, const Frame& display,
                     int warmup, int repeat);

}  // namespace aalab::vk
