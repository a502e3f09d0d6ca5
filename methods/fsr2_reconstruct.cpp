// FSR 2.2.1's "reconstruct previous depth" pass (ffx_fsr2_reconstruct_previous_depth_pass.glsl,
// ReconstructAndDilate of ffx_fsr2_reconstruct_dilated_velocity_and_previous_depth.h), fp32
// path. The conventions of every FSR 2 pass file (stores, pow, dispatch extent) are in
// methods/fsr2_common.cpp's doc block; docs/fsr2.md has the oracle's figures.
// Its dispatch covers whole 8×8 groups and the invocations past the render size run too: their
// previous-depth atomics can land on screen (with jittered motion vectors), so the loop covers
// the whole extent. FindNearestDepth's 3×3 ignores samples outside the image, as the shader does.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "methods/fsr2.h"
#include "methods/fsr2_internal.h"

namespace aalab {

using namespace fsr2_detail;  // NOLINT(google-build-using-namespace): the passes' shared helpers

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

}  // namespace aalab
