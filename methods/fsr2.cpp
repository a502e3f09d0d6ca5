// AMD FidelityFX Super Resolution 2.2.1 (GPUOpen-Effects/FidelityFX-FSR2, MIT, © 2023 Advanced
// Micro Devices, Inc.), ported from the GLSL shaders of its Vulkan backend
// (src/ffx-fsr2-api/shaders/*.glsl with their *.h), fp32 path (FFX_HALF=0). This is aalab's
// own code written from the shaders; the originals are not in the repository: the oracle
// (tests/oracle/fsr2_oracle_test.cpp) reads them from ../shared/third_party/fidelityfx-fsr2.
//
// Each pass is a function over whole planes that computes, for every invocation the shader's
// dispatch covers, what it stores; every arithmetic step is a float operation in the order the
// shader writes it (no fused multiply-adds: -ffp-contract=off). Stores into 16-bit float
// images go through Fsr2Half, as the image formats the shaders declare round them: to nearest
// even by default, toward zero with Fsr2Options::half_toward_zero (what lavapipe does; Vulkan
// allows either, so the oracle runs the port that way).
//
// Ported and proven against the shader (docs/fsr2.md has the figures):
//   - ReconstructAndDilate (ffx_fsr2_reconstruct_previous_depth_pass.glsl).
//
// Where the shader reads outside an image (FindNearestDepth's 3×3 at the border), the port
// reads 0 (robust image access) and, as the shader does, ignores those samples.
// pow(x, y) is computed as exp2(y·log2(x)), as Mesa lowers it; lavapipe evaluates exp2 and
// log2 with its own polynomials, so a pow result can differ from ours in the last bits: a
// difference the 16-bit store hides except at rounding ties (docs/fsr2.md, measured).
#include "methods/fsr2.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace aalab {

namespace {

struct V2 {
  float x, y;
};
struct I2 {
  int x, y;
};

float Pow(float x, float y) { return std::exp2(y * std::log2(x)); }

// IsOnScreen: both coordinates, as unsigned, below the size.
bool OnScreen(I2 p, const int32_t size[2]) {
  return static_cast<uint32_t>(p.x) < static_cast<uint32_t>(size[0]) && static_cast<uint32_t>(p.y) < static_cast<uint32_t>(size[1]);
}

float Luma(float r, float g, float b) {
  float l = r * 0.2126f;
  l = l + g * 0.7152f;
  return l + b * 0.0722f;
}

float PerceivedLuma(float r, float g, float b) {
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
I2 HrPosFromLrPos(const Fsr2Constants& k, I2 lr) {
  const float sx = (static_cast<float>(lr.x) + 0.5f) - k.jitter[0], sy = (static_cast<float>(lr.y) + 0.5f) - k.jitter[1];
  return {static_cast<int>(std::floor((sx / static_cast<float>(k.render_size[0])) * static_cast<float>(k.display_size[0]))),
          static_cast<int>(std::floor((sy / static_cast<float>(k.render_size[1])) * static_cast<float>(k.display_size[1])))};
}

int RoundUp8(int n) { return (n + 7) / 8 * 8; }

float ExposureOf(float texel) { return texel == 0.0f ? 1.0f : texel; }

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

}  // namespace

float Fsr2Plane::Fetch(int x, int y, int k) const {
  if (x < 0 || y < 0 || x >= w || y >= h) return 0.0f;
  return v[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * static_cast<size_t>(c) + static_cast<size_t>(k)];
}

float Fsr2Half(float f, bool toward_zero) {
  _Float16 h = static_cast<_Float16>(f);  // round to nearest even
  if (toward_zero && std::fabs(static_cast<float>(h)) > std::fabs(f) && !std::isnan(f)) {
    uint16_t bits;
    std::memcpy(&bits, &h, 2);
    --bits;  // one step toward zero in magnitude, the sign bit untouched
    std::memcpy(&h, &bits, 2);
  }
  return static_cast<float>(h);
}

float Fsr2LockInputLuma(const Fsr2Constants& k, const Fsr2Options& o, float r, float g, float b, float exposure_texel) {
  const float exposure = ExposureOf(exposure_texel);
  r = std::max(0.0f, r);
  g = std::max(0.0f, g);
  b = std::max(0.0f, b);
  r = r / k.pre_exposure;
  g = g / k.pre_exposure;
  b = b / k.pre_exposure;
  r = r * exposure;
  g = g * exposure;
  b = b * exposure;
  if (o.hdr_color_input) {  // Tonemap
    const float d = std::max(std::max(0.0f, r), std::max(g, b)) + 1.0f;
    r = r / d;
    g = g / d;
    b = b / d;
  }
  return Pow(PerceivedLuma(r, g, b), 1.0f / 6.0f);
}

void Fsr2ReconstructAndDilate(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& color, const Fsr2Plane& depth,
                              const Fsr2Plane& motion, float exposure_texel, Fsr2ReconstructOut* out) {
  const int rw = k.render_size[0], rh = k.render_size[1];
  out->dilated_depth = Fsr2Plane(rw, rh, 1);
  out->dilated_motion = Fsr2Plane(rw, rh, 2);
  out->lock_luma = Fsr2Plane(rw, rh, 1);
  static constexpr I2 kOffsets[9] = {{0, 0}, {1, 0}, {0, 1}, {0, -1}, {-1, 0}, {-1, 1}, {1, 1}, {-1, -1}, {1, -1}};
  if (out->prev_depth.size() != static_cast<size_t>(rw) * static_cast<size_t>(rh)) {
    out->prev_depth.assign(static_cast<size_t>(rw) * static_cast<size_t>(rh), o.inverted_depth ? 0u : Bits(1.0f));
  }
  // The dispatch covers whole 8×8 groups: invocations past the render size run too, read 0
  // (robust access) and can push that depth into prev_depth (with jittered motion vectors,
  // -cancellation can move them back on screen); only their image stores fall outside.
  for (int y = 0; y < RoundUp8(rh); ++y) {
    for (int x = 0; x < RoundUp8(rw); ++x) {
      const bool inside = x < rw && y < rh;
      // FindNearestDepth.
      I2 nearest{x, y};
      float nd = depth.Fetch(x, y, 0);
      for (int i = 1; i < 9; ++i) {
        const I2 p{x + kOffsets[i].x, y + kOffsets[i].y};
        if (!OnScreen(p, k.render_size)) continue;
        const float d = depth.Fetch(p.x, p.y, 0);
        if (o.inverted_depth ? d > nd : d < nd) {
          nearest = p;
          nd = d;
        }
      }
      // The motion vector at the nearest sample (at render or display resolution).
      const I2 mpos = o.low_res_motion_vectors ? nearest : HrPosFromLrPos(k, nearest);
      V2 mv{motion.Fetch(mpos.x, mpos.y, 0) * k.motion_vector_scale[0], motion.Fetch(mpos.x, mpos.y, 1) * k.motion_vector_scale[1]};
      if (o.jittered_motion_vectors) {
        mv.x = mv.x - k.motion_vector_jitter_cancellation[0];
        mv.y = mv.y - k.motion_vector_jitter_cancellation[1];
      }
      if (inside) {
        out->dilated_depth.At(x, y, 0) = Fsr2Half(nd, o.half_toward_zero);
        out->dilated_motion.At(x, y, 0) = Fsr2Half(mv.x, o.half_toward_zero);
        out->dilated_motion.At(x, y, 1) = Fsr2Half(mv.y, o.half_toward_zero);
      }
      // ReconstructPrevDepth: push the depth to the previous frame's pixels with weight > 0.01.
      {
        const float dx = mv.x * static_cast<float>(k.display_size[0]), dy = mv.y * static_cast<float>(k.display_size[1]);
        const float keep = std::sqrt(dx * dx + dy * dy) > 0.1f ? 1.0f : 0.0f;
        const V2 m{mv.x * keep, mv.y * keep};
        const V2 uv{(static_cast<float>(x) + 0.5f) / static_cast<float>(rw), (static_cast<float>(y) + 0.5f) / static_cast<float>(rh)};
        const V2 ruv{uv.x + m.x, uv.y + m.y};
        const V2 s{ruv.x * static_cast<float>(rw) - 0.5f, ruv.y * static_cast<float>(rh) - 0.5f};
        const V2 fl{std::floor(s.x), std::floor(s.y)};
        const I2 base{static_cast<int>(fl.x), static_cast<int>(fl.y)};
        const V2 fr{s.x - fl.x, s.y - fl.y};
        const float wts[4] = {(1 - fr.x) * (1 - fr.y), fr.x * (1 - fr.y), (1 - fr.x) * fr.y, fr.x * fr.y};
        static constexpr I2 kCorner[4] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
        const uint32_t ud = Bits(nd);
        for (int i = 0; i < 4; ++i) {
          if (!(wts[i] > 0.01f)) continue;
          const I2 p{base.x + kCorner[i].x, base.y + kCorner[i].y};
          if (!OnScreen(p, k.render_size)) continue;
          uint32_t& cell = out->prev_depth[static_cast<size_t>(p.y) * static_cast<size_t>(rw) + static_cast<size_t>(p.x)];
          cell = o.inverted_depth ? std::max(cell, ud) : std::min(cell, ud);
        }
      }
      if (!inside) continue;
      out->lock_luma.At(x, y, 0) =
          Fsr2Half(Fsr2LockInputLuma(k, o, color.Fetch(x, y, 0), color.Fetch(x, y, 1), color.Fetch(x, y, 2), exposure_texel),
                   o.half_toward_zero);
    }
  }
}

namespace {

// ClampLoad: pos + off, clamped to the texture only on the side the offset points to.
I2 ClampLoad(I2 pos, I2 off, const int32_t size[2]) {
  I2 r{pos.x + off.x, pos.y + off.y};
  if (off.x < 0) r.x = std::max(r.x, 0);
  if (off.x > 0) r.x = std::min(r.x, size[0] - 1);
  if (off.y < 0) r.y = std::max(r.y, 0);
  if (off.y > 0) r.y = std::min(r.y, size[1] - 1);
  return r;
}

// ComputeThinFeatureConfidence.
bool ThinFeature(const Fsr2Constants& k, const Fsr2Plane& luma, I2 pos) {
  const float nucleus = luma.Fetch(pos.x, pos.y, 0);
  float dmin = 3.402823466e+38f, dmax = 0.0f;
  uint32_t mask = 1u << 4;
  int idx = 0;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x, ++idx) {
      if (x == 0 && y == 0) continue;
      const I2 p = ClampLoad(pos, {x, y}, k.render_size);
      const float s = luma.Fetch(p.x, p.y, 0);
      const float difference = std::max(s, nucleus) / std::min(s, nucleus);
      if (difference > 0.0f && difference < 1.05f) {
        mask |= 1u << idx;
      } else {
        dmin = std::min(dmin, s);
        dmax = std::max(dmax, s);
      }
    }
  }
  if (!(nucleus > dmax || nucleus < dmin)) return false;
  static constexpr uint32_t kCorners[4] = {0x1Bu, 0x36u, 0xD8u, 0x1B0u};  // bits {0,1,3,4} {1,2,4,5} {3,4,6,7} {4,5,7,8}
  for (uint32_t c : kCorners) {
    if ((mask & c) == c) return false;
  }
  return true;
}

}  // namespace

void Fsr2ComputeLock(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& lock_luma, Fsr2Plane* new_locks,
                     std::vector<uint32_t>* prev_depth) {
  const int rw = k.render_size[0], rh = k.render_size[1];
  for (int y = 0; y < RoundUp8(rh); ++y) {
    for (int x = 0; x < RoundUp8(rw); ++x) {
      if (ThinFeature(k, lock_luma, {x, y})) {
        const I2 hr = HrPosFromLrPos(k, {x, y});
        if (hr.x >= 0 && hr.y >= 0 && hr.x < new_locks->w && hr.y < new_locks->h) new_locks->At(hr.x, hr.y, 0) = 1.0f;
      }
      if (x < rw && y < rh) {  // ClearResourcesForNextFrame
        (*prev_depth)[static_cast<size_t>(y) * static_cast<size_t>(rw) + static_cast<size_t>(x)] = o.inverted_depth ? 0u : Bits(1.0f);
      }
    }
  }
}

}  // namespace aalab
