// Intel Conservative Morphological Anti-Aliasing 2.3 (CMAA2), single sample.
//
// Port of Projects/CMAA2/CMAA2/CMAA2.hlsl of GameTechDev/CMAA2 at commit 071c6b08 (Apache-2.0,
// © 2018 Intel Corporation, author Filip Strugar), written from reading the shader, pass by
// pass: EdgesColor2x2CS, ComputeDispatchArgsCS, ProcessCandidatesCS (with
// CMAA2_COLLECT_EXPAND_BLEND_ITEMS), DeferredColorApply2x2CS. Configuration as its sample
// runs an 8-bit sRGB frame: the input view is R8G8B8A8_UNORM_SRGB (loads return linear
// colour), the output a typed R8G8B8A8_UNORM UAV with CMAA2_UAV_STORE_CONVERT_TO_SRGB
// (LINEAR_to_SRGB in the shader, then the UNORM store), CMAA_MSAA_SAMPLE_COUNT 1,
// CMAA_PACK_SINGLE_SAMPLE_EDGE_TO_HALF_WIDTH 1, CMAA2_SUPPORT_HDR_COLOR_RANGE 0 (the
// R11G11B10 "E4" packing of the deferred colours), no half precision.
//
// Methods (family cmaa2): cmaa2-low, cmaa2-medium, cmaa2-high, cmaa2-ultra =
// CMAA2_STATIC_QUALITY_PRESET 0..3 (edge thresholds 0.15, 0.10, 0.07, 0.05).
// Parameters: extra_sharpness (0/1: CMAA2_EXTRA_SHARPNESS), edges (luma: the default
// CMAA2_EDGE_DETECTION_LUMA_PATH 1, sqrt-colour Rec. 601 luma computed in place; color: path
// 0, weighted per-channel differences; paths 2 and 3 read a precomputed luma, which aalab's
// frames do not carry).
//
// Order. The shader appends to lists with atomics (the candidate list, the per-group blend
// item buffer, the per-quad linked lists of colour samples), so the order of those lists is
// whatever order the GPU's threads reach the atomics in. The port fixes one: workgroups in
// dispatch order (x fastest), and inside a workgroup "lanes" threads run in lock step (each
// statement for every lane of a wave, in lane order, waves one after another between
// barriers; Cmaa2Params::lanes = 32 in aalab, the oracle sets 4, llvmpipe's SSE width). What the order
// changes: (1) the float sum of a pixel's samples in DeferredColorApply2x2CS (the list is
// walked newest first) — last-bit differences of the linear colour, rarely a byte;
// (2) which Z shapes overflow the 768-item groupshared buffer (their samples are then
// blended with the exact lerp factor instead of its 10-bit code); (3) which items a quad
// with more than 32 items drops. tests/oracle/cmaa2_oracle_test.cpp measures each.
//
// Where the shader is undefined or reads what nobody wrote (rule: do the safe thing):
//   * Loads outside the frame (colour and edges): D3D returns 0, and the shader relies on it
//     (edge detection runs over a one-block apron, the line search walks off the frame). The
//     port returns 0, so frame borders are edges against black as on D3D hardware; the edge
//     texture is ceil(W/2) texels (two pixels each) wide, as the sample allocates it.
//   * ProcessCandidatesCS: a Z shape whose items do not fit the 768-slot buffer still adds
//     its count, and the expansion loop then reads min(768, count) slots, some never written
//     in this dispatch (stale groupshared memory). The port skips unwritten slots.
//   * DeferredColorApply2x2CS stores alpha 0; aalab keeps the frame's alpha.
// Arithmetic as Mesa's lavapipe evaluates the SPIR-V that glslang makes of it (the oracle):
// float32, x/y correctly rounded, lerp as a + t·(b − a), f32tof16 rounding to nearest even
// (tests/oracle/cmaa2_oracle_test.cpp: x·(1/y) or a truncating f32tof16 match fewer pixels;
// docs/cmaa2.md gives the figures and the few pixels that still differ).
#include "methods/cmaa2.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <tuple>

#include "core/error.h"
#include "core/parallel.h"
#include "core/sampler.h"
#include "methods/families.h"

namespace aalab {

namespace {

constexpr int kInKernel = 16;            // CMAA2_CS_INPUT_KERNEL_SIZE_X/Y
constexpr int kOutKernel = 14;           // CMAA2_CS_OUTPUT_KERNEL_SIZE_X/Y
constexpr int kGroup = 128;              // CMAA2_PROCESS_CANDIDATES_NUM_THREADS
constexpr int kSlmItems = 768;           // CMAA2_BLEND_ITEM_SLM_SIZE
constexpr int kApplyWalk = 32;           // DeferredColorApply2x2CS's maxLoops
constexpr float kMaxLineLength = 86.0f;  // c_maxLineLength

float Div(float a, float b) { return a / b; }  // IEEE division (what lavapipe runs; see the doc block)
float Sat(float x) { return std::fminf(std::fmaxf(x, 0.0f), 1.0f); }
float Lerp(float a, float b, float t) { return a + t * (b - a); }

using V3 = std::array<float, 3>;
struct V4 {
  float r, g, b, a;  // right, bottom, left, top edge (the shader's .rgba)
};

float Dot3(const V3& a, const V3& w) { return a[0] * w[0] + a[1] * w[1] + a[2] * w[2]; }

// Preset constants (CMAA2_STATIC_QUALITY_PRESET, CMAA2_EXTRA_SHARPNESS).
struct Consts {
  float threshold, contrast, blur, dampen;
  bool sharp;
};
Consts ConstsOf(const Cmaa2Params& p) {
  static constexpr float kThr[4] = {0.15f, 0.10f, 0.07f, 0.05f};
  return {kThr[p.preset], p.extra_sharpness ? 0.15f : 0.10f, p.extra_sharpness ? 0.07f : 0.10f,
          p.extra_sharpness ? 0.11f : 0.15f, p.extra_sharpness};
}

uint16_t F32ToF16(float f) {  // f32tof16 for f in [0, 2): round to nearest even
  const uint32_t u = std::bit_cast<uint32_t>(f);
  const int e = static_cast<int>((u >> 23) & 0xffu) - 127 + 15;
  const uint32_t m = (u & 0x7fffffu) | 0x800000u;
  if (e < -10) return 0;
  const int shift = e >= 1 ? 13 : 14 - e;
  uint32_t h = m >> shift;
  const uint32_t rest = m & ((1u << shift) - 1u), half = 1u << (shift - 1);
  if (rest > half || (rest == half && (h & 1u))) ++h;
  if (e >= 1)
    h = (static_cast<uint32_t>(e) << 10) + (h - 0x400u);  // drop the implicit bit; carries roll into the exponent
  return static_cast<uint16_t>(h);
}

float F16ToF32(uint32_t h) {  // f16tof32 of a non-negative half
  const uint32_t e = (h >> 10) & 0x1fu, m = h & 0x3ffu;
  if (e == 0) return static_cast<float>(m) * 0x1p-24f;
  return std::bit_cast<float>(((e + 112u) << 23) | (m << 13));
}

// The frame as the shader's loads see it, zero outside.
struct Frame {
  int w, h;
  const std::vector<float>* rgb;
  V3 At(int x, int y) const {
    if (x < 0 || y < 0 || x >= w || y >= h) return {0.0f, 0.0f, 0.0f};
    const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 3;
    return {(*rgb)[i], (*rgb)[i + 1], (*rgb)[i + 2]};
  }
};

// EdgesColor2x2CS, position by position: every value a thread reads from its neighbours in
// groupshared memory is the same function of the pixel position, so the pass is computed per
// pixel. Edge texture: pixels [0, W2) x [0, H), W2 = 2·ceil(W/2); 4 bits each (R 1, G 2, B 4, A 8).
struct Edges {
  int w2, h;
  std::vector<uint8_t> bits;
  uint32_t Load(int x, int y) const {  // LoadEdge: 0 outside the texture
    if (x < 0 || y < 0 || x >= w2 || y >= h) return 0;
    return bits[static_cast<size_t>(y) * static_cast<size_t>(w2) + static_cast<size_t>(x)];
  }
  V4 LoadF(int x, int y) const {  // UnpackEdgesFlt
    const uint32_t e = Load(x, y);
    return {(e & 1u) ? 1.0f : 0.0f, (e & 2u) ? 1.0f : 0.0f, (e & 4u) ? 1.0f : 0.0f, (e & 8u) ? 1.0f : 0.0f};
  }
};

Edges DetectEdges(const Frame& f, const Cmaa2Params& p, const Consts& k) {
  const int w2 = (f.w + 1) / 2 * 2, h = f.h;
  // Raw differences dR (to the right) and dB (below) on [-2, w2+1] x [-2, h+1].
  const int m = 2, dw = w2 + 4, dh = h + 4;
  std::vector<float> dR(static_cast<size_t>(dw) * static_cast<size_t>(dh)), dB(dR.size());
  const V3 wts{0.299f, 0.587f, 0.114f};
  auto sq = [](V3 c) { return V3{std::sqrt(c[0]), std::sqrt(c[1]), std::sqrt(c[2])}; };
  ParallelForChunks(dh, 16, [&](int y0, int y1) {
    for (int yy = y0; yy < y1; ++yy) {
      const int y = yy - m;
      for (int xx = 0; xx < dw; ++xx) {
        const int x = xx - m;
        const V3 c = sq(f.At(x, y)), r = sq(f.At(x + 1, y)), b = sq(f.At(x, y + 1));
        const size_t i = static_cast<size_t>(yy) * static_cast<size_t>(dw) + static_cast<size_t>(xx);
        if (p.color_edges) {  // EdgeDetectColorCalcDiff on ProcessColorForEdgeDetect (sqrt) colours
          dR[i] = Dot3({std::fabs(c[0] - r[0]), std::fabs(c[1] - r[1]), std::fabs(c[2] - r[2])}, wts);
          dB[i] = Dot3({std::fabs(c[0] - b[0]), std::fabs(c[1] - b[1]), std::fabs(c[2] - b[2])}, wts);
        } else {  // RGBToLumaForEdges, ComputeEdgeLuma
          const float lc = Dot3(c, wts);
          dR[i] = std::fabs(lc - Dot3(r, wts));
          dB[i] = std::fabs(lc - Dot3(b, wts));
        }
      }
    }
  });
  auto at = [&](const std::vector<float>& d, int x, int y) {
    return d[static_cast<size_t>(y + m) * static_cast<size_t>(dw) + static_cast<size_t>(x + m)];
  };
  // Local contrast adaptation (ComputeLocalContrastV/H) and the threshold: edge right of
  // (x, y) and edge below (x, y).
  auto right = [&](int x, int y) {
    const float lc =
        std::max(std::max(at(dB, x, y - 1), at(dB, x, y)), std::max(at(dB, x + 1, y - 1), at(dB, x + 1, y))) *
        k.contrast;
    return (at(dR, x, y) - lc) > k.threshold;
  };
  auto below = [&](int x, int y) {
    const float lc =
        std::max(std::max(at(dR, x - 1, y), at(dR, x, y)), std::max(at(dR, x - 1, y + 1), at(dR, x, y + 1))) *
        k.contrast;
    return (at(dB, x, y) - lc) > k.threshold;
  };
  Edges e{w2, h, std::vector<uint8_t>(static_cast<size_t>(w2) * static_cast<size_t>(h))};
  ParallelForChunks(h, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < w2; ++x) {
        const uint32_t bits = (right(x, y) ? 1u : 0u) | (below(x, y) ? 2u : 0u) | (right(x - 1, y) ? 4u : 0u) |
                              (below(x, y - 1) ? 8u : 0u);
        e.bits[static_cast<size_t>(y) * static_cast<size_t>(w2) + static_cast<size_t>(x)] = static_cast<uint8_t>(bits);
      }
    }
  });
  return e;
}

bool IsCandidate(uint32_t e) {  // two edges meeting at a corner
  const bool r = e & 1u, g = e & 2u, b = e & 4u, a = e & 8u;
  return (r && g) || (g && b) || (b && a) || (a && r);
}

// The candidate list in the port's order: workgroups of EdgesColor2x2CS in dispatch order;
// in each, waves of `lanes` threads; per wave the unrolled i = 0..3 loop, lanes in order.
std::vector<std::pair<int, int>> Candidates(const Edges& e, int w, int h, int lanes) {
  std::vector<std::pair<int, int>> out;
  const int gx_n = ((w + 1) / 2 + kOutKernel - 1) / kOutKernel, gy_n = ((h + 1) / 2 + kOutKernel - 1) / kOutKernel;
  for (int gy = 0; gy < gy_n; ++gy) {
    for (int gx = 0; gx < gx_n; ++gx) {
      for (int wave = 0; wave < kInKernel * kInKernel; wave += lanes) {
        for (int i = 0; i < 4; ++i) {
          for (int t = wave; t < wave + lanes; ++t) {
            const int tx = t % kInKernel, ty = t / kInKernel;
            if (tx == 0 || ty == 0 || tx == kInKernel - 1 || ty == kInKernel - 1) continue;
            const int x = (gx * kOutKernel + tx - 1) * 2 + i % 2, y = (gy * kOutKernel + ty - 1) * 2 + i / 2;
            if (x < w && y < h && IsCandidate(e.Load(x, y))) out.emplace_back(x, y);
          }
        }
      }
    }
  }
  return out;
}

// ComputeSimpleShapeBlendValues(..., dontTestShapeValidity = true): (left, above, right, below).
V4 SimpleShapeBlend(const V4& e, const V4& l, const V4& r, const V4& t, const V4& b, const Consts& k) {
  float fromRight = e.r, fromBelow = e.g, fromLeft = e.b, fromAbove = e.a;
  float blur = k.blur;
  const float n = ((e.r + e.g) + e.b) + e.a;
  const float around = ((l.b + r.r) + t.r + b.r) + ((l.g + r.g) + t.b + b.g) + ((l.a + r.a) + t.a + b.b);
  if (n == 2.0f) {
    blur *= 0.75f;
    const float kk = 0.9f;
    fromRight += kk * (e.g * t.r * (1.0f - l.g) + e.a * b.r * (1.0f - l.a));
    fromBelow += kk * (e.b * r.g * (1.0f - t.b) + e.r * l.g * (1.0f - t.r));
    fromLeft += kk * (e.a * b.b * (1.0f - r.a) + e.g * t.b * (1.0f - r.g));
    fromAbove += kk * (e.r * l.a * (1.0f - b.r) + e.b * r.a * (1.0f - b.b));
  }
  blur *= k.sharp ? Sat(1.15f - Div(around, 8.0f)) : Sat(1.30f - Div(around, 10.0f));
  return {fromLeft * blur, fromAbove * blur, fromRight * blur, fromBelow * blur};
}

// DetectZsHorizontal: (invertedZScore, normalZScore).
std::pair<float, float> DetectZs(const V4& e, const V4& m1, const V4& p1, const V4& p2) {
  float inv = e.r * e.g * p1.a;
  inv *= 2.0f + (m1.g + p2.a) - (e.a + p1.g) - 0.7f * (p2.g + m1.a + e.b + p1.r);
  float nrm = e.r * e.a * p1.g;
  nrm *= 2.0f + (m1.a + p2.g) - (e.g + p1.a) - 0.7f * (p2.a + m1.g + e.b + p1.r);
  return {inv, nrm};
}
V4 Argb(const V4& v) { return {v.a, v.r, v.g, v.b}; }

struct Item {  // one deferred colour sample
  uint32_t packed;
  uint8_t offset;  // (y % 2)·2 + x % 2 in the quad
  bool complex;
};

class Processor {
 public:
  Processor(const Frame& f, const Edges& e, const Consts& k, Cmaa2Stats& s)
      : f_(f),
        e_(e),
        k_(k),
        s_(s),
        qw_((f.w + 1) / 2),
        quads_(static_cast<size_t>(qw_) * static_cast<size_t>((f.h + 1) / 2)) {}

  // ProcessCandidatesCS for one workgroup (up to 128 candidates), waves of `lanes` threads.
  void Group(const std::pair<int, int>* cand, int n, int lanes) {
    struct Z {
      int x, y;
      bool horizontal, inverted;
      float quality, left, right;
      bool in_slm;
      int slm_index;
    };
    std::vector<Slot> slm(kSlmItems);
    int slm_count = 0;
    for (int wave = 0; wave < n; wave += lanes) {
      const int end = std::min(n, wave + lanes);
      std::vector<Z> zs;
      for (int t = wave; t < end; ++t) SimpleShape(cand[t].first, cand[t].second);
      for (int t = wave; t < end; ++t) {
        Z z{cand[t].first, cand[t].second, true, false, 0.0f, 0.0f, 0.0f, false, 0};
        if (!DetectZ(z.x, z.y, z.horizontal, z.inverted, z.quality, z.left, z.right)) continue;
        ++s_.z_shapes;
        const int count = ItemCount(z.left, z.right);
        z.slm_index = slm_count;
        slm_count += count;
        z.in_slm = z.slm_index + count <= kSlmItems;
        if (z.in_slm) {
          CollectBlendZs(z.x, z.y, z.horizontal, z.inverted, z.quality, z.left, z.right, slm.data() + z.slm_index);
        } else {
          ++s_.slm_fallbacks;
          zs.push_back(z);
        }
      }
      // BlendZs for the Zs that did not fit, the wave's loops in lock step.
      for (int step = 0;; ++step) {
        bool any = false;
        for (const Z& z : zs) any |= BlendZ(z.x, z.y, z.horizontal, z.inverted, z.quality, z.left, z.right, step);
        if (!any) break;
      }
    }
    // The expansion loop: thread t handles slots loop·128 + t; waves in order, loops inside.
    const int total = std::min(kSlmItems, slm_count);
    for (int wave = 0; wave < kGroup; wave += lanes) {
      for (int loop = 0; loop * kGroup < total; ++loop) {
        for (int t = wave; t < wave + lanes; ++t) {
          const int index = loop * kGroup + t;
          if (index < total && slm[static_cast<size_t>(index)].used) Expand(slm[static_cast<size_t>(index)]);
        }
      }
    }
  }

  // DeferredColorApply2x2CS: the linear colour of each written pixel.
  void Apply(std::vector<float>& rgb, std::vector<uint8_t>& written, bool reverse) const {
    ParallelForChunks(static_cast<int>(quads_.size()), 256, [&](int q0, int q1) {
      for (int q = q0; q < q1; ++q) {
        const std::vector<Item>& list = quads_[static_cast<size_t>(q)];
        const int walk = std::min(static_cast<int>(list.size()), kApplyWalk);
        for (int o = 0; o < 4; ++o) {
          const int x = (q % qw_) * 2 + o % 2, y = (q / qw_) * 2 + o / 2;
          if (x >= f_.w || y >= f_.h) continue;
          float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
          for (int i = 0; i < walk; ++i) {  // newest first (the list's head), at most 32 items
            const int j = reverse ? static_cast<int>(list.size()) - walk + i : static_cast<int>(list.size()) - 1 - i;
            const Item& it = list[static_cast<size_t>(j)];
            if (it.offset != o) continue;
            const V3 c = Unpack(it.packed);
            const float wgt = 0.8f + 1.0f * (it.complex ? 1.0f : 0.0f);
            for (int ch = 0; ch < 3; ++ch) sum[ch] += c[static_cast<size_t>(ch)] * wgt;
            sum[3] += wgt;
          }
          if (sum[3] == 0.0f) continue;
          const size_t pi = static_cast<size_t>(y) * static_cast<size_t>(f_.w) + static_cast<size_t>(x);
          for (int ch = 0; ch < 3; ++ch) rgb[pi * 3 + static_cast<size_t>(ch)] = Div(sum[ch], sum[3]);
          written[pi] = 1;
        }
      }
    });
  }

  void CountTruncated() {
    for (const auto& l : quads_) s_.truncated_quads += l.size() > static_cast<size_t>(kApplyWalk) ? 1 : 0;
  }

  static uint32_t Pack(const V3& c) {  // Pack_R11G11B10_E4_FLOAT
    const float hi = std::bit_cast<float>(0x3FFFFFFFu);
    auto h = [&](float v) { return static_cast<uint32_t>(F32ToF16(std::fminf(std::fmaxf(v, 0.0f), hi))); };
    return (((h(c[0]) + 4u) >> 3) & 0x7FFu) | (((h(c[1]) + 4u) << 8) & 0x3FF800u) |
           (((h(c[2]) + 8u) << 18) & 0xFFC00000u);
  }
  static V3 Unpack(uint32_t v) {
    return {F16ToF32((v << 3) & 0x3FF8u), F16ToF32((v >> 8) & 0x3FF8u), F16ToF32((v >> 18) & 0x3FF0u)};
  }

 private:
  struct Slot {
    bool used = false;
    int x = 0, y = 0;
    bool horizontal = false, inverted = false;
    float step = 0.0f, src = 0.0f;
    uint32_t lerp_code = 0;
  };

  void Store(int x, int y, const V3& c, bool complex) {  // StoreColorSample
    ++s_.blend_items;
    quads_[static_cast<size_t>(y / 2) * static_cast<size_t>(qw_) + static_cast<size_t>(x / 2)].push_back(
        {Pack(c), static_cast<uint8_t>((y % 2) * 2 + x % 2), complex});
  }

  void SimpleShape(int x, int y) {
    const V4 e = e_.LoadF(x, y), l = e_.LoadF(x - 1, y), r = e_.LoadF(x + 1, y), b = e_.LoadF(x, y + 1),
             t = e_.LoadF(x, y - 1);
    const V4 bv = SimpleShapeBlend(e, l, r, t, b, k_);
    const float center = 1.0f - (((bv.r + bv.g) + bv.b) + bv.a);
    V3 out = f_.At(x, y);
    for (float& c : out) c *= center;
    auto add = [&](float wgt, int dx, int dy) {
      if (!(wgt > 0.0f)) return;
      const V3 c = f_.At(x + dx, y + dy);
      for (int ch = 0; ch < 3; ++ch) out[static_cast<size_t>(ch)] += wgt * c[static_cast<size_t>(ch)];
    };
    add(bv.r, -1, 0);  // from left
    add(bv.g, 0, -1);  // from above
    add(bv.b, 1, 0);   // from right
    add(bv.a, 0, 1);   // from below
    Store(x, y, out, false);
  }

  // The complex-shape half of ProcessCandidatesCS up to the call of CollectBlendZs/BlendZs.
  bool DetectZ(int x, int y, bool& horizontal, bool& inverted, float& quality, float& left, float& right) const {
    const V4 e = e_.LoadF(x, y), l = e_.LoadF(x - 1, y), r = e_.LoadF(x + 1, y), b = e_.LoadF(x, y + 1),
             t = e_.LoadF(x, y - 1);
    auto [inv, nrm] = DetectZs(e, l, r, e_.LoadF(x + 2, y));
    float max_score = std::fmaxf(inv, nrm);
    horizontal = true;
    inverted = false;
    if (max_score > 0.0f) inverted = inv > nrm;
    std::tie(inv, nrm) = DetectZs(Argb(e), Argb(b), Argb(t), Argb(e_.LoadF(x, y - 2)));
    const float vert = std::fmaxf(inv, nrm);
    if (vert > max_score) {
      max_score = vert;
      horizontal = false;
      inverted = inv > nrm;
    }
    if (!(max_score > 0.0f)) return false;
    const float q = std::fminf(std::fmaxf(4.0f - max_score, 0.0f), 3.0f);
    quality = k_.sharp ? std::nearbyint(q) : std::floor(q);
    FindZLineLengths(x, y, horizontal, inverted, left, right);
    left -= quality;
    right -= quality;
    return (left + right) >= 5.0f;
  }

  void FindZLineLengths(int x, int y, bool horizontal, bool inverted, float& left, float& right) const {
    uint32_t mask_left = horizontal ? 0x08u : 0x04u, mask_right = horizontal ? 0x02u : 0x01u;
    if (inverted) std::swap(mask_left, mask_right);
    const int sx = horizontal ? 1 : 0, sy = horizontal ? 0 : -1;  // stepRight
    bool go_left = true, go_right = true;
    left = 1.0f;
    right = 1.0f;
    for (;;) {
      const int ll = static_cast<int>(left), rr = static_cast<int>(right) + 1;
      const uint32_t edge_left = e_.Load(x - sx * ll, y - sy * ll);
      const uint32_t edge_right = e_.Load(x + sx * rr, y + sy * rr);
      go_left = go_left && (edge_left & mask_left) == mask_left;
      go_right = go_right && (edge_right & mask_right) == mask_right;
      left += go_left ? 1.0f : 0.0f;
      right += go_right ? 1.0f : 0.0f;
      float max_lr = std::fmaxf(right, left);
      if (!go_left && !go_right) max_lr = kMaxLineLength;
      const float limit = k_.sharp ? 1.20f * std::fminf(right, left) - 0.20f : 1.25f * std::fminf(right, left) - 0.25f;
      if (max_lr >= std::fminf(kMaxLineLength, limit)) break;
    }
  }

  // The loop bounds and lerp ramp shared by CollectBlendZs and BlendZs.
  struct Ramp {
    float from, to, step, from_k, dampen;
  };
  Ramp RampOf(float quality, float left, float right) const {
    const float left_odd = 0.22f * std::fmod(left, 2.0f), right_odd = 0.22f * std::fmod(right, 2.0f);
    Ramp r;
    r.dampen = Sat((left + right - quality) * k_.dampen);
    r.from = -std::floor((left + 1.0f) * 0.5f) + 1.0f;
    r.to = std::floor((right + 1.0f) * 0.5f);
    const float total = (r.to - r.from) + 1.0f - left_odd - right_odd;
    r.step = 1.0f / total;
    r.from_k = (0.5f - left_odd - r.from) * r.step;
    return r;
  }
  int ItemCount(float left, float right) const {
    const Ramp r = RampOf(0.0f, left, right);
    return static_cast<int>(r.to - r.from + 1.0f);
  }
  static float LerpK(const Ramp& r, float i, float& src) {
    const float second = i > 0.0f ? 1.0f : 0.0f;
    src = 1.0f - second * 2.0f;
    float k = (r.step * i + r.from_k) * src + second;
    return k * r.dampen;
  }

  void CollectBlendZs(int x, int y, bool horizontal, bool inverted, float quality, float left, float right,
                      Slot* out) const {
    const Ramp r = RampOf(quality, left, right);
    for (float i = r.from; i <= r.to; i += 1.0f) {
      Slot s;
      s.used = true;
      s.x = x;
      s.y = y;
      s.horizontal = horizontal;
      s.inverted = inverted;
      const float k = LerpK(r, i, s.src);
      s.step = i;
      s.lerp_code = static_cast<uint32_t>(Sat(k) * 1023.0f + 0.5f);
      *out++ = s;
    }
  }

  // One iteration (number `step`) of BlendZs's loop; false once past its end.
  bool BlendZ(int x, int y, bool horizontal, bool inverted, float quality, float left, float right, int step) {
    const Ramp r = RampOf(quality, left, right);
    const float i = r.from + static_cast<float>(step);
    if (!(i <= r.to)) return false;
    float src = 0.0f;
    const float k = LerpK(r, i, src);
    Blend(x, y, horizontal, inverted, i, src, k);
    return true;
  }

  void Expand(const Slot& s) {
    Blend(s.x, s.y, s.horizontal, s.inverted, s.step, s.src, Div(static_cast<float>(s.lerp_code), 1023.0f));
  }

  void Blend(int x, int y, bool horizontal, bool inverted, float i, float src, float k) {
    const int ii = static_cast<int>(i), s = static_cast<int>(src);
    const int px = x + (horizontal ? ii : 0), py = y - (horizontal ? 0 : ii);
    int bx = horizontal ? 0 : -1, by = horizontal ? -1 : 0;
    if (inverted) {
      bx = -bx;
      by = -by;
    }
    const V3 center = f_.At(px, py), from = f_.At(px + bx * s, py + by * s);
    V3 out;
    for (int ch = 0; ch < 3; ++ch)
      out[static_cast<size_t>(ch)] = Lerp(center[static_cast<size_t>(ch)], from[static_cast<size_t>(ch)], k);
    Store(px, py, out, true);
  }

  const Frame& f_;
  const Edges& e_;
  const Consts& k_;
  Cmaa2Stats& s_;
  int qw_;
  std::vector<std::vector<Item>> quads_;
};

}  // namespace

float Cmaa2SrgbToLinear(uint8_t k) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double v = i / 255.0;
      t[static_cast<size_t>(i)] = static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table[k];
}

float Cmaa2LinearToSrgb(float x) {
  if (x < 0.0031308f) return x * 12.92f;
  return 1.055f * std::pow(std::fabs(x), 1.0f / 2.4f) - 0.055f;
}

std::array<float, 3> Cmaa2PackUnpack(const std::array<float, 3>& rgb) {
  return Processor::Unpack(Processor::Pack(rgb));
}

std::vector<float> Cmaa2Linear(const std::vector<float>& rgb, int w, int h, const Cmaa2Params& p,
                               std::vector<uint8_t>* written, Cmaa2Stats* stats) {
  AALAB_CHECK(w > 0 && h > 0 && rgb.size() == static_cast<size_t>(w) * static_cast<size_t>(h) * 3,
              "CMAA2 needs a non-empty frame");
  AALAB_CHECK(w <= 8192 && h <= 8192, "CMAA2 packs coordinates in 14 bits (at most 8192 x 8192 here)");
  AALAB_CHECK(p.preset >= 0 && p.preset <= 3, "CMAA2 preset must be 0..3");
  AALAB_CHECK(p.lanes >= 1 && 128 % p.lanes == 0, "CMAA2 lanes must divide 128");
  Cmaa2Stats local;
  Cmaa2Stats& s = stats ? *stats : local;
  const Consts k = ConstsOf(p);
  const Frame f{w, h, &rgb};
  const Edges e = DetectEdges(f, p, k);
  const auto cand = Candidates(e, w, h, p.lanes);
  s.candidates += cand.size();
  Processor proc(f, e, k, s);
  for (size_t g = 0; g < cand.size(); g += kGroup) {
    proc.Group(cand.data() + g, static_cast<int>(std::min(cand.size() - g, static_cast<size_t>(kGroup))), p.lanes);
  }
  proc.CountTruncated();
  std::vector<float> out = rgb;
  std::vector<uint8_t> wr(static_cast<size_t>(w) * static_cast<size_t>(h), 0);
  proc.Apply(out, wr, p.reverse_sum);
  for (uint8_t v : wr) s.pixels_written += v;
  if (written) *written = std::move(wr);
  return out;
}

Image8 Cmaa2(const Image8& in, const Cmaa2Params& p, Cmaa2Stats* stats) {
  AALAB_CHECK(in.Channels() == 4 && !in.Empty(), "CMAA2 needs a non-empty RGBA8 frame");
  const int w = in.Width(), h = in.Height();
  std::vector<float> rgb(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
  ParallelForChunks(h, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < w; ++x) {
        for (int ch = 0; ch < 3; ++ch) {
          rgb[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 3 +
              static_cast<size_t>(ch)] = Cmaa2SrgbToLinear(in.Pixel(x, y)[ch]);
        }
      }
    }
  });
  std::vector<uint8_t> written;
  const std::vector<float> lin = Cmaa2Linear(rgb, w, h, p, &written, stats);
  // Untouched pixels keep the input's bytes; written ones get the stored colour and keep the
  // input's alpha: every byte written once, rows in parallel, no copy of the frame first.
  Image8 out(w, h, 4, kUninitialized);
  ParallelForChunks(h, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const uint8_t* src = in.Row(y);
      uint8_t* dst = out.Row(y);
      std::memcpy(dst, src, static_cast<size_t>(w) * 4);
      for (int x = 0; x < w; ++x) {
        const size_t pi = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
        if (!written[pi]) continue;
        for (int ch = 0; ch < 3; ++ch)
          dst[4 * x + ch] = StoreUnorm8(Cmaa2LinearToSrgb(lin[pi * 3 + static_cast<size_t>(ch)]));
      }
    }
  });
  return out;
}

// ---- Registry rows ----------------------------------------------------------------------

namespace {

MethodEntry Cmaa2Entry(const std::string& name, int preset, const std::string& what) {
  std::vector<ParamDef> defs = {
      IntParam("extra_sharpness", 0, 0, 1, "CMAA2_EXTRA_SHARPNESS: 1 keeps more text and shape detail, less AA"),
      ChoiceParam("edges", "luma", {"luma", "color"},
                  "edge detection: luma (CMAA2_EDGE_DETECTION_LUMA_PATH 1, the default) or color (path 0)")};
  return {name, "CMAA2 " + what + " (CMAA2_STATIC_QUALITY_PRESET " + std::to_string(preset) + ")", defs,
          [name, preset](const ParamValues& v) {
            Cmaa2Params cp;
            cp.preset = preset;
            cp.extra_sharpness = v.Int("extra_sharpness") == 1;
            cp.color_edges = v.Choice("edges") == "color";
            MethodPlan plan;
            plan.name = name;
            plan.params = v;
            plan.config = cp;
            plan.post = [cp, name](const Image8& in, const PostOptions& options, PostStats* stats) {
              if (!options.debug_view.empty()) {
                throw UserError("method '" + name + "' has no debug view '" + options.debug_view + "'");
              }
              Cmaa2Stats s;
              Image8 out = Cmaa2(in, cp, &s);
              // Taps: 8 colour loads per pixel for the edges, and per candidate its edge and colour loads.
              if (stats)
                stats->taps +=
                    8u * static_cast<uint64_t>(in.Width()) * static_cast<uint64_t>(in.Height()) + 2u * s.blend_items;
              return out;
            };
            return plan;
          }};
}

}  // namespace

std::vector<MethodEntry> Cmaa2Methods() {
  std::vector<MethodEntry> out;
  out.push_back(Cmaa2Entry("cmaa2-low", 0, "LOW: edge threshold 0.15"));
  out.push_back(Cmaa2Entry("cmaa2-medium", 1, "MEDIUM: edge threshold 0.10"));
  out.push_back(Cmaa2Entry("cmaa2-high", 2, "HIGH, the shader's default: edge threshold 0.07"));
  out.push_back(Cmaa2Entry("cmaa2-ultra", 3, "ULTRA: edge threshold 0.05"));
  for (auto& e : out) e.in_default_list = e.name == "cmaa2-high";  // the shader's default preset
  return out;
}

}  // namespace aalab
