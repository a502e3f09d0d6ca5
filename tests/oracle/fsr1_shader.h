// The original FSR 1 (ffx_a.h + ffx_fsr1.h, read from ../shared/third_party/fidelityfx-fsr1 at
// test time) run as an OpenGL 4.5 compute shader on llvmpipe (the EGL context of
// tests/oracle/gl_oracle.h: StartGl first), called as the sample's FSR_Pass.glsl calls it in
// its fp32 build (A_GPU, A_GLSL, FSR_EASU_F / FSR_RCAS_F, 64-thread groups over 16×16 tiles,
// ARmp8x8 swizzle). Our wrapper's callbacks: FsrEasu{R,G,B}F = textureGather of channel 0/1/2
// (RGBA8 texture, LINEAR, CLAMP_TO_EDGE, image row y at t = (y + 0.5)/H); FsrRcasLoadF =
// texelFetch with the position clamped to the texture (the sample reads outside at the
// border; see methods/fsr1.cpp). Output: an RGBA32F image, so the floats before any store
// come back.
//
// `precise`: our wrapper declares its result `precise AF3 c;` (no edit to AMD's text). GLSL
// lets a compiler rewrite non-precise float expressions, and Mesa's NIR does (for example
// (a·b) + (a·c) -> a·(b + c), RCAS's lobe·b + lobe·d + ...; ffma fusions of products); Mesa
// propagates `precise` back to every value that contributes to c, so with it the shader is
// evaluated as written, in IEEE float32, which is what the port computes. Without it the
// result is llvmpipe's compilation of the same text.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace aalab::oracle {

/// FsrEasuF over out_w × out_h from `frame` with the given constants; rgba floats, row-major.
std::vector<float> RunFsr1EasuShader(const Image8& frame, int out_w, int out_h,
                                     const std::array<std::array<uint32_t, 4>, 4>& con, bool precise = true);

/// FsrRcasF over `frame`'s size with con.x = `con_x`; rgba floats, row-major.
std::vector<float> RunFsr1RcasShader(const Image8& frame, uint32_t con_x, bool precise = true);

}  // namespace aalab::oracle
