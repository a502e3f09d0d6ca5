#include "core/color.h"

#include <algorithm>
#include <bit>
#include <cstdint>
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

// SrgbEncode's power x^(1/2.4), x in (0.0031308, 1), with the bits of glibc's powf but
// without its call (issue #41: 9 calls a reference pixel). x = 2^e · m, m in [1, 2):
//   x^y = 2^(e·y) · m0^y · (1 + t)^y,  m0 = the centre of m's 1/256 bin, t = m/m0 − 1,
// |t| <= 2^-9; the first two factors come from tables (double std::pow), the last from its
// binomial series to t^6 (the next term is below 2^-63). The double result d is within a few
// double ulps (~1e-15 relative) of the exact power. Rounding it to float gives the correctly
// rounded power unless the exact value may lie near a midpoint between two floats: when
// d·(1 ∓ kPowMargin) round to different floats, powf itself is called (~1.5 % of inputs).
// glibc's powf (2.36) is not correctly rounded for 45,775 of the ~75 M inputs of this branch;
// for each, the exact power (x87 powl) lies within 2^-33.2 (relative) of the midpoint, so the
// margin 2^-31 sends them all to powf (measured 2026-11-26 by a scan of every input).
// tests/core/color_test.cpp compares SrgbEncode with SrgbEncodeLibm on every float in [0, 1].
namespace {
constexpr float kEncodeExponent = 1.0f / 2.4f;
constexpr double kPowMargin = 0x1p-31;

struct EncodePowTables {
  double scale[10];                   // 2^(e·y) for e = -9..0
  double head[256], inv_centre[256];  // m0^y and 1/m0 for bin i: m0 = 1 + (i + 0.5)/256
  double c[7];                        // binomial coefficients C(y, k)
};

const EncodePowTables& PowTables() {
  static const EncodePowTables t = [] {
    EncodePowTables x{};
    const double y = static_cast<double>(kEncodeExponent);
    for (int e = -9; e <= 0; ++e) x.scale[e + 9] = std::pow(2.0, static_cast<double>(e) * y);
    for (int i = 0; i < 256; ++i) {
      const double m0 = 1.0 + (static_cast<double>(i) + 0.5) / 256.0;
      x.head[i] = std::pow(m0, y);
      x.inv_centre[i] = 1.0 / m0;
    }
    x.c[0] = 1.0;
    for (int k = 1; k < 7; ++k) x.c[k] = x.c[k - 1] * (y - static_cast<double>(k - 1)) / static_cast<double>(k);
    return x;
  }();
  return t;
}

float EncodePow(float v) {
  const EncodePowTables& t = PowTables();
  const uint32_t bits = std::bit_cast<uint32_t>(v);
  const int e = static_cast<int>(bits >> 23) - 127;
  if (e < -9 || e > -1) return std::pow(v, kEncodeExponent);  // not reached: v in (0.0031308, 1)
  const uint32_t frac = bits & 0x7FFFFFu;
  const int i = static_cast<int>(frac >> 15);
  const double m = static_cast<double>(std::bit_cast<float>(frac | 0x3F800000u));
  const double s = m * t.inv_centre[i] - 1.0;
  const double series = 1.0 + s * (t.c[1] + s * (t.c[2] + s * (t.c[3] + s * (t.c[4] + s * (t.c[5] + s * t.c[6])))));
  const double d = t.scale[e + 9] * t.head[i] * series;
  const float lo = static_cast<float>(d * (1.0 - kPowMargin));
  const float hi = static_cast<float>(d * (1.0 + kPowMargin));
  if (lo == hi) return lo;
  return std::pow(v, kEncodeExponent);
}
}  // namespace

float SrgbEncode(float v) {
  if (!(v > 0.0f)) return 0.0f;  // also maps NaN to 0
  if (v >= 1.0f) return 1.0f;
  if (v <= 0.0031308f) return 12.92f * v;
  return 1.055f * EncodePow(v) - 0.055f;
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_ENCODE_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define AALAB_ENCODE_CLONES
#endif

// SrgbEncode over n values, written so that the first loop vectorises (table gathers): every
// lane takes EncodePow's operations in its order (the same doubles, the same two roundings to
// float, 1.055f · p − 0.055f) and is flagged when SrgbEncode would not return that value (its
// input outside (0.0031308, 1), NaN included, or d's two roundings differ); the flagged ones
// (~1.5 % of the pow branch, plus the clamped and linear ones) take SrgbEncode itself.
AALAB_ENCODE_CLONES
void SrgbEncodeN(const float* in, float* out, int n) {
  const EncodePowTables& t = PowTables();
  constexpr int kBlock = 64;
  for (int base = 0; base < n; base += kBlock) {
    const int m = std::min(kBlock, n - base);
    int32_t slow[kBlock];
    float v_in[kBlock];  // the block's inputs (in and out may be one array)
    for (int k = 0; k < m; ++k) {
      const float v = in[base + k];
      v_in[k] = v;
      const uint32_t bits = std::bit_cast<uint32_t>(v);
      const bool pow_branch = v > 0.0031308f && v < 1.0f;  // false for NaN; then e in [-9, -1]
      const int e = pow_branch ? static_cast<int>(bits >> 23) - 127 : -1;
      const int i = static_cast<int>((bits & 0x7FFFFFu) >> 15);
      const double mant = static_cast<double>(std::bit_cast<float>((bits & 0x7FFFFFu) | 0x3F800000u));
      const double sv = mant * t.inv_centre[i] - 1.0;
      const double series =
          1.0 + sv * (t.c[1] + sv * (t.c[2] + sv * (t.c[3] + sv * (t.c[4] + sv * (t.c[5] + sv * t.c[6])))));
      const double d = t.scale[e + 9] * t.head[i] * series;
      const float lo = static_cast<float>(d * (1.0 - kPowMargin));
      const float hi = static_cast<float>(d * (1.0 + kPowMargin));
      slow[k] = !pow_branch || lo != hi;
      out[base + k] = 1.055f * lo - 0.055f;
    }
    for (int k = 0; k < m; ++k) {
      if (slow[k]) out[base + k] = SrgbEncode(v_in[k]);
    }
  }
}

float SrgbEncodeLibm(float v) {
  if (!(v > 0.0f)) return 0.0f;
  if (v >= 1.0f) return 1.0f;
  if (v <= 0.0031308f) return 12.92f * v;
  return 1.055f * std::pow(v, kEncodeExponent) - 0.055f;
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
