// FSR 2 rows (`fsr2-native` 1×, `fsr2-quality` 1.5×, `fsr2-balanced` 1.7×, `fsr2-performance` 2×,
// `fsr2-ultra-performance` 3×): AMD FidelityFX Super Resolution 2.2.1 (GPUOpen-Effects/
// FidelityFX-FSR2, MIT) as ported pass by pass (methods/fsr2*.cpp), driven frame by frame by
// the API's host side (methods/fsr2_sequence.cpp) on aalab's jittered renders, as `taau-*` get
// them (rendered at 1/ratio of the output size, needs --frames > 1). How aalab's data becomes
// FSR 2's inputs, each choice with its reason:
//
// - Colour: the RGBA8 sRGB frame decoded to linear [0, 1] (SrgbDecode8), HDR flag off. aalab's
//   frames are display-referred (tonemapped, 8-bit); FSR 2 works on linear colour (its
//   README, "HDR support": "Images should be provided to FSR2 in linear color space") and
//   without FFX_FSR2_ENABLE_HIGH_DYNAMIC_RANGE treats it as [0, 1] data, which it is. The output
//   (accumulate's, or RCAS's with sharpening) is clamped to [0, 1] and sRGB-encoded to 8 bits
//   (EncodeSrgb8, TAA's encoder; NaN → 0).
// - Depth: FFX_FSR2_ENABLE_DEPTH_INVERTED | FFX_FSR2_ENABLE_DEPTH_INFINITE, device depth
//   near / z of aalab's view depth z (distance along the camera's forward axis): the API's
//   inverted infinite transform turns it back into view depth (near / (d + FLT_EPSILON)), the
//   background's +Inf becomes exactly 0 (the far plane), and the README's example context uses
//   inverted depth. aalab's ray tracer has no near plane: `near` is half the nearest finite
//   depth of the reset frame, fixed for the sequence (a rasterizer's is fixed too), so that
//   device depths stay ≤ 1 and normal half floats (FSR 2 stores the dilated depth as r16f).
//   Without depth (captured sequences whose manifest gives none) every pixel reads 0: FSR 2
//   then sees one flat far plane, so its depth clip never finds a disocclusion and only the
//   colour rectification guards the history.
// - Motion vectors: FSR 2 reprojects with uv + motion (the vector points to the previous
//   frame), render-size vectors (FFX_FSR2_ENABLE_DISPLAY_RESOLUTION_MOTION_VECTORS off),
//   motionVectorScale (1, 1) in render pixels, without jitter cancellation: aalab's `previous`
//   positions minus the pixel centre are exactly that (the surface's own motion, unjittered;
//   scenes/motion_render.h). Frame 0: zero. NaN (the surface was behind the previous camera):
//   a vector twice the render size off screen, which FSR 2 treats as a new sample.
// - Camera: the frame's vertical FOV (TemporalInput::fov_y_radians; 60° when unknown:
//   captured sequences, orthographic cameras), near as above, far 10⁶·near (unused by the
//   infinite transform).
// - Jitter: FSR 2's own sequence, ffxFsr2GetJitterOffset (Fsr2JitterOffset) with the mode's
//   phase count (Fsr2ModePhaseCount: 18, 23, 32, 72, 8). FSR 2's jitter is the image's shift
//   (the sample of render pixel i lies at unjittered i + 0.5 − jitter, ffx_fsr2_upsample.h;
//   the sample applies it to the projection as +2·jx/w, −2·jy/h in y-up NDC), aalab's
//   FrameJitter the sample's offset from the pixel centre (y down): so the render's
//   JitterSpec::sequence is −Fsr2JitterOffset and the driver hands FSR 2 −FrameJitter
//   (Fsr2JitterFromFrame), bit for bit Fsr2JitterOffset. tests/methods/fsr2_sequence_test.cpp
//   shows the wrong sign fails a still scene.
// - Exposure: FFX_FSR2_ENABLE_AUTO_EXPOSURE (parameter `exposure=auto`, the default), as the
//   README recommends ("unless there is a particular reason not to") and its example context
//   sets; `exposure=one` gives the API's default exposure texture (read as 1). Pre-exposure 1.
// - Frame time: 16.6667 ms (60 fps; only the auto exposure's smoothing reads it).
// - Shader options: Lanczos table for the reprojection (REPROJECT_USE_LANCZOS_TYPE=1: the
//   Vulkan and D3D12 backends pick it on GPUs with waves of 32 to 64 lanes, i.e. every current
//   AMD and NVIDIA GPU), 16-bit stores rounded to nearest even (what D3D requires).
// - Sharpening: on, sharpness 0.8 by default (FSR 2's sample application starts with RCAS on
//   at 0.8; recalled from its UI, not in the pinned sources, which hold no sample).
// - Sizes: the render size is the pipeline's round(W / ratio) (as taau-*), the API's
//   ffxFsr2GetRenderResolutionFromQualityMode would truncate; FSR 2 takes any render size, and
//   its constants (downscale factor, the lock's jitter phase count) come from the real sizes.
// The context is created on the first frame (which resets it) and kept for the sequence; Step
// copies it (Clone) so that timing repeats never advance the sequence twice.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/color.h"
#include "core/params.h"
#include "methods/families.h"
#include "methods/fsr2_sequence.h"
#include "methods/taa.h"

namespace aalab {

Fsr2Plane Fsr2ColorFromSrgb8(const Image8& frame) {
  const int w = frame.Width(), h = frame.Height();
  Fsr2Plane out(w, h, 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const uint8_t* p = frame.Pixel(x, y);
      for (int c = 0; c < 3; ++c) out.At(x, y, c) = SrgbDecode8(p[c]);
      out.At(x, y, 3) = 1.0f;
    }
  }
  return out;
}

float Fsr2NearPlane(const std::vector<float>* depth) {
  float nearest = std::numeric_limits<float>::infinity();
  if (depth) {
    for (float z : *depth) {
      if (std::isfinite(z) && z > 0.0f) nearest = std::min(nearest, z);
    }
  }
  return std::isfinite(nearest) ? 0.5f * nearest : 1.0f;
}

Fsr2Plane Fsr2DeviceDepth(const std::vector<float>* depth, int w, int h, float near_plane) {
  Fsr2Plane out(w, h, 1);
  if (!depth) return out;
  for (size_t i = 0; i < out.v.size() && i < depth->size(); ++i) {
    const float z = (*depth)[i];
    out.v[i] = (std::isfinite(z) && z > 0.0f) ? near_plane / z : 0.0f;
  }
  return out;
}

Fsr2Plane Fsr2MotionFromPrevious(const std::vector<float>* previous, int w, int h) {
  Fsr2Plane out(w, h, 2);
  if (!previous) return out;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      const float px = (*previous)[2 * i], py = (*previous)[2 * i + 1];
      if (std::isnan(px) || std::isnan(py)) {
        out.At(x, y, 0) = 2.0f * static_cast<float>(w);
        out.At(x, y, 1) = 2.0f * static_cast<float>(h);
      } else {
        out.At(x, y, 0) = px - (static_cast<float>(x) + 0.5f);
        out.At(x, y, 1) = py - (static_cast<float>(y) + 0.5f);
      }
    }
  }
  return out;
}

Fsr2Jitter Fsr2JitterFromFrame(const FrameJitter& j) { return {-j.x, -j.y}; }

int Fsr2ModePhaseCount(double ratio) {
  const int display = 3840;
  const int render = static_cast<int>(static_cast<float>(display) / static_cast<float>(ratio));
  return Fsr2JitterPhaseCount(render, display);
}

namespace {

// The render's sample offsets: −ffxFsr2GetJitterOffset (the doc block: FSR 2's jitter is the image's shift).
FrameJitter Fsr2RenderJitter(int frame, int samples) {
  const Fsr2Jitter j = Fsr2JitterOffset(frame, samples);
  return {-j.x, -j.y};
}

class Fsr2State final : public TemporalState {
 public:
  explicit Fsr2State(const Fsr2MethodParams& p) : p_(p) {}

  Image8 Step(const TemporalInput& in, PostStats* stats) override {
    (void)stats;
    const Image8& frame = *in.frame;
    const int rw = frame.Width(), rh = frame.Height();
    const int dw = in.output_width > 0 ? in.output_width : rw;
    const int dh = in.output_height > 0 ? in.output_height : rh;
    if (!ctx_) {
      near_ = Fsr2NearPlane(in.depth);
      Fsr2ContextParams cp;
      cp.max_render_size[0] = rw;
      cp.max_render_size[1] = rh;
      cp.display_size[0] = dw;
      cp.display_size[1] = dh;
      cp.inverted_depth = true;
      cp.infinite_depth = true;
      Fsr2Options o;
      o.inverted_depth = true;
      o.low_res_motion_vectors = true;
      o.reproject_lanczos_lut = true;
      ctx_.emplace(cp, o, p_.auto_exposure);
    }
    const Fsr2Plane color = Fsr2ColorFromSrgb8(frame);
    const Fsr2Plane depth = Fsr2DeviceDepth(in.depth, rw, rh, near_);
    const Fsr2Plane motion = Fsr2MotionFromPrevious(in.previous, rw, rh);
    Fsr2DispatchInput d;
    d.color = &color;
    d.depth = &depth;
    d.motion = &motion;
    const Fsr2Jitter j = Fsr2JitterFromFrame(in.jitter);
    d.dispatch.jitter[0] = j.x;
    d.dispatch.jitter[1] = j.y;
    d.dispatch.motion_vector_scale[0] = 1.0f;
    d.dispatch.motion_vector_scale[1] = 1.0f;
    d.dispatch.render_size[0] = d.dispatch.input_color_size[0] = rw;
    d.dispatch.render_size[1] = d.dispatch.input_color_size[1] = rh;
    d.dispatch.frame_time_delta_ms = 1000.0f / 60.0f;
    d.dispatch.pre_exposure = 1.0f;
    d.dispatch.camera_near = near_;
    d.dispatch.camera_far = near_ * 1e6f;
    d.dispatch.camera_fov_vertical = in.fov_y_radians > 0.0f ? in.fov_y_radians : 1.0471976f;
    d.sharpen = p_.sharpen;
    d.sharpness = p_.sharpness;
    const Fsr2DispatchResult r = ctx_->Dispatch(d);
    Image8 out(dw, dh, 4, 255);
    for (int y = 0; y < dh; ++y) {
      for (int x = 0; x < dw; ++x) {
        uint8_t* px = out.Pixel(x, y);
        const size_t i = (static_cast<size_t>(y) * dw + x) * 3;
        for (int c = 0; c < 3; ++c) {
          const float v = r.output[i + static_cast<size_t>(c)];
          px[c] = EncodeSrgb8(std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f));
        }
      }
    }
    return out;
  }

  std::unique_ptr<TemporalState> Clone() const override { return std::make_unique<Fsr2State>(*this); }

 private:
  Fsr2MethodParams p_;
  std::optional<Fsr2Context> ctx_;
  float near_ = 1.0f;
};

}  // namespace

std::unique_ptr<TemporalState> MakeFsr2State(const Fsr2MethodParams& p) { return std::make_unique<Fsr2State>(p); }

std::vector<MethodEntry> Fsr2Methods() {
  struct Mode {
    const char* name;
    double ratio;
    const char* label;
  };
  const Mode modes[] = {{"fsr2-native", 1.0, "Native AA (1x)"},
                        {"fsr2-quality", 1.5, "Quality (1.5x)"},
                        {"fsr2-balanced", 1.7, "Balanced (1.7x)"},
                        {"fsr2-performance", 2.0, "Performance (2x)"},
                        {"fsr2-ultra-performance", 3.0, "Ultra Performance (3x)"}};
  std::vector<MethodEntry> out;
  for (const Mode& m : modes) {
    std::vector<ParamDef> defs = {
        ChoiceParam("sharpening", "on", {"on", "off"}, "RCAS after accumulation (enableSharpening)"),
        FloatParam("sharpness", 0.8, 0.0, 1.0, "RCAS sharpness, 0 = none, 1 = most (FSR 2 sample: 0.8)"),
        ChoiceParam("exposure", "auto", {"auto", "one"},
                    "auto: FSR 2's auto exposure (FFX_FSR2_ENABLE_AUTO_EXPOSURE); one: exposure 1")};
    const double ratio = m.ratio;
    out.push_back({m.name,
                   std::string("AMD FSR 2.2.1 ") + m.label + ": the six ported passes on jittered renders at 1/" +
                       (ratio == 1.0 ? std::string("1") : FormatNumber(ratio)) +
                       " of the output size with depth and motion (needs --frames > 1)",
                   defs, [ratio](const ParamValues& v) {
                     MethodPlan plan;
                     plan.render.scale = 1.0 / ratio;
                     plan.render.jitter.samples = Fsr2ModePhaseCount(ratio);
                     plan.render.jitter.sequence = Fsr2RenderJitter;
                     Fsr2MethodParams p;
                     p.ratio = ratio;
                     p.sharpen = v.Choice("sharpening") == "on";
                     p.sharpness = static_cast<float>(v.Number("sharpness"));
                     p.auto_exposure = v.Choice("exposure") == "auto";
                     plan.make_state = [p] { return MakeFsr2State(p); };
                     return plan;
                   }});
  }
  return out;
}

}  // namespace aalab
