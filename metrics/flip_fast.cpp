// LDR-FLIP, production path: the maths of metrics/flip.cpp (its header block is the
// definition) in float32, laid out for speed. flip.cpp keeps the double-precision
// implementation (flip::ErrorValuesUncached, ColorErrorValues, FeatureErrorValues) that the
// tests compare this path with.
//
// Layout:
//  - The image goes to YCxCz planes (float; the achromatic plane as Ŷ = (Y + 16)/116):
//    metrics/flip_planes.cpp (its header block tells how; declared in flip_fast_internal.h).
//  - The image is cut into fixed chunks of kChunkRows rows (in parallel). A chunk streams its
//    rows through two rings: the horizontal CSF sums (Y, Cx, and the two Cz Gaussians) of the
//    last 2R+1 rows, and the horizontal feature sums (Gaussian, first and second derivative)
//    of the last 2Rf+1 rows; an output row is finished (vertical sums, then the per-pixel
//    colour transform or the feature magnitudes) as soon as its last input row is in. No
//    full-size intermediate plane is written.
//  - Sums run tap-outer, pixel-inner (each output's sum over the taps in a fixed order; the
//    even kernels add the two pixels of one weight first: k(0)·v(0) + Σ k(i)·(v(i) + v(−i))),
//    so the compiler vectorises across pixels; the kernels are compiled for
//    AVX-512, AVX2 and the baseline (target_clones), separate multiplies and adds
//    (-ffp-contract=off): every clone and every thread count gives the same bits.
//  - The reference's half (Hunt-adjusted Lab after the CSF, edge and point magnitudes: 20
//    bytes a pixel) depends on the reference and ppd alone; PrepareReference forms it once
//    per scene and ErrorValues(side, test) computes only the test's half and the error.
//  - The error of a finished row: the arithmetic before and after each library pow in vector
//    lanes, the pow per pixel, skipped where its result is exact (pow(+0, y > 0) = +0, and
//    pow(x, 1) = x for x in [0, 1], which the tests check on every such float). The chunks'
//    rings and row buffers are written before they are read: no zero-fill.
//
// Precision: float32 as NVIDIA's implementations; against the double path per-pixel
// |Δ| ≲ 1e-5 and the mean ≲ 1e-7 (tests/equivalence/metrics_fast_test.cpp, METRICS.md).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "metrics/flip.h"
#include "metrics/flip_fast_internal.h"
#include "metrics/metric.h"

namespace aalab {
namespace flip {
namespace {

using fast_detail::kChunkRows;
using fast_detail::Planes;
using fast_detail::ToPlanes;

constexpr int kLanes = 16;   // outputs kept in registers per block of a horizontal sum
constexpr int kVLanes = 16;  // the same for a vertical sum

int ClampI(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

// Kernels as float.
struct Kernels {
  int rc = 0, rf = 0;                  // CSF and feature radii
  std::vector<float> y, cx, cz1, cz2;  // CSF, 2·rc + 1 taps
  std::vector<float> g, dg, ddg;       // features, 2·rf + 1 taps
};

Kernels MakeKernels(double ppd) {
  const SpatialKernels s = MakeSpatialKernels(ppd);
  const FeatureKernels f = MakeFeatureKernels(ppd);
  Kernels k;
  k.rc = s.radius;
  k.rf = f.radius;
  auto to_float = [](const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); };
  k.y = to_float(s.y);
  k.cx = to_float(s.cx);
  k.cz1 = to_float(s.cz1);
  k.cz2 = to_float(s.cz2);
  k.g = to_float(f.g);
  k.dg = to_float(f.dg);
  k.ddg = to_float(f.ddg);
  return k;
}

// ---- horizontal passes (one row; `py` etc. are the row padded by the radius, replicated)

// The CSF kernels are even (tap r − i equals tap r + i bit for bit: both are computed from
// the same squared offset), so each sum pairs the two taps of one weight:
// k(0)·v(x) + Σ_{i=1..r} k(i)·(v(x+i) + v(x−i)), i in increasing order.
AALAB_FLIP_CLONES
void HorizontalCsf(const float* py, const float* pcx, const float* pcz, int w, int r, const float* ky, const float* kcx,
                   const float* kcz1, const float* kcz2, float* oy, float* ocx, float* ocz1, float* ocz2) {
  int x = 0;
  for (; x + kLanes <= w; x += kLanes) {
    float sy[kLanes], scx[kLanes], s1[kLanes], s2[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      sy[l] = ky[r] * py[x + l + r];
      scx[l] = kcx[r] * pcx[x + l + r];
      s1[l] = kcz1[r] * pcz[x + l + r];
      s2[l] = kcz2[r] * pcz[x + l + r];
    }
    for (int i = 1; i <= r; ++i) {
      const float a = ky[r + i], b = kcx[r + i], c = kcz1[r + i], d = kcz2[r + i];
      for (int l = 0; l < kLanes; ++l) {
        const int q = x + l + r;
        const float z = pcz[q + i] + pcz[q - i];
        sy[l] += a * (py[q + i] + py[q - i]);
        scx[l] += b * (pcx[q + i] + pcx[q - i]);
        s1[l] += c * z;
        s2[l] += d * z;
      }
    }
    for (int l = 0; l < kLanes; ++l) {
      oy[x + l] = sy[l];
      ocx[x + l] = scx[l];
      ocz1[x + l] = s1[l];
      ocz2[x + l] = s2[l];
    }
  }
  for (; x < w; ++x) {
    const int q = x + r;
    float sy = ky[r] * py[q], scx = kcx[r] * pcx[q], s1 = kcz1[r] * pcz[q], s2 = kcz2[r] * pcz[q];
    for (int i = 1; i <= r; ++i) {
      const float z = pcz[q + i] + pcz[q - i];
      sy += ky[r + i] * (py[q + i] + py[q - i]);
      scx += kcx[r + i] * (pcx[q + i] + pcx[q - i]);
      s1 += kcz1[r + i] * z;
      s2 += kcz2[r + i] * z;
    }
    oy[x] = sy;
    ocx[x] = scx;
    ocz1[x] = s1;
    ocz2[x] = s2;
  }
}

// Gaussian, first and second derivative along x of the padded Ŷ row (derivatives in the
// cancellation-free form of flip.cpp: Σ_{i>0} dg(i)·(v(x+i) − v(x−i)), Σ_{i>0}
// ddg(i)·((v(x+i) − v(x)) + (v(x−i) − v(x)))).
AALAB_FLIP_CLONES
void HorizontalFeatures(const float* pv, int w, int r, const float* g, const float* dg, const float* ddg, float* og,
                        float* odg, float* oddg) {
  int x = 0;
  for (; x + kLanes <= w; x += kLanes) {
    float sg[kLanes], sd[kLanes] = {}, sdd[kLanes] = {};
    for (int l = 0; l < kLanes; ++l) sg[l] = g[r] * pv[x + l + r];
    for (int i = 1; i <= r; ++i) {
      const float k = g[r + i], a = dg[r + i], b = ddg[r + i];
      for (int l = 0; l < kLanes; ++l) {
        const float c = pv[x + l + r];
        const float up = pv[x + l + r + i], down = pv[x + l + r - i];
        sg[l] += k * (up + down);
        sd[l] += a * (up - down);
        sdd[l] += b * ((up - c) + (down - c));
      }
    }
    for (int l = 0; l < kLanes; ++l) {
      og[x + l] = sg[l];
      odg[x + l] = sd[l];
      oddg[x + l] = sdd[l];
    }
  }
  for (; x < w; ++x) {
    const float c = pv[x + r];
    float sg = g[r] * c, sd = 0.0f, sdd = 0.0f;
    for (int i = 1; i <= r; ++i) {
      const float up = pv[x + r + i], down = pv[x + r - i];
      sg += g[r + i] * (up + down);
      sd += dg[r + i] * (up - down);
      sdd += ddg[r + i] * ((up - c) + (down - c));
    }
    og[x] = sg;
    odg[x] = sd;
    oddg[x] = sdd;
  }
}

// ---- vertical passes (one output row from the ring rows of its taps)

// Vertical sums are kept in registers for a block of kLanes neighbouring pixels over all
// taps (each output's sum still over the taps in index order).
AALAB_FLIP_CLONES
void VerticalCsf(const float* const* ry, const float* const* rcx, const float* const* rcz1, const float* const* rcz2,
                 int w, int taps, const float* ky, const float* kcx, const float* kcz1, const float* kcz2, float* sy,
                 float* scx, float* scz) {
  int x = 0;
  for (; x + kVLanes <= w; x += kVLanes) {
    float a[kVLanes] = {}, b[kVLanes] = {}, c[kVLanes] = {}, d[kVLanes] = {};
    for (int t = 0; t < taps; ++t) {
      const float ka = ky[t], kb = kcx[t], kc = kcz1[t], kd = kcz2[t];
      const float* y = ry[t] + x;
      const float* cx = rcx[t] + x;
      const float* cz1 = rcz1[t] + x;
      const float* cz2 = rcz2[t] + x;
      for (int l = 0; l < kVLanes; ++l) {
        a[l] += ka * y[l];
        b[l] += kb * cx[l];
        c[l] += kc * cz1[l];
        d[l] += kd * cz2[l];
      }
    }
    for (int l = 0; l < kVLanes; ++l) {
      sy[x + l] = a[l];
      scx[x + l] = b[l];
      scz[x + l] = c[l] + d[l];  // the two Cz Gaussians, summed separately, then added
    }
  }
  for (; x < w; ++x) {
    float a = 0.0f, b = 0.0f, c = 0.0f, d = 0.0f;
    for (int t = 0; t < taps; ++t) {
      a += ky[t] * ry[t][x];
      b += kcx[t] * rcx[t][x];
      c += kcz1[t] * rcz1[t][x];
      d += kcz2[t] * rcz2[t][x];
    }
    sy[x] = a;
    scx[x] = b;
    scz[x] = c + d;
  }
}

AALAB_FLIP_CLONES
void VerticalFeatures(const float* const* rg, const float* const* rdg, const float* const* rddg, int w, int r,
                      const float* g, const float* dg, const float* ddg, float* edge, float* point) {
  const int taps = 2 * r + 1;
  int x = 0;
  for (; x + kVLanes <= w; x += kVLanes) {
    float dx[kVLanes] = {}, ddx[kVLanes] = {}, dy[kVLanes] = {}, ddy[kVLanes] = {};
    for (int t = 0; t < taps; ++t) {
      const float a = g[t];
      const float* d1 = rdg[t] + x;
      const float* d2 = rddg[t] + x;
      for (int l = 0; l < kVLanes; ++l) {
        dx[l] += a * d1[l];
        ddx[l] += a * d2[l];
      }
    }
    const float* centre = rg[r] + x;
    for (int i = 1; i <= r; ++i) {
      const float a = dg[r + i], b = ddg[r + i];
      const float* up = rg[r - i] + x;
      const float* down = rg[r + i] + x;
      for (int l = 0; l < kVLanes; ++l) {
        const float c = centre[l];
        dy[l] += a * (down[l] - up[l]);
        ddy[l] += b * ((down[l] - c) + (up[l] - c));
      }
    }
    for (int l = 0; l < kVLanes; ++l) {
      edge[x + l] = std::sqrt(dx[l] * dx[l] + dy[l] * dy[l]);
      point[x + l] = std::sqrt(ddx[l] * ddx[l] + ddy[l] * ddy[l]);
    }
  }
  for (; x < w; ++x) {
    float dx = 0.0f, ddx = 0.0f, dy = 0.0f, ddy = 0.0f;
    for (int t = 0; t < taps; ++t) {
      dx += g[t] * rdg[t][x];
      ddx += g[t] * rddg[t][x];
    }
    const float c = rg[r][x];
    for (int i = 1; i <= r; ++i) {
      const float down = rg[r + i][x], up = rg[r - i][x];
      dy += dg[r + i] * (down - up);
      ddy += ddg[r + i] * ((down - c) + (up - c));
    }
    edge[x] = std::sqrt(dx * dx + dy * dy);
    point[x] = std::sqrt(ddx * ddx + ddy * ddy);
  }
}

// ---- per-pixel colour transform of a filtered row: YCxCz → linear RGB (clamped) → XYZ →
// Lab → Hunt, float.

struct FloatMatrices {
  float to_xyz[3][3], to_rgb[3][3];
  FloatMatrices() {
    for (int i = 0; i < 3; ++i) {
      Color e{};
      e[i] = 1.0;
      const Color a = LinearRgbToXyz(e), b = XyzToLinearRgb(e);
      for (int j = 0; j < 3; ++j) {
        to_xyz[j][i] = static_cast<float>(a[j]);
        to_rgb[j][i] = static_cast<float>(b[j]);
      }
    }
  }
};

// Cube root of t > 0 without a library call (so the colour loop vectorises): a bit-level
// first guess (within ~5 %), then three Newton steps in double (error 5e-2 → 4e-3 → 1e-5 →
// 1e-10), rounded to float. Pure arithmetic: the same bits on every clone and thread.
inline float CbrtPositive(float t) {
  const uint32_t bits = std::bit_cast<uint32_t>(t) / 3u + 0x2a5137a0u;
  double y = static_cast<double>(std::bit_cast<float>(bits));
  const double td = static_cast<double>(t);
  y = y - (y * y * y - td) / (3.0 * y * y);
  y = y - (y * y * y - td) / (3.0 * y * y);
  y = y - (y * y * y - td) / (3.0 * y * y);
  return static_cast<float>(y);
}

inline float LabFf(float t) {
  constexpr float d3 = static_cast<float>((6.0 / 29.0) * (6.0 / 29.0) * (6.0 / 29.0));
  constexpr float inv3d2 = static_cast<float>(1.0 / (3.0 * (6.0 / 29.0) * (6.0 / 29.0)));
  constexpr float off = static_cast<float>(4.0 / 29.0);
  const float root = CbrtPositive(std::max(t, d3));  // t <= d3 takes the linear segment
  const float linear = t * inv3d2 + off;
  return t > d3 ? root : linear;
}

AALAB_FLIP_CLONES
void HuntLabRow(const float* __restrict sy, const float* __restrict scx, const float* __restrict scz, int w,
                const FloatMatrices& m, float* __restrict L, float* __restrict A, float* __restrict B) {
  const float wx = static_cast<float>(kWhite[0]), wy = static_cast<float>(kWhite[1]),
              wz = static_cast<float>(kWhite[2]);
  const float iwx = static_cast<float>(1.0 / kWhite[0]), iwz = static_cast<float>(1.0 / kWhite[2]);
  const float r0 = m.to_rgb[0][0], r1 = m.to_rgb[0][1], r2 = m.to_rgb[0][2];
  const float g0 = m.to_rgb[1][0], g1 = m.to_rgb[1][1], g2 = m.to_rgb[1][2];
  const float b0 = m.to_rgb[2][0], b1 = m.to_rgb[2][1], b2 = m.to_rgb[2][2];
  const float x0 = m.to_xyz[0][0], x1 = m.to_xyz[0][1], x2 = m.to_xyz[0][2];
  const float y0 = m.to_xyz[1][0], y1 = m.to_xyz[1][1], y2 = m.to_xyz[1][2];
  const float z0 = m.to_xyz[2][0], z1 = m.to_xyz[2][1], z2 = m.to_xyz[2][2];
  for (int x = 0; x < w; ++x) {
    const float yy = sy[x];  // filtered Ŷ
    const float X = (yy + scx[x] * (1.0f / 500.0f)) * wx;
    const float Y = yy * wy;
    const float Z = (yy - scz[x] * (1.0f / 200.0f)) * wz;
    const float r = std::min(std::max(r0 * X + r1 * Y + r2 * Z, 0.0f), 1.0f);
    const float g = std::min(std::max(g0 * X + g1 * Y + g2 * Z, 0.0f), 1.0f);
    const float b = std::min(std::max(b0 * X + b1 * Y + b2 * Z, 0.0f), 1.0f);
    const float xyz[3] = {x0 * r + x1 * g + x2 * b, y0 * r + y1 * g + y2 * b, z0 * r + z1 * g + z2 * b};
    const float fx = LabFf(xyz[0] * iwx), fy = LabFf(xyz[1] / wy), fz = LabFf(xyz[2] * iwz);
    const float l = 116.0f * fy - 16.0f;
    L[x] = l;
    A[x] = 0.01f * l * (500.0f * (fx - fy));
    B[x] = 0.01f * l * (200.0f * (fy - fz));
  }
}

// The row padded by r on each side, the edge values replicated (w + 2r values).
void PadRow(const float* src, int w, int r, float* dst) {
  std::fill(dst, dst + r, src[0]);
  std::memcpy(dst + r, src, sizeof(float) * w);
  std::fill(dst + r + w, dst + 2 * r + w, src[w - 1]);
}

// A chunk's rings and row buffers: every value is written before it is read, so no zero-fill
// (25 MB of memset a 1080p call otherwise). Under the tests' poison (SetUninitializedPoison)
// they are filled with it, so a value read before it is written changes the result.
using Scratch = std::vector<float, DefaultInitAllocator<float>>;

Scratch MakeScratch(size_t n) {
  Scratch v(n);
  if (const int poison = UninitializedPoison(); poison >= 0)
    std::memset(static_cast<void*>(v.data()), poison, n * sizeof(float));
  return v;
}

// ---- one chunk of rows of one image, streamed through the rings. colour(y, L, A, B) and
// feature(y, edge, point) receive each finished row (w values).

template <typename ColourSink, typename FeatureSink>
void ChunkRows(const Planes& p, const Kernels& k, int y0, int y1, const ColourSink& colour,
               const FeatureSink& feature) {
  static const FloatMatrices m;
  const int w = p.w, h = p.h;
  // Colour: ring of 2·rc + 1 rows × 4 planes.
  {
    const int r = k.rc, taps = 2 * r + 1, pw = w + 2 * r;
    Scratch ring = MakeScratch(static_cast<size_t>(4) * taps * w);
    Scratch pad = MakeScratch(static_cast<size_t>(3) * pw);
    Scratch acc = MakeScratch(static_cast<size_t>(3) * w), lab = MakeScratch(static_cast<size_t>(3) * w);
    std::vector<const float*> ry(taps), rcx(taps), rcz1(taps), rcz2(taps);
    auto slot = [&](int plane, int yy) {
      return ring.data() + (static_cast<size_t>(plane) * taps + (yy + taps * 4) % taps) * w;
    };
    for (int yy = y0 - r; yy < y1 + r; ++yy) {
      const size_t row = static_cast<size_t>(ClampI(yy, 0, h - 1)) * w;
      PadRow(p.y.data() + row, w, r, pad.data());
      PadRow(p.cx.data() + row, w, r, pad.data() + pw);
      PadRow(p.cz.data() + row, w, r, pad.data() + 2 * pw);
      HorizontalCsf(pad.data(), pad.data() + pw, pad.data() + 2 * pw, w, r, k.y.data(), k.cx.data(), k.cz1.data(),
                    k.cz2.data(), slot(0, yy), slot(1, yy), slot(2, yy), slot(3, yy));
      const int y = yy - r;  // output row complete once its last input row is in
      if (y < y0) continue;
      for (int t = 0; t < taps; ++t) {
        ry[t] = slot(0, y - r + t);
        rcx[t] = slot(1, y - r + t);
        rcz1[t] = slot(2, y - r + t);
        rcz2[t] = slot(3, y - r + t);
      }
      VerticalCsf(ry.data(), rcx.data(), rcz1.data(), rcz2.data(), w, taps, k.y.data(), k.cx.data(), k.cz1.data(),
                  k.cz2.data(), acc.data(), acc.data() + w, acc.data() + 2 * w);
      HuntLabRow(acc.data(), acc.data() + w, acc.data() + 2 * w, w, m, lab.data(), lab.data() + w, lab.data() + 2 * w);
      colour(y, lab.data(), lab.data() + w, lab.data() + 2 * w);
    }
  }
  // Features: ring of 2·rf + 1 rows × 3 planes, on Ŷ = (Y + 16) / 116.
  {
    const int r = k.rf, taps = 2 * r + 1, pw = w + 2 * r;
    Scratch ring = MakeScratch(static_cast<size_t>(3) * taps * w);
    Scratch pad = MakeScratch(pw), out = MakeScratch(static_cast<size_t>(2) * w);
    std::vector<const float*> rg(taps), rdg(taps), rddg(taps);
    auto slot = [&](int plane, int yy) {
      return ring.data() + (static_cast<size_t>(plane) * taps + (yy + taps * 4) % taps) * w;
    };
    for (int yy = y0 - r; yy < y1 + r; ++yy) {
      const size_t row = static_cast<size_t>(ClampI(yy, 0, h - 1)) * w;
      PadRow(p.y.data() + row, w, r, pad.data());
      HorizontalFeatures(pad.data(), w, r, k.g.data(), k.dg.data(), k.ddg.data(), slot(0, yy), slot(1, yy),
                         slot(2, yy));
      const int y = yy - r;
      if (y < y0) continue;
      for (int t = 0; t < taps; ++t) {
        rg[t] = slot(0, y - r + t);
        rdg[t] = slot(1, y - r + t);
        rddg[t] = slot(2, y - r + t);
      }
      VerticalFeatures(rg.data(), rdg.data(), rddg.data(), w, r, k.g.data(), k.dg.data(), k.ddg.data(), out.data(),
                       out.data() + w);
      feature(y, out.data(), out.data() + w);
    }
  }
}

// ---- the error of a finished row, in three steps each: the arithmetic before the library
// pow in vector lanes, the pow one pixel at a time, the arithmetic after it in lanes (the same
// operations per pixel as one loop: only split where the pow call is).

// HyAB distance of the reference's and the test's Hunt-adjusted Lab: |ΔL| + √(Δa² + Δb²).
AALAB_FLIP_CLONES
void HyAbRow(const float* __restrict rl, const float* __restrict ra, const float* __restrict rb,
             const float* __restrict L, const float* __restrict A, const float* __restrict B, int w,
             float* __restrict hy) {
  for (int x = 0; x < w; ++x) {
    const float da = ra[x] - A[x], db = rb[x] - B[x];
    hy[x] = std::abs(rl[x] - L[x]) + std::sqrt(da * da + db * db);
  }
}

// The remap of v = HyAB^qc to the colour error in [0, 1] (in place).
AALAB_FLIP_CLONES
void RemapColourRow(float* __restrict e, int w, float pccmax, float below, float pt, float above) {
  for (int x = 0; x < w; ++x) {
    const float v = e[x];
    e[x] = v < pccmax ? v * below : pt + (v - pccmax) * above;
  }
}

// The feature exponent ef = (max(|Δedge|, |Δpoint|) / √2)^qf, qf = 1/2.
AALAB_FLIP_CLONES
void FeatureExponentRow(const float* __restrict re, const float* __restrict rp, const float* __restrict edge,
                        const float* __restrict point, int w, float inv_sqrt2, float* __restrict ef) {
  for (int x = 0; x < w; ++x) {
    const float d = std::max(std::abs(re[x] - edge[x]), std::abs(rp[x] - point[x]));
    ef[x] = std::sqrt(inv_sqrt2 * d);
  }
}

AALAB_FLIP_CLONES
void WidenRow(const float* __restrict v, int w, double* __restrict o) {
  for (int x = 0; x < w; ++x) o[x] = static_cast<double>(v[x]);
}

// std::pow(x, y) for x >= 0 and y > 0, with the call skipped where its result is known
// exactly: pow(+0, y > 0) is +0 (C17 F.10.4.4).
inline float PowOrZero(float x, float y) { return x == 0.0f ? 0.0f : std::pow(x, y); }

// std::pow(x, 1 − ef) with the call skipped where ef = 0 and 0 <= x <= 1: pow(x, 1) is x
// there. C specifies pow(+0, 1) = +0; for x > 0, pow(x, 1) = x exactly and x is a float, so
// a pow whose result is the exact value rounded with an error below half an ulp of it
// returns x (glibc's powf, the one linked here, documents a worst total error of 0.82 ulp:
// the exact value with a relative error of at most 0.32 · 2^-24 before rounding).
// tests/metrics/flip_test.cpp checks std::pow(x, 1.0f) == x for every float in [0, 1]
// against the library in use (Flip.PowOfOneIsTheValueOnEveryFloatInTheUnitInterval).
inline float PowOrSelf(float x, float ef) {
  const bool exact = ef == 0.0f && x >= 0.0f && x <= 1.0f;
  return exact ? x : std::pow(x, 1.0f - ef);
}

void CheckPpdValue(double ppd) {
  if (!std::isfinite(ppd) || !(ppd > 0.0)) {
    throw UserError("flip: pixels per degree must be a finite number > 0 (got " + std::to_string(ppd) + ")");
  }
}

void CheckRgb(const ImageF& img) {
  if (img.Channels() < 3) {
    throw UserError("flip: needs RGB images (got " + std::to_string(img.Channels()) + " channels)");
  }
}

}  // namespace

struct ReferenceSide {
  int w = 0, h = 0;
  double ppd = 0.0;
  Kernels kernels;
  std::vector<float> lab;    // L, A, B planes of each row: row y at 3·w·y
  std::vector<float> feats;  // edge, point of each row: row y at 2·w·y
};

std::shared_ptr<const ReferenceSide> PrepareReference(const ImageF& reference, double ppd) {
  CheckRgb(reference);
  CheckPpdValue(ppd);
  auto side = std::make_shared<ReferenceSide>();
  side->w = reference.Width();
  side->h = reference.Height();
  side->ppd = ppd;
  side->kernels = MakeKernels(ppd);
  const int w = side->w;
  const size_t n = reference.PixelCount();
  side->lab.resize(3 * n);
  side->feats.resize(2 * n);
  if (n == 0) return side;
  const Planes a = ToPlanes(reference);
  ParallelForChunks(side->h, kChunkRows, [&](int y0, int y1) {
    ChunkRows(
        a, side->kernels, y0, y1,
        [&](int y, const float* L, const float* A, const float* B) {
          float* dst = side->lab.data() + static_cast<size_t>(3) * w * y;
          std::memcpy(dst, L, sizeof(float) * w);
          std::memcpy(dst + w, A, sizeof(float) * w);
          std::memcpy(dst + 2 * w, B, sizeof(float) * w);
        },
        [&](int y, const float* edge, const float* point) {
          float* dst = side->feats.data() + static_cast<size_t>(2) * w * y;
          std::memcpy(dst, edge, sizeof(float) * w);
          std::memcpy(dst + w, point, sizeof(float) * w);
        });
  });
  return side;
}

FlipValues ErrorValues(const ReferenceSide& ref, const ImageF& test) {
  if (test.Width() != ref.w || test.Height() != ref.h) {
    throw UserError("flip: test image is " + std::to_string(test.Width()) + "x" + std::to_string(test.Height()) +
                    ", the prepared reference " + std::to_string(ref.w) + "x" + std::to_string(ref.h));
  }
  CheckRgb(test);
  const int w = ref.w;
  FlipValues out(test.PixelCount());  // every value written below: no zero-fill
  if (out.empty()) return out;
  if (const int poison = UninitializedPoison(); poison >= 0) {  // tests: a value left unwritten shows
    std::memset(static_cast<void*>(out.data()), poison, out.size() * sizeof(double));
  }
  const Planes b = ToPlanes(test);
  const float cmax = static_cast<float>(Cmax());
  const float pccmax = static_cast<float>(kPc) * cmax;
  const float below = static_cast<float>(kPt) / pccmax;
  const float above = static_cast<float>(1.0 - kPt) / (cmax - pccmax);
  const float pt = static_cast<float>(kPt), qc = static_cast<float>(kQc);
  const float inv_sqrt2 = static_cast<float>(1.0 / std::sqrt(2.0));
  ParallelForChunks(ref.h, kChunkRows, [&](int y0, int y1) {
    Scratch ec = MakeScratch(static_cast<size_t>(y1 - y0) * w);  // ΔEc of the chunk's rows
    Scratch row = MakeScratch(w);                                // the feature exponent, then the error
    ChunkRows(
        b, ref.kernels, y0, y1,
        [&](int y, const float* L, const float* A, const float* B) {
          const float* rl = ref.lab.data() + static_cast<size_t>(3) * w * y;
          float* e = ec.data() + static_cast<size_t>(y - y0) * w;
          HyAbRow(rl, rl + w, rl + 2 * w, L, A, B, w, e);
          for (int x = 0; x < w; ++x) e[x] = PowOrZero(e[x], qc);  // library calls: one pixel at a time
          RemapColourRow(e, w, pccmax, below, pt, above);
        },
        [&](int y, const float* edge, const float* point) {
          const float* re = ref.feats.data() + static_cast<size_t>(2) * w * y;
          const float* e = ec.data() + static_cast<size_t>(y - y0) * w;
          FeatureExponentRow(re, re + w, edge, point, w, inv_sqrt2, row.data());
          for (int x = 0; x < w; ++x) row[x] = PowOrSelf(e[x], row[x]);
          WidenRow(row.data(), w, out.data() + static_cast<size_t>(y) * w);
        });
  });
  return out;
}

FlipValues ErrorValues(const ImageF& reference, const ImageF& test, double ppd) {
  RequireSameShape(reference, test, "flip");
  return ErrorValues(*PrepareReference(reference, ppd), test);
}

}  // namespace flip
}  // namespace aalab
