#include "harness/core/color.h"

#include <algorithm>
#include <cmath>

#include "harness/core/error.h"

namespace aalab {

Tonemap ParseTonemap(const std::string& name) {
  if (name == "none") return Tonemap::kNone;
  if (name == "reinhard") return Tonemap::kReinhard;
  if (name == "aces") return Tonemap::kAces;
  throw UserError("unknown tonemap '" + name + "' (allowed: none, reinhard, aces)");
}

std::string TonemapName(Tonemap t) {
  switch (t) {
    case Tonemap::kNone: return "none";
    case Tonemap::kReinhard: return "reinhard";
    case Tonemap::kAces: return "aces";
  }
  return "none";
}

float SrgbEncode(float v) {
  if (!(v > 0.0f)) return 0.0f;  // also maps NaN to 0
  if (v >= 1.0f) return 1.0f;
  if (v <= 0.0031308f) return 12.92f * v;
  return 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float SrgbDecode(float v) {
  if (!(v > 0.0f)) return 0.0f;
  if (v >= 1.0f) return 1.0f;
  if (v <= 0.04045f) return v / 12.92f;
  return std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float ApplyTonemap(Tonemap t, float v) {
  switch (t) {
    case Tonemap::kNone: return v;
    case Tonemap::kReinhard:
      // inf / (1 + inf) would be NaN; for every finite v the quotient is at most 1.
      return std::isinf(v) && v > 0.0f ? 1.0f : v / (1.0f + v);
    case Tonemap::kAces: {
      // Narkowicz 2015 fit of the ACES RRT+ODT (per channel), input pre-scaled by 0.6 so
      // that exposure 1 maps scene value 1 near display 0.8, as in the original note.
      const float x = v * 0.6f;
      // Beyond 1e15 the fit equals its limit 2.51/2.43 to float precision, and from about
      // 1.8e19 on x*x overflows: inf / inf = NaN, which the display transform turned into
      // black. Return the limit instead (the caller clamps it to 1).
      if (x > 1e15f) return 2.51f / 2.43f;
      return (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    }
  }
  return v;
}

std::array<float, 3> DisplayLinear(const Display& d, const std::array<float, 3>& rgb) {
  std::array<float, 3> out{};
  for (int c = 0; c < 3; ++c) {
    float v = rgb[c];
    if (!(v > 0.0f)) v = 0.0f;  // negatives and NaN → 0
    v = ApplyTonemap(d.tonemap, v * d.exposure);
    out[c] = std::clamp(v, 0.0f, 1.0f);
  }
  return out;
}

uint8_t QuantizeUnorm8(float v) {
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  return static_cast<uint8_t>(std::lround(v * 255.0f));
}

float SrgbDecode8(uint8_t code) {
  static const auto table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = SrgbDecode(static_cast<float>(i) / 255.0f);
    return t;
  }();
  return table[code];
}

}  // namespace aalab
