// FXAA 3.11 production path internals (methods/fxaa311_fast.cpp and its tests): the luma
// plane's rows in SSE2. Not part of the methods API.
#pragma once
#include <cstdint>

#include "methods/fxaa311.h"

namespace aalab::fxaa311_internal {

/// One row of the 8-bit luma plane: o[x] = the byte the luma pre-pass (Fxaa311LumaFrame,
/// kGl arithmetic) stores for input pixel p[4x..4x+3], for x in [0, w). `luma` is kRec601
/// (the stored alpha), kSqrtLuminance (the stored alpha) or kGreen (the green byte).
/// Bit-identical to the scalar expressions of Fxaa311LumaFrame: the same IEEE float32
/// operations in the same order, four pixels at a time (SSE2, the x86-64 baseline), eight
/// with AVX2 where the CPU has it, sixteen for rec601 with AVX-512F.
void PlaneRow8(const uint8_t* p, int w, Fxaa311Params::Luma luma, uint8_t* o);

/// The widest vector code PlaneRow8 may use (it also needs the CPU to have it).
enum class PlaneIsa { kSse2, kAvx2, kAvx512 };
/// Tests only: caps PlaneRow8's instruction set (default kAvx512: the best the CPU has).
void SetPlaneRow8IsaCap(PlaneIsa cap);

/// The scalar form of PlaneRow8 (per-channel product tables), kept as its reference.
void PlaneRow8Scalar(const uint8_t* p, int w, Fxaa311Params::Luma luma, uint8_t* o);

/// One row of the float luma plane (kRec601Rgb: r·0.299 + (g·0.587 + b·0.114) of the
/// UnormToFloat texels).
void PlaneRowF(const uint8_t* p, int w, float* o);

}  // namespace aalab::fxaa311_internal
