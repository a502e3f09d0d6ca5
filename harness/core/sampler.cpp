#include "harness/core/sampler.h"

#include <algorithm>
#include <cmath>

namespace aalab {

BilinearSampler::BilinearSampler(const Image8& img) : img_(img) {
  AALAB_CHECK(img.Channels() == 4, "BilinearSampler needs an RGBA8 frame");
  AALAB_CHECK(!img.Empty(), "BilinearSampler needs a non-empty frame");
}

Float4 BilinearSampler::Fetch(int x, int y) const {
  x = std::clamp(x, 0, img_.Width() - 1);
  y = std::clamp(y, 0, img_.Height() - 1);
  const uint8_t* p = img_.Pixel(x, y);
  return Float4{UnormToFloat(p[0]), UnormToFloat(p[1]), UnormToFloat(p[2]), UnormToFloat(p[3])};
}

Float4 BilinearSampler::Texel(int x, int y) {
  ++taps_;
  return Fetch(x, y);
}

Float4 BilinearSampler::SampleNormalized(float s, float t) {
  const float u = s * static_cast<float>(img_.Width());
  const float v = t * static_cast<float>(img_.Height());
  return Sample(u, v);
}

Float4 BilinearSampler::SampleNormalizedOffset(float s, float t, int dx, int dy) {
  return Sample(s * static_cast<float>(img_.Width()) + static_cast<float>(dx),
                t * static_cast<float>(img_.Height()) + static_cast<float>(dy));
}

Float4 BilinearSampler::Sample(float u, float v) {
  return Blend(BilinearAt(u, v, img_.Width(), img_.Height()));
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
    out[c] = BilinearBlend(img.At(xa, ya, c), img.At(xb, ya, c), img.At(xa, yb, c),
                           img.At(xb, yb, c), f);
  }
  return Float4{out[0], out[1], out[2], out[3]};
}

}  // namespace aalab
