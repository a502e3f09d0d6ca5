/// FSR 2.2.1's luminance pyramid pass (ffx_fsr2_compute_luminance_pyramid_pass.glsl: AMD's
/// single-pass downsampler SPD, ffx_spd.h, with FSR 2's callbacks in
/// ffx_fsr2_compute_luminance_pyramid.h) ported in its 32-bit float path with wave operations
/// (the GLSL default): the log luminance of the render, averaged down 2×2 at a time, the mip
/// that later passes read (luma_mip_level, 4) and mip 5 stored as r16f, and the auto-exposure
/// texel (rg32f: exposure, log average) from the last mip. docs/fsr2.md has the proof.
#pragma once
#include <cstdint>
#include <functional>

#include "methods/fsr2.h"

namespace aalab {

/// cbSPD of the pass (std140, 24 bytes) and the dispatch the API gives it (SpdSetup over the
/// rectangle (0, 0, render width, render height), mips from the larger side).
struct Fsr2SpdConstants {
  uint32_t mips = 0;             ///< min(floor(log2(max(w, h))), 12)
  uint32_t num_work_groups = 0;  ///< groups_x · groups_y
  uint32_t work_group_offset[2] = {0, 0};
  uint32_t render_size[2] = {0, 0};
};
struct Fsr2SpdDispatch {
  Fsr2SpdConstants c;
  int groups_x = 0, groups_y = 0;  ///< ceil(w / 64), ceil(h / 64): one 256-thread group per 64×64 tile
};
/// SpdSetup as ffxFsr2ContextDispatch calls it. Throws std::invalid_argument unless both sides
/// are positive.
Fsr2SpdDispatch Fsr2SpdSetup(int render_width, int render_height);

/// What the pass reads back and leaves for the next frame: the two r16f mips it stores (sized
/// as the views of FSR2_ExposureMips, a max_render_size/2 chain: mip m is
/// max(1, floor((max_render_size / 2) >> m)) on each side), the auto-exposure texel and the
/// global atomic counter (r32ui 1×1).
struct Fsr2PyramidState {
  Fsr2Plane luma_mip;  ///< scene luminance mip luma_mip_level (log luminance, what accumulate samples)
  Fsr2Plane mip5;      ///< mip 5 (SPD's hand-over from the workgroups to the last one)
  float auto_exposure[2] = {-1.0f, 1e8f};  ///< (exposure, log average); the API's reset clear is (−1, 1e8)
  uint32_t atomic_counter = 0;
};
/// The state the API leaves after a reset (its clears): mips 0, exposure (−1, 1e8), counter 0.
Fsr2PyramidState Fsr2PyramidReset(const Fsr2Constants& k);

/// The transcendental functions the pass uses, as Mesa lowers GLSL's: log(x) = log2(x)·(1/log2 e),
/// exp(x) = exp2(x·log2 e) (the exposure's pow(2, log2(y)) is y). Empty: the C library's log2f/exp2f.
/// (A test may put the oracle's own implementation's values here to separate those few ulps from
/// the rest of the arithmetic: tests/oracle/fsr2_pyramid_oracle_test.cpp.)
struct Fsr2Transcendentals {
  std::function<float(float)> log2, exp2;
};

/// The pass over the whole dispatch: every 64×64 tile's SPD reduction (mips 0–5), then, when
/// spd.mips > 6, the last workgroup's (mips 6 up from the stored mip 5), with every 2×2 average
/// in the order the shader's lanes give it (docs/fsr2.md). `color` is the app's colour texture
/// (k.input_color_size), sampled bilinearly at each render pixel's jittered centre; `state` is
/// updated (a state with empty planes is reset first).
void Fsr2LuminancePyramid(const Fsr2Constants& k, const Fsr2SpdDispatch& spd, const Fsr2Plane& color,
                          Fsr2PyramidState* state, const Fsr2Options& o = {}, const Fsr2Transcendentals& math = {});

/// The size of mip `m` of FSR2_ExposureMips for a max render size: max(1, (size / 2) >> m).
int Fsr2LumaMipExtent(int max_render_extent, int m);

}  // namespace aalab
