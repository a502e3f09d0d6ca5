// FSR 2.2.1's RCAS pass (ffx_fsr2_rcas_pass.glsl: FsrRcasF of FSR 2's ffx_fsr1.h with
// FSR_RCAS_DENOISE, 16×16 tiles), fp32 path. min/max are std::fmin/fmax (IEEE minNum/maxNum,
// the non-NaN operand), as lavapipe evaluates GLSL's min/max: RCAS's limiter makes 0·∞ = NaN
// on a black ring. Conventions: methods/fsr2_common.cpp's doc block; figures: docs/fsr2.md.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "methods/fsr2.h"
#include "methods/fsr2_internal.h"

namespace aalab {

using namespace fsr2_detail;  // NOLINT(google-build-using-namespace): the passes' shared helpers

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
