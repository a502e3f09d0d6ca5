// FSR 2.2.1's depth-clip pass (ffx_fsr2_depth_clip_pass.glsl, DepthClip of
// ffx_fsr2_depth_clip.h), fp32 path: depth clip, prepared YCoCg colour, dilated reactive masks.
// Conventions: methods/fsr2_common.cpp's doc block; figures: docs/fsr2.md.
// Upstream quirks kept: with display-resolution motion vectors, ComputeMotionDivergence clamps
// its 3×3 to the render size (it passes RenderSize() as the motion-vector size); DepthClip
// computes the input depth's view depth and does not use it (no effect).
// The previous dilated motion is sampled with a LINEAR CLAMP_TO_EDGE sampler: SampleLinear
// (fsr2_internal.h) filters as lavapipe does, fractions in float32 and
// lerp(lerp(a, b, fx), lerp(c, d, fx), fy) with fused a + f·(b − a). A GPU's texture unit uses
// 8-bit fractions instead; the value only feeds a ratio that ends in an 8-bit store.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "methods/fsr2.h"
#include "methods/fsr2_internal.h"

namespace aalab {

using namespace fsr2_detail;  // NOLINT(google-build-using-namespace): the passes' shared helpers

namespace {

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

}  // namespace aalab
