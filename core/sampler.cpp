#include "core/sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace aalab {

const char* SamplerArithmeticName(SamplerArithmetic a) { return a == SamplerArithmetic::kGl ? "gl" : "gpu-texture"; }

SamplerArithmetic ParseSamplerArithmetic(const std::string& name) {
  if (name == "gl") return SamplerArithmetic::kGl;
  if (name == "gpu-texture") return SamplerArithmetic::kGpuTexture;
  throw UserError("unknown sampler '" + name + "' (allowed: gl, gpu-texture)");
}

namespace {

std::array<float, 65536> MakeHwUnorm16() {
  std::array<float, 65536> t{};
  // The double quotient is within 2^-53 relative of q/65535, which is never a float rounding
  // tie for 0 < q < 65535 (its binary expansion does not end), so one rounding to float gives
  // the nearest float (tests/core/sampler_gpu_texture_test.cpp checks all 256 UNORM8 codes).
  for (uint32_t q = 0; q < t.size(); ++q) t[q] = static_cast<float>(static_cast<double>(q) / 65535.0);
  return t;
}

}  // namespace

const std::array<float, 65536> kHwUnorm16 = MakeHwUnorm16();

namespace {

// floor(x) for |x| < 2^62 by truncation (std::floor is a libm call on baseline x86-64).
int64_t FloorToInt(double x) {
  const auto i = static_cast<int64_t>(x);
  return static_cast<double>(i) > x ? i - 1 : i;
}

// One axis of HwFootprintAt: the coordinate in 1/256 texel, rounded with ties upwards,
// split into texel and fraction; clamped so that far-away coordinates stay integers (any
// x0 < −1 or > size reads the edge texel twice, as x0 = −1 or size does).
void HwAxis(double u, int size, int* x0, int* k) {
  if (std::isnan(u)) u = 0.0;
  const double lim = 4.0 * (static_cast<double>(size) + 2.0);
  u = std::clamp(u, -lim, lim);
  const int64_t t = FloorToInt((u - 0.5) * 256.0 + 0.5);
  const int64_t t0 = t >= 0 ? t / 256 : -((-t + 255) / 256);  // floor(t / 256)
  *k = static_cast<int>(t - 256 * t0);
  *x0 = static_cast<int>(std::clamp<int64_t>(t0, -1, size));
}

// floor(s·2^21)·size/2^21, exact in double for |s| < 2^31 (clamped beyond: far outside).
double HwNormalizedAxis(float s, int size) {
  if (std::isnan(s)) return 0.0;
  const double sc = std::clamp(static_cast<double>(s), -1024.0, 1024.0);
  return static_cast<double>(FloorToInt(sc * 2097152.0)) * static_cast<double>(size) / 2097152.0;
}

// Rounds a finite double to float with ties upwards (towards +∞), as the texture unit rounds
// its float filter sum. Exact for normal results.
float RoundFloatTiesUp(double x) {
  if (x == 0.0 || !std::isfinite(x)) return static_cast<float>(x);
  int e = 0;
  const double m = std::frexp(x, &e);                    // x = m·2^e, |m| in [0.5, 1)
  const double q = std::floor(std::ldexp(m, 24) + 0.5);  // 24 significant bits
  return static_cast<float>(std::ldexp(q, e - 24));
}

}  // namespace

HwFootprint HwFootprintAt(double u, double v, int width, int height) {
  HwFootprint f;
  HwAxis(u, width, &f.x0, &f.kx);
  HwAxis(v, height, &f.y0, &f.ky);
  return f;
}

HwFootprint HwFootprintNormalized(float s, float t, int width, int height) {
  return HwFootprintAt(HwNormalizedAxis(s, width), HwNormalizedAxis(t, height), width, height);
}

float HwFilterFloat(float a, float b, float c, float d, const HwWeights& w) {
  const double sum = static_cast<double>(w.a) * a + static_cast<double>(w.b) * b + static_cast<double>(w.c) * c +
                     static_cast<double>(w.d) * d;
  return RoundFloatTiesUp(sum / 256.0);
}

BilinearSampler::BilinearSampler(const Image8& img, SubTexel mode, SamplerArithmetic arithmetic)
    : img_(img), mode_(mode), arithmetic_(arithmetic) {
  AALAB_CHECK(img.Channels() == 4, "BilinearSampler needs an RGBA8 frame");
  AALAB_CHECK(!img.Empty(), "BilinearSampler needs a non-empty frame");
}

Float4 BilinearSampler::Fetch(int x, int y) const {
  x = std::clamp(x, 0, img_.Width() - 1);
  y = std::clamp(y, 0, img_.Height() - 1);
  const uint8_t* p = img_.Pixel(x, y);
  const SamplerArithmetic a = arithmetic_;
  return Float4{TexelValue(p[0], a), TexelValue(p[1], a), TexelValue(p[2], a), TexelValue(p[3], a)};
}

Float4 BilinearSampler::Texel(int x, int y) {
  ++taps_;
  return Fetch(x, y);
}

Float4 BilinearSampler::SampleNormalized(float s, float t) {
  if (arithmetic_ == SamplerArithmetic::kGpuTexture) {
    return BlendHw(HwFootprintNormalized(s, t, img_.Width(), img_.Height()));
  }
  const float u = s * static_cast<float>(img_.Width());
  const float v = t * static_cast<float>(img_.Height());
  return Sample(u, v);
}

Float4 BilinearSampler::SampleNormalizedOffset(float s, float t, int dx, int dy) {
  return Sample(s * static_cast<float>(img_.Width()) + static_cast<float>(dx),
                t * static_cast<float>(img_.Height()) + static_cast<float>(dy));
}

Float4 BilinearSampler::Sample(float u, float v) {
  if (arithmetic_ == SamplerArithmetic::kGpuTexture) {
    return BlendHw(HwFootprintAt(u, v, img_.Width(), img_.Height()));
  }
  return Blend(BilinearAt(u, v, img_.Width(), img_.Height(), mode_));
}

Float4 BilinearSampler::Blend(const BilinearFootprint& f) {
  ++taps_;
  const Float4 a = Fetch(f.x0, f.y0);
  const Float4 b = Fetch(f.x0 + 1, f.y0);
  const Float4 c = Fetch(f.x0, f.y0 + 1);
  const Float4 d = Fetch(f.x0 + 1, f.y0 + 1);
  Float4 r;
  r.r = BilinearBlend(a.r, b.r, c.r, d.r, f);
  r.g = BilinearBlend(a.g, b.g, c.g, d.g, f);
  r.b = BilinearBlend(a.b, b.b, c.b, d.b, f);
  r.a = BilinearBlend(a.a, b.a, c.a, d.a, f);
  return r;
}

Float4 BilinearSampler::BlendHw(const HwFootprint& f) {
  ++taps_;
  const int w = img_.Width(), h = img_.Height();
  const int xa = std::clamp(f.x0, 0, w - 1), xb = std::clamp(f.x0 + 1, 0, w - 1);
  const int ya = std::clamp(f.y0, 0, h - 1), yb = std::clamp(f.y0 + 1, 0, h - 1);
  const uint8_t* a = img_.Pixel(xa, ya);
  const uint8_t* b = img_.Pixel(xb, ya);
  const uint8_t* c = img_.Pixel(xa, yb);
  const uint8_t* d = img_.Pixel(xb, yb);
  const HwWeights wt = HwWeightsOf(f.kx, f.ky);
  return Float4{HwFilter8(a[0], b[0], c[0], d[0], wt), HwFilter8(a[1], b[1], c[1], d[1], wt),
                HwFilter8(a[2], b[2], c[2], d[2], wt), HwFilter8(a[3], b[3], c[3], d[3], wt)};
}

Float4 SampleBilinear(const ImageF& img, float u, float v) {
  AALAB_CHECK(!img.Empty(), "SampleBilinear needs a non-empty image");
  const int nc = img.Channels();
  const int w = img.Width();
  const int h = img.Height();
  const BilinearFootprint f = BilinearAt(u, v, w, h);
  const int xa = std::clamp(f.x0, 0, w - 1), xb = std::clamp(f.x0 + 1, 0, w - 1);
  const int ya = std::clamp(f.y0, 0, h - 1), yb = std::clamp(f.y0 + 1, 0, h - 1);
  float out[4] = {0, 0, 0, 0};
  for (int c = 0; c < nc && c < 4; ++c) {
    out[c] = BilinearBlend(img.At(xa, ya, c), img.At(xb, ya, c), img.At(xa, yb, c), img.At(xb, yb, c), f);
  }
  return Float4{out[0], out[1], out[2], out[3]};
}

}  // namespace aalab
