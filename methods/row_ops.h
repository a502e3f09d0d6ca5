/// Small row helpers shared by the fast post-filter paths (methods/fxaa1.cpp, fxaa311.cpp).
#pragma once
#include <bit>
#include <cstdint>
#include <cstring>

namespace aalab {

/// dst = src with alpha 255, for `w` RGBA8 pixels (little-endian words: alpha is the high
/// byte). What an early-exit pixel writes: its input colour, opaque.
inline void CopyRowOpaque(const uint8_t* src, uint8_t* dst, int w) {
  static_assert(std::endian::native == std::endian::little, "RGBA8 word layout");
  for (int x = 0; x < w; ++x) {
    uint32_t v;
    std::memcpy(&v, src + 4 * x, 4);
    v |= 0xFF000000u;
    std::memcpy(dst + 4 * x, &v, 4);
  }
}

}  // namespace aalab
