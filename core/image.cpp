#include "core/image.h"

#include <atomic>

#include "core/color.h"

namespace aalab {

namespace {
std::atomic<int> g_poison{-1};
}  // namespace

void SetUninitializedPoison(int byte) {
  AALAB_CHECK(byte >= -1 && byte <= 255, "uninitialised-image poison must be -1 (off) or a byte 0..255");
  g_poison.store(byte, std::memory_order_relaxed);
}

int UninitializedPoison() { return g_poison.load(std::memory_order_relaxed); }

ImageF ToFloat(const Image8& img, int channels) {
  AALAB_CHECK(channels >= 1 && channels <= img.Channels(), "channel count");
  ImageF out(img.Width(), img.Height(), channels, kUninitialized);  // every value written below
  for (int y = 0; y < img.Height(); ++y) {
    const uint8_t* src = img.Row(y);
    float* dst = out.Row(y);
    for (int x = 0; x < img.Width(); ++x) {
      for (int c = 0; c < channels; ++c) {
        dst[x * channels + c] = static_cast<float>(src[x * img.Channels() + c]) / 255.0f;
      }
    }
  }
  return out;
}

Image8 ToUnorm8(const ImageF& img) {
  Image8 out(img.Width(), img.Height(), 4, 255);
  const int nc = img.Channels() < 4 ? img.Channels() : 4;
  for (int y = 0; y < img.Height(); ++y) {
    const float* src = img.Row(y);
    uint8_t* dst = out.Row(y);
    for (int x = 0; x < img.Width(); ++x) {
      for (int c = 0; c < nc; ++c) dst[x * 4 + c] = QuantizeUnorm8(src[x * img.Channels() + c]);
      if (nc == 1) dst[x * 4 + 1] = dst[x * 4 + 2] = dst[x * 4];
    }
  }
  return out;
}

}  // namespace aalab
