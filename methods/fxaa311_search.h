// FXAA 3.11 production path internals (methods/fxaa311_fast.cpp and its tests): the edge
// pixels' shader (3x3 taps, edge direction, end-of-edge search, final tap) eight pixels at a
// time in AVX2. Not part of the methods API.
#pragma once
#include <cstdint>

#include "core/image.h"
#include "methods/fxaa311.h"
#include "methods/fxaa311_plane.h"

namespace aalab::fxaa311_internal {

/// Extra bytes allocated (and zeroed) after an 8-bit luma plane's w·h values: the gathers of
/// EdgePixelsX8 read 4 bytes at each texel's address and keep the first.
constexpr int kPlanePad = 4;

/// True when EdgePixelsX8 may run: the CPU has AVX2, this build has the kernel, and tests
/// have not switched it off (SetEdgePixelsX8Enabled).
bool EdgePixelsX8Available();

/// Tests only: false makes EdgePixelsX8Available() false (the scalar EdgePixel runs), true
/// restores the CPU's answer. Not thread-safe against a running filter.
void SetEdgePixelsX8Enabled(bool enabled);

/// The shader for n (1..8) edge pixels (xs[i], ys[i]) of an 8-bit luma plane `pl` (with
/// kPlanePad readable bytes after its end): for each, the statements of EdgePixel in
/// methods/fxaa311_fast.cpp from the 3x3 taps to the final tap, the same IEEE float32
/// operations in the same order per lane, writing the pixel's rgb and alpha 255 into `out`.
/// Returns the taps the n pixels took (9 + 2 + search taps + 1 each). Requires
/// EdgePixelsX8Available(), params.luma an 8-bit mode and w·h + kPlanePad < 2^31.
uint64_t EdgePixelsX8(const LumaPlane<uint8_t>& pl, const Image8& src, const int* xs, const int* ys, int n,
                      const Fxaa311Params& params, float rcpX, float rcpY, Image8& out);

}  // namespace aalab::fxaa311_internal
