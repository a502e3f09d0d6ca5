// SMAA 1x: the production path (the filter `Smaa` that methods run).
//
// Same shader as SmaaReference in methods/smaa.cpp — same float operations in the same
// order, same fetches, same 8-bit textures — organised for a CPU. Parameters, sources and
// deviations are documented at the top of methods/smaa.cpp.
//   Pass 1: lumas (or UNORM values) from 256-entry product tables, one plane per frame, so
//     each pixel's expressions read floats instead of going through the sampler; point
//     samples at texel centres are exact texel reads in both paths.
//   Pass 2: only pixels with an edge byte in their 3×3 neighbourhood run the shader: any
//     other pixel's first fetch (the edge texture at its own centre; its bilinear footprint
//     lies in that 3×3 block because the coordinate misses the centre by far less than half
//     a texel) returns (0, 0), so its weights are 0 after one fetch. The shader itself is
//     the one definition in smaa_shader.h, reading the edge texture through PlaneEdges
//     (BilinearSampler's footprint, clamp, k/255 and weighted sum for the r and g channels
//     only, in the same order).
//   Pass 3: only pixels with a non-zero blend byte in rows y−1..y+2, columns x−1..x+2 (the
//     footprints of the three blend fetches) run BlendPixel; the others see a = 0 and
//     return the colour fetched at their own centre, which rounds back to the input bytes:
//     its weights put at most a few float ulps (exact mode), or nothing (8-bit mode), on
//     another texel, far below the 0.5/255 that would change the 8-bit result. The guard
//     below keeps that argument's bound (coordinate error < 1/512 texel) to frames up to
//     8192 pixels wide and high; larger frames run BlendPixel everywhere.
// Tap counts equal the reference's. tests/perf/smaa_fast_test.cpp compares this path with
// SmaaReference bit for bit, taps included, at 1 and 2 threads.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "harness/core/color.h"
#include "harness/core/error.h"
#include "harness/core/parallel.h"
#include "methods/smaa.h"
#include "methods/smaa_shader.h"

namespace aalab {

namespace smaa_detail {
Image8 EdgesView(const Image8& edges);
Image8 WeightsView(const Image8& blend);
int ParseView(const std::string& view);
}  // namespace smaa_detail

namespace {

using smaa_detail::F2;
using smaa_detail::Frame;

constexpr int kGrain = 8;
constexpr int kMaxShortcutSize = 8192;

// k / 255 as BilinearSampler::Fetch computes it.
struct UnormTable {
  float v[256];
};
const UnormTable& Unorm() {
  static const UnormTable t = [] {
    UnormTable u{};
    for (int k = 0; k < 256; ++k) u.v[k] = static_cast<float>(k) / 255.0f;
    return u;
  }();
  return t;
}

// Luma plane: (r·0.2126 + g·0.7152) + b·0.0722 with r = k/255, per pixel.
std::unique_ptr<float[]> LumaPlane(const Image8& in) {
  const int w = in.Width(), h = in.Height();
  struct Products {
    float r[256], g[256], b[256];
  };
  static const Products tab = [] {
    Products p{};
    for (int k = 0; k < 256; ++k) {
      const float u = static_cast<float>(k) / 255.0f;
      p.r[k] = u * 0.2126f;
      p.g[k] = u * 0.7152f;
      p.b[k] = u * 0.0722f;
    }
    return p;
  }();
  std::unique_ptr<float[]> plane(new float[static_cast<size_t>(w) * h]);
  ParallelForChunks(h, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const uint8_t* p = in.Row(y);
      float* o = plane.get() + static_cast<size_t>(y) * w;
      for (int x = 0; x < w; ++x) o[x] = (tab.r[p[4 * x]] + tab.g[p[4 * x + 1]]) + tab.b[p[4 * x + 2]];
    }
  });
  return plane;
}

// Pass 1 for luma detection: EdgePixel's expressions on the plane.
Image8 EdgesLuma(const Image8& in, const SmaaParams& p, uint64_t* taps) {
  const int w = in.Width(), h = in.Height();
  const std::unique_ptr<float[]> lum = LumaPlane(in);
  Image8 edges(w, h, 4, 0);
  std::vector<uint64_t> t(static_cast<size_t>((h + kGrain - 1) / kGrain), 0);
  const float thr = p.threshold, lcf = p.local_contrast_factor;
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    uint64_t n = 0;
    for (int y = y0; y < y1; ++y) {
      const float* r0 = lum.get() + static_cast<size_t>(y) * w;
      const float* rt = lum.get() + static_cast<size_t>(std::max(y - 1, 0)) * w;
      const float* rtt = lum.get() + static_cast<size_t>(std::max(y - 2, 0)) * w;
      const float* rb = lum.get() + static_cast<size_t>(std::min(y + 1, h - 1)) * w;
      uint8_t* out = edges.Row(y);
      n += 3 * static_cast<uint64_t>(w);
      for (int x = 0; x < w; ++x) {
        const float L = r0[x];
        const float Lleft = r0[std::max(x - 1, 0)];
        const float Ltop = rt[x];
        const float dx = std::fabs(L - Lleft);
        const float dy = std::fabs(L - Ltop);
        const bool ex = dx >= thr, ey = dy >= thr;
        if (!ex && !ey) continue;
        n += 4;
        float mx = std::max(dx, std::fabs(L - r0[std::min(x + 1, w - 1)]));
        float my = std::max(dy, std::fabs(L - rb[x]));
        mx = std::max(mx, std::fabs(Lleft - r0[std::max(x - 2, 0)]));
        my = std::max(my, std::fabs(Ltop - rtt[x]));
        const float final_delta = std::max(mx, my);
        out[4 * x] = ex && lcf * dx >= final_delta ? 255 : 0;
        out[4 * x + 1] = ey && lcf * dy >= final_delta ? 255 : 0;
      }
    }
    t[static_cast<size_t>(y0 / kGrain)] = n;
  });
  for (uint64_t v : t) *taps += v;
  return edges;
}

// Pass 1 for colour detection: max over channels of |C − N| with C, N = k/255.
Image8 EdgesColor(const Image8& in, const SmaaParams& p, uint64_t* taps) {
  const int w = in.Width(), h = in.Height();
  const float* u = Unorm().v;
  Image8 edges(w, h, 4, 0);
  std::vector<uint64_t> t(static_cast<size_t>((h + kGrain - 1) / kGrain), 0);
  const float thr = p.threshold, lcf = p.local_contrast_factor;
  auto diff = [u](const uint8_t* a, const uint8_t* b) {
    const float r = std::fabs(u[a[0]] - u[b[0]]), g = std::fabs(u[a[1]] - u[b[1]]), bl = std::fabs(u[a[2]] - u[b[2]]);
    return std::max(std::max(r, g), bl);
  };
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    uint64_t n = 0;
    for (int y = y0; y < y1; ++y) {
      const uint8_t* r0 = in.Row(y);
      const uint8_t* rt = in.Row(std::max(y - 1, 0));
      const uint8_t* rtt = in.Row(std::max(y - 2, 0));
      const uint8_t* rb = in.Row(std::min(y + 1, h - 1));
      uint8_t* out = edges.Row(y);
      n += 3 * static_cast<uint64_t>(w);
      for (int x = 0; x < w; ++x) {
        const uint8_t* C = r0 + 4 * x;
        const float dx = diff(C, r0 + 4 * std::max(x - 1, 0));
        const float dy = diff(C, rt + 4 * x);
        const bool ex = dx >= thr, ey = dy >= thr;
        if (!ex && !ey) continue;
        n += 4;
        float mx = std::max(dx, diff(C, r0 + 4 * std::min(x + 1, w - 1)));
        float my = std::max(dy, diff(C, rb + 4 * x));
        mx = std::max(mx, diff(C, r0 + 4 * std::max(x - 2, 0)));
        my = std::max(my, diff(C, rtt + 4 * x));
        const float final_delta = std::max(mx, my);
        out[4 * x] = ex && lcf * dx >= final_delta ? 255 : 0;
        out[4 * x + 1] = ey && lcf * dy >= final_delta ? 255 : 0;
      }
    }
    t[static_cast<size_t>(y0 / kGrain)] = n;
  });
  for (uint64_t v : t) *taps += v;
  return edges;
}

// The edge-texture reader of the production path: BilinearSampler::Sample's footprint,
// clamp and sums for the r and g channels of the RGBA8 edge texture.
class PlaneEdges {
 public:
  PlaneEdges(const Image8& e, SubTexel mode) : e_(e), w_(e.Width()), h_(e.Height()), mode_(mode), u_(Unorm().v) {}
  F2 Sample(float u, float v) {
    ++taps_;
    const BilinearFootprint f = BilinearAt(u, v, w_, h_, mode_);
    const int xa = std::clamp(f.x0, 0, w_ - 1), xb = std::clamp(f.x0 + 1, 0, w_ - 1);
    const int ya = std::clamp(f.y0, 0, h_ - 1), yb = std::clamp(f.y0 + 1, 0, h_ - 1);
    const uint8_t* a = e_.Pixel(xa, ya);
    const uint8_t* b = e_.Pixel(xb, ya);
    const uint8_t* c = e_.Pixel(xa, yb);
    const uint8_t* d = e_.Pixel(xb, yb);
    return {u_[a[0]] * f.wa + u_[b[0]] * f.wb + u_[c[0]] * f.wc + u_[d[0]] * f.wd,
            u_[a[1]] * f.wa + u_[b[1]] * f.wb + u_[c[1]] * f.wc + u_[d[1]] * f.wd};
  }
  uint64_t Taps() const { return taps_; }

 private:
  const Image8& e_;
  int w_, h_;
  SubTexel mode_;
  const float* u_;
  uint64_t taps_ = 0;
};

// Non-zero when any of the bytes [0, nbytes) of pixel x's channels `mask` is set, OR-ed
// over rows r0..r1 (clamped) and columns x + c0 .. x + c1 (clamped): one row of flags.
void NeighbourFlags(const Image8& img, int y, int r0, int r1, int c0, int c1, uint32_t mask, std::vector<uint8_t>* flags) {
  const int w = img.Width(), h = img.Height();
  std::vector<uint8_t>& f = *flags;
  f.assign(static_cast<size_t>(w), 0);
  std::vector<uint8_t> col(static_cast<size_t>(w), 0);
  for (int dy = r0; dy <= r1; ++dy) {
    const uint8_t* row = img.Row(std::clamp(y + dy, 0, h - 1));
    for (int x = 0; x < w; ++x) {
      uint32_t v;
      std::memcpy(&v, row + 4 * x, 4);
      col[static_cast<size_t>(x)] |= (v & mask) != 0;
    }
  }
  for (int x = 0; x < w; ++x) {
    uint8_t any = 0;
    for (int dx = c0; dx <= c1; ++dx) any |= col[static_cast<size_t>(std::clamp(x + dx, 0, w - 1))];
    f[static_cast<size_t>(x)] = any;
  }
}

Image8 WeightsFast(const Image8& edges, const SmaaParams& p, uint64_t* taps) {
  const int w = edges.Width(), h = edges.Height();
  const Frame f(w, h);
  Image8 blend(w, h, 4, 0);
  const Image8& area_tex = SmaaAreaTexture();
  const Image8& search_tex = SmaaSearchTexture();
  std::vector<uint64_t> t(static_cast<size_t>((h + kGrain - 1) / kGrain), 0);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    PlaneEdges reader(edges, p.subtexel);
    BilinearSampler as(area_tex, p.subtexel), ss(search_tex, p.subtexel);
    smaa_detail::WeightsShader<PlaneEdges> shader(reader, as, ss, p, f);
    std::vector<uint8_t> flags;
    uint64_t skipped = 0;
    for (int y = y0; y < y1; ++y) {
      NeighbourFlags(edges, y, -1, 1, -1, 1, 0x0000FFFFu, &flags);  // r and g bytes
      for (int x = 0; x < w; ++x) {
        if (!flags[static_cast<size_t>(x)]) {
          ++skipped;  // its one fetch returns (0, 0): weights 0
          continue;
        }
        const Float4 wt = shader.Run(x, y);
        uint8_t* o = blend.Pixel(x, y);
        o[0] = QuantizeUnorm8(wt.r);
        o[1] = QuantizeUnorm8(wt.g);
        o[2] = QuantizeUnorm8(wt.b);
        o[3] = QuantizeUnorm8(wt.a);
      }
    }
    t[static_cast<size_t>(y0 / kGrain)] = skipped + reader.Taps() + as.Taps() + ss.Taps();
  });
  for (uint64_t v : t) *taps += v;
  return blend;
}

Image8 BlendFast(const Image8& in, const Image8& blend, const SmaaParams& p, uint64_t* taps) {
  const int w = in.Width(), h = in.Height();
  const Frame f(w, h);
  const bool shortcut = w <= kMaxShortcutSize && h <= kMaxShortcutSize;
  Image8 out(w, h, 4);
  std::vector<uint64_t> t(static_cast<size_t>((h + kGrain - 1) / kGrain), 0);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    BilinearSampler bs(blend, p.subtexel), cs(in, p.subtexel);
    std::vector<uint8_t> flags;
    uint64_t copied = 0;
    for (int y = y0; y < y1; ++y) {
      if (shortcut) {
        NeighbourFlags(blend, y, -1, 2, -1, 2, 0xFFFFFFFFu, &flags);
      } else {
        flags.assign(static_cast<size_t>(w), 1);
      }
      const uint8_t* src = in.Row(y);
      uint8_t* dst = out.Row(y);
      for (int x = 0; x < w; ++x) {
        if (!flags[static_cast<size_t>(x)]) {
          copied += 4;  // three blend fetches and the colour fetch of a = 0
          dst[4 * x] = src[4 * x];
          dst[4 * x + 1] = src[4 * x + 1];
          dst[4 * x + 2] = src[4 * x + 2];
          dst[4 * x + 3] = 255;
          continue;
        }
        smaa_detail::BlendPixel(bs, cs, f, x, y, dst + 4 * x);
      }
    }
    t[static_cast<size_t>(y0 / kGrain)] = copied + bs.Taps() + cs.Taps();
  });
  for (uint64_t v : t) *taps += v;
  return out;
}

}  // namespace

Image8 Smaa(const Image8& in, const SmaaParams& params, const std::string& debug_view, PostStats* stats) {
  AALAB_CHECK(in.Channels() == 4, "SMAA needs an RGBA8 frame");
  AALAB_CHECK(params.max_search_steps >= 0 && params.max_search_steps_diag >= 0, "SMAA search steps must be >= 0");
  const int view = smaa_detail::ParseView(debug_view);
  if (in.Empty()) return in;
  uint64_t taps = 0;
  const Image8 edges = params.detection == SmaaParams::Detection::kLuma ? EdgesLuma(in, params, &taps)
                                                                        : EdgesColor(in, params, &taps);
  if (view == 1) return smaa_detail::EdgesView(edges);
  const Image8 blend = WeightsFast(edges, params, &taps);
  if (view == 2) return smaa_detail::WeightsView(blend);
  Image8 out = BlendFast(in, blend, params, &taps);
  if (stats) stats->taps += taps;
  return out;
}

}  // namespace aalab
