// FSR 2.2.1's sequence driver (methods/fsr2_sequence.h): the host side of
// `api/ffx_fsr2.cpp` (ffxFsr2ContextCreate, fsr2Dispatch) over whole planes, calling the ported
// passes (or, in the oracle, the original shaders) in the API's order.
//
// What it keeps, as the API does (Fsr2Resources):
// - LOCK_STATUS, INTERNAL_UPSCALED_COLOR, LUMA_HISTORY: two each. An even frame (the parity of
//   the API's resource frame index, Fsr2FrameSetup::odd) reads _1 and writes _2, an odd one
//   the other way round.
// - INTERNAL_DILATED_MOTION_VECTORS: two; an even frame writes _1 and reads _2 as the
//   previous frame's, an odd one the other way round.
// - RECONSTRUCTED_PREVIOUS_NEAREST_DEPTH (one): reconstruct pushes this frame's depth into it,
//   depth clip reads it, the lock pass resets it to the far depth for the next frame.
// - NEW_LOCKS (one): the lock pass sets, accumulate reads and clears.
// - the luminance pyramid's mips, AUTO_EXPOSURE and SPD's global atomic counter.
// Resets: a fresh context resets on its first dispatch, and a dispatch with `reset`; the API
// then clears the lock status and upscaled colour it reads this frame to 0, the scene
// luminance mips to 0 and the auto exposure to (−1, 1e8) (Fsr2PyramidReset). It does not
// clear the luma history or the dilated motion vectors (accumulate ignores the history on a
// reset frame; depth clip's motion divergence reads the previous motion but frame 0's is
// zero here).
// Initial contents: the API creates its resources without initial data (their contents are
// the driver's); here every resource starts at 0 and the previous depth at the far depth
// (0 with inverted depth, as a zeroed r32ui holds; 1.0 otherwise), the value the lock pass
// leaves for every later frame.
// Exposure: with `auto_exposure` (FFX_FSR2_ENABLE_AUTO_EXPOSURE) the passes after the pyramid
// read the exposure the pyramid just computed (AUTO_EXPOSURE.x), else the API's default
// exposure texture (R32G32 (0, 0)): 0, which every pass reads as 1.
// The Lanczos look-up table is bound as the API creates it (Fsr2LanczosLut); the passes read
// it only with Fsr2Options::reproject_lanczos_lut.
// The dispatch sizes are those of the API (8×8 groups over render and display sizes, 64×64
// SPD tiles, 16×16 RCAS tiles): each ported pass already covers its dispatch's invocations.
#include "methods/fsr2_sequence.h"

#include <cstring>
#include <stdexcept>
#include <string>

namespace aalab {

Fsr2Passes Fsr2PortedPasses() {
  Fsr2Passes p;
  p.pyramid = [](const Fsr2Constants& k, const Fsr2Options& o, const Fsr2SpdDispatch& spd, const Fsr2Plane& color,
                 Fsr2PyramidState* state) { Fsr2LuminancePyramid(k, spd, color, state, o); };
  p.reconstruct = Fsr2ReconstructAndDilate;
  p.depth_clip = Fsr2DepthClip;
  p.lock = Fsr2ComputeLock;
  p.accumulate = Fsr2Accumulate;
  p.rcas = Fsr2Rcas;
  return p;
}

namespace {

void CheckPlane(const Fsr2Plane* p, int w, int h, int c, const char* what) {
  if (!p || p->w != w || p->h != h || p->c != c || p->v.size() != static_cast<size_t>(w) * h * c) {
    throw std::invalid_argument(std::string("FSR 2 dispatch: the ") + what + " must be a " + std::to_string(w) + "x" +
                                std::to_string(h) + " plane of " + std::to_string(c) + " channel(s)");
  }
}

}  // namespace

Fsr2Context::Fsr2Context(const Fsr2ContextParams& ctx, const Fsr2Options& options, bool auto_exposure,
                         Fsr2Passes passes)
    : ctx_(ctx), options_(options), auto_exposure_(auto_exposure), passes_(std::move(passes)) {
  const int rw = ctx.max_render_size[0], rh = ctx.max_render_size[1];
  const int dw = ctx.display_size[0], dh = ctx.display_size[1];
  if (rw <= 0 || rh <= 0 || dw <= 0 || dh <= 0) {
    throw std::invalid_argument("FSR 2 context: render and display sizes must be positive");
  }
  if (options.inverted_depth != ctx.inverted_depth) {
    throw std::invalid_argument("FSR 2 context: the shader option and the context flag for inverted depth differ");
  }
  for (int i = 0; i < 2; ++i) {
    res_.lock_status[i] = Fsr2Plane(dw, dh, 2);
    res_.internal_upscaled[i] = Fsr2Plane(dw, dh, 4);
    res_.luma_history[i] = Fsr2Plane(dw, dh, 4);
    res_.dilated_motion[i] = Fsr2Plane(rw, rh, 2);
  }
  res_.new_locks = Fsr2Plane(dw, dh, 1);
  const float far_depth = ctx.inverted_depth ? 0.0f : 1.0f;
  uint32_t far_bits = 0;
  std::memcpy(&far_bits, &far_depth, sizeof far_bits);
  res_.prev_depth.assign(static_cast<size_t>(rw) * rh, far_bits);
  lanczos_lut_ = Fsr2Plane(kFsr2LanczosLutWidth, 1, 1);
  const auto lut = Fsr2LanczosLut();
  for (int i = 0; i < kFsr2LanczosLutWidth; ++i) lanczos_lut_.v[static_cast<size_t>(i)] = lut[static_cast<size_t>(i)];
}

Fsr2DispatchResult Fsr2Context::Dispatch(const Fsr2DispatchInput& in) {
  const int rw = ctx_.max_render_size[0], rh = ctx_.max_render_size[1];
  if (in.dispatch.render_size[0] != rw || in.dispatch.render_size[1] != rh) {
    throw std::invalid_argument("FSR 2 dispatch: the render size must be the context's (" + std::to_string(rw) + "x" +
                                std::to_string(rh) + ")");
  }
  CheckPlane(in.color, rw, rh, 4, "colour");
  CheckPlane(in.depth, rw, rh, 1, "depth");
  CheckPlane(in.motion, rw, rh, 2, "motion vectors");
  Fsr2DispatchResult out;
  out.setup = Fsr2NextFrameConstants(ctx_, in.dispatch, &state_);
  const Fsr2Constants& k = state_.constants;
  out.constants = k;
  const int read = out.setup.odd ? 1 : 0;  // lock status, upscaled colour, luma history read
  const int write = 1 - read;
  const int mv_write = out.setup.odd ? 1 : 0;  // dilated motion written; the other is the previous
  const int mv_prev = 1 - mv_write;
  if (out.setup.reset) {
    for (float& v : res_.lock_status[read].v) v = 0.0f;
    for (float& v : res_.internal_upscaled[read].v) v = 0.0f;
    res_.pyramid = Fsr2PyramidReset(k);
  }
  // 1. Luminance pyramid (always: its luma mip feeds the lock's shading-change test).
  const Fsr2SpdDispatch spd = Fsr2SpdSetup(rw, rh);
  passes_.pyramid(k, options_, spd, *in.color, &res_.pyramid);
  const float exposure = auto_exposure_ ? res_.pyramid.auto_exposure[0] : 0.0f;
  out.exposure = exposure;
  // 2. Reconstruct & dilate.
  Fsr2ReconstructOut rec;
  rec.prev_depth = std::move(res_.prev_depth);
  passes_.reconstruct(k, options_, *in.color, *in.depth, *in.motion, exposure, &rec);
  res_.dilated_motion[mv_write] = std::move(rec.dilated_motion);
  // 3. Depth clip.
  Fsr2DepthClipIn dc;
  dc.prev_depth = &rec.prev_depth;
  dc.dilated_motion = &res_.dilated_motion[mv_write];
  dc.dilated_depth = &rec.dilated_depth;
  dc.previous_dilated_motion = &res_.dilated_motion[mv_prev];
  dc.motion = in.motion;
  dc.color = in.color;
  dc.depth = in.depth;
  dc.exposure = exposure;
  Fsr2DepthClipOut clip;
  passes_.depth_clip(k, options_, dc, &clip);
  // 4. Lock (also resets the previous depth to far for the next frame).
  passes_.lock(k, options_, rec.lock_luma, &res_.new_locks, &rec.prev_depth);
  res_.prev_depth = std::move(rec.prev_depth);
  // 5. Accumulate (APPLY_SHARPENING when RCAS follows).
  Fsr2Options acc_options = options_;
  acc_options.apply_sharpening = in.sharpen;
  Fsr2AccumulateIn ai;
  ai.exposure = exposure;
  ai.dilated_reactive_masks = &clip.reactive_masks;
  ai.dilated_motion = &res_.dilated_motion[mv_write];
  ai.motion = in.motion;
  ai.history = &res_.internal_upscaled[read];
  ai.lock_status = &res_.lock_status[read];
  ai.prepared_color = &clip.prepared_color;
  ai.lanczos_lut = &lanczos_lut_;
  ai.luma_mip = &res_.pyramid.luma_mip;
  ai.luma_history = &res_.luma_history[read];
  ai.new_locks = &res_.new_locks;
  Fsr2AccumulateOut acc;
  passes_.accumulate(k, acc_options, ai, &acc);
  res_.internal_upscaled[write] = std::move(acc.internal_upscaled);
  res_.lock_status[write] = std::move(acc.lock_status);
  res_.luma_history[write] = std::move(acc.luma_history);
  // 6. RCAS on the upscaled colour just written (RCAS_INPUT is the upscaled colour UAV).
  if (in.sharpen) {
    out.output = passes_.rcas(k, res_.internal_upscaled[write], exposure, Fsr2RcasCon(in.sharpness));
  } else {
    out.output = std::move(acc.output.v);  // rgb, 3 per pixel
  }
  return out;
}

}  // namespace aalab
