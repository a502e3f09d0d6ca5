// Internal helpers shared by the FSR 2 pass files (methods/fsr2_*.cpp): small vector types,
// the shaders' common functions (ffx_fsr2_common.h, ffx_fsr2_sample.h) that more than one pass
// uses, float bit casts. Not a public header: only methods/fsr2*.cpp include it.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "methods/fsr2.h"

namespace aalab::fsr2_detail {

struct V2 {
  float x, y;
};
struct I2 {
  int x, y;
};

inline float Pow(float x, float y) { return std::exp2(y * std::log2(x)); }

// IsOnScreen: both coordinates, as unsigned, below the size.
inline bool OnScreen(I2 p, const int32_t size[2]) {
  return static_cast<uint32_t>(p.x) < static_cast<uint32_t>(size[0]) &&
         static_cast<uint32_t>(p.y) < static_cast<uint32_t>(size[1]);
}

inline float Luma(float r, float g, float b) {
  float l = r * 0.2126f;
  l = l + g * 0.7152f;
  return l + b * 0.0722f;
}

inline float PerceivedLuma(float r, float g, float b) {
  const float lum = Luma(r, g, b);
  float p;
  if (lum <= 216.0f / 24389.0f) {
    p = lum * (24389.0f / 27.0f);
  } else {
    p = Pow(lum, 1.0f / 3.0f) * 116.0f - 16.0f;
  }
  return p * 0.01f;
}

// ComputeHrPosFromLrPos: the display pixel under a render pixel's jittered centre.
inline I2 HrPosFromLrPos(const Fsr2Constants& k, I2 lr) {
  const float sx = (static_cast<float>(lr.x) + 0.5f) - k.jitter[0],
              sy = (static_cast<float>(lr.y) + 0.5f) - k.jitter[1];
  return {
      static_cast<int>(std::floor((sx / static_cast<float>(k.render_size[0])) * static_cast<float>(k.display_size[0]))),
      static_cast<int>(
          std::floor((sy / static_cast<float>(k.render_size[1])) * static_cast<float>(k.display_size[1])))};
}

inline int RoundUp8(int n) { return (n + 7) / 8 * 8; }

inline float ExposureOf(float texel) { return texel == 0.0f ? 1.0f : texel; }

inline uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

inline float FloatOfBits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

// ClampLoad: pos + off, clamped to the texture only on the side the offset points to.
inline I2 ClampLoad(I2 pos, I2 off, const int32_t size[2]) {
  I2 r{pos.x + off.x, pos.y + off.y};
  if (off.x < 0) r.x = std::max(r.x, 0);
  if (off.x > 0) r.x = std::min(r.x, size[0] - 1);
  if (off.y < 0) r.y = std::max(r.y, 0);
  if (off.y > 0) r.y = std::min(r.y, size[1] - 1);
  return r;
}

inline float Sat(float x) { return std::min(std::max(x, 0.0f), 1.0f); }
inline float Length2(float x, float y) { return std::sqrt(x * x + y * y); }
inline float Length3(float x, float y, float z) { return std::sqrt((x * x + y * y) + z * z); }
inline float Dot3(const float a[3], const float b[3]) { return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]; }
inline float Mix(float a, float b, float t) { return a * (1.0f - t) + b * t; }

// GetViewSpaceDepth.
inline float ViewDepth(const Fsr2Constants& k, float device_depth) {
  return k.device_to_view_depth[1] / (device_depth - k.device_to_view_depth[0]);
}

inline V2 InputMotion(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& m, I2 p) {
  V2 mv{m.Fetch(p.x, p.y, 0) * k.motion_vector_scale[0], m.Fetch(p.x, p.y, 1) * k.motion_vector_scale[1]};
  if (o.jittered_motion_vectors) {
    mv.x = mv.x - k.motion_vector_jitter_cancellation[0];
    mv.y = mv.y - k.motion_vector_jitter_cancellation[1];
  }
  return mv;
}

// A bilinear sample of a texture at uv with a LINEAR CLAMP_TO_EDGE sampler, channel c, as
// Mesa's lavapipe filters float and (with GALLIVM_PERF=no_aos_sampling) UNORM texels on a CPU
// with FMA: fractions in float32, each lerp a + f·(b − a) with one fused multiply-add
// (measured against lavapipe by tests/oracle/fsr2_accumulate_oracle_test.cpp, where the
// unfused form left 1.4 % of output floats a few ulps off). A GPU's texture unit uses 8-bit
// fractions instead. The texel coordinate is first limited to [−1, size]: past that both taps
// are the same edge texel, so every finite coordinate samples exactly as before, and an
// infinite one (ClampUv divides by a luma mip size of 0 when the render is under 32 pixels on
// a side: LumaMipDimensions = ⌊render / 32⌋) reads the edge texel, as lavapipe does (measured:
// tests/oracle/fsr2_chain_oracle_test.cpp's 40×24 renders), instead of an undefined float-to-
// int conversion. NaN reads the far edge (fmin's rule), also defined.
inline float SampleLinear(const Fsr2Plane& t, V2 uv, int c) {
  const float tw = static_cast<float>(t.w), th = static_cast<float>(t.h);
  const float u = std::fmax(-1.0f, std::fmin(uv.x * tw - 0.5f, tw));
  const float v = std::fmax(-1.0f, std::fmin(uv.y * th - 0.5f, th));
  const float x0f = std::floor(u), y0f = std::floor(v);
  const float fx = u - x0f, fy = v - y0f;
  auto at = [&](int x, int y) { return t.Fetch(std::clamp(x, 0, t.w - 1), std::clamp(y, 0, t.h - 1), c); };
  const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
  const float a = at(x0, y0), b = at(x0 + 1, y0), cc = at(x0, y0 + 1), d = at(x0 + 1, y0 + 1);
  const float top = std::fma(fx, b - a, a), bottom = std::fma(fx, d - cc, cc);
  return std::fma(fy, bottom - top, top);
}

}  // namespace aalab::fsr2_detail
