// Deterministic test images shared by the metrics tests (integer-only, so the python
// cross-check script tests/metrics/crosscheck_reference.py builds identical pixels).
#pragma once
#include <algorithm>
#include <cstdint>
#include <utility>

#include "core/image.h"

namespace aalab::testimg {

/// lowbias32 integer hash.
inline uint32_t Hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/// 8-bit codes / 255: a gradient with a slanted edge and ±10 texture (reference), and a
/// 3-tap horizontal box blur of it with ±4 noise (test). Mirrors make_pair() in the script.
inline std::pair<ImageF, ImageF> MakePair(int w, int h, uint32_t seed) {
  Image<int> ref(w, h, 3, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        int v = 40 + (x * 3 + y * 2 + c * 20) % 160;
        if (5 * x + 3 * y > 2 * w + h) v += 60;
        v += static_cast<int>(Hash32(seed * 1000003u + x + 1000u * y + 7919u * c) % 21u) - 10;
        ref.At(x, y, c) = std::clamp(v, 0, 255);
      }
  ImageF a(w, h, 3), b(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const int s = ref.At(std::max(x - 1, 0), y, c) + ref.At(x, y, c) + ref.At(std::min(x + 1, w - 1), y, c);
        int v = (s + 1) / 3 + static_cast<int>(Hash32(seed * 1000003u + 12345u + x + 1000u * y + 7919u * c) % 9u) - 4;
        v = std::clamp(v, 0, 255);
        a.At(x, y, c) = static_cast<float>(ref.At(x, y, c) / 255.0);
        b.At(x, y, c) = static_cast<float>(v / 255.0);
      }
  return {a, b};
}

}  // namespace aalab::testimg
