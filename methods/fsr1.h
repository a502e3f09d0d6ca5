/// AMD FidelityFX Super Resolution 1 (FSR 1.0.2, ffx_fsr1.h with ffx_a.h): EASU, the edge-adaptive
/// spatial upscaler, and RCAS, robust contrast-adaptive sharpening, in the shader's 32-bit float
/// path (FsrEasuF, FsrRcasF), with its approximations (the APrxLoRcpF1 / APrxLoRsqF1 /
/// APrxMedRcpF1 bit tricks) kept. docs/fsr1.md; methods/fsr1.cpp says what differs.
#pragma once
#include <array>
#include <cstdint>

#include "core/image.h"
#include "core/sampler.h"
#include "methods/method.h"

namespace aalab {

/// The four uint4 constants FsrEasuCon writes (float bit patterns), for an input viewport of
/// in_w × in_h pixels in an input texture of the same size, scaled to out_w × out_h (the
/// sample's call: viewport = texture = the render size).
struct Fsr1EasuConst {
  std::array<uint32_t, 4> con0{}, con1{}, con2{}, con3{};
};
/// FsrEasuCon on the CPU (A_CPU: ARcpF1(a) = 1/a in float, products and sums rounded in order).
Fsr1EasuConst Fsr1EasuCon(float in_w, float in_h, float out_w, float out_h);

/// FsrRcasCon's con.x: the bits of exp2(-sharpness) (sharpness in stops: 0 = the most).
uint32_t Fsr1RcasCon(float sharpness_stops);

/// ffx_a.h's approximations, bit for bit (float bits as unsigned, integer subtract / shift).
float Fsr1PrxLoRcp(float a);   ///< APrxLoRcpF1: 0x7ef07ebb - bits(a)
float Fsr1PrxMedRcp(float a);  ///< APrxMedRcpF1: b = 0x7ef19fff - bits(a), then b·(−b·a + 2)
float Fsr1PrxLoRsq(float a);   ///< APrxLoRsqF1: 0x5f347d74 - (bits(a) >> 1)

/// A frame as the shader's texture reads it: three float planes, texel (x, y) of channel c at
/// [c][y·w + x], each the UNORM8 code through TexelValue (the run's sampler arithmetic).
struct Fsr1Planes {
  int w = 0, h = 0;
  std::array<std::vector<float>, 3> c;
  /// Texel (x, y) of channel ch, clamped to the edge (CLAMP_TO_EDGE gathers).
  float At(int ch, int x, int y) const;
};
Fsr1Planes Fsr1PlanesOf(const Image8& in, SamplerArithmetic sampler);

/// FsrEasuF for output pixel (x, y): rgb in float before the store. The four textureGather
/// calls read integer texels (the gather's corner is half-way between texel centres, so its
/// footprint is exact; no filtering), clamped to the edge.
std::array<float, 3> Fsr1EasuPixel(const Fsr1Planes& in, const Fsr1EasuConst& con, int x, int y);

/// FsrRcasF for pixel (x, y) of `in` (no denoise, no alpha pass-through, as the sample):
/// rgb before the store. The 5 texel loads clamp to the edge (see methods/fsr1.cpp).
std::array<float, 3> Fsr1RcasPixel(const Fsr1Planes& in, uint32_t con_x, int x, int y);

/// EASU of `in` (RGBA8, the render-size frame) to out_w × out_h, stored to RGBA8 (GL's UNORM
/// store, alpha 255) as the sample's intermediate. Adds 12 texture fetches per output pixel
/// (the 12 textureGather calls) to stats->taps.
Image8 Fsr1Easu(const Image8& in, int out_w, int out_h, PostStats* stats,
                SamplerArithmetic sampler = SamplerArithmetic::kGl);

/// RCAS of `in` (same size out) with sharpness in stops; 5 texel fetches per pixel.
Image8 Fsr1Rcas(const Image8& in, float sharpness_stops, PostStats* stats,
                SamplerArithmetic sampler = SamplerArithmetic::kGl);

}  // namespace aalab
