// FSR 2.2.1's luminance pyramid (GPUOpen-Effects/FidelityFX-FSR2, MIT, © 2023 Advanced Micro
// Devices, Inc.), written from ffx_fsr2_compute_luminance_pyramid_pass.glsl,
// ffx_fsr2_compute_luminance_pyramid.h, ffx_spd.h (SPD) and the API's SpdSetup call in
// api/ffx_fsr2.cpp; fp32 path (FFX_HALF=0) with wave operations (SPD_NO_WAVE_OPERATIONS
// undefined, as the GLSL passes are built). The originals are not in the repository: the
// oracle (tests/oracle/fsr2_pyramid_oracle_test.cpp) reads them from ../shared/third_party.
//
// What the pass computes. One 256-thread workgroup per 64×64 tile of the render: each render
// pixel's log luminance, log(max(1e-3, luma(colour at its jittered centre / pre-exposure))),
// 0 for pixels past the render size (they still count in the average); then 2×2 averages,
// mip 0 (a 32×32 tile) to mip 5 (one texel). Mip luma_mip_level (4) and mip 5 are stored as
// r16f into their views of FSR2_ExposureMips (stores outside a view are dropped). With more
// than 6 mips, the last workgroup to finish (a global atomic counter) reads mip 5 back (0
// outside its view) and reduces on, mips 6 to 11. At mip `mips − 1`, texel (0, 0) becomes
// the auto-exposure texel: the log average, smoothed against the previous one by
// 1 − exp(−Δt) unless the previous is the reset value 1e8, and ComputeAutoExposureFromLavg.
// With 6 or fewer mips (renders under 128 pixels on the longer side) that texel is tile (0,0)'s
// own mip, so the exposure sees only the top-left 64×64 pixels: AMD's code, kept.
//
// The order of every sum. Each average is (v0 + v1 + v2 + v3)·0.25, added left to right
// (NoContraction in the oracle). Which texel is v0..v3 follows from the shader, not from a
// choice: mip 0 and mip 6 read their four inputs as (0,0), (0,1), (1,0), (1,1) (column-major:
// SpdReduceLoadSourceImage4 and SpdReduceLoad4 take base + (0,0), (0,1), (1,0), (1,1)); mips 1–5
// and 7–11 reduce across a quad of lanes with subgroupQuadSwapHorizontal / Vertical / Diagonal,
// and ffxRemapForWaveReduction puts lane 4q + i at (i & 1, i >> 1) of its 2×2, so the quad's
// first lane (the one that stores) adds itself, its right, lower and diagonal neighbours:
// (0,0), (1,0), (0,1), (1,1) (row-major); SpdDownsampleMips_6_7's mip 7 adds v0..v3 in that
// order too. Across workgroups nothing is summed: the atomic only picks which workgroup runs
// the tail, and that workgroup reads the mip 5 every workgroup has stored, so the result does
// not depend on the order the workgroups run in. The port runs them in dispatch order (x
// fastest), as lavapipe does with one thread; with the counter at 0 on entry (the API's clear
// and the tail's reset leave it there) any order gives the same bits.
//
// Arithmetic as Mesa evaluates the shader: log(x) is log2(x)·0.6931472 (float(1/log2 e)),
// exp(x) is exp2(x·1.442695) (float(log2 e)), and the exposure's pow(2, log2(y)) is y (Mesa
// folds it: ExposureFromLavg). log2 and exp2 are the C library's by default (lavapipe's are
// polynomials a few ulps away: docs/fsr2.md measures what that changes; Fsr2Transcendentals
// lets the oracle put lavapipe's in). Reads outside an image return 0 and stores outside are
// dropped (robust image access, as Vulkan and D3D give the shader). min/max are
// std::fmin/fmax (IEEE minNum/maxNum). The colour is sampled with FSR2's LINEAR CLAMP sampler
// as lavapipe filters float textures: fractions in float and each lerp a + f·(b − a) as ONE
// fused multiply-add (lavapipe's LLVM fuses them with the CPU's FMA). Measured: with unfused
// lerps (the depth-clip pass's model in methods/fsr2.cpp, where an 8-bit store hides the
// difference) 2 of 370 outputs differ when the colour texture is larger than the render; with
// fused lerps none. A GPU's texture unit filters with 8-bit fractions instead (core/sampler.h).
#include "methods/fsr2_pyramid.h"

#include "methods/fsr2_internal.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace aalab {

namespace {

constexpr float kLog2E = 1.44269502162933349609375f;  // float(M_LOG2E): exp(x) = exp2(x · log2 e)
constexpr float kLn2 = 0.693147182464599609375f;      // float(1 / M_LOG2E): log(x) = log2(x) · ln 2
constexpr float kEpsilon = 1e-03f;                    // FSR2_EPSILON
constexpr float kResetLavg = 1e8f;                    // resetAutoExposureAverageSmoothing
constexpr int kShadingChangeMip = 4;                  // FFX_FSR2_SHADING_CHANGE_MIP_LEVEL

struct Math {
  const Fsr2Transcendentals& t;
  float Log2(float x) const { return t.log2 ? t.log2(x) : std::log2(x); }
  float Exp2(float x) const { return t.exp2 ? t.exp2(x) : std::exp2(x); }
  float Log(float x) const { return Log2(x) * kLn2; }
  float Exp(float x) const { return Exp2(x * kLog2E); }
};

float Reduce4(float v0, float v1, float v2, float v3) { return (((v0 + v1) + v2) + v3) * 0.25f; }

// A bilinear sample as lavapipe filters a float texture (fused lerps): fsr2_detail::SampleLinear,
// shared with the other passes.
float SampleLinear(const Fsr2Plane& t, float uv_x, float uv_y, int c) {
  return fsr2_detail::SampleLinear(t, {uv_x, uv_y}, c);
}

// SpdLoadSourceImage: the log luma of render pixel (x, y) (0 past the render size).
float SourceLogLuma(const Fsr2Constants& k, const Math& m, const Fsr2Plane& color, int x, int y) {
  const float tx = static_cast<float>(x), ty = static_cast<float>(y);
  const float rw = static_cast<float>(k.render_size[0]), rh = static_cast<float>(k.render_size[1]);
  float u = ((tx + 0.5f) + k.jitter[0]) / rw, v = ((ty + 0.5f) + k.jitter[1]) / rh;
  // ClampUv(uv, RenderSize(), InputColorResourceDimensions()).
  u = std::fmax(0.5f, std::fmin(u * rw, rw - 0.5f)) / static_cast<float>(k.input_color_size[0]);
  v = std::fmax(0.5f, std::fmin(v * rh, rh - 0.5f)) / static_cast<float>(k.input_color_size[1]);
  const float r = SampleLinear(color, u, v, 0) / k.pre_exposure, g = SampleLinear(color, u, v, 1) / k.pre_exposure,
              b = SampleLinear(color, u, v, 2) / k.pre_exposure;
  float luma = r * 0.2126f;  // dot(rgb, (0.2126, 0.7152, 0.0722)), in order
  luma = luma + g * 0.7152f;
  luma = luma + b * 0.0722f;
  const float log_luma = m.Log(std::fmax(kEpsilon, luma));
  return (tx < rw && ty < rh) ? log_luma : 0.0f;
}

// A square block of texels, n × n, (x, y) at v[y·n + x].
struct Block {
  int n = 0;
  std::vector<float> v;
  explicit Block(int size) : n(size), v(static_cast<size_t>(size) * static_cast<size_t>(size)) {}
  float& At(int x, int y) { return v[static_cast<size_t>(y) * static_cast<size_t>(n) + static_cast<size_t>(x)]; }
  float At(int x, int y) const { return v[static_cast<size_t>(y) * static_cast<size_t>(n) + static_cast<size_t>(x)]; }
};

// The quad reduction of mips 1–5 and 7–11: (0,0), (1,0), (0,1), (1,1).
Block ReduceRowMajor(const Block& in) {
  Block out(in.n / 2);
  for (int y = 0; y < out.n; ++y) {
    for (int x = 0; x < out.n; ++x) {
      out.At(x, y) =
          Reduce4(in.At(2 * x, 2 * y), in.At(2 * x + 1, 2 * y), in.At(2 * x, 2 * y + 1), in.At(2 * x + 1, 2 * y + 1));
    }
  }
  return out;
}

// The loads of mips 0 and 6: (0,0), (0,1), (1,0), (1,1).
Block ReduceColumnMajor(const Block& in) {
  Block out(in.n / 2);
  for (int y = 0; y < out.n; ++y) {
    for (int x = 0; x < out.n; ++x) {
      out.At(x, y) =
          Reduce4(in.At(2 * x, 2 * y), in.At(2 * x, 2 * y + 1), in.At(2 * x + 1, 2 * y), in.At(2 * x + 1, 2 * y + 1));
    }
  }
  return out;
}

class Pass {
 public:
  Pass(const Fsr2Constants& k, const Fsr2SpdDispatch& spd, const Fsr2Options& o, const Math& m, Fsr2PyramidState* s)
      : k_(k), spd_(spd), o_(o), m_(m), s_(s) {}

  // SpdStore of mip `index` at texel (px, py) of that mip.
  void Store(int index, int px, int py, float value) {
    if (index == k_.luma_mip_level || index == 5) {
      // SPD_SetMipmap: the switch has cases FFX_FSR2_SHADING_CHANGE_MIP_LEVEL and 5 only.
      Fsr2Plane* p = index == kShadingChangeMip ? &s_->luma_mip : index == 5 ? &s_->mip5 : nullptr;
      if (p && px >= 0 && py >= 0 && px < p->w && py < p->h) p->At(px, py, 0) = Fsr2Half(value, o_.half_toward_zero);
    }
    if (index == static_cast<int>(spd_.c.mips) - 1 && px == 0 && py == 0) {
      const float prev = s_->auto_exposure[1];
      float result = value;
      if (prev < kResetLavg) result = prev + (result - prev) * (1.0f - m_.Exp(-k_.delta_time * 1.0f));
      s_->auto_exposure[0] = ExposureFromLavg(result);
      s_->auto_exposure[1] = result;
    }
  }

  // Mips `from`..5 (or 11) of one block: each level computed while mips > level, stored at
  // origin·size + texel.
  void ReduceOn(Block b, int from, int last, int ox, int oy) {
    for (int level = from; level <= last && static_cast<int>(spd_.c.mips) > level; ++level) {
      b = ReduceRowMajor(b);
      for (int y = 0; y < b.n; ++y) {
        for (int x = 0; x < b.n; ++x) Store(level, ox * b.n + x, oy * b.n + y, b.At(x, y));
      }
    }
  }

  void Workgroup(const Fsr2Plane& color, int gx, int gy) {
    Block src(64);
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) src.At(x, y) = SourceLogLuma(k_, m_, color, gx * 64 + x, gy * 64 + y);
    }
    const Block mip0 = ReduceColumnMajor(src);
    for (int y = 0; y < 32; ++y) {
      for (int x = 0; x < 32; ++x) Store(0, gx * 32 + x, gy * 32 + y, mip0.At(x, y));
    }
    ReduceOn(mip0, 1, 5, gx, gy);
  }

  // The last workgroup: mip 6 from the stored mip 5 (64×64 texels read, 0 outside the view).
  void Tail() {
    Block mip5(64);
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) mip5.At(x, y) = s_->mip5.Fetch(x, y, 0);
    }
    const Block mip6 = ReduceColumnMajor(mip5);
    for (int y = 0; y < 32; ++y) {
      for (int x = 0; x < 32; ++x) Store(6, x, y, mip6.At(x, y));
    }
    ReduceOn(mip6, 7, 11, 0, 0);
  }

 private:
  // ComputeAutoExposureFromLavg: Lmax = 78/(0.65·100) · pow(2, log2(Lavg·100/12.5)), 1/Lmax.
  // pow(2, log2(y)) is y: Mesa folds it so (pow → exp2(log2(2)·…) → exp2(log2(y)) → y), and the
  // port computes y, the exact value, with no transcendental in between.
  float ExposureFromLavg(float lavg_log) const {
    const float lavg = m_.Exp(lavg_log);
    const float lmax = (78.0f / (0.65f * 100.0f)) * ((lavg * 100.0f) / 12.5f);
    return 1.0f / lmax;
  }

  const Fsr2Constants& k_;
  const Fsr2SpdDispatch& spd_;
  const Fsr2Options& o_;
  const Math& m_;
  Fsr2PyramidState* s_;
};

}  // namespace

Fsr2SpdDispatch Fsr2SpdSetup(int render_width, int render_height) {
  if (render_width <= 0 || render_height <= 0) {
    throw std::invalid_argument("FSR2 luminance pyramid: the render size must be positive (got " +
                                std::to_string(render_width) + "x" + std::to_string(render_height) + ")");
  }
  Fsr2SpdDispatch d;
  d.groups_x = (render_width - 1) / 64 + 1;
  d.groups_y = (render_height - 1) / 64 + 1;
  d.c.num_work_groups = static_cast<uint32_t>(d.groups_x * d.groups_y);
  const float longer = static_cast<float>(std::max(render_width, render_height));
  d.c.mips = static_cast<uint32_t>(std::min(std::floor(std::log2(longer)), 12.0f));
  d.c.render_size[0] = static_cast<uint32_t>(render_width);
  d.c.render_size[1] = static_cast<uint32_t>(render_height);
  return d;
}

int Fsr2LumaMipExtent(int max_render_extent, int m) { return std::max(1, (max_render_extent / 2) >> m); }

Fsr2PyramidState Fsr2PyramidReset(const Fsr2Constants& k) {
  Fsr2PyramidState s;
  s.luma_mip = Fsr2Plane(Fsr2LumaMipExtent(k.max_render_size[0], kShadingChangeMip),
                         Fsr2LumaMipExtent(k.max_render_size[1], kShadingChangeMip), 1);
  s.mip5 = Fsr2Plane(Fsr2LumaMipExtent(k.max_render_size[0], 5), Fsr2LumaMipExtent(k.max_render_size[1], 5), 1);
  return s;
}

void Fsr2LuminancePyramid(const Fsr2Constants& k, const Fsr2SpdDispatch& spd, const Fsr2Plane& color,
                          Fsr2PyramidState* state, const Fsr2Options& o, const Fsr2Transcendentals& math) {
  if (k.render_size[0] <= 0 || k.render_size[1] <= 0 || k.max_render_size[0] < k.render_size[0] ||
      k.max_render_size[1] < k.render_size[1]) {
    throw std::invalid_argument(
        "FSR2 luminance pyramid: the render size must be positive and within the max render size");
  }
  if (color.w != k.input_color_size[0] || color.h != k.input_color_size[1] || color.c < 3) {
    throw std::invalid_argument("FSR2 luminance pyramid: the colour must be input_color_size with 3 or 4 channels");
  }
  if (state->luma_mip.v.empty() || state->mip5.v.empty()) *state = Fsr2PyramidReset(k);
  const Math m{math};
  Pass pass(k, spd, o, m, state);
  const uint32_t n = spd.c.num_work_groups;
  for (int gy = 0; gy < spd.groups_y; ++gy) {
    for (int gx = 0; gx < spd.groups_x; ++gx) {
      pass.Workgroup(color, gx + static_cast<int>(spd.c.work_group_offset[0]),
                     gy + static_cast<int>(spd.c.work_group_offset[1]));
      if (spd.c.mips <= 6) continue;
      const uint32_t before = state->atomic_counter++;  // SpdExitWorkgroup's imageAtomicAdd
      if (before != n - 1) continue;
      state->atomic_counter = 0;  // SpdResetAtomicCounter
      pass.Tail();
    }
  }
}

}  // namespace aalab
