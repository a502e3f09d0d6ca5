// AMD FidelityFX Super Resolution 1 — EASU (upscale) and RCAS (sharpen), 32-bit float path.
//
// Ports FsrEasuCon / FsrEasuF and FsrRcasCon / FsrRcasF of ffx_fsr1.h (FidelityFX-FSR v1.0.2,
// with ffx_a.h; MIT licence, AMD), statement by statement in float32 and in the shader's
// order (no FMA: the project builds with -ffp-contract=off, and the oracle runs llvmpipe
// without FMA), as the sample's FSR_Pass.glsl calls them in its SAMPLE_SLOW_FALLBACK (fp32)
// build: EASU from the render-size texture into an RGBA8 intermediate, then RCAS from that
// into the RGBA8 output (FSR_Filter.cpp: the intermediate is R8G8B8A8_UNORM when not HDR).
//
// Methods (family fsr1, methods/fsr1.cpp):
//   scale43-easu                 render at 1/upscale of the output size (default upscale 4/3,
//                                round(W/upscale) × round(H/upscale), one centre sample per
//                                pixel), EASU to W × H.
//   scale43-easu-rcas            the same, then RCAS at W × H (sharpness in stops).
//   scale43-fxaa-high-easu-rcas  FXAA high (the tutorial's, as scale43-fxaa-high) at the
//                                render size, then EASU and RCAS: AMD asks for an anti-aliased
//                                input to EASU.
//   rcas                         RCAS alone on the 1x frame (a post filter).
// Parameters:
//   upscale    [1..2]  default 4/3   output/render size per axis (EASU's range is 1x-4x area);
//                                   FSR 1's modes: Ultra Quality 1.3, Quality 1.5, Balanced
//                                   1.7, Performance 2.
//   sharpness  [0..8]  default 0.2   RCAS's attenuation in stops (FsrRcasCon: exp2(-sharpness);
//                                   0 = the strongest), 0.2 as in AMD's sample.
//
// Fidelity and deviations (read with ffx_fsr1.h open; tests/oracle/fsr1_oracle_test.cpp runs
// the original header on llvmpipe and compares the floats before the store):
//   * Texture reads. EASU's textureGather at p0..p3 sits exactly on the corner between four
//     texel centres (F + (1,-1), (0,2), (2,2), (1,4) texels), so the gather's 2×2 footprint
//     is exact and it returns unfiltered texels: the port reads integer texels (clamped to the
//     edge, as the sample's CLAMP_TO_EDGE sampler) through TexelValue, i.e. the UNORM8 code
//     as the run's --sampler arithmetic converts it (gl: k·fl(1/255); gpu-texture: k/255).
//   * RCAS reads its 3×3 cross with texelFetch at ip ± 1 without a bounds check; at the frame
//     border that is outside the image (undefined in GL/Vulkan without robustness). Safe
//     thing: the loads clamp to the edge (the oracle's FsrRcasLoadF callback clamps too).
//   * GLSL min/max: the port uses fminf/fmaxf (IEEE minNum/maxNum: a NaN operand yields the
//     other). This matters in RCAS: where a channel's ring is all 0, hitMin = 0·(1/0) = NaN
//     (and where the ring is all 1, hitMax = 0·(1/0)); max(-NaN, hitMax) then returns
//     hitMax, as D3D and llvmpipe do.
//   * ARcpF1 is 1/x (the GLSL definition); APrxLoRcpF1, APrxLoRsqF1 and APrxMedRcpF1 are the
//     integer bit tricks of ffx_a.h (APrxLoRcpF1(0) is a large finite value, as in the shader).
//   * Constants: FsrEasuCon and FsrRcasCon on the CPU in float (A_CPU), as FSR_Filter.cpp.
//   * Not ported: the 16-bit paths (FsrEasuH, FsrRcasH/Hx2: the sample's default build),
//     FSR_RCAS_DENOISE and FSR_RCAS_PASSTHROUGH_ALPHA (off in the sample), LFGA/SRTM/TEPD.
#include "methods/fsr1.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "methods/families.h"
#include "methods/fxaa311.h"

namespace aalab {

namespace {

float F(uint32_t u) { return std::bit_cast<float>(u); }
uint32_t U(float f) { return std::bit_cast<uint32_t>(f); }
float Sat(float x) { return std::fminf(std::fmaxf(x, 0.0f), 1.0f); }  // clamp(x, 0, 1)
float Min3(float x, float y, float z) { return std::fminf(x, std::fminf(y, z)); }
float Max3(float x, float y, float z) { return std::fmaxf(x, std::fmaxf(y, z)); }

struct V2 {
  float x, y;
};

// One axis of FsrEasuSetF: lo, c, hi are the lumas before, at and after the centre texel
// (B C D across, A C E down). Adds the weighted gradient to dir and the weighted squared
// edge length to len, in the shader's order.
void EasuAxis(float& dir, float& len, float w, float lo, float c, float hi) {
  const float d1 = hi - c;
  const float d0 = c - lo;
  float l = std::fmaxf(std::fabs(d1), std::fabs(d0));
  l = Fsr1PrxLoRcp(l);
  const float d = hi - lo;
  dir += d * w;
  l = Sat(std::fabs(d) * l);
  l *= l;
  len += l * w;
}

// FsrEasuSetF for one of the four bilinear corners (s t / u v): direction and length.
void EasuSet(V2& dir, float& len, V2 pp, int corner, float lA, float lB, float lC, float lD, float lE) {
  float w = 0.0f;
  if (corner == 0) w = (1.0f - pp.x) * (1.0f - pp.y);
  if (corner == 1) w = pp.x * (1.0f - pp.y);
  if (corner == 2) w = (1.0f - pp.x) * pp.y;
  if (corner == 3) w = pp.x * pp.y;
  EasuAxis(dir.x, len, w, lB, lC, lD);
  EasuAxis(dir.y, len, w, lA, lC, lE);
}

// FsrEasuTapF: one tap of the approximate Lanczos-2 window.
void EasuTap(float aC[3], float& aW, V2 off, V2 dir, V2 len, float lob, float clp, const float c[3]) {
  V2 v;
  v.x = (off.x * dir.x) + (off.y * dir.y);
  v.y = (off.x * (-dir.y)) + (off.y * dir.x);
  v.x *= len.x;
  v.y *= len.y;
  float d2 = v.x * v.x + v.y * v.y;
  d2 = std::fminf(d2, clp);
  float wB = (2.0f / 5.0f) * d2 + (-1.0f);
  float wA = lob * d2 + (-1.0f);
  wB *= wB;
  wA *= wA;
  wB = (25.0f / 16.0f) * wB + (-(25.0f / 16.0f - 1.0f));
  const float w = wB * wA;
  for (int ch = 0; ch < 3; ++ch) aC[ch] += c[ch] * w;
  aW += w;
}

void CheckFrame(const Image8& in, const char* what) {
  AALAB_CHECK(in.Channels() == 4, std::string(what) + " needs an RGBA8 frame");
  AALAB_CHECK(!in.Empty(), std::string(what) + " needs a non-empty frame");
}

}  // namespace

float Fsr1PrxLoRcp(float a) { return F(0x7ef07ebbu - U(a)); }
float Fsr1PrxMedRcp(float a) {
  const float b = F(0x7ef19fffu - U(a));
  return b * (-b * a + 2.0f);
}
float Fsr1PrxLoRsq(float a) { return F(0x5f347d74u - (U(a) >> 1u)); }

Fsr1EasuConst Fsr1EasuCon(float in_w, float in_h, float out_w, float out_h) {
  // FsrEasuCon(viewport = in, input size = in, output = out), term by term in float.
  Fsr1EasuConst k;
  const float rox = 1.0f / out_w, roy = 1.0f / out_h, rix = 1.0f / in_w, riy = 1.0f / in_h;
  k.con0 = {U(in_w * rox), U(in_h * roy), U(0.5f * in_w * rox - 0.5f), U(0.5f * in_h * roy - 0.5f)};
  k.con1 = {U(rix), U(riy), U(1.0f * rix), U(-1.0f * riy)};
  k.con2 = {U(-1.0f * rix), U(2.0f * riy), U(1.0f * rix), U(2.0f * riy)};
  k.con3 = {U(0.0f * rix), U(4.0f * riy), 0u, 0u};
  return k;
}

uint32_t Fsr1RcasCon(float sharpness_stops) { return U(std::exp2f(-sharpness_stops)); }

float Fsr1Planes::At(int ch, int x, int y) const {
  x = std::clamp(x, 0, w - 1);
  y = std::clamp(y, 0, h - 1);
  return c[static_cast<size_t>(ch)][static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)];
}

Fsr1Planes Fsr1PlanesOf(const Image8& in, SamplerArithmetic sampler) {
  Fsr1Planes p;
  p.w = in.Width();
  p.h = in.Height();
  for (auto& plane : p.c) plane.resize(static_cast<size_t>(p.w) * static_cast<size_t>(p.h));
  for (int y = 0; y < p.h; ++y) {
    for (int x = 0; x < p.w; ++x) {
      const uint8_t* px = in.Pixel(x, y);
      for (int ch = 0; ch < 3; ++ch) {
        p.c[static_cast<size_t>(ch)][static_cast<size_t>(y) * static_cast<size_t>(p.w) + static_cast<size_t>(x)] =
            TexelValue(px[ch], sampler);
      }
    }
  }
  return p;
}

std::array<float, 3> Fsr1EasuPixel(const Fsr1Planes& in, const Fsr1EasuConst& con, int x, int y) {
  V2 pp{static_cast<float>(static_cast<uint32_t>(x)) * F(con.con0[0]) + F(con.con0[2]),
        static_cast<float>(static_cast<uint32_t>(y)) * F(con.con0[1]) + F(con.con0[3])};
  const V2 fp{std::floor(pp.x), std::floor(pp.y)};
  pp.x -= fp.x;
  pp.y -= fp.y;
  const int fx = static_cast<int>(fp.x), fy = static_cast<int>(fp.y);
  // The 12 texels: b c / e f g h / i j k l / n o, 'f' at (fx, fy).
  enum { b, c, e, f, g, h, i, j, k, l, n, o, kTaps };
  static constexpr int kOff[kTaps][2] = {{0, -1}, {1, -1}, {-1, 0}, {0, 0}, {1, 0}, {2, 0},
                                         {-1, 1}, {0, 1},  {1, 1},  {2, 1}, {0, 2}, {1, 2}};
  float t[kTaps][3];
  float L[kTaps];
  for (int q = 0; q < kTaps; ++q) {
    for (int ch = 0; ch < 3; ++ch) t[q][ch] = in.At(ch, fx + kOff[q][0], fy + kOff[q][1]);
    L[q] = t[q][2] * 0.5f + (t[q][0] * 0.5f + t[q][1]);  // luma times 2
  }
  V2 dir{0.0f, 0.0f};
  float len = 0.0f;
  EasuSet(dir, len, pp, 0, L[b], L[e], L[f], L[g], L[j]);
  EasuSet(dir, len, pp, 1, L[c], L[f], L[g], L[h], L[k]);
  EasuSet(dir, len, pp, 2, L[f], L[i], L[j], L[k], L[n]);
  EasuSet(dir, len, pp, 3, L[g], L[j], L[k], L[l], L[o]);
  const V2 dir2{dir.x * dir.x, dir.y * dir.y};
  float dirR = dir2.x + dir2.y;
  const bool zro = dirR < 1.0f / 32768.0f;
  dirR = Fsr1PrxLoRsq(dirR);
  dirR = zro ? 1.0f : dirR;
  dir.x = zro ? 1.0f : dir.x;
  dir.x *= dirR;
  dir.y *= dirR;
  len = len * 0.5f;
  len *= len;
  const float stretch = (dir.x * dir.x + dir.y * dir.y) * Fsr1PrxLoRcp(std::fmaxf(std::fabs(dir.x), std::fabs(dir.y)));
  const V2 len2{1.0f + (stretch - 1.0f) * len, 1.0f + (-0.5f) * len};
  const float lob = 0.5f + ((1.0f / 4.0f - 0.04f) - 0.5f) * len;
  const float clp = Fsr1PrxLoRcp(lob);
  float mn[3], mx[3];
  for (int ch = 0; ch < 3; ++ch) {
    mn[ch] = std::fminf(Min3(t[f][ch], t[g][ch], t[j][ch]), t[k][ch]);
    mx[ch] = std::fmaxf(Max3(t[f][ch], t[g][ch], t[j][ch]), t[k][ch]);
  }
  float aC[3] = {0.0f, 0.0f, 0.0f};
  float aW = 0.0f;
  // The shader's tap order: b c i j f e k l h g o n.
  for (int q : {b, c, i, j, f, e, k, l, h, g, o, n}) {
    const V2 off{static_cast<float>(kOff[q][0]) - pp.x, static_cast<float>(kOff[q][1]) - pp.y};
    EasuTap(aC, aW, off, dir, len2, lob, clp, t[q]);
  }
  const float r = 1.0f / aW;
  std::array<float, 3> pix;
  for (int ch = 0; ch < 3; ++ch) pix[static_cast<size_t>(ch)] = std::fminf(mx[ch], std::fmaxf(mn[ch], aC[ch] * r));
  return pix;
}

std::array<float, 3> Fsr1RcasPixel(const Fsr1Planes& in, uint32_t con_x, int x, int y) {
  float b[3], d[3], e[3], f[3], h[3];
  for (int ch = 0; ch < 3; ++ch) {
    b[ch] = in.At(ch, x, y - 1);
    d[ch] = in.At(ch, x - 1, y);
    e[ch] = in.At(ch, x, y);
    f[ch] = in.At(ch, x + 1, y);
    h[ch] = in.At(ch, x, y + 1);
  }
  // Luma and the noise detection (nz) only feed FSR_RCAS_DENOISE, which is off.
  float lobeC[3];
  for (int ch = 0; ch < 3; ++ch) {
    const float mn4 = std::fminf(Min3(b[ch], d[ch], f[ch]), h[ch]);
    const float mx4 = std::fmaxf(Max3(b[ch], d[ch], f[ch]), h[ch]);
    const float hitMin = std::fminf(mn4, e[ch]) * (1.0f / (4.0f * mx4));
    const float hitMax = (1.0f - std::fmaxf(mx4, e[ch])) * (1.0f / (4.0f * mn4 + (-4.0f)));
    lobeC[ch] = std::fmaxf(-hitMin, hitMax);
  }
  const float limit = 0.25f - 1.0f / 16.0f;  // FSR_RCAS_LIMIT
  const float lobe = std::fmaxf(-limit, std::fminf(Max3(lobeC[0], lobeC[1], lobeC[2]), 0.0f)) * F(con_x);
  const float rcpL = Fsr1PrxMedRcp(4.0f * lobe + 1.0f);
  std::array<float, 3> pix;
  for (int ch = 0; ch < 3; ++ch) {
    pix[static_cast<size_t>(ch)] = (lobe * b[ch] + lobe * d[ch] + lobe * h[ch] + lobe * f[ch] + e[ch]) * rcpL;
  }
  return pix;
}

namespace {

template <class Pixel>
Image8 Store(int w, int h, Pixel pixel) {
  Image8 out(w, h, 4);
  ParallelForChunks(h, 8, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::array<float, 3> c = pixel(x, y);
        uint8_t* o = out.Pixel(x, y);
        for (int ch = 0; ch < 3; ++ch) o[ch] = StoreUnorm8(c[static_cast<size_t>(ch)]);
        o[3] = 255;
      }
    }
  });
  return out;
}

}  // namespace

Image8 Fsr1Easu(const Image8& in, int out_w, int out_h, PostStats* stats, SamplerArithmetic sampler) {
  CheckFrame(in, "EASU");
  AALAB_CHECK(out_w > 0 && out_h > 0, "EASU needs a positive output size");
  const Fsr1Planes planes = Fsr1PlanesOf(in, sampler);
  const Fsr1EasuConst con = Fsr1EasuCon(static_cast<float>(in.Width()), static_cast<float>(in.Height()),
                                        static_cast<float>(out_w), static_cast<float>(out_h));
  if (stats) stats->taps += 12u * static_cast<uint64_t>(out_w) * static_cast<uint64_t>(out_h);
  return Store(out_w, out_h, [&](int x, int y) { return Fsr1EasuPixel(planes, con, x, y); });
}

Image8 Fsr1Rcas(const Image8& in, float sharpness_stops, PostStats* stats, SamplerArithmetic sampler) {
  CheckFrame(in, "RCAS");
  const Fsr1Planes planes = Fsr1PlanesOf(in, sampler);
  const uint32_t con = Fsr1RcasCon(sharpness_stops);
  if (stats) stats->taps += 5u * static_cast<uint64_t>(in.Width()) * static_cast<uint64_t>(in.Height());
  return Store(in.Width(), in.Height(), [&](int x, int y) { return Fsr1RcasPixel(planes, con, x, y); });
}

// ---- Registry rows ----------------------------------------------------------------------

namespace {

ParamDef UpscaleParam() {
  return FloatParam("upscale", 4.0 / 3.0, 1.0, 2.0,
                    "output/render size per axis: the frame is rendered at round(W/upscale) x round(H/upscale) "
                    "and EASU scales it to W x H (FSR 1 modes: 1.3, 1.5, 1.7, 2)");
}
ParamDef SharpnessParam() {
  return FloatParam("sharpness", 0.2, 0.0, 8.0, "RCAS sharpness reduction in stops (0 = sharpest)");
}

PostFilter RcasFilter(const std::string& name, float stops) {
  return [name, stops](const Image8& in, const PostOptions& options, PostStats* stats) {
    if (!options.debug_view.empty()) {
      throw UserError("method '" + name + "' has no debug view '" + options.debug_view + "'");
    }
    return Fsr1Rcas(in, stops, stats, options.sampler);
  };
}

MethodPlan EasuPlan(const std::string& name, const ParamValues& v, bool fxaa, bool rcas) {
  MethodPlan plan;
  plan.name = name;
  plan.params = v;
  plan.render.pattern = SamplePattern::kCenter;
  plan.render.scale = 1.0 / v.Number("upscale");
  plan.rescale = Rescale::kEasu;
  if (fxaa) SetFxaa311Post(plan, FxaaTutorialHighParams());
  if (rcas) plan.sharpen = RcasFilter(name, static_cast<float>(v.Number("sharpness")));
  return plan;
}

}  // namespace

std::vector<MethodEntry> Fsr1Methods() {
  std::vector<MethodEntry> out;
  out.push_back({"scale43-easu",
                 "render at 1/upscale (default 3/4), FSR 1 EASU to the output size",
                 {UpscaleParam()},
                 [](const ParamValues& v) { return EasuPlan("scale43-easu", v, false, false); }});
  out.push_back({"scale43-easu-rcas",
                 "render at 1/upscale (default 3/4), FSR 1 EASU, then RCAS at the output size",
                 {UpscaleParam(), SharpnessParam()},
                 [](const ParamValues& v) { return EasuPlan("scale43-easu-rcas", v, false, true); }});
  out.push_back({"scale43-fxaa-high-easu-rcas",
                 "render at 1/upscale, tutorial high-quality FXAA at that size, FSR 1 EASU, then RCAS",
                 {UpscaleParam(), SharpnessParam()},
                 [](const ParamValues& v) { return EasuPlan("scale43-fxaa-high-easu-rcas", v, true, true); }});
  out.push_back({"rcas", "FSR 1 RCAS sharpening alone on the 1x frame", {SharpnessParam()}, [](const ParamValues& v) {
                   MethodPlan plan;
                   plan.post = RcasFilter("rcas", static_cast<float>(v.Number("sharpness")));
                   return plan;
                 }});
  return out;
}

}  // namespace aalab
