#include "core/color.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

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
