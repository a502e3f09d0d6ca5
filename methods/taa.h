/// Helpers of the TAA method (methods/taa.cpp) that tests check on their own.
#pragma once
#include <cstdint>

namespace aalab {

/// QuantizeUnorm8(SrgbEncode(v)) for v in [0, 1] (same bits), by a search over the 255 code
/// thresholds instead of a pow per value: TAA's output encode.
uint8_t EncodeSrgb8(float v);

}  // namespace aalab
