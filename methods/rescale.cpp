// Frame rescaling for render-scale methods: bilinear and B-spline bicubic.
//
// Implements the final rescale of the Catlike Coding tutorial's render scale (seed 000,
// "Combine FXAA and render scale"; the rescale pass itself is the previous part of that
// series, which the seed summarises as "bilinear" vs "bicubic rescaling"):
//   bilinear  one bilinear fetch at the output pixel centre in normalised coordinates;
//   bicubic   the cubic B-spline evaluated with four bilinear fetches (the classic folding
//             of GPU Gems 2 ch. 20, also what Unity's SampleTexture2DBicubic does): per axis
//             the 4 weights w0..w3 are folded into two taps of weight g0 = w0+w1 and
//             g1 = w2+w3 placed at texel positions (i-1) + w1/g0 and (i+1) + w3/g1.
//             The B-spline is smoothing, not interpolating: all weights are positive, so
//             the result never overshoots (no ringing) and stays in [0, 1].
// Deviations: filtering runs on the sRGB-encoded 8-bit values (docs/design.md "Colour"); Unity samples the
// sRGB render texture, so its GPU filters in linear light. Bicubic taps are computed in
// texel coordinates and passed to BilinearSampler::Sample (the shader converts them to
// normalised coordinates and the GPU multiplies back; the difference is float rounding of
// the tap position). The tutorial's "Up Only" mode would not use bicubic for scales > 1;
// rescale=bicubic here always does ("Up And Down").
#include "methods/rescale.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/sampler.h"
#include "methods/fsr1.h"

namespace aalab {

BsplineTaps BsplineCubicTaps(float t) {
  BsplineTaps b{};
  const float s = 1.0f - t;
  const float t2 = t * t;
  const float t3 = t2 * t;
  b.w[0] = (s * s * s) / 6.0f;
  b.w[1] = ((3.0f * t3 - 6.0f * t2) + 4.0f) / 6.0f;
  b.w[2] = (((-3.0f * t3 + 3.0f * t2) + 3.0f * t) + 1.0f) / 6.0f;
  b.w[3] = t3 / 6.0f;
  b.g0 = b.w[0] + b.w[1];
  b.g1 = b.w[2] + b.w[3];
  b.h0 = b.w[1] / b.g0;  // g0 >= 2/3 > 0 for t in [0, 1]
  b.h1 = b.w[3] / b.g1;  // g1 >= 1/6 > 0
  return b;
}

namespace {

struct Axis {
  float tap0, tap1;  // bilinear tap positions in input pixel coordinates
  float g0, g1;
};

// One axis of the bicubic: output index X of n_out mapped onto n_in input pixels.
Axis BicubicAxis(int X, int n_out, int n_in) {
  const float s = (static_cast<float>(X) + 0.5f) / static_cast<float>(n_out);
  const float u = s * static_cast<float>(n_in);  // input pixel coordinates
  const float x = u - 0.5f;                      // texel-centre space
  const float i = std::floor(x);
  const float t = x - i;
  const BsplineTaps b = BsplineCubicTaps(t);
  Axis a;
  a.tap0 = ((i - 1.0f) + b.h0) + 0.5f;
  a.tap1 = ((i + 1.0f) + b.h1) + 0.5f;
  a.g0 = b.g0;
  a.g1 = b.g1;
  return a;
}

}  // namespace

Image8 RescaleFrameReference(const Image8& in, int out_w, int out_h, Rescale kind, PostStats* stats,
                             SamplerArithmetic sampler) {
  AALAB_CHECK(in.Channels() == 4, "RescaleFrame needs an RGBA8 frame");
  AALAB_CHECK(out_w > 0 && out_h > 0, "RescaleFrame needs a positive output size");
  if (kind == Rescale::kEasu) return Fsr1Easu(in, out_w, out_h, stats, sampler);
  if (kind == Rescale::kNone) {
    AALAB_CHECK(out_w == in.Width() && out_h == in.Height(), "Rescale::kNone with a frame of another size");
    return in;
  }
  AALAB_CHECK(!in.Empty(), "RescaleFrame needs a non-empty frame");
  Image8 out(out_w, out_h, 4);
  constexpr int kGrain = 8;
  std::vector<uint64_t> taps(static_cast<size_t>((out_h + kGrain - 1) / kGrain), 0);
  std::vector<Axis> xs;
  if (kind == Rescale::kBicubic) {
    for (int X = 0; X < out_w; ++X) xs.push_back(BicubicAxis(X, out_w, in.Width()));
  }
  ParallelForChunks(out_h, kGrain, [&](int y0, int y1) {
    BilinearSampler tex(in, SubTexel::kExact, sampler);
    for (int Y = y0; Y < y1; ++Y) {
      const Axis ay = kind == Rescale::kBicubic ? BicubicAxis(Y, out_h, in.Height()) : Axis{};
      const float t = (static_cast<float>(Y) + 0.5f) / static_cast<float>(out_h);
      for (int X = 0; X < out_w; ++X) {
        float rgb[3];
        if (kind == Rescale::kBilinear) {
          const float s = (static_cast<float>(X) + 0.5f) / static_cast<float>(out_w);
          const Float4 c = tex.SampleNormalized(s, t);
          rgb[0] = c.r;
          rgb[1] = c.g;
          rgb[2] = c.b;
        } else {
          const Axis& ax = xs[static_cast<size_t>(X)];
          const Float4 c00 = tex.Sample(ax.tap0, ay.tap0);
          const Float4 c10 = tex.Sample(ax.tap1, ay.tap0);
          const Float4 c01 = tex.Sample(ax.tap0, ay.tap1);
          const Float4 c11 = tex.Sample(ax.tap1, ay.tap1);
          const float a00[3] = {c00.r, c00.g, c00.b};
          const float a10[3] = {c10.r, c10.g, c10.b};
          const float a01[3] = {c01.r, c01.g, c01.b};
          const float a11[3] = {c11.r, c11.g, c11.b};
          for (int c = 0; c < 3; ++c) {
            rgb[c] = ay.g0 * (ax.g0 * a00[c] + ax.g1 * a10[c]) + ay.g1 * (ax.g0 * a01[c] + ax.g1 * a11[c]);
          }
        }
        uint8_t* o = out.Pixel(X, Y);
        o[0] = QuantizeUnorm8(rgb[0]);
        o[1] = QuantizeUnorm8(rgb[1]);
        o[2] = QuantizeUnorm8(rgb[2]);
        o[3] = 255;
      }
    }
    taps[static_cast<size_t>(y0 / kGrain)] = tex.Taps();
  });
  if (stats) {
    for (uint64_t n : taps) stats->taps += n;
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// The production path: the same taps and float expressions as RescaleFrameReference, with
// each tap's texel indices and fractions computed once per output column and row (they
// depend on one axis each), k/255 from a table, and only the rgb channels filtered (alpha is
// written as 255). Tested bit for bit against the reference (tests/equivalence/fxaa_fast_test.cpp).

namespace {

// One axis of a BilinearSampler::Sample at coordinate u (pixels): the two clamped texel
// indices and the fraction, exactly as Sample and Fetch compute them.
struct Tap1 {
  int i0, i1;
  float f;
};

Tap1 MakeTap(float u, int n) {
  const float x = u - 0.5f;
  const float x0f = std::floor(x);
  Tap1 t;
  t.f = x - x0f;
  const int x0 = static_cast<int>(std::clamp(x0f, -1.0f, static_cast<float>(n)));
  t.i0 = std::clamp(x0, 0, n - 1);
  t.i1 = std::clamp(x0 + 1, 0, n - 1);
  return t;
}

const float* UnormTable() {
  static const auto table = [] {
    std::array<float, 256> t{};
    for (int k = 0; k < 256; ++k) t[k] = UnormToFloat(static_cast<uint8_t>(k));
    return t;
  }();
  return table.data();
}

// The rgb of a bilinear fetch (BilinearSampler::Sample's arithmetic, channels 0..2).
inline void Bilerp(const Image8& in, const float* u8, const Tap1& tx, const Tap1& ty, float out[3]) {
  const float fx = tx.f, fy = ty.f;
  const uint8_t* a = in.Pixel(tx.i0, ty.i0);
  const uint8_t* b = in.Pixel(tx.i1, ty.i0);
  const uint8_t* c = in.Pixel(tx.i0, ty.i1);
  const uint8_t* d = in.Pixel(tx.i1, ty.i1);
  BilinearFootprint f;
  f.fx = fx;
  f.fy = fy;
  for (int k = 0; k < 3; ++k) out[k] = BilinearBlend(u8[a[k]], u8[b[k]], u8[c[k]], u8[d[k]], f);
}

inline uint8_t Quantize(float v) {  // QuantizeUnorm8: lround(v·255) = floor(v·255 + 0.5) in double
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  return static_cast<uint8_t>(static_cast<int>(static_cast<double>(v * 255.0f) + 0.5));
}

}  // namespace

Image8 RescaleFrame(const Image8& in, int out_w, int out_h, Rescale kind, PostStats* stats, SamplerArithmetic sampler) {
  AALAB_CHECK(in.Channels() == 4, "RescaleFrame needs an RGBA8 frame");
  AALAB_CHECK(out_w > 0 && out_h > 0, "RescaleFrame needs a positive output size");
  if (kind == Rescale::kEasu) return Fsr1Easu(in, out_w, out_h, stats, sampler);
  if (kind == Rescale::kNone || sampler != SamplerArithmetic::kGl) {
    return RescaleFrameReference(in, out_w, out_h, kind, stats, sampler);  // no fast path for kGpuTexture
  }
  AALAB_CHECK(!in.Empty(), "RescaleFrame needs a non-empty frame");
  const int W = in.Width(), H = in.Height();
  const float* u8 = UnormTable();
  Image8 out(out_w, out_h, 4);
  // Per column / row: the taps of that axis.
  std::vector<Tap1> cx0(static_cast<size_t>(out_w)), cx1, cy0(static_cast<size_t>(out_h)), cy1;
  std::vector<Axis> ax, ay;
  if (kind == Rescale::kBilinear) {
    for (int X = 0; X < out_w; ++X) {
      const float s = (static_cast<float>(X) + 0.5f) / static_cast<float>(out_w);
      cx0[X] = MakeTap(s * static_cast<float>(W), W);  // SampleNormalized: u = s·W
    }
    for (int Y = 0; Y < out_h; ++Y) {
      const float t = (static_cast<float>(Y) + 0.5f) / static_cast<float>(out_h);
      cy0[Y] = MakeTap(t * static_cast<float>(H), H);
    }
  } else {
    cx1.resize(static_cast<size_t>(out_w));
    cy1.resize(static_cast<size_t>(out_h));
    for (int X = 0; X < out_w; ++X) {
      ax.push_back(BicubicAxis(X, out_w, W));
      cx0[X] = MakeTap(ax.back().tap0, W);
      cx1[X] = MakeTap(ax.back().tap1, W);
    }
    for (int Y = 0; Y < out_h; ++Y) {
      ay.push_back(BicubicAxis(Y, out_h, H));
      cy0[Y] = MakeTap(ay.back().tap0, H);
      cy1[Y] = MakeTap(ay.back().tap1, H);
    }
  }
  ParallelForChunks(out_h, 8, [&](int y0, int y1) {
    for (int Y = y0; Y < y1; ++Y) {
      uint8_t* o = out.Row(Y);
      for (int X = 0; X < out_w; ++X, o += 4) {
        float rgb[3];
        if (kind == Rescale::kBilinear) {
          Bilerp(in, u8, cx0[X], cy0[Y], rgb);
        } else {
          float a00[3], a10[3], a01[3], a11[3];
          Bilerp(in, u8, cx0[X], cy0[Y], a00);
          Bilerp(in, u8, cx1[X], cy0[Y], a10);
          Bilerp(in, u8, cx0[X], cy1[Y], a01);
          Bilerp(in, u8, cx1[X], cy1[Y], a11);
          const Axis& bx = ax[static_cast<size_t>(X)];
          const Axis& by = ay[static_cast<size_t>(Y)];
          for (int c = 0; c < 3; ++c) {
            rgb[c] = by.g0 * (bx.g0 * a00[c] + bx.g1 * a10[c]) + by.g1 * (bx.g0 * a01[c] + bx.g1 * a11[c]);
          }
        }
        o[0] = Quantize(rgb[0]);
        o[1] = Quantize(rgb[1]);
        o[2] = Quantize(rgb[2]);
        o[3] = 255;
      }
    }
  });
  if (stats) stats->taps += static_cast<uint64_t>(out_w) * out_h * (kind == Rescale::kBicubic ? 4 : 1);
  return out;
}

}  // namespace aalab
