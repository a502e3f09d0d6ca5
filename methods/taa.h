/// Helpers of the TAA method (methods/taa.cpp) that tests check on their own.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "methods/method.h"

namespace aalab {

/// QuantizeUnorm8(SrgbEncode(v)) for v in [0, 1] (same bits), by a search over the 255 code
/// thresholds instead of a pow per value: TAA's output encode.
uint8_t EncodeSrgb8(float v);

/// EncodeSrgb8 of w pixels of planar linear RGB (r, g, b; each value in [0, 1]) into RGBA8
/// with alpha 255: the row encode TAA's step uses (four pixels at a time with SSE2).
void EncodeSrgb8Rgba(const float* r, const float* g, const float* b, int w, uint8_t* rgba);

/// A copy of a TAA state (one made by MakeMethod("taa...").make_state()) whose Step runs the
/// simple implementation of the temporal step (one loop nest per pass, per pixel) instead of
/// the production path: the reference tests/motion/taa_test.cpp compares the two with, bit
/// for bit. InternalError for any other state.
std::unique_ptr<TemporalState> TaaReferenceCopy(const TemporalState& taa_state);

/// The history a TAA state holds after its last step (linear display RGB, 3 floats per pixel,
/// row-major; empty before the first step), for tests that compare the production step's
/// with the reference step's bit for bit. InternalError for any other state.
std::vector<float> TaaHistory(const TemporalState& taa_state);

}  // namespace aalab
