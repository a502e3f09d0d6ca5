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
//   - ReconstructAndDilate (ffx_fsr2_reconstruct_previous_depth_pass.glsl);
//   - ComputeLock (ffx_fsr2_lock_pass.glsl);
//   - DepthClip (ffx_fsr2_depth_clip_pass.glsl);
//   - RCAS (ffx_fsr2_rcas_pass.glsl: FsrRcasF of FSR 2's ffx_fsr1.h, FSR_RCAS_DENOISE).
// Not yet: the luminance pyramid (SPD) and accumulate; so no registry rows.
// In RCAS, min/max are std::fmin/fmax (IEEE minNum/maxNum, the non-NaN operand), as lavapipe
// evaluates GLSL's min/max: RCAS's limiter makes 0·∞ = NaN on a black ring.
//
// Dispatch extent: every pass's dispatch covers whole 8×8 groups. Invocations past the render
// size only matter where they can store inside: ReconstructAndDilate's previous-depth atomics
// (their reprojected positions can land on screen), so that loop runs the whole extent; the
// others stop at the render size (their stores outside are discarded).
// Upstream quirks kept: with display-resolution motion vectors, ComputeMotionDivergence clamps
// its 3×3 to the render size (it passes RenderSize() as the motion-vector size); DepthClip
// computes the input depth's view depth and does not use it (no effect).
// The depth-clip pass samples the previous dilated motion with a LINEAR CLAMP_TO_EDGE sampler:
// the port filters as lavapipe does for float textures, fractions in float32 and
// lerp(lerp(a, b, fx), lerp(c, d, fx), fy) with a + f·(b − a) (core/sampler.h's kGl model). A
// GPU's texture unit uses 8-bit fractions instead; the value only feeds a ratio that ends in
// an 8-bit store.
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
  return static_cast<uint32_t>(p.x) < static_cast<uint32_t>(size[0]) &&
         static_cast<uint32_t>(p.y) < static_cast<uint32_t>(size[1]);
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
  const float sx = (static_cast<float>(lr.x) + 0.5f) - k.jitter[0],
              sy = (static_cast<float>(lr.y) + 0.5f) - k.jitter[1];
  return {
      static_cast<int>(std::floor((sx / static_cast<float>(k.render_size[0])) * static_cast<float>(k.display_size[0]))),
      static_cast<int>(
          std::floor((sy / static_cast<float>(k.render_size[1])) * static_cast<float>(k.display_size[1])))};
}

int RoundUp8(int n) { return (n + 7) / 8 * 8; }

float ExposureOf(float texel) { return texel == 0.0f ? 1.0f : texel; }

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

float FloatOfBits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

}  // namespace

float Fsr2Plane::Fetch(int x, int y, int k) const {
  if (x < 0 || y < 0 || x >= w || y >= h) return 0.0f;
  return v[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * static_cast<size_t>(c) +
           static_cast<size_t>(k)];
}

uint16_t Fsr2HalfBits(float f, bool toward_zero) {
  const uint32_t x = Bits(f);
  const uint32_t sign = (x >> 16) & 0x8000u, ax = x & 0x7fffffffu;
  if (ax >= 0x7f800000u) return static_cast<uint16_t>(sign | (ax > 0x7f800000u ? 0x7e00u : 0x7c00u));  // NaN, ∞
  if (ax < 0x38800000u) {  // below 2^-14: a subnormal half, |f|·2^24 (exact) rounded to an integer
    const float q = FloatOfBits(ax) * 16777216.0f;
    return static_cast<uint16_t>(sign | static_cast<uint32_t>(toward_zero ? std::floor(q) : std::nearbyint(q)));
  }
  const uint32_t e = (ax >> 23) - 127u + 15u, m = ax & 0x7fffffu;
  if (e >= 31u) return static_cast<uint16_t>(sign | (toward_zero ? 0x7bffu : 0x7c00u));  // ≥ 65536
  uint32_t h = (e << 10) | (m >> 13);
  const uint32_t rest = m & 0x1fffu;
  if (!toward_zero && (rest > 0x1000u || (rest == 0x1000u && (h & 1u)))) ++h;  // a carry may reach ∞: right
  return static_cast<uint16_t>(sign | h);
}

float Fsr2HalfToFloat(uint16_t h) {
  const uint32_t sign = (static_cast<uint32_t>(h) & 0x8000u) << 16, e = (h >> 10) & 0x1fu, m = h & 0x3ffu;
  if (e == 0) {
    const float v = static_cast<float>(m) * (1.0f / 16777216.0f);
    return sign ? -v : v;
  }
  if (e == 31) return FloatOfBits(sign | 0x7f800000u | (m << 13));
  return FloatOfBits(sign | ((e - 15u + 127u) << 23) | (m << 13));
}

float Fsr2Half(float f, bool toward_zero) { return Fsr2HalfToFloat(Fsr2HalfBits(f, toward_zero)); }

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

void Fsr2ReconstructAndDilate(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& color,
                              const Fsr2Plane& depth, const Fsr2Plane& motion, float exposure_texel,
                              Fsr2ReconstructOut* out) {
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
      V2 mv{motion.Fetch(mpos.x, mpos.y, 0) * k.motion_vector_scale[0],
            motion.Fetch(mpos.x, mpos.y, 1) * k.motion_vector_scale[1]};
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
        const float dx = mv.x * static_cast<float>(k.display_size[0]),
                    dy = mv.y * static_cast<float>(k.display_size[1]);
        const float keep = std::sqrt(dx * dx + dy * dy) > 0.1f ? 1.0f : 0.0f;
        const V2 m{mv.x * keep, mv.y * keep};
        const V2 uv{(static_cast<float>(x) + 0.5f) / static_cast<float>(rw),
                    (static_cast<float>(y) + 0.5f) / static_cast<float>(rh)};
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
          uint32_t& cell =
              out->prev_depth[static_cast<size_t>(p.y) * static_cast<size_t>(rw) + static_cast<size_t>(p.x)];
          cell = o.inverted_depth ? std::max(cell, ud) : std::min(cell, ud);
        }
      }
      if (!inside) continue;
      out->lock_luma.At(x, y, 0) = Fsr2Half(
          Fsr2LockInputLuma(k, o, color.Fetch(x, y, 0), color.Fetch(x, y, 1), color.Fetch(x, y, 2), exposure_texel),
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
  static constexpr uint32_t kCorners[4] = {0x1Bu, 0x36u, 0xD8u,
                                           0x1B0u};  // bits {0,1,3,4} {1,2,4,5} {3,4,6,7} {4,5,7,8}
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
        (*prev_depth)[static_cast<size_t>(y) * static_cast<size_t>(rw) + static_cast<size_t>(x)] =
            o.inverted_depth ? 0u : Bits(1.0f);
      }
    }
  }
}

float Fsr2Unorm8(float v) {
  float c = 0.0f;
  if (v >= 1.0f) {
    c = 255.0f;
  } else if (v > 0.0f) {
    c = std::nearbyint(v * 255.0f);
  }
  return c / 255.0f;
}

namespace {

float Sat(float x) { return std::min(std::max(x, 0.0f), 1.0f); }
float Length2(float x, float y) { return std::sqrt(x * x + y * y); }
float Length3(float x, float y, float z) { return std::sqrt((x * x + y * y) + z * z); }
float Dot3(const float a[3], const float b[3]) { return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]; }
float Mix(float a, float b, float t) { return a * (1.0f - t) + b * t; }

// GetViewSpaceDepth.
float ViewDepth(const Fsr2Constants& k, float device_depth) {
  return k.device_to_view_depth[1] / (device_depth - k.device_to_view_depth[0]);
}

// LoadReconstructedPrevDepth (0 outside).
float PrevDepth(const Fsr2Constants& k, const std::vector<uint32_t>& prev, I2 p) {
  if (!OnScreen(p, k.render_size)) return 0.0f;
  return FloatOfBits(prev[static_cast<size_t>(p.y) * static_cast<size_t>(k.render_size[0]) + static_cast<size_t>(p.x)]);
}

// GetViewSpacePosition's length: (X, Y, Z) at viewport pixel p for device depth d.
float ViewPositionLength(const Fsr2Constants& k, float px, float py, float d) {
  const float z = ViewDepth(k, d);
  const float nx = (px / static_cast<float>(k.render_size[0])) * 2.0f + -1.0f;
  const float ny = (py / static_cast<float>(k.render_size[1])) * -2.0f + 1.0f;
  const float x = (k.device_to_view_depth[2] * nx) * z, y = (k.device_to_view_depth[3] * ny) * z;
  return Length3(x, y, z);
}

// ComputeDepthClip.
float DepthClipAt(const Fsr2Constants& k, const Fsr2Options& o, const std::vector<uint32_t>& prev, V2 uv, float cur) {
  const float cur_vs = ViewDepth(k, cur);
  const int rw = k.render_size[0], rh = k.render_size[1];
  const V2 s{uv.x * static_cast<float>(rw) - 0.5f, uv.y * static_cast<float>(rh) - 0.5f};
  const V2 fl{std::floor(s.x), std::floor(s.y)};
  const I2 base{static_cast<int>(fl.x), static_cast<int>(fl.y)};
  const V2 fr{s.x - fl.x, s.y - fl.y};
  const float wts[4] = {(1 - fr.x) * (1 - fr.y), fr.x * (1 - fr.y), (1 - fr.x) * fr.y, fr.x * fr.y};
  static constexpr I2 kCorner[4] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  float depth = 0.0f, wsum = 0.0f;
  for (int i = 0; i < 4; ++i) {
    const I2 p{base.x + kCorner[i].x, base.y + kCorner[i].y};
    if (!OnScreen(p, k.render_size) || !(wts[i] > 0.01f)) continue;
    const float pd = PrevDepth(k, prev, p);
    const float prev_vs = ViewDepth(k, pd);
    const float diff = cur_vs - prev_vs;
    if (!(diff > 0.0f)) continue;
    const float plane = o.inverted_depth ? std::min(pd, cur) : std::max(pd, cur);
    const float cx = static_cast<float>(static_cast<int>(static_cast<float>(rw) * 0.5f));
    const float cy = static_cast<float>(static_cast<int>(static_cast<float>(rh) * 0.5f));
    const float center = ViewPositionLength(k, cx, cy, plane), corner = ViewPositionLength(k, 0.0f, 0.0f, plane);
    const float half_width = Length2(static_cast<float>(rw), static_cast<float>(rh));
    const float threshold = std::max(cur_vs, prev_vs);
    const float kfov = corner / center;
    const float required = ((1.37e-05f * kfov) * half_width) * threshold;
    const float res = Sat(Length2(static_cast<float>(rw), static_cast<float>(rh)) / Length2(1920.0f, 1080.0f));
    const float power = Mix(1.0f, 3.0f, res);
    depth = depth + Pow(Sat(required / diff), power) * wts[i];
    wsum = wsum + wts[i];
  }
  return wsum > 0.0f ? Sat(1.0f - depth / wsum) : 0.0f;
}

// EvaluateSurface.
float Surface(const Fsr2Constants& k, const std::vector<uint32_t>& prev, I2 p) {
  const float d0 = ViewDepth(k, PrevDepth(k, prev, {p.x, p.y - 1}));
  const float d1 = ViewDepth(k, PrevDepth(k, prev, p));
  const float d2 = ViewDepth(k, PrevDepth(k, prev, {p.x, p.y + 1}));
  return 1.0f - (((d0 - d1) > (d1 * 0.01f)) && ((d1 - d2) > (d2 * 0.01f)) ? 1.0f : 0.0f);
}

V2 InputMotion(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& m, I2 p) {
  V2 mv{m.Fetch(p.x, p.y, 0) * k.motion_vector_scale[0], m.Fetch(p.x, p.y, 1) * k.motion_vector_scale[1]};
  if (o.jittered_motion_vectors) {
    mv.x = mv.x - k.motion_vector_jitter_cancellation[0];
    mv.y = mv.y - k.motion_vector_jitter_cancellation[1];
  }
  return mv;
}

// ComputeMotionDivergence.
float MotionDivergence(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& m, I2 p) {
  float minconv = 1.0f;
  const V2 n = InputMotion(k, o, m, p);
  const float n_lr = Length2(n.x * static_cast<float>(k.render_size[0]), n.y * static_cast<float>(k.render_size[1]));
  float max_vel = Length2(n.x, n.y);
  if (n_lr > 1e-02f) {
    for (int y = -1; y <= 1; ++y) {
      for (int x = -1; x <= 1; ++x) {
        const V2 mv = InputMotion(k, o, m, ClampLoad(p, {x, y}, k.render_size));
        float vel = Length2(mv.x, mv.y);
        max_vel = std::max(vel, max_vel);
        vel = std::max(vel, max_vel);
        const float ax = mv.x / vel, ay = mv.y / vel, bx = n.x / vel, by = n.y / vel;
        minconv = std::min(minconv, ax * bx + ay * by);
      }
    }
  }
  return Sat(1.0f - minconv) * Sat(max_vel / 0.01f);
}

// ComputeDepthDivergence.
float DepthDivergence(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& dilated_depth, I2 p) {
  const float max_dist = ViewDepth(k, o.inverted_depth ? 0.0f : 1.0f) * k.view_space_to_meters;
  float dmax = 0.0f, dmin = max_dist;
  bool found = false;
  for (int y = -1; y < 2; ++y) {
    for (int x = -1; x < 2; ++x) {
      const I2 s{p.x + x, p.y + y};
      const float on = OnScreen(s, k.render_size) ? 1.0f : 0.0f;
      const float d = (ViewDepth(k, dilated_depth.Fetch(s.x, s.y, 0)) * k.view_space_to_meters) * on;
      found |= max_dist == d;
      dmin = std::min(dmin, d);
      dmax = std::max(dmax, d);
    }
  }
  return (1.0f - dmin / dmax) * (found ? 0.0f : 1.0f);
}

// A bilinear sample of a 2-channel texture at uv with a LINEAR CLAMP_TO_EDGE sampler, channel c.
float SampleLinear(const Fsr2Plane& t, V2 uv, int c) {
  const float u = uv.x * static_cast<float>(t.w) - 0.5f, v = uv.y * static_cast<float>(t.h) - 0.5f;
  const float x0f = std::floor(u), y0f = std::floor(v);
  const float fx = u - x0f, fy = v - y0f;
  auto at = [&](int x, int y) { return t.Fetch(std::clamp(x, 0, t.w - 1), std::clamp(y, 0, t.h - 1), c); };
  const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
  const float a = at(x0, y0), b = at(x0 + 1, y0), cc = at(x0, y0 + 1), d = at(x0 + 1, y0 + 1);
  const float top = a + fx * (b - a), bottom = cc + fx * (d - cc);
  return top + fy * (bottom - top);
}

// ComputeTemporalMotionDivergence.
float TemporalMotionDivergence(const Fsr2Constants& k, const Fsr2DepthClipIn& in, I2 p) {
  const int rw = k.render_size[0], rh = k.render_size[1];
  const V2 uv{(static_cast<float>(p.x) + 0.5f) / static_cast<float>(rw),
              (static_cast<float>(p.y) + 0.5f) / static_cast<float>(rh)};
  const V2 mv{in.dilated_motion->Fetch(p.x, p.y, 0), in.dilated_motion->Fetch(p.x, p.y, 1)};
  V2 r{uv.x + mv.x, uv.y + mv.y};
  // ClampUv to the render size, in UV of the max render size.
  const float lx = r.x * static_cast<float>(rw), ly = r.y * static_cast<float>(rh);
  r.x = std::max(0.5f, std::min(lx, static_cast<float>(rw) - 0.5f)) / static_cast<float>(k.max_render_size[0]);
  r.y = std::max(0.5f, std::min(ly, static_cast<float>(rh) - 0.5f)) / static_cast<float>(k.max_render_size[1]);
  const V2 pm{SampleLinear(*in.previous_dilated_motion, r, 0), SampleLinear(*in.previous_dilated_motion, r, 1)};
  const float dist =
      Length2(mv.x * static_cast<float>(k.display_size[0]), mv.y * static_cast<float>(k.display_size[1]));
  if (!(dist > 1.0f)) return 0.0f;
  return Mix(0.0f, 1.0f - Sat(Length2(pm.x, pm.y) / Length2(mv.x, mv.y)), Sat(Pow(dist / 20.0f, 3.0f)));
}

}  // namespace

void Fsr2DepthClip(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2DepthClipIn& in, Fsr2DepthClipOut* out) {
  const int rw = k.render_size[0], rh = k.render_size[1];
  out->prepared_color = Fsr2Plane(rw, rh, 4);
  out->reactive_masks = Fsr2Plane(rw, rh, 2);
  const float exposure = ExposureOf(in.exposure);
  // Invocations past the render size only store outside the images: the loop stops there.
  for (int y = 0; y < rh; ++y) {
    for (int x = 0; x < rw; ++x) {
      const I2 p{x, y};
      const V2 uv{(static_cast<float>(x) + 0.5f) / static_cast<float>(rw),
                  (static_cast<float>(y) + 0.5f) / static_cast<float>(rh)};
      V2 mv{in.dilated_motion->Fetch(x, y, 0), in.dilated_motion->Fetch(x, y, 1)};
      const float keep =
          Length2(mv.x * static_cast<float>(k.display_size[0]), mv.y * static_cast<float>(k.display_size[1])) > 0.01f
              ? 1.0f
              : 0.0f;
      mv = {mv.x * keep, mv.y * keep};
      const V2 duv{uv.x + mv.x, uv.y + mv.y};
      const float clip =
          DepthClipAt(k, o, *in.prev_depth, duv, in.dilated_depth->Fetch(x, y, 0)) * Surface(k, *in.prev_depth, p);
      // ComputePreparedInputColor: max(0, rgb) / pre-exposure · exposure, clamped to the fp16 range, YCoCg.
      float rgb[3];
      for (int c = 0; c < 3; ++c) {
        float v = std::max(0.0f, in.color->Fetch(x, y, c));
        v = v / k.pre_exposure;
        v = v * exposure;
        rgb[c] = std::min(std::max(v, 0.0f), 65504.0f);
      }
      const float yy = (0.25f * rgb[0] + 0.5f * rgb[1]) + 0.25f * rgb[2];
      const float co = 0.5f * rgb[0] - 0.5f * rgb[2];
      const float cg = (-0.25f * rgb[0] + 0.5f * rgb[1]) - 0.25f * rgb[2];
      out->prepared_color.At(x, y, 0) = Fsr2Half(yy, o.half_toward_zero);
      out->prepared_color.At(x, y, 1) = Fsr2Half(co, o.half_toward_zero);
      out->prepared_color.At(x, y, 2) = Fsr2Half(cg, o.half_toward_zero);
      out->prepared_color.At(x, y, 3) = Fsr2Half(clip, o.half_toward_zero);
      // The dilated reactive masks.
      const I2 sp = o.low_res_motion_vectors ? p : HrPosFromLrPos(k, p);
      const float md = MotionDivergence(k, o, *in.motion, sp);
      const float tmd = Sat(TemporalMotionDivergence(k, in, p) - DepthDivergence(k, o, *in.dilated_depth, p));
      // PreProcessReactiveMasks.
      const float ref[3] = {in.color->Fetch(x, y, 0), in.color->Fetch(x, y, 1), in.color->Fetch(x, y, 2)};
      float fac[2] = {0.0f, std::max(tmd, md)};
      float samples[9][3], reactive[9], comp[9];
      float sum = 0.0f;
      for (int dy = -1; dy < 2; ++dy) {
        for (int dx = -1; dx < 2; ++dx) {
          const I2 c = ClampLoad(p, {dx, dy}, k.render_size);
          const int i = (dy + 1) * 3 + dx + 1;
          for (int ch = 0; ch < 3; ++ch) samples[i][ch] = in.color->Fetch(c.x, c.y, ch);
          reactive[i] = in.reactive.v.empty() ? 0.0f : in.reactive.Fetch(c.x, c.y, 0);
          comp[i] = in.composition.v.empty() ? 0.0f : in.composition.Fetch(c.x, c.y, 0);
          sum = sum + (reactive[i] + comp[i]);
        }
      }
      if (sum > 0.0f) {
        for (int i = 0; i < 9; ++i) {
          const float max_len_sq = std::max(Dot3(ref, ref), Dot3(samples[i], samples[i]));
          const float similarity = Dot3(ref, samples[i]) / max_len_sq;
          const float power = 1.0f + (6.0f - similarity * 6.0f);
          fac[0] = std::max(fac[0], Pow(reactive[i], power));
          fac[1] = std::max(fac[1], Pow(comp[i], power));
        }
      }
      out->reactive_masks.At(x, y, 0) = Fsr2Unorm8(fac[0]);
      out->reactive_masks.At(x, y, 1) = Fsr2Unorm8(fac[1]);
    }
  }
}

uint32_t Fsr2RcasCon(float sharpness) {
  const float stops = (-2.0f * sharpness) + 2.0f;
  return Bits(std::exp2(-stops));
}

namespace {

// ffxApproximateReciprocalMedium: b = bits⁻¹(0x7ef19fff − bits(a)), then b·(−b·a + 2).
float MedRcp(float a) {
  const float b = FloatOfBits(0x7ef19fffu - Bits(a));
  return b * (-b * a + 2.0f);
}
float Max3(float x, float y, float z) { return std::fmax(x, std::fmax(y, z)); }
float Min3(float x, float y, float z) { return std::fmin(x, std::fmin(y, z)); }

}  // namespace

std::vector<float> Fsr2Rcas(const Fsr2Constants& k, const Fsr2Plane& in, float exposure_texel, uint32_t con_x) {
  const int w = in.w, h = in.h;
  const float exposure = ExposureOf(exposure_texel);
  std::vector<float> out(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
  struct Px {
    float r, g, b;
  };
  auto load = [&](int x, int y) {  // FsrRcasLoadF: texelFetch, then PrepareRgb
    float c[3];
    for (int ch = 0; ch < 3; ++ch) {
      float v = in.Fetch(x, y, ch);
      v = v / k.pre_exposure;
      v = v * exposure;
      c[ch] = std::fmin(std::fmax(v, 0.0f), 65504.0f);
    }
    return Px{c[0], c[1], c[2]};
  };
  auto luma2 = [](const Px& p) { return p.b * 0.5f + (p.r * 0.5f + p.g); };
  const float sharp = FloatOfBits(con_x);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Px b = load(x, y - 1), d = load(x - 1, y), e = load(x, y), f = load(x + 1, y), hh = load(x, y + 1);
      const float bL = luma2(b), dL = luma2(d), eL = luma2(e), fL = luma2(f), hL = luma2(hh);
      float nz = (((0.25f * bL + 0.25f * dL) + 0.25f * fL) + 0.25f * hL) - eL;
      nz = Sat(std::fabs(nz) * MedRcp(Max3(Max3(bL, dL, eL), fL, hL) - Min3(Min3(bL, dL, eL), fL, hL)));
      nz = -0.5f * nz + 1.0f;
      float lobes[3];
      const float bc[3] = {b.r, b.g, b.b}, dc[3] = {d.r, d.g, d.b}, fc[3] = {f.r, f.g, f.b}, hc[3] = {hh.r, hh.g, hh.b};
      for (int c = 0; c < 3; ++c) {
        const float mn4 = std::fmin(Min3(bc[c], dc[c], fc[c]), hc[c]);
        const float mx4 = std::fmax(Max3(bc[c], dc[c], fc[c]), hc[c]);
        const float hit_min = mn4 * (1.0f / (4.0f * mx4));
        const float hit_max = (1.0f - mx4) * (1.0f / (4.0f * mn4 + -4.0f));
        lobes[c] = std::fmax(-hit_min, hit_max);
      }
      float lobe = std::fmax(-0.1875f, std::fmin(Max3(lobes[0], lobes[1], lobes[2]), 0.0f)) * sharp;
      lobe = lobe * nz;
      const float rcp_l = MedRcp(4.0f * lobe + 1.0f);
      const float ec[3] = {e.r, e.g, e.b};
      for (int c = 0; c < 3; ++c) {
        const float pix = ((((lobe * bc[c] + lobe * dc[c]) + lobe * hc[c]) + lobe * fc[c]) + ec[c]) * rcp_l;
        // UnprepareRgb.
        out[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 3 + static_cast<size_t>(c)] =
            (pix / exposure) * k.pre_exposure;
      }
    }
  }
  return out;
}

}  // namespace aalab
