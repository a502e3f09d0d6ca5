// The original FSR 2.2.1 passes (ffx_fsr2_*_pass.glsl with their headers, read from
// ../shared/third_party/fidelityfx-fsr2/shaders at test time) compiled by glslangValidator
// (GLSL → SPIR-V, FFX_GPU FFX_GLSL FFX_HALF=0 and the FFX_FSR2_OPTION_* of Fsr2Options, as the
// Vulkan backend builds its permutations) and run on lavapipe through tests/oracle/vk_compute.h,
// with the descriptor layout the GLSL declares: set 0 the two samplers (point and linear
// clamp), set 1 the pass's textures and images at the pass's FSR2_BIND_* numbers and cbFSR2.
// Each resource has the format the shader declares for it (r16f, rg16f, r32ui, ...); the
// app-provided inputs are float (colour rgba32f, depth r32f, motion rg32f, exposure rg32f 1×1).
// Every pass is compiled, then made precise (PreciseSpirv) before lavapipe compiles it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "methods/fsr2.h"
#include "methods/fsr2_pyramid.h"

namespace aalab::oracle {

/// `words` (a SPIR-V module) with every float arithmetic result (OpFAdd, OpFSub, OpFMul,
/// OpFDiv, OpFNegate, OpDot, the vector/matrix products, ...) decorated NoContraction: what
/// GLSL's `precise` does, without an edit to AMD's text. Mesa then neither fuses multiply-adds
/// nor reassociates (it would turn RCAS's lobe·b + lobe·d + ... into lobe·(b + d + ...)), so
/// the shader is evaluated as written, in IEEE float32: the arithmetic the port computes.
std::vector<uint32_t> PreciseSpirv(const std::vector<uint32_t>& words);

/// "" when the FSR2 sources, glslangValidator and lavapipe are there, else what is missing.
std::string Fsr2ShaderAvailable();

/// ffx_fsr2_reconstruct_previous_depth_pass.glsl over the render size (8×8 groups); `out`'s
/// prev_depth is the r32ui image's initial contents (render-size long) and comes back updated.
void RunFsr2ReconstructShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& color,
                              const Fsr2Plane& depth, const Fsr2Plane& motion, float exposure, Fsr2ReconstructOut* out);

/// ffx_fsr2_lock_pass.glsl over the render size: `lock_luma` goes in as r16f (its values must
/// be halves), `new_locks` (display size, values 0 or 1) as r8 unorm, `prev_depth` as r32ui;
/// both come back updated.
void RunFsr2LockShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& lock_luma, Fsr2Plane* new_locks,
                       std::vector<uint32_t>* prev_depth);

/// ffx_fsr2_depth_clip_pass.glsl over the render size: the reconstruct outputs and the
/// previous dilated motion go in as the formats FSR2 gives them (r32ui, rg16f, r16f; their
/// values must be halves), masks as r8 unorm (values k/255; empty planes: 1×1 zero textures,
/// as the API binds when the app gives none).
void RunFsr2DepthClipShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2DepthClipIn& in,
                            Fsr2DepthClipOut* out);

/// ffx_fsr2_accumulate_pass.glsl over the display size (8×8 groups): every input texture in
/// the format FSR2 gives it (planes of halves for the 16-bit float ones, k/255 for the UNORM
/// ones; the app's display-size motion as rg32f), the Lanczos table as its r16 snorm codes
/// (`lanczos_lut`, 128), the luma mip as a one-level r16f texture (textureLod of level
/// luma_mip_level reads level 0: the port is handed that level); the upscaled output as
/// rgba32f (floats before any rounding). `in.new_locks` comes back cleared as the pass leaves it.
void RunFsr2AccumulateShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2AccumulateIn& in,
                             const std::vector<int16_t>& lanczos_lut, Fsr2AccumulateOut* out);

/// GLSL's exp2 of every value of `exp2_of`, log2 of `log2_of`, sin of `sin_of`, as lavapipe
/// evaluates them (one compute dispatch over a storage buffer): the three results concatenated.
std::vector<float> RunGlslExp2Log2Sin(const std::vector<float>& exp2_of, const std::vector<float>& log2_of,
                                      const std::vector<float>& sin_of);

/// The float values lavapipe reads (texelFetch) from an r16 snorm texture of `codes`, one row.
std::vector<float> ReadR16SnormTexels(const std::vector<int16_t>& codes);

/// ffx_fsr2_rcas_pass.glsl over upscaled's size (64-thread groups over 16×16 tiles):
/// `upscaled` as rgba32f, the output as rgba32f (the app-controlled format: floats before any
/// rounding); rgb floats, 3 per pixel.
/// `precise` false: the module as glslang wrote it (Mesa may fuse and reassociate).
std::vector<float> RunFsr2RcasShader(const Fsr2Constants& k, const Fsr2Plane& upscaled, float exposure, uint32_t con_x,
                                     bool precise = true);

/// ffx_fsr2_compute_luminance_pyramid_pass.glsl over spd's dispatch (256-thread groups over
/// 64×64 tiles, cbSPD = spd.c): `color` as rgba32f (k.input_color_size), the global atomic as
/// r32ui 1×1, the shading-change mip and mip 5 as r16f images of `state`'s plane sizes (their
/// values must be halves), the auto exposure as rg32f 1×1; all four come back updated.
void RunFsr2PyramidShader(const Fsr2Constants& k, const Fsr2SpdDispatch& spd, const Fsr2Plane& color,
                          Fsr2PyramidState* state);

/// lavapipe's own log2 and exp2 of each value of `x` (a compute shader of aalab's, not AMD's):
/// {log2(x[i]), exp2(x[i])} at [2i], [2i + 1], the values the pass's log/exp/pow come from.
std::vector<float> RunLavapipeLog2Exp2(const std::vector<float>& x);

}  // namespace aalab::oracle
