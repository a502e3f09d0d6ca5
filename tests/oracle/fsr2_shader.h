// The original FSR 2.2.1 passes (ffx_fsr2_*_pass.glsl with their headers, read from
// ../shared/third_party/fidelityfx-fsr2/shaders at test time) compiled by glslangValidator
// (GLSL → SPIR-V, FFX_GPU FFX_GLSL FFX_HALF=0 and the FFX_FSR2_OPTION_* of Fsr2Options, as the
// Vulkan backend builds its permutations) and run on lavapipe through tests/oracle/vk_compute.h,
// with the descriptor layout the GLSL declares: set 0 the two samplers (point and linear
// clamp), set 1 the pass's textures and images at the pass's FSR2_BIND_* numbers and cbFSR2.
// Each resource has the format the shader declares for it (r16f, rg16f, r32ui, ...); the
// app-provided inputs are float (colour rgba32f, depth r32f, motion rg32f, exposure rg32f 1×1).
#pragma once
#include <string>

#include "methods/fsr2.h"

namespace aalab::oracle {

/// "" when the FSR2 sources, glslangValidator and lavapipe are there, else what is missing.
std::string Fsr2ShaderAvailable();

/// ffx_fsr2_reconstruct_previous_depth_pass.glsl over the render size (8×8 groups); `out`'s
/// prev_depth is the r32ui image's initial contents (render-size long) and comes back updated.
void RunFsr2ReconstructShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& color, const Fsr2Plane& depth,
                              const Fsr2Plane& motion, float exposure, Fsr2ReconstructOut* out);

/// ffx_fsr2_lock_pass.glsl over the render size: `lock_luma` goes in as r16f (its values must
/// be halves), `new_locks` (display size, values 0 or 1) as r8 unorm, `prev_depth` as r32ui;
/// both come back updated.
void RunFsr2LockShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& lock_luma, Fsr2Plane* new_locks,
                       std::vector<uint32_t>* prev_depth);

/// ffx_fsr2_depth_clip_pass.glsl over the render size: the reconstruct outputs and the
/// previous dilated motion go in as the formats FSR2 gives them (r32ui, rg16f, r16f; their
/// values must be halves), masks as r8 unorm (values k/255; empty planes: 1×1 zero textures,
/// as the API binds when the app gives none).
void RunFsr2DepthClipShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2DepthClipIn& in, Fsr2DepthClipOut* out);

}  // namespace aalab::oracle
