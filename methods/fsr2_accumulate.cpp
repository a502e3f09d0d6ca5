// FSR 2.2.1's accumulate pass (ffx_fsr2_accumulate_pass.glsl: Accumulate of
// ffx_fsr2_accumulate.h with ffx_fsr2_reproject.h, ffx_fsr2_upsample.h,
// ffx_fsr2_postprocess_lock_status.h and ffx_fsr2_sample.h), fp32 path (FFX_HALF=0), with the
// base options FSR2's build gives every backend (UPSAMPLE_USE_LANCZOS_TYPE=2: the upsample's
// kernel is the polynomial Lanczos2ApproxSq; the *_SAMPLERS_USE_DATA_HALF options only act
// with FFX_HALF) and the permutations of Fsr2Options (REPROJECT_USE_LANCZOS_TYPE 0 or 1,
// APPLY_SHARPENING, HDR, motion-vector resolution and jitter; depth is not read here).
// Conventions (stores, pow, float order): methods/fsr2_common.cpp's doc block; figures and
// what differs from lavapipe: docs/fsr2.md.
//
// The dispatch covers 8×8 groups over the display size (its rows in reverse order, which
// changes nothing: no invocation reads what another writes); every store is at the
// invocation's own pixel, so the loop stops at the display size.
// Reads, as the shader makes them:
//   - texelFetch (prepared colour, history, new locks): 0 outside the image (robust access).
//     The upsample's 3×3 of the prepared colour is clamped by ClampLoad with a zero offset,
//     which clamps nothing: samples past the render size read 0 (weight 0, but they still
//     enter the rectification box, as in the shader; FSR2's textures are the maximum render
//     size, so on a GPU they read whatever lies there when the render size is smaller).
//   - the history's custom filter (DeclareCustomTextureSample): texel
//     coordinates clamped to [0, size] (not size − 1), ClampCoord on the offset's side only.
//   - LINEAR CLAMP_TO_EDGE samples (depth clip, reactive masks, luma history, the luma mip,
//     the Lanczos table): SampleLinear (fsr2_internal.h), the float model of Mesa's filter
//     (fractions in float32, fused a + f·(b − a)); a GPU's texture unit uses 8-bit fractions.
// The shader's transcendental builtins are evaluated as Mesa lowers them: exp(x) =
// exp2(x·log2 e), pow(x, y) = exp2(log2(x)·y), sin; exp2, log2 and sin are the C library's
// unless Fsr2Options::math supplies others (the oracle supplies lavapipe's own values: its
// polynomials differ from the C library in the last float bits; docs/fsr2.md measures what
// that changes and shows that it is the only difference).
// Safe where the shader is: MinDividedByMax returns 0 for a zero maximum, the box weight sum
// falls back to 1, the upsampled colour is divided only when its weight exceeds 1e-3.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "methods/fsr2.h"
#include "methods/fsr2_internal.h"

namespace aalab {

using namespace fsr2_detail;  // NOLINT(google-build-using-namespace): the passes' shared helpers

namespace {

constexpr float kEpsilon = 1e-03f;             // FSR2_EPSILON
constexpr float kFltMax = 3.402823466e+38f;    // FSR2_FLT_MAX
constexpr float kLanczosScale = 1.0f / 12.0f;  // fUpsampleLanczosWeightScale
// fAverageLanczosWeightPerFrame = 0.74 · (1/12), folded by glslang in double precision.
const float kAverageLanczosWeight = static_cast<float>(0.74 * (1.0 / 12.0));
constexpr float kPi = 3.141592653589793f;

struct V3 {
  float v[3];
};
struct V4 {
  float v[4];
};

// GLSL's mix as Mesa lowers it for exact (NoContraction) operations: a·(1 − t) + b·t.
float Lerp(float a, float b, float t) { return a * (1.0f - t) + b * t; }

// The transcendental builtins: the C library's, or Fsr2Options::math's.
float Exp2(const Fsr2Options& o, float x) { return o.math ? o.math->Exp2(x) : std::exp2(x); }
float Log2(const Fsr2Options& o, float x) { return o.math ? o.math->Log2(x) : std::log2(x); }
float Sin(const Fsr2Options& o, float x) { return o.math ? o.math->Sin(x) : std::sin(x); }
float PowO(const Fsr2Options& o, float x, float y) { return Exp2(o, Log2(o, x) * y); }
// exp(x) as Mesa lowers it: exp2(x·log2 e).
float ExpO(const Fsr2Options& o, float x) { return Exp2(o, x * static_cast<float>(1.4426950408889634)); }

// GLSL's min/max/clamp as lavapipe evaluates them (IEEE minNum/maxNum).
float Min(float a, float b) { return std::fmin(a, b); }
float Max(float a, float b) { return std::fmax(a, b); }
float Clamp(float x, float lo, float hi) { return Min(Max(x, lo), hi); }
float Saturate(float x) { return Clamp(x, 0.0f, 1.0f); }

V3 YCoCgToRgb(const V3& c) { return {{(c.v[0] + c.v[1]) - c.v[2], c.v[0] + c.v[2], (c.v[0] - c.v[1]) - c.v[2]}}; }
V3 RgbToYCoCg(const V3& c) {
  return {{(0.25f * c.v[0] + 0.5f * c.v[1]) + 0.25f * c.v[2], 0.5f * c.v[0] - 0.5f * c.v[2],
           (-0.25f * c.v[0] + 0.5f * c.v[1]) - 0.25f * c.v[2]}};
}
V3 Tonemap(const V3& c) {
  const float d = Max(Max(0.0f, c.v[0]), Max(c.v[1], c.v[2])) + 1.0f;
  return {{c.v[0] / d, c.v[1] / d, c.v[2] / d}};
}
V3 InverseTonemap(const V3& c) {
  const float d = Max(1.0f / 65504.0f, 1.0f - Max(c.v[0], Max(c.v[1], c.v[2])));
  return {{c.v[0] / d, c.v[1] / d, c.v[2] / d}};
}
float MinDividedByMax(float a, float b) {
  const float m = Max(a, b);
  return m != 0.0f ? Min(a, b) / m : 0.0f;
}
bool UvInside(V2 uv) { return (uv.x >= 0.0f && uv.x <= 1.0f) && (uv.y >= 0.0f && uv.y <= 1.0f); }

// ClampUv: uv in a texture of `size` texels, clamped half a texel inside, in UV of `resource`.
V2 ClampUv(V2 uv, I2 size, I2 resource) {
  const float x = uv.x * static_cast<float>(size.x), y = uv.y * static_cast<float>(size.y);
  return {Max(0.5f, Min(x, static_cast<float>(size.x) - 0.5f)) / static_cast<float>(resource.x),
          Max(0.5f, Min(y, static_cast<float>(size.y) - 0.5f)) / static_cast<float>(resource.y)};
}

// Lanczos2 (reference) and the table's weight (Lanczos2_UseLUT: a linear sample at x/2).
float Lanczos2(const Fsr2Options& o, float x) {
  x = Min(std::fabs(x), 2.0f);
  if (std::fabs(x) < kEpsilon) return 1.0f;
  const float px = kPi * x, hx = (0.5f * kPi) * x;
  return (Sin(o, px) / px) * (Sin(o, hx) / hx);
}
float LanczosWeight(const Fsr2Options& o, const Fsr2Plane* lut, float x) {
  if (!o.reproject_lanczos_lut) return Lanczos2(o, x);
  return SampleLinear(*lut, {std::fabs(x) / 2.0f, 0.5f}, 0);
}

// The 1-D Lanczos of four texels at fraction t (Lanczos2 / Lanczos2_UseLUT with four colours).
V4 Lanczos4(const Fsr2Options& o, const Fsr2Plane* lut, const V4 c[4], float t) {
  const float w0 = LanczosWeight(o, lut, -1.0f - t), w1 = LanczosWeight(o, lut, -0.0f - t),
              w2 = LanczosWeight(o, lut, 1.0f - t), w3 = LanczosWeight(o, lut, 2.0f - t);
  const float wsum = ((w0 + w1) + w2) + w3;
  V4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = (((w0 * c[0].v[i] + w1 * c[1].v[i]) + w2 * c[2].v[i]) + w3 * c[3].v[i]) / wsum;
  return r;
}

// ClampCoord: pos + off, clamped on the offset's side only.
I2 ClampCoord(I2 p, I2 off, I2 size) {
  I2 r{p.x + off.x, p.y + off.y};
  if (off.x < 0) r.x = std::max(r.x, 0);
  if (off.x > 0) r.x = std::min(r.x, size.x - 1);
  if (off.y < 0) r.y = std::max(r.y, 0);
  if (off.y > 0) r.y = std::min(r.y, size.y - 1);
  return r;
}

V4 FetchV4(const Fsr2Plane& t, I2 p) {
  V4 r{{0, 0, 0, 0}};
  for (int c = 0; c < std::min(t.c, 4); ++c) r.v[c] = t.Fetch(p.x, p.y, c);
  return r;
}

// DeclareCustomTextureSample's texel position: uv·size − 0.5, clamped to [0, size].
void CustomSamplePos(V2 uv, I2 size, I2* base, V2* frac) {
  float x = uv.x * static_cast<float>(size.x) - 0.5f, y = uv.y * static_cast<float>(size.y) - 0.5f;
  x = Max(0.0f, Min(static_cast<float>(size.x), x));
  y = Max(0.0f, Min(static_cast<float>(size.y), y));
  const float fx = std::floor(x), fy = std::floor(y);
  *base = {static_cast<int>(fx), static_cast<int>(fy)};
  *frac = {x - fx, y - fy};
}

// HistorySample: the 4×4 Lanczos of the history (reference or table), clamped to the 2×2
// around the sample (deringing).
V4 HistorySample(const Fsr2Options& o, const Fsr2AccumulateIn& in, V2 uv, I2 size) {
  I2 base;
  V2 f;
  CustomSamplePos(uv, size, &base, &f);
  V4 s[4][4];  // [row][col], offsets −1..+2
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) s[r][c] = FetchV4(*in.history, ClampCoord(base, {c - 1, r - 1}, size));
  V4 rows[4];
  for (int r = 0; r < 4; ++r) rows[r] = Lanczos4(o, in.lanczos_lut, s[r], f.x);
  V4 xy = Lanczos4(o, in.lanczos_lut, rows, f.y);
  const V4* ring[4] = {&s[1][1], &s[1][2], &s[2][1], &s[2][2]};
  for (int i = 0; i < 4; ++i) {
    float lo = ring[0]->v[i], hi = ring[0]->v[i];
    for (int j = 1; j < 4; ++j) {
      lo = Min(lo, ring[j]->v[i]);
      hi = Max(hi, ring[j]->v[i]);
    }
    xy.v[i] = Clamp(xy.v[i], lo, hi);
  }
  return xy;
}

struct Params {
  I2 hr;
  V2 hr_uv, lr_uv, mv, reprojected_uv;
  float hr_velocity, depth_clip, dilated_reactive, accumulation_mask;
  bool reset, existing, new_sample;
};

Params InitParams(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2AccumulateIn& in, I2 hr) {
  Params p;
  p.hr = hr;
  p.hr_uv = {(static_cast<float>(hr.x) + 0.5f) / static_cast<float>(k.display_size[0]),
             (static_cast<float>(hr.y) + 0.5f) / static_cast<float>(k.display_size[1])};
  const V2 lr{p.hr_uv.x + k.jitter[0] / static_cast<float>(k.render_size[0]),
              p.hr_uv.y + k.jitter[1] / static_cast<float>(k.render_size[1])};
  p.lr_uv = ClampUv(lr, {k.render_size[0], k.render_size[1]}, {k.max_render_size[0], k.max_render_size[1]});
  if (o.low_res_motion_vectors) {  // LoadDilatedMotionVector(ivec2(fHrUv · RenderSize()))
    const int x = static_cast<int>(p.hr_uv.x * static_cast<float>(k.render_size[0]));
    const int y = static_cast<int>(p.hr_uv.y * static_cast<float>(k.render_size[1]));
    p.mv = {in.dilated_motion->Fetch(x, y, 0), in.dilated_motion->Fetch(x, y, 1)};
  } else {
    p.mv = InputMotion(k, o, *in.motion, hr);
  }
  p.hr_velocity =
      Length2(p.mv.x * static_cast<float>(k.display_size[0]), p.mv.y * static_cast<float>(k.display_size[1]));
  p.reprojected_uv = {p.hr_uv.x + p.mv.x, p.hr_uv.y + p.mv.y};
  p.existing = UvInside(p.reprojected_uv);
  p.depth_clip = Saturate(SampleLinear(*in.prepared_color, p.lr_uv, 3));
  p.dilated_reactive = SampleLinear(*in.dilated_reactive_masks, p.lr_uv, 0);
  p.accumulation_mask = SampleLinear(*in.dilated_reactive_masks, p.lr_uv, 1);
  p.reset = k.frame_index == 0;
  p.new_sample = !p.existing || p.reset;
  return p;
}

// GetShadingChangeLuma: pow(exposure · exp(the luma mip, bilinear), 1/6).
float ShadingChangeLuma(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2AccumulateIn& in, float exposure,
                        V2 uv) {
  const float div = static_cast<float>(2 << k.luma_mip_level);
  const I2 mip_render{static_cast<int>(static_cast<float>(k.render_size[0]) / div),
                      static_cast<int>(static_cast<float>(k.render_size[1]) / div)};
  uv = ClampUv(uv, mip_render, {k.luma_mip_size[0], k.luma_mip_size[1]});
  const float luma = exposure * ExpO(o, SampleLinear(*in.luma_mip, uv, 0));
  return PowO(o, luma, 1.0f / 6.0f);
}

struct Box {
  V3 center{}, vec{}, aabb_min{}, aabb_max{};
  float weight = 0.0f;
  void Add(bool initial, const V3& s, float w) {
    for (int i = 0; i < 3; ++i) {
      const float ws = s.v[i] * w;
      if (initial) {
        aabb_min.v[i] = aabb_max.v[i] = s.v[i];
        center.v[i] = ws;
        vec.v[i] = s.v[i] * ws;
      } else {
        aabb_min.v[i] = Min(aabb_min.v[i], s.v[i]);
        aabb_max.v[i] = Max(aabb_max.v[i], s.v[i]);
        center.v[i] = center.v[i] + ws;
        vec.v[i] = vec.v[i] + s.v[i] * ws;
      }
    }
    weight = initial ? w : weight + w;
  }
  void ComputeVariance() {  // RectificationBoxComputeVarianceBoxData
    weight = std::fabs(weight) > kEpsilon ? weight : 1.0f;
    for (int i = 0; i < 3; ++i) {
      center.v[i] = center.v[i] / weight;
      vec.v[i] = vec.v[i] / weight;
      vec.v[i] = std::sqrt(std::fabs(vec.v[i] - center.v[i] * center.v[i]));
    }
  }
};

// ComputeUpsampledColorAndWeight: the approximate Lanczos 2 of the 3×3 jittered samples
// nearest the output pixel (YCoCg), its weight, and the rectification box.
V4 UpsampledColorAndWeight(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2AccumulateIn& in, const Params& p,
                           float reactive, Box* box) {
  const V2 dst{static_cast<float>(p.hr.x) + 0.5f, static_cast<float>(p.hr.y) + 0.5f};
  const V2 src{dst.x * k.downscale_factor[0], dst.y * k.downscale_factor[1]};
  const I2 isrc{static_cast<int>(std::floor(src.x)), static_cast<int>(std::floor(src.y))};
  const V2 unjittered{(static_cast<float>(isrc.x) + 0.5f) - k.jitter[0],
                      (static_cast<float>(isrc.y) + 0.5f) - k.jitter[1]};
  const bool flip_col = unjittered.x > src.x, flip_row = unjittered.y > src.y;
  const I2 tl{flip_col ? -2 : -1, flip_row ? -2 : -1};
  const V2 base_offset{unjittered.x - src.x, unjittered.y - src.y};
  const float kernel_reactive = Max(reactive, p.new_sample ? 1.0f : 0.0f);
  const float max_kernel = Min(1.99f, 1.0f + ((1.0f / k.downscale_factor[0]) - 1.0f) * 1.0f);
  const float bias_max = max_kernel * (1.0f - kernel_reactive);
  const float bias_min = Max(1.0f, (1.0f + bias_max) * 0.3f);
  const float bias_factor = Max(0.0f, Max(0.25f * p.depth_clip, kernel_reactive));
  const float bias = Lerp(bias_max, bias_min, bias_factor);
  const float curve = Lerp(-2.0f, -3.0f, Saturate(p.hr_velocity / 50.0f));
  V4 cw{{0, 0, 0, 0}};
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      const I2 cr{flip_col ? 3 - col : col, flip_row ? 3 - row : row};
      const I2 pos{isrc.x + tl.x + cr.x, isrc.y + tl.y + cr.y};
      const V3 s{{in.prepared_color->Fetch(pos.x, pos.y, 0), in.prepared_color->Fetch(pos.x, pos.y, 1),
                  in.prepared_color->Fetch(pos.x, pos.y, 2)}};
      const V2 off{base_offset.x + (static_cast<float>(tl.x) + static_cast<float>(cr.x)),
                   base_offset.y + (static_cast<float>(tl.y) + static_cast<float>(cr.y))};
      const float on = OnScreen(pos, k.render_size) ? 1.0f : 0.0f;
      // GetUpsampleLanczosWeight, LANCZOS_TYPE_APPROXIMATE: Lanczos2ApproxSq(|offset·bias|²).
      const float bx = off.x * bias, by = off.y * bias;
      const float x2 = Min(bx * bx + by * by, 4.0f);
      const float a = (2.0f / 5.0f) * x2 - 1.0f, b = (1.0f / 4.0f) * x2 - 1.0f;
      const float w = on * ((((25.0f / 16.0f) * a) * a - (25.0f / 16.0f - 1.0f)) * (b * b));
      for (int i = 0; i < 3; ++i) cw.v[i] = cw.v[i] + s.v[i] * w;
      cw.v[3] = cw.v[3] + w;
      const float box_w = ExpO(o, curve * (off.x * off.x + off.y * off.y));
      box->Add(row == 0 && col == 0, s, box_w);
    }
  }
  box->ComputeVariance();
  cw.v[3] = cw.v[3] * (cw.v[3] > kEpsilon ? 1.0f : 0.0f);
  if (cw.v[3] > kEpsilon) {
    for (int i = 0; i < 3; ++i) cw.v[i] = cw.v[i] / cw.v[3];
    cw.v[3] = cw.v[3] * kLanczosScale;
    for (int i = 0; i < 3; ++i) cw.v[i] = Clamp(cw.v[i], box->aabb_min.v[i], box->aabb_max.v[i]);  // Deringing
  }
  return cw;
}

float Sign(float x) { return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f); }

// ComputeLumaInstabilityFactor, with the luma history it stores.
float LumaInstability(const Fsr2Options& o, const Fsr2AccumulateIn& in, const Params& p, const Box& box, float reactive,
                      float luminance_diff, float history_out[4]) {
  const float threshold = 1.0f / 255.0f;
  float luma = box.center.v[0];
  if (o.hdr_color_input) luma = luma / (1.0f + Max(0.0f, luma));
  luma = std::nearbyint(luma * 255.0f) / 255.0f;
  const bool sample = Max(Max(p.depth_clip, p.accumulation_mask), luminance_diff) < 0.1f && !p.new_sample;
  float h[4] = {0, 0, 0, 0};
  if (sample) {
    for (int c = 0; c < 4; ++c) h[c] = SampleLinear(*in.luma_history, p.reprojected_uv, c);
  }
  float instability = 0.0f;
  const float d0 = luma - h[0];
  float mn = std::fabs(d0);
  if (mn >= threshold) {
    for (int i = 1; i <= 3; ++i) {
      const float d1 = luma - h[i];
      if (Sign(d0) == Sign(d1)) mn = Min(mn, std::fabs(d1) * 1.0f);
    }
    const float box_size_factor = PowO(o, Saturate(box.vec.v[0] / 0.1f), 6.0f);
    instability = (mn != std::fabs(d0) ? 1.0f : 0.0f) * box_size_factor;
    instability = instability > threshold ? 1.0f : 0.0f;
    instability = instability * (1.0f - Max(p.accumulation_mask, PowO(o, reactive, 1.0f / 6.0f)));
  }
  h[3] = h[2];
  h[2] = h[1];
  h[1] = h[0];
  h[0] = luma;
  for (int c = 0; c < 4; ++c) history_out[c] = Fsr2Unorm8(h[c]);
  return instability * (h[3] != 0.0f ? 1.0f : 0.0f);
}

}  // namespace

void Fsr2Accumulate(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2AccumulateIn& in, Fsr2AccumulateOut* out) {
  const int dw = k.display_size[0], dh = k.display_size[1];
  const bool tz = o.half_toward_zero;
  out->internal_upscaled = Fsr2Plane(dw, dh, 4);
  out->lock_status = Fsr2Plane(dw, dh, 2);
  out->luma_history = Fsr2Plane(dw, dh, 4);
  out->output = o.apply_sharpening ? Fsr2Plane() : Fsr2Plane(dw, dh, 3);
  const float exposure = ExposureOf(in.exposure);
  const I2 display{dw, dh};
  for (int y = 0; y < dh; ++y) {
    for (int x = 0; x < dw; ++x) {
      const Params p = InitParams(k, o, in, {x, y});
      V3 history{{0, 0, 0}};
      float lock[2] = {0.0f, 0.0f};  // LOCK_LIFETIME_REMAINING, LOCK_TEMPORAL_LUMA
      float temporal_reactive = 0.0f;
      bool in_motion_last_frame = false, new_lock = false;
      if (p.existing && !p.reset) {
        // ReprojectHistoryColor.
        const V4 h = HistorySample(o, in, p.reprojected_uv, display);
        for (int i = 0; i < 3; ++i) {
          float v = h.v[i] / k.previous_pre_exposure;  // PrepareRgb
          v = v * exposure;
          history.v[i] = Clamp(v, 0.0f, 65504.0f);
        }
        history = RgbToYCoCg(history);
        temporal_reactive = Saturate(std::fabs(h.v[3]));
        in_motion_last_frame = h.v[3] < 0.0f;
        // ReprojectHistoryLockStatus.
        new_lock = in.new_locks->Fetch(x, y, 0) > (127.0f / 255.0f);
        // SampleLockStatus: the LINEAR sampler (ffx_fsr2_reproject.h declares a custom bilinear
        // LockStatusSample but does not call it).
        lock[0] = SampleLinear(*in.lock_status, p.reprojected_uv, 0);
        lock[1] = SampleLinear(*in.lock_status, p.reprojected_uv, 1);
      }
      float reactive = Max(p.dilated_reactive, temporal_reactive);
      // UpdateLockStatus.
      const float shading = ShadingChangeLuma(k, o, in, exposure, p.hr_uv);
      lock[1] = lock[1] == 0.0f ? shading : lock[1];
      const float previous_shading = lock[1];
      const float luminance_diff = 1.0f - MinDividedByMax(previous_shading, shading);
      if (new_lock) {
        lock[1] = shading;
        lock[0] = lock[0] != 0.0f ? 2.0f : 1.0f;
      } else if (lock[0] <= 1.0f) {
        lock[1] = Lerp(lock[1], shading, 0.5f);
      } else if (luminance_diff > 0.1f) {
        lock[0] = 0.0f;  // KillLock
      }
      reactive = Max(reactive, Saturate((luminance_diff - 0.1f) * 10.0f));
      lock[0] = lock[0] * (1.0f - reactive);
      lock[0] = lock[0] * Saturate(1.0f - p.accumulation_mask);
      lock[0] = lock[0] * (p.depth_clip < 0.1f ? 1.0f : 0.0f);
      const float lifetime_contribution = Saturate(lock[0] - 1.0f);
      const float shading_contribution = Saturate(MinDividedByMax(lock[1], shading));
      const float lock_contribution = Saturate(Saturate(lifetime_contribution * 4.0f) * shading_contribution);

      Box box;
      const V4 up = UpsampledColorAndWeight(k, o, in, p, reactive, &box);
      float luma_history[4];
      const float luma_instability = LumaInstability(o, in, p, box, reactive, luminance_diff, luma_history);
      // ComputeBaseAccumulationWeight.
      float base = ((1.0f * (p.existing ? 1.0f : 0.0f)) * (1.0f - reactive)) * (1.0f - p.depth_clip);
      base = Min(base,
                 Lerp(base, up.v[3] * 10.0f, Max(in_motion_last_frame ? 1.0f : 0.0f, Saturate(p.hr_velocity * 10.0f))));
      base = Min(base, Lerp(base, up.v[3], Saturate(p.hr_velocity / 20.0f)));
      float acc[3] = {base, base, base};
      const V3 up_color{{up.v[0], up.v[1], up.v[2]}};
      if (p.new_sample) {
        history = YCoCgToRgb(up_color);
      } else {
        // RectifyHistory.
        const float ds = k.downscale_factor[0] * k.downscale_factor[1];
        const float scale_influence = Min(20.0f, PowO(o, 1.0f / std::fabs(ds), 3.0f));
        const float velocity_factor = Saturate(p.hr_velocity / 20.0f);
        const float box_t = Max(p.depth_clip, Max(p.accumulation_mask, velocity_factor));
        const float box_scale = Lerp(scale_influence, 1.0f, box_t);
        float bmin[3], bmax[3];
        bool outside = false;
        for (int i = 0; i < 3; ++i) {
          const float sv = box.vec.v[i] * box_scale;
          bmin[i] = Max(box.aabb_min.v[i], box.center.v[i] - sv);
          bmax[i] = Min(box.aabb_max.v[i], box.center.v[i] + sv);
          outside = outside || bmin[i] > history.v[i] || history.v[i] > bmax[i];
        }
        if (outside) {
          const float contribution =
              Max(luma_instability, lock_contribution) * (1.0f - PowO(o, p.dilated_reactive, 0.5f));
          for (int i = 0; i < 3; ++i) {
            const float clamped = Clamp(history.v[i], bmin[i], bmax[i]);
            history.v[i] = Lerp(clamped, history.v[i], Saturate(contribution));
            const float acc_min = Min(acc[i], 0.1f);
            acc[i] = Lerp(acc_min, acc[i], Saturate(contribution));
          }
        }
        // Accumulate.
        V3 u = up_color;
        if (o.hdr_color_input) {
          u = RgbToYCoCg(Tonemap(YCoCgToRgb(u)));
          history = RgbToYCoCg(Tonemap(YCoCgToRgb(history)));
        }
        for (int i = 0; i < 3; ++i) {
          acc[i] = Max(kEpsilon, acc[i] + up.v[3]);
          history.v[i] = Lerp(history.v[i], u.v[i], up.v[3] / acc[i]);
        }
        history = YCoCgToRgb(history);
        if (o.hdr_color_input) history = InverseTonemap(history);
      }
      for (int i = 0; i < 3; ++i) history.v[i] = (history.v[i] / exposure) * k.pre_exposure;  // UnprepareRgb
      // FinalizeLockStatus.
      if (!UvInside({p.hr_uv.x - p.mv.x, p.hr_uv.y - p.mv.y})) {
        lock[0] = 0.0f;
      } else {
        const float decrease_max = k.jitter_sequence_length * kAverageLanczosWeight;
        lock[0] = Max(0.0f, lock[0] - up.v[3] / decrease_max);
      }
      out->lock_status.At(x, y, 0) = Fsr2Half(lock[0], tz);
      out->lock_status.At(x, y, 1) = Fsr2Half(lock[1], tz);
      // ComputeTemporalReactiveFactor.
      float f = Min(0.99f, reactive);
      f = Max(f, Lerp(f, 0.4f, Saturate(p.hr_velocity)));
      f = Max(f * f, Max(p.depth_clip * 0.1f, p.dilated_reactive));
      f = p.new_sample ? 1.0f : f;
      if (Saturate(p.hr_velocity * 10.0f) >= 1.0f) f = Max(kEpsilon, f) * -1.0f;
      for (int i = 0; i < 3; ++i) out->internal_upscaled.At(x, y, i) = Fsr2Half(history.v[i], tz);
      out->internal_upscaled.At(x, y, 3) = Fsr2Half(f, tz);
      for (int c = 0; c < 4; ++c) out->luma_history.At(x, y, c) = luma_history[c];
      if (!o.apply_sharpening) {
        for (int i = 0; i < 3; ++i) out->output.At(x, y, i) = history.v[i];
      }
    }
  }
  // StoreNewLocks(pos, 0) by every invocation inside the display size.
  for (int y = 0; y < std::min(dh, in.new_locks->h); ++y)
    for (int x = 0; x < std::min(dw, in.new_locks->w); ++x) in.new_locks->At(x, y, 0) = 0.0f;
}

}  // namespace aalab
