/// Colour conventions: display transform (exposure → tonemap → clamp → sRGB encode).
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace aalab {

/// Tonemap operators a scene may choose.
enum class Tonemap { kNone, kReinhard, kAces };

/// Parses "none" | "reinhard" | "aces"; throws UserError naming the allowed values.
Tonemap ParseTonemap(const std::string& name);
std::string TonemapName(Tonemap t);

/// Scene display settings: linear scene radiance → display-linear [0, 1].
struct Display {
  float exposure = 1.0f;  ///< linear multiplier applied before tonemapping (not stops)
  Tonemap tonemap = Tonemap::kNone;
};

/// sRGB OETF (IEC 61966-2-1) for x in [0, 1]; input is clamped to [0, 1].
float SrgbEncode(float linear);
/// SrgbEncode of n values: out[k] = SrgbEncode(in[k]), the same bits, vectorised (table
/// gathers; the inputs SrgbEncode sends to powf, or that it clamps, take SrgbEncode itself).
/// in and out may be the same array.
void SrgbEncodeN(const float* in, float* out, int n);
/// SrgbEncode as it is written in the standard, with libm's powf: the same bits as SrgbEncode
/// for every float (SrgbEncode computes the power without the call; tests prove them equal).
float SrgbEncodeLibm(float linear);
/// Inverse sRGB OETF for x in [0, 1].
float SrgbDecode(float encoded);
/// Tonemaps one linear channel value (exposure already applied). Output is not clamped.
/// Defined for every v in [0, +inf]: very large and infinite values give the curve's limit
/// (1 for reinhard, 2.51/2.43 for aces, v for none), never NaN.
/// Inline: the renderer applies it to every sample.
inline float ApplyTonemap(Tonemap t, float v) {
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
/// Display transform of one linear RGB sample to display-linear RGB, clamped to [0, 1].
/// NaN inputs map to 0 (documented sanitisation: the tracer never produces NaN, but a user
/// float image may).
std::array<float, 3> DisplayLinear(const Display& d, const std::array<float, 3>& rgb);
/// Round-to-nearest UNORM8 quantisation of a value in [0, 1] (clamped; NaN → 0).
uint8_t QuantizeUnorm8(float v);
/// Lookup table: value of an 8-bit sRGB-encoded code decoded to linear.
float SrgbDecode8(uint8_t code);

}  // namespace aalab
