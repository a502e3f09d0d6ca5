/// Colour conventions: display transform (exposure → tonemap → clamp → sRGB encode).
#pragma once
#include <array>
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
/// Inverse sRGB OETF for x in [0, 1].
float SrgbDecode(float encoded);
/// Tonemaps one linear channel value (exposure already applied). Output is not clamped.
/// Defined for every v in [0, +inf]: very large and infinite values give the curve's limit
/// (1 for reinhard, 2.51/2.43 for aces, v for none), never NaN.
float ApplyTonemap(Tonemap t, float v);
/// Display transform of one linear RGB sample to display-linear RGB, clamped to [0, 1].
/// NaN inputs map to 0 (documented sanitisation: the tracer never produces NaN, but a user
/// float image may).
std::array<float, 3> DisplayLinear(const Display& d, const std::array<float, 3>& rgb);
/// Round-to-nearest UNORM8 quantisation of a value in [0, 1] (clamped; NaN → 0).
uint8_t QuantizeUnorm8(float v);
/// Lookup table: value of an 8-bit sRGB-encoded code decoded to linear.
float SrgbDecode8(uint8_t code);

}  // namespace aalab
