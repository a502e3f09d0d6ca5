// The host side of aalab_vk's FSR 2 (gpu/vk/vk_fsr2.h): the presets and render sizes, the
// per-frame constants (cbFSR2, cbSPD, cbRCAS) and the Lanczos table as api/ffx_fsr2.cpp computes
// them (tests/gpu_vk/vk_fsr2_constants_test.cpp holds them to aalab's port byte for byte),
// and the synthetic sequence the frames show.
//
// The sequence (what the frames hold; whether FSR 2's cost depends on them is not measured:
// its passes have no data-dependent loops, only the lock's and the rectification's branches): 8 frames
// of a scene built from the frame `aalab export-frames` wrote for the scene (its 8-bit values
// /255 as linear colour), the camera panning by (1.25, 0.5) display pixels a frame (the scene
// wraps around), a striped disc in front of it moving (−3, 2) display pixels a frame, depth
// 0.3 in the disc and 0.8 + 0.15·luma behind it, motion vectors (the previous position −
// the current, render pixels) of each. Render pixel (x, y) of frame k samples the scene
// (nearest texel) at (x + 0.5 − jitter_k) · display/render, jitter_k = Halton phase k of the
// sequence's phase count (what ffxFsr2GetJitterOffset gives for index k). Frame n of the
// run shows frame n mod 8, with cbFSR2's jitter for phase n mod 8 and frame index n mod 8 (8
// where that is 0; 0 on the reset frame); the pan jumps back every 8 frames (a disocclusion FSR 2 handles as a game's
// camera cut without reset).
#include "gpu/vk/vk_fsr2.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace aalab::vk {

namespace {

constexpr float kPi = 3.141592653589793f;

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

// IEEE binary16 from float, round to nearest even (finite inputs of the content only).
uint16_t Half(float f) {
  uint32_t x = Bits(f);
  const uint32_t sign = (x >> 16) & 0x8000u;
  x &= 0x7fffffffu;
  if (x >= 0x477ff000u) return static_cast<uint16_t>(sign | 0x7c00u);  // rounds to >= 65520: inf
  if (x < 0x38800000u) {                                               // below 2^-14: subnormal
    float a;
    std::memcpy(&a, &x, 4);
    return static_cast<uint16_t>(sign | static_cast<uint32_t>(std::nearbyint(a * 16777216.0f)));
  }
  const uint32_t mant = x & 0x1fffu;
  uint32_t h = ((x - 0x38000000u) >> 13);
  if (mant > 0x1000u || (mant == 0x1000u && (h & 1u))) ++h;
  return static_cast<uint16_t>(sign | h);
}

}  // namespace

float Fsr2HalfToFloat(uint16_t h) {
  const uint32_t sign = (h & 0x8000u) << 16, e = (h >> 10) & 0x1fu, m = h & 0x3ffu;
  float f;
  if (e == 0) {
    f = std::ldexp(static_cast<float>(m), -24);
  } else if (e == 31) {
    f = m ? std::nanf("") : INFINITY;
  } else {
    f = std::ldexp(static_cast<float>(m | 0x400u), static_cast<int>(e) - 25);
  }
  return sign ? -f : f;
}

namespace {

// The synthetic scene (see the file's comment) at display-pixel position (px, py) of frame k:
// rgb, depth and the motion vector in display pixels.
struct Scene {
  const Frame* src;
  void At(int k, float px, float py, float rgb[3], float* depth, float mv[2]) const {
    const int w = src->width, h = src->height;
    const float dx = static_cast<float>(w) * 0.3f + static_cast<float>(k) * -3.0f - px;
    const float dy = static_cast<float>(h) * 0.45f + static_cast<float>(k) * 2.0f - py;
    const float r = 0.2f * static_cast<float>(std::min(w, h));
    if (dx * dx + dy * dy < r * r) {
      const bool stripe = static_cast<int>(std::floor((dx + dy + 4.0f * static_cast<float>(k)) / 3.0f)) % 2 == 0;
      rgb[0] = 0.95f;
      rgb[1] = stripe ? 0.55f : 0.2f;
      rgb[2] = stripe ? 0.1f : 0.6f;
      *depth = 0.3f;
      mv[0] = 3.0f;  // the disc moved by (−3, 2): its previous position is (+3, −2) away
      mv[1] = -2.0f;
      return;
    }
    const float sx = px + 1.25f * static_cast<float>(k), sy = py + 0.5f * static_cast<float>(k);
    int ix = static_cast<int>(std::floor(sx)) % w, iy = static_cast<int>(std::floor(sy)) % h;
    if (ix < 0) ix += w;
    if (iy < 0) iy += h;
    const uint8_t* p = &src->rgba[(static_cast<size_t>(iy) * static_cast<size_t>(w) + static_cast<size_t>(ix)) * 4];
    for (int c = 0; c < 3; ++c) rgb[c] = static_cast<float>(p[c]) / 255.0f;
    *depth = 0.8f + 0.15f * (0.25f * rgb[0] + 0.5f * rgb[1] + 0.25f * rgb[2]);
    mv[0] = 1.25f;  // the camera panned by (1.25, 0.5): the point was there last frame
    mv[1] = 0.5f;
  }
};

}  // namespace

void Fsr2SceneColor(const Frame& display, int k, float px, float py, float rgb[3]) {
  float depth, mv[2];
  Scene{&display}.At(k, px, py, rgb, &depth, mv);
}

void Fsr2SequenceJitter(int slot, int phases, float out[2]) {
  out[0] = Fsr2HaltonF((slot % phases) + 1, 2) - 0.5f;
  out[1] = Fsr2HaltonF((slot % phases) + 1, 3) - 0.5f;
}

Fsr2InputFrame Fsr2MakeInput(const Frame& display, int k, int rw, int rh, const float jitter[2]) {
  const Scene s{&display};
  Fsr2InputFrame f;
  const size_t n = static_cast<size_t>(rw) * static_cast<size_t>(rh);
  f.color.resize(n * 4);
  f.motion.resize(n * 2);
  f.depth.resize(n);
  const float sx = static_cast<float>(s.src->width) / static_cast<float>(rw);
  const float sy = static_cast<float>(s.src->height) / static_cast<float>(rh);
  for (int y = 0; y < rh; ++y) {
    for (int x = 0; x < rw; ++x) {
      float rgb[3], depth, mv[2];
      s.At(k, (static_cast<float>(x) + 0.5f - jitter[0]) * sx, (static_cast<float>(y) + 0.5f - jitter[1]) * sy, rgb,
           &depth, mv);
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(rw) + static_cast<size_t>(x);
      for (int c = 0; c < 3; ++c) f.color[i * 4 + static_cast<size_t>(c)] = Half(rgb[c]);
      f.color[i * 4 + 3] = Half(1.0f);
      f.depth[i] = depth;
      f.motion[i * 2] = Half(mv[0] / sx);
      f.motion[i * 2 + 1] = Half(mv[1] / sy);
    }
  }
  return f;
}

const std::vector<Fsr2Preset>& Fsr2Presets() {
  static const std::vector<Fsr2Preset> p = {{"fsr2-quality", 1.5f},
                                            {"fsr2-balanced", 1.7f},
                                            {"fsr2-performance", 2.0f},
                                            {"fsr2-ultra-performance", 3.0f},
                                            {"fsr2-native", 1.0f}};
  return p;
}

const Fsr2Preset* FindFsr2Preset(const std::string& spec) {
  for (const Fsr2Preset& p : Fsr2Presets()) {
    if (p.spec == spec) return &p;
  }
  return nullptr;
}

int Fsr2RenderSide(int display, float ratio) {
  return static_cast<int>(static_cast<uint32_t>(static_cast<float>(display) / ratio));
}

int Fsr2PhaseCount(int render_width, int display_width) {
  return static_cast<int32_t>(8.0f *
                              std::pow(static_cast<float>(display_width) / static_cast<float>(render_width), 2.0f));
}

float Fsr2HaltonF(int index, int base) {
  float f = 1.0f, result = 0.0f;
  for (int i = index; i > 0;) {
    f /= static_cast<float>(base);
    result = result + f * static_cast<float>(i % base);
    i = static_cast<int>(std::floor(static_cast<float>(i) / static_cast<float>(base)));
  }
  return result;
}

Fsr2Cb Fsr2FrameConstants(int rw, int rh, int dw, int dh, const float jitter[2], int frame) {
  Fsr2Cb c{};
  c.render_size[0] = c.max_render_size[0] = c.input_color_size[0] = rw;
  c.render_size[1] = c.max_render_size[1] = c.input_color_size[1] = rh;
  c.display_size[0] = dw;
  c.display_size[1] = dh;
  c.jitter[0] = jitter[0];
  c.jitter[1] = jitter[1];
  // setupDeviceDepthToViewSpaceDepthParams, not inverted, not infinite.
  // The camera is read at run time (volatile) so that tan, atan, sin and cos are the C
  // library's, as the API's are: GCC would fold them for constants with correctly rounded
  // MPFR, and glibc's tanf(π/6) is one ulp from that.
  static volatile float camera[3] = {0.1f, 100.0f, 1.0471976f};
  const float near = camera[0], far = camera[1], fov = camera[2];
  const float q = far / (near - far);
  c.device_to_view_depth[0] = -1.0f * q;
  c.device_to_view_depth[1] = q * near;
  const float aspect = static_cast<float>(rw) / static_cast<float>(rh);
  const float cot = std::cos(0.5f * fov) / std::sin(0.5f * fov);
  c.device_to_view_depth[2] = 1.0f / (cot / aspect);
  c.device_to_view_depth[3] = 1.0f / cot;
  const float horizontal = static_cast<float>(std::atan(std::tan(fov / 2) * aspect) * 2);
  c.tan_half_fov = std::tan(horizontal * 0.5f);
  c.view_space_to_meters = 1.0f;
  c.downscale_factor[0] = static_cast<float>(rw) / static_cast<float>(dw);
  c.downscale_factor[1] = static_cast<float>(rh) / static_cast<float>(dh);
  c.previous_pre_exposure = frame == 0 ? 0.0f : 1.0f;
  c.pre_exposure = 1.0f;
  c.motion_vector_scale[0] = 1.0f / static_cast<float>(rw);
  c.motion_vector_scale[1] = 1.0f / static_cast<float>(rh);
  c.jitter_sequence_length = static_cast<float>(Fsr2PhaseCount(rw, dw));
  c.delta_time = std::max(0.0f, std::min(1.0f, 16.6667f / 1000.0f));
  c.frame_index = frame;
  c.luma_mip_level = 4;  // FFX_FSR2_SHADING_CHANGE_MIP_LEVEL
  const float div = static_cast<float>(2 << 4);
  c.luma_mip_size[0] = static_cast<int32_t>(static_cast<uint32_t>(static_cast<float>(rw) / div));
  c.luma_mip_size[1] = static_cast<int32_t>(static_cast<uint32_t>(static_cast<float>(rh) / div));
  return c;
}

Fsr2Spd Fsr2SpdSetup(int rw, int rh) {
  Fsr2Spd s{};
  const uint32_t w = static_cast<uint32_t>(rw), h = static_cast<uint32_t>(rh);
  s.groups_x = (w - 1) / 64 + 1;
  s.groups_y = (h - 1) / 64 + 1;
  s.num_work_groups = s.groups_x * s.groups_y;
  s.mips = static_cast<uint32_t>(std::min(std::floor(std::log2(static_cast<float>(std::max(w, h)))), 12.0f));
  s.render_size[0] = w;
  s.render_size[1] = h;
  return s;
}

std::array<int16_t, 128> Fsr2LanczosCodes() {
  std::array<int16_t, 128> codes{};
  for (uint32_t i = 0; i < 128; ++i) {
    const float x = 2.0f * static_cast<float>(i) / static_cast<float>(127);
    const float y =
        std::fabs(x) < 1e-6f ? 1.0f : (std::sin(kPi * x) / (kPi * x)) * (std::sin(0.5f * kPi * x) / (0.5f * kPi * x));
    codes[i] = static_cast<int16_t>(std::round(y * 32767.0f));
  }
  return codes;
}

uint32_t Fsr2RcasConstant(float sharpness) { return Bits(std::exp2(-((-2.0f * sharpness) + 2.0f))); }

const std::vector<std::string>& Fsr2PassNames() {
  static const std::vector<std::string> n = {
      "compute_luminance_pyramid", "reconstruct_previous_depth", "depth_clip", "lock", "accumulate", "rcas"};
  return n;
}

std::vector<std::string> Fsr2Modules() {
  std::vector<std::string> m;
  for (const std::string& p : Fsr2PassNames()) m.push_back("fsr2-" + p);
  return m;
}

}  // namespace aalab::vk
