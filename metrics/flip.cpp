// LDR-FLIP: a perceptual per-pixel difference for flipping between two images.
//
// Source: P. Andersson, J. Nilsson, T. Akenine-Möller, M. Oskarsson, K. Åström,
// M. D. Fairchild, "FLIP: A Difference Evaluator for Alternating Images", Proc. ACM Comput.
// Graph. Interact. Tech. 3(2), 15:1–15:23 (HPG 2020). The constants and every formula below
// were checked against NVIDIA's reference code (github.com/NVlabs/flip: python/flip.py
// `compute_ldrflip`, cpp/FLIP.h); equation numbers of the paper are not quoted because its
// text was not available to check them against.
//
// Parameters: ppd (pixels per degree of visual angle, default 67; NVIDIA's default is
// 0.7·3840/0.7·π/180 = 67.0206). Fixed constants (the paper's): qc = 0.7, pc = 0.4,
// pt = 0.95, w = 0.082°, qf = 0.5; CSF (a1, b1, a2, b2): Y (1, 0.0047, 0, 1e-5),
// Cx (1, 0.0053, 0, 1e-5), Cz (34.1, 0.04, 13.5, 0.025).
//
// Colour pipeline (per image): sRGB-encoded → linear (IEC 61966-2-1) → XYZ (D65) → YCxCz
// (linear opponent space). Each channel is filtered with its spatial CSF
//   s(r) = a1·sqrt(π/b1)·exp(−π²r²/b1) + a2·sqrt(π/b2)·exp(−π²r²/b2),  r = distance in
// degrees = pixels / ppd, sampled on a (2R+1)² grid, R = ceil(3·sqrt(0.04/(2π²))·ppd), and
// normalised to unit sum. The filtered YCxCz goes back to linear RGB, is clamped to [0, 1],
// then → XYZ → CIELAB → Hunt adjustment (a, b scaled by 0.01·L). ΔE_HyAB = |ΔL| +
// sqrt(Δa² + Δb²) between reference and test, raised to qc, then remapped with
// cmax = HyAB(Hunt(Lab(green)), Hunt(Lab(blue)))^qc ≈ 41.2761: x < pc·cmax → x·pt/(pc·cmax),
// otherwise pt + (x − pc·cmax)/(cmax − pc·cmax)·(1 − pt). That is ΔEc.
//
// Feature pipeline (achromatic only): Ŷ = (Y + 16)/116 from the unfiltered YCxCz. Gaussian
// σ = 0.5·w·ppd pixels, radius ceil(3σ). Edge kernel: ∂/∂x of the Gaussian, −x·g(x, y),
// positive and negative weights normalised to sum to +1 and −1; point kernel: ∂²/∂x²,
// (x²/σ² − 1)·g, normalised the same way; both also transposed for y. Edge magnitude
// |∇| = sqrt(dx² + dy²), point magnitude sqrt(ddx² + ddy²).
// ΔEf = ( max(| |∇ref| − |∇test| |, | |pt ref| − |pt test| |) / sqrt(2) )^qf.
// Final: ΔE = ΔEc^(1 − ΔEf).
//
// This file is the double-precision implementation (flip::ErrorValuesUncached,
// ColorErrorValues, FeatureErrorValues: what the outside-oracle cross-checks test); the
// production path, the same maths in float32 laid out for speed, is metrics/flip_fast.cpp.
//
// Implementation (same maths as the reference, different arithmetic; documented so the
// numbers can be reproduced):
//  - Separable filtering. The Y and Cx CSF filters and the feature kernels are products of
//    1-D kernels; the Cz filter is a sum of two Gaussians, filtered as two separable passes
//    with 1-D kernels sqrt(a·sqrt(π/b))·exp(−π²x²/b) divided by sqrt(S1² + S2²) (S = 1-D
//    sums), which reproduces the unit-sum 2-D kernel exactly in exact arithmetic (the
//    method of NVIDIA's misc/separatedConvolutions.pdf). The normalised 2-D derivative
//    kernels also factor exactly: (dg(x)/S+)·(g(y)/Σg).
//  - Borders: clamp-to-edge (replicate), as NVIDIA's C++/CUDA code and python flip.py
//    (cv.BORDER_REPLICATE). (The 2020 python release used symmetric reflection.)
//  - Feature sums are evaluated in a form that is zero for constant input: the first
//    derivative as Σ_{i>0} dg(i)·(Ŷ(x+i) − Ŷ(x−i)) (dg is odd), the second as
//    Σ_{i>0} ddg(i)·((Ŷ(x+i) − Ŷ(x)) + (Ŷ(x−i) − Ŷ(x))) (ddg is even and sums to 0). This is
//    the same sum in exact arithmetic, but a constant region gives ΔEf = 0 exactly instead
//    of a ~1e-16 residue from weights that do not cancel in floating point.
//  - Precision: everything in double (NVIDIA's implementations use float32); the XYZ→RGB
//    matrix is the double inverse of the RGB→XYZ matrix (NVIDIA uses a 10-digit rounded
//    inverse). Measured on a 960×540 pair: against a float64 2-D transcription of NVIDIA's
//    python code, per-pixel |Δ| <= 4e-14; against the same transcription run in float32
//    (as NVIDIA computes), per-pixel |Δ| max 9.2e-6, mean 6.9e-7 (flip_mean 1e-8, weighted
//    median 5e-7). So expect agreement with NVIDIA's tool to ~1e-5, not bit for bit; worst
//    where ΔEc is near 0 while ΔEf > 0 (x^(1−ΔEf) has an unbounded slope at x = 0), at
//    the remap knee, or at a ppd where a float32 radius would round differently. The
//    kernels are truncated at 3 standard deviations of the widest Gaussian (weights
//    renormalised), as in the reference: part of the definition, matched exactly.
//  - Inputs are clamped to [0, 1] (NaN → 0) before decoding; the reference assumes [0, 1].
//  - Sums in a fixed order (taps in index order, pooling row-major), every pixel computed
//    independently: bit-identical at any thread count.
#include "metrics/flip.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numbers>
#include <span>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "metrics/families.h"
#include "metrics/metric.h"

namespace aalab {
namespace flip {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kGrain = 8;  // rows per parallel chunk (fixed: results never depend on it)

using Matrix = std::array<std::array<double, 3>, 3>;

// Linear sRGB → XYZ (D65), as rational numbers in NVIDIA's code (from the image-engineering
// technote on sRGB/XYZ).
const Matrix& RgbToXyzMatrix() {
  static const Matrix m = {{{10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
                            {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
                            {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}}};
  return m;
}

const Matrix& XyzToRgbMatrix() {
  static const Matrix inv = [] {
    const Matrix& m = RgbToXyzMatrix();
    Matrix r{};
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
    r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
    r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
    r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    return r;
  }();
  return inv;
}

Color Mul(const Matrix& m, const Color& v) {
  Color r{};
  for (int i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
  return r;
}

double LabF(double t) {
  constexpr double d = 6.0 / 29.0;
  if (t > d * d * d) return std::cbrt(t);
  return t / (3.0 * d * d) + 4.0 / 29.0;
}

void CheckPpd(double ppd) {
  if (!std::isfinite(ppd) || !(ppd > 0.0)) {
    throw UserError("flip: pixels per degree must be a finite number > 0 (got " + std::to_string(ppd) + ")");
  }
}

void CheckPair(const ImageF& reference, const ImageF& test) {
  RequireSameShape(reference, test, "flip");
  if (reference.Channels() < 3) {
    throw UserError("flip: needs RGB images (got " + std::to_string(reference.Channels()) + " channels)");
  }
}

int Clamp(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

// body(i) for every pixel index in [0, n), in parallel; each call writes only element i.
template <typename F>
void ForEachPixel(size_t n, const F& body) {
  constexpr int kBlock = 4096;
  const int blocks = static_cast<int>((n + kBlock - 1) / kBlock);
  ParallelFor(blocks, [&](int blk) {
    const size_t end = std::min(n, static_cast<size_t>(blk + 1) * kBlock);
    for (size_t i = static_cast<size_t>(blk) * kBlock; i < end; ++i) body(i);
  });
}

// An image in YCxCz, one plane per channel, row-major.
struct Planes {
  int w = 0, h = 0;
  std::vector<double> y, cx, cz;
};

Planes ToYCxCz(const ImageF& img) {
  Planes p;
  p.w = img.Width();
  p.h = img.Height();
  const size_t n = img.PixelCount();
  p.y.resize(n);
  p.cx.resize(n);
  p.cz.resize(n);
  ParallelForChunks(p.h, kGrain, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < p.w; ++x) {
        const Color lin = {SrgbToLinear(img.At(x, y, 0)), SrgbToLinear(img.At(x, y, 1)), SrgbToLinear(img.At(x, y, 2))};
        const Color o = XyzToYCxCz(LinearRgbToXyz(lin));
        const size_t i = static_cast<size_t>(y) * p.w + x;
        p.y[i] = o[0];
        p.cx[i] = o[1];
        p.cz[i] = o[2];
      }
    }
  });
  return p;
}

// CSF-filtered image → clamped linear RGB → Hunt-adjusted Lab, per pixel.
std::vector<Color> FilteredHuntLab(const Planes& p, const SpatialKernels& k) {
  const int w = p.w, h = p.h, r = k.radius, taps = 2 * r + 1;
  const size_t n = static_cast<size_t>(w) * h;
  std::vector<double> hy(n), hcx(n), hcz1(n), hcz2(n);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    std::vector<double> py(w + 2 * r), pcx(w + 2 * r), pcz(w + 2 * r);  // clamped rows
    for (int y = y0; y < y1; ++y) {
      const size_t row = static_cast<size_t>(y) * w;
      for (int i = 0; i < w + 2 * r; ++i) {
        const size_t s = row + Clamp(i - r, 0, w - 1);
        py[i] = p.y[s];
        pcx[i] = p.cx[s];
        pcz[i] = p.cz[s];
      }
      for (int x = 0; x < w; ++x) {
        double sy = 0.0, scx = 0.0, scz1 = 0.0, scz2 = 0.0;
        for (int t = 0; t < taps; ++t) {  // input x + t − r at padded index x + t
          sy += k.y[t] * py[x + t];
          scx += k.cx[t] * pcx[x + t];
          scz1 += k.cz1[t] * pcz[x + t];
          scz2 += k.cz2[t] * pcz[x + t];
        }
        hy[row + x] = sy;
        hcx[row + x] = scx;
        hcz1[row + x] = scz1;
        hcz2[row + x] = scz2;
      }
    }
  });
  std::vector<Color> out(n);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    std::vector<double> sy(w), scx(w), scz1(w), scz2(w);
    for (int y = y0; y < y1; ++y) {
      std::fill(sy.begin(), sy.end(), 0.0);
      std::fill(scx.begin(), scx.end(), 0.0);
      std::fill(scz1.begin(), scz1.end(), 0.0);
      std::fill(scz2.begin(), scz2.end(), 0.0);
      for (int t = 0; t < taps; ++t) {
        const size_t src = static_cast<size_t>(Clamp(y + t - r, 0, h - 1)) * w;
        for (int x = 0; x < w; ++x) {
          sy[x] += k.y[t] * hy[src + x];
          scx[x] += k.cx[t] * hcx[src + x];
          scz1[x] += k.cz1[t] * hcz1[src + x];
          scz2[x] += k.cz2[t] * hcz2[src + x];
        }
      }
      const size_t row = static_cast<size_t>(y) * w;
      for (int x = 0; x < w; ++x) {
        Color rgb = XyzToLinearRgb(YCxCzToXyz({sy[x], scx[x], scz1[x] + scz2[x]}));
        for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
        out[row + x] = HuntAdjust(XyzToLab(LinearRgbToXyz(rgb)));
      }
    }
  });
  return out;
}

// Edge and point magnitudes of the normalised achromatic channel Ŷ = (Y + 16) / 116.
struct Features {
  std::vector<double> edge, point;
};

Features DetectFeatures(const Planes& p, const FeatureKernels& k) {
  const int w = p.w, h = p.h, r = k.radius, taps = 2 * r + 1;
  const size_t n = static_cast<size_t>(w) * h;
  // Horizontal pass: Gaussian, first and second derivative along x.
  std::vector<double> hg(n), hdg(n), hddg(n);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    std::vector<double> row_y(w + 2 * r);
    for (int y = y0; y < y1; ++y) {
      const size_t row = static_cast<size_t>(y) * w;
      for (int i = 0; i < w + 2 * r; ++i) {
        row_y[i] = (p.y[row + Clamp(i - r, 0, w - 1)] + 16.0) / 116.0;
      }
      for (int x = 0; x < w; ++x) {
        const int c = x + r;  // padded index of x
        double sg = 0.0;
        for (int t = 0; t < taps; ++t) sg += k.g[t] * row_y[x + t];
        double sdg = 0.0, sddg = 0.0;
        const double centre = row_y[c];
        for (int i = 1; i <= r; ++i) {
          sdg += k.dg[r + i] * (row_y[c + i] - row_y[c - i]);
          sddg += k.ddg[r + i] * ((row_y[c + i] - centre) + (row_y[c - i] - centre));
        }
        hg[row + x] = sg;
        hdg[row + x] = sdg;
        hddg[row + x] = sddg;
      }
    }
  });
  // Vertical pass: Gaussian on the x-derivatives, derivatives on the x-Gaussian.
  Features f;
  f.edge.resize(n);
  f.point.resize(n);
  ParallelForChunks(h, kGrain, [&](int y0, int y1) {
    std::vector<double> dx(w), ddx(w), dy(w), ddy(w);
    for (int y = y0; y < y1; ++y) {
      std::fill(dx.begin(), dx.end(), 0.0);
      std::fill(ddx.begin(), ddx.end(), 0.0);
      std::fill(dy.begin(), dy.end(), 0.0);
      std::fill(ddy.begin(), ddy.end(), 0.0);
      for (int t = 0; t < taps; ++t) {
        const size_t src = static_cast<size_t>(Clamp(y + t - r, 0, h - 1)) * w;
        for (int x = 0; x < w; ++x) {
          dx[x] += k.g[t] * hdg[src + x];
          ddx[x] += k.g[t] * hddg[src + x];
        }
      }
      const size_t centre = static_cast<size_t>(y) * w;
      for (int i = 1; i <= r; ++i) {
        const size_t up = static_cast<size_t>(Clamp(y - i, 0, h - 1)) * w;
        const size_t down = static_cast<size_t>(Clamp(y + i, 0, h - 1)) * w;
        for (int x = 0; x < w; ++x) {
          const double c = hg[centre + x];
          dy[x] += k.dg[r + i] * (hg[down + x] - hg[up + x]);
          ddy[x] += k.ddg[r + i] * ((hg[down + x] - c) + (hg[up + x] - c));
        }
      }
      for (int x = 0; x < w; ++x) {
        f.edge[centre + x] = std::sqrt(dx[x] * dx[x] + dy[x] * dy[x]);
        f.point[centre + x] = std::sqrt(ddx[x] * ddx[x] + ddy[x] * ddy[x]);
      }
    }
  });
  return f;
}

std::vector<double> ColorErrorFromPlanes(const Planes& ref, const Planes& test, double ppd) {
  const SpatialKernels k = MakeSpatialKernels(ppd);
  const std::vector<Color> a = FilteredHuntLab(ref, k);
  const std::vector<Color> b = FilteredHuntLab(test, k);
  std::vector<double> out(a.size());
  ForEachPixel(out.size(), [&](size_t i) { out[i] = RemapColorError(std::pow(HyAB(a[i], b[i]), kQc)); });
  return out;
}

std::vector<double> FeatureErrorFromPlanes(const Planes& ref, const Planes& test, double ppd) {
  const FeatureKernels k = MakeFeatureKernels(ppd);
  const Features a = DetectFeatures(ref, k);
  const Features b = DetectFeatures(test, k);
  std::vector<double> out(a.edge.size());
  const double inv_sqrt2 = 1.0 / std::sqrt(2.0);
  ForEachPixel(out.size(), [&](size_t i) {
    const double d = std::max(std::abs(a.edge[i] - b.edge[i]), std::abs(a.point[i] - b.point[i]));
    out[i] = std::pow(inv_sqrt2 * d, kQf);
  });
  return out;
}

}  // namespace

double SrgbToLinear(double v) {
  if (!(v > 0.0)) return 0.0;  // also NaN
  if (v >= 1.0) return 1.0;
  if (v <= 0.04045) return v / 12.92;
  return std::pow((v + 0.055) / 1.055, 2.4);
}

Color LinearRgbToXyz(const Color& rgb) { return Mul(RgbToXyzMatrix(), rgb); }

Color XyzToLinearRgb(const Color& xyz) { return Mul(XyzToRgbMatrix(), xyz); }

Color XyzToYCxCz(const Color& xyz) {
  const double x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Color YCxCzToXyz(const Color& o) {
  const double y = (o[0] + 16.0) / 116.0;
  const double x = y + o[1] / 500.0;
  const double z = y - o[2] / 200.0;
  return {x * kWhite[0], y * kWhite[1], z * kWhite[2]};
}

Color XyzToLab(const Color& xyz) {
  const double fx = LabF(xyz[0] / kWhite[0]);
  const double fy = LabF(xyz[1] / kWhite[1]);
  const double fz = LabF(xyz[2] / kWhite[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Color HuntAdjust(const Color& lab) { return {lab[0], 0.01 * lab[0] * lab[1], 0.01 * lab[0] * lab[2]}; }

double HyAB(const Color& p, const Color& q) {
  const double da = p[1] - q[1], db = p[2] - q[2];
  return std::abs(p[0] - q[0]) + std::sqrt(da * da + db * db);
}

double Cmax() {
  static const double cmax = [] {
    const Color green = HuntAdjust(XyzToLab(LinearRgbToXyz({0.0, 1.0, 0.0})));
    const Color blue = HuntAdjust(XyzToLab(LinearRgbToXyz({0.0, 0.0, 1.0})));
    return std::pow(HyAB(green, blue), kQc);
  }();
  return cmax;
}

double RemapColorError(double x) {
  const double cmax = Cmax();
  const double pccmax = kPc * cmax;
  if (x < pccmax) return x * (kPt / pccmax);
  return kPt + ((x - pccmax) / (cmax - pccmax)) * (1.0 - kPt);
}

int SpatialFilterRadius(double ppd) {
  CheckPpd(ppd);
  const double max_b = std::max({kCsfY.b1, kCsfY.b2, kCsfCx.b1, kCsfCx.b2, kCsfCz.b1, kCsfCz.b2});
  return static_cast<int>(std::ceil(3.0 * std::sqrt(max_b / (2.0 * kPi * kPi)) * ppd));
}

int FeatureFilterRadius(double ppd) {
  CheckPpd(ppd);
  return static_cast<int>(std::ceil(3.0 * (0.5 * kW * ppd)));
}

SpatialKernels MakeSpatialKernels(double ppd) {
  SpatialKernels k;
  k.radius = SpatialFilterRadius(ppd);
  const int taps = 2 * k.radius + 1;
  k.y.resize(taps);
  k.cx.resize(taps);
  k.cz1.resize(taps);
  k.cz2.resize(taps);
  auto gauss = [](double x2, double a, double b) {  // a·sqrt(π/b)·exp(−π²x²/b)
    return a * std::sqrt(kPi / b) * std::exp(-kPi * kPi * x2 / b);
  };
  auto gauss_sqrt = [](double x2, double a, double b) {  // sqrt(a·sqrt(π/b))·exp(−π²x²/b)
    return std::sqrt(a * std::sqrt(kPi / b)) * std::exp(-kPi * kPi * x2 / b);
  };
  double sy = 0.0, scx = 0.0, s1 = 0.0, s2 = 0.0;
  for (int t = 0; t < taps; ++t) {
    const double x = (t - k.radius) / ppd;  // degrees
    const double x2 = x * x;
    k.y[t] = gauss(x2, kCsfY.a1, kCsfY.b1) + gauss(x2, kCsfY.a2, kCsfY.b2);
    k.cx[t] = gauss(x2, kCsfCx.a1, kCsfCx.b1) + gauss(x2, kCsfCx.a2, kCsfCx.b2);
    k.cz1[t] = gauss_sqrt(x2, kCsfCz.a1, kCsfCz.b1);
    k.cz2[t] = gauss_sqrt(x2, kCsfCz.a2, kCsfCz.b2);
    sy += k.y[t];
    scx += k.cx[t];
    s1 += k.cz1[t];
    s2 += k.cz2[t];
  }
  const double norm_cz = std::sqrt(s1 * s1 + s2 * s2);
  for (int t = 0; t < taps; ++t) {
    k.y[t] /= sy;
    k.cx[t] /= scx;
    k.cz1[t] /= norm_cz;
    k.cz2[t] /= norm_cz;
  }
  return k;
}

FeatureKernels MakeFeatureKernels(double ppd) {
  FeatureKernels k;
  k.radius = FeatureFilterRadius(ppd);
  k.sigma = 0.5 * kW * ppd;
  const int taps = 2 * k.radius + 1;
  k.g.resize(taps);
  k.dg.resize(taps);
  k.ddg.resize(taps);
  double g_sum = 0.0, dg_pos = 0.0, dg_neg = 0.0, ddg_pos = 0.0, ddg_neg = 0.0;
  for (int t = 0; t < taps; ++t) {
    const double x = t - k.radius;
    const double g = std::exp(-(x * x) / (2.0 * k.sigma * k.sigma));
    k.g[t] = g;
    k.dg[t] = -x * g;
    k.ddg[t] = (x * x / (k.sigma * k.sigma) - 1.0) * g;
    g_sum += g;
    if (k.dg[t] > 0.0)
      dg_pos += k.dg[t];
    else
      dg_neg -= k.dg[t];
    if (k.ddg[t] > 0.0)
      ddg_pos += k.ddg[t];
    else
      ddg_neg -= k.ddg[t];
  }
  for (int t = 0; t < taps; ++t) {
    k.g[t] /= g_sum;
    k.dg[t] /= (k.dg[t] > 0.0 ? dg_pos : dg_neg);
    k.ddg[t] /= (k.ddg[t] > 0.0 ? ddg_pos : ddg_neg);
  }
  return k;
}

std::vector<double> ColorErrorValues(const ImageF& reference, const ImageF& test, double ppd) {
  CheckPair(reference, test);
  CheckPpd(ppd);
  return ColorErrorFromPlanes(ToYCxCz(reference), ToYCxCz(test), ppd);
}

std::vector<double> FeatureErrorValues(const ImageF& reference, const ImageF& test, double ppd) {
  CheckPair(reference, test);
  CheckPpd(ppd);
  return FeatureErrorFromPlanes(ToYCxCz(reference), ToYCxCz(test), ppd);
}

std::vector<double> ErrorValuesUncached(const ImageF& reference, const ImageF& test, double ppd) {
  CheckPair(reference, test);
  CheckPpd(ppd);
  const Planes a = ToYCxCz(reference);
  const Planes b = ToYCxCz(test);
  std::vector<double> out = ColorErrorFromPlanes(a, b, ppd);
  const std::vector<double> feature = FeatureErrorFromPlanes(a, b, ppd);
  ForEachPixel(out.size(), [&](size_t i) { out[i] = std::pow(out[i], 1.0 - feature[i]); });
  return out;
}

}  // namespace flip

ImageF FlipErrorMap(const ImageF& reference, const ImageF& test, double ppd) {
  const FlipValues v = flip::ErrorValues(reference, test, ppd);
  ImageF map(reference.Width(), reference.Height(), 1, 0.0f);
  for (size_t i = 0; i < v.size(); ++i) map.Data()[i] = static_cast<float>(v[i]);
  return map;
}

namespace {

// Pooling (PoolFlip) sorts the values ascending and sums them in that order, as NVIDIA's
// tool does. FLIP maps hold float values >= 0 (flip_fast.cpp): their bit patterns order as
// unsigned integers, so they are sorted by an LSD radix sort (3 passes of 11 bits) whose
// passes run in parallel: per chunk a histogram of the pass's digit, then every chunk
// scatters its keys to offsets fixed by the histograms of the chunks before it (a stable
// pass). The sorted sequence is unique (equal values are indistinguishable), so the result is
// the same at any thread count and equals a std::sort of the values. Any other input (a value
// < 0, NaN, or one that is not a float) takes std::sort. What stays serial, for 2-thread
// scaling: the mean's sum in the given order (one pass, run as a task beside the sort so a
// second thread hides it), the 2048-digit prefix of each pass and the weighted median's sum
// in sorted order (one pass, its running sum kept in a register); buffers the loops write
// whole are not zero-filled first (DefaultInitAllocator).
constexpr int kSortGrain = 1 << 15;  // keys per chunk (fixed: chunks never depend on threads)
constexpr int kDigits = 2048;        // 11-bit digits

// Storage for sort keys whose every value is written before it is read: no zero-fill pass
// (a serial memset of 8 MB at 1080p, before the parallel loops that write them anyway).
using KeyVector = std::vector<uint32_t, DefaultInitAllocator<uint32_t>>;

// The values' float bit patterns, or nothing when some value is not a float >= 0.
bool FloatKeys(std::span<const double> values, KeyVector* keys) {
  const int n = static_cast<int>(values.size());
  keys->resize(values.size());
  std::vector<uint8_t> bad(static_cast<size_t>((n + kSortGrain - 1) / kSortGrain), 0);
  ParallelForChunks(n, kSortGrain, [&](int b, int e) {
    for (int i = b; i < e; ++i) {
      const double v = values[static_cast<size_t>(i)];
      const float f = static_cast<float>(v);
      if (!(v >= 0.0) || static_cast<double>(f) != v) bad[static_cast<size_t>(b / kSortGrain)] = 1;
      std::memcpy(&(*keys)[static_cast<size_t>(i)], &f, sizeof f);
    }
  });
  return std::find(bad.begin(), bad.end(), 1) == bad.end();
}

// Turns per-chunk digit counts (hist, chunk-major: chunk c's count of digit d at
// c · kDigits + d) into each chunk's first slot per digit (digit-major, then chunk order).
// Integer sums, so the same offsets whatever the split; the digit totals and the column walk
// run in parallel over ranges of digits (each range walks the chunks with contiguous rows),
// only the 2048-digit prefix is serial. Returns true when one digit holds every key.
bool DigitOffsets(std::vector<uint32_t>* hist, int chunks, uint32_t n) {
  constexpr int kDigitGrain = 256;
  std::vector<uint32_t> start(kDigits, 0);  // digit totals, then each digit's first slot
  ParallelForChunks(kDigits, kDigitGrain, [&](int d0, int d1) {
    for (int c = 0; c < chunks; ++c) {
      const uint32_t* h = hist->data() + static_cast<size_t>(c) * kDigits;
      for (int d = d0; d < d1; ++d) start[static_cast<size_t>(d)] += h[d];
    }
  });
  bool one_digit = false;
  uint32_t next = 0;
  for (uint32_t& s : start) {
    const uint32_t total = s;
    if (total == n) one_digit = true;
    s = next;
    next += total;
  }
  if (one_digit) return true;
  ParallelForChunks(kDigits, kDigitGrain, [&](int d0, int d1) {
    for (int c = 0; c < chunks; ++c) {
      uint32_t* h = hist->data() + static_cast<size_t>(c) * kDigits;
      for (int d = d0; d < d1; ++d) {
        const uint32_t count = h[d];
        h[d] = start[static_cast<size_t>(d)];
        start[static_cast<size_t>(d)] += count;
      }
    }
  });
  return false;
}

// Sorts `keys` ascending in place (parallel stable LSD radix, see above).
void RadixSortKeys(KeyVector* keys) {
  const int n = static_cast<int>(keys->size());
  const int chunks = (n + kSortGrain - 1) / kSortGrain;
  KeyVector tmp(keys->size());
  std::vector<uint32_t> hist(static_cast<size_t>(chunks) * kDigits);
  for (int shift = 0; shift < 32; shift += 11) {
    const uint32_t* src = keys->data();
    uint32_t* dst = tmp.data();
    ParallelForChunks(n, kSortGrain, [&](int b, int e) {
      uint32_t* h = &hist[static_cast<size_t>(b / kSortGrain) * kDigits];
      std::fill(h, h + kDigits, 0u);
      for (int i = b; i < e; ++i) ++h[(src[i] >> shift) & (kDigits - 1)];
    });
    // every key has this digit: the pass would not move anything
    if (DigitOffsets(&hist, chunks, static_cast<uint32_t>(n))) continue;
    ParallelForChunks(n, kSortGrain, [&](int b, int e) {
      uint32_t* h = &hist[static_cast<size_t>(b / kSortGrain) * kDigits];
      for (int i = b; i < e; ++i) dst[h[(src[i] >> shift) & (kDigits - 1)]++] = src[i];
    });
    keys->swap(tmp);
  }
}

double KeyValue(uint32_t key) {
  float f;
  std::memcpy(&f, &key, sizeof f);
  return static_cast<double>(f);
}

// The value-weighted median (PoolFlip): sums in sorted order, one pass. The running sum is
// kept at every kBlock-th element, so the crossing is found again by re-walking one block with
// the very additions of the pass (the same bits as a second full running pass).
template <typename Sorted>
double WeightedMedianOfSorted(size_t n, const Sorted& at) {
  constexpr size_t kBlock = 4096;
  std::vector<double> block_start((n + kBlock - 1) / kBlock);  // running sum before element b · kBlock
  double total = 0.0;
  for (size_t b = 0; b < block_start.size(); ++b) {
    block_start[b] = total;
    // The running sum stays in a register (no reference to it escapes): the chain costs one
    // add's latency per value; a push_back(total) made GCC keep it in memory (~2× slower).
    const size_t e = std::min(n, (b + 1) * kBlock);
    for (size_t i = b * kBlock; i < e; ++i) total += at(i);
  }
  if (!(total > 0.0)) return 0.0;
  const double half = 0.5 * total;
  // The running sum never decreases (values >= 0); the crossing lies in the last block that
  // starts at or below half.
  size_t b = 0;
  while (b + 1 < block_start.size() && !(block_start[b + 1] > half)) ++b;
  double running = block_start[b];
  for (size_t i = b * kBlock; i < n; ++i) {
    running += at(i);
    if (running > half) return at(i);
  }
  return 0.0;  // not reached: the running sum ends at total > half
}

}  // namespace

FlipPooled PoolFlip(std::span<const double> values) {
  AALAB_CHECK(!values.empty(), "PoolFlip of no values");
  FlipPooled p;
  // The mean's sum is one serial chain in the given order; it runs as a task beside the
  // sort (whose loops are parallel), so a second thread hides it. Same additions, same bits.
  KeyVector keys;
  bool float_keys = false;
  ParallelFor(2, [&](int task) {
    if (task == 0) {
      double sum = 0.0;
      double max = values[0];
      for (double v : values) {
        sum += v;
        max = std::max(max, v);
      }
      p.mean = sum / static_cast<double>(values.size());
      p.max = max;
    } else {
      float_keys = FloatKeys(values, &keys);
      if (float_keys) RadixSortKeys(&keys);
    }
  });
  if (float_keys) {
    p.weighted_median = WeightedMedianOfSorted(keys.size(), [&](size_t i) { return KeyValue(keys[i]); });
  } else {
    std::vector<double> sorted(values.begin(), values.end());
    std::sort(sorted.begin(), sorted.end());
    p.weighted_median = WeightedMedianOfSorted(sorted.size(), [&](size_t i) { return sorted[i]; });
  }
  return p;
}

namespace {

std::vector<MetricValue> ComputeFlipMetric(const MetricInput& in) {
  AALAB_CHECK(in.image && in.reference, "flip needs image and reference");
  RequireSameShape(*in.reference, *in.image, "flip");
  if (in.reference->Empty()) {
    return {MetricValue{"flip_mean", std::nullopt, "empty image"},
            MetricValue{"flip_median_weighted", std::nullopt, "empty image"},
            MetricValue{"flip_max", std::nullopt, "empty image"}};
  }
  const FlipPooled p =
      in.flip_values ? PoolFlip(*in.flip_values) : PoolFlip(flip::ErrorValues(*in.reference, *in.image, in.flip_ppd));
  return {MetricValue{"flip_mean", p.mean, ""}, MetricValue{"flip_median_weighted", p.weighted_median, ""},
          MetricValue{"flip_max", p.max, ""}};
}

}  // namespace

std::vector<MetricEntry> FlipMetrics() {
  return {
      {"flip",
       "LDR-FLIP (Andersson 2020) at the viewing condition's pixels/degree (--viewing; default 67): mean, "
       "value-weighted median and "
       "max of the per-pixel error in [0,1]",
       {{"flip_mean", "FLIP mean", "", Improves::kLower, kSignificantDigits,
         "LDR-FLIP per-pixel error (0..1) averaged over the image, at the run's viewing condition (pixels per "
         "degree in the header; default 67).",
         "Rewards what a viewer sees when flipping between the result and the reference at this viewing "
         "distance: both jaggies and lost sharpness count, fine detail below the eye's resolution does not. A "
         "method that trades aliasing for blur can score worse than no AA."},
        {"flip_median_weighted", "FLIP wtd. median", "", Improves::kLower, kSignificantDigits,
         "Value-weighted median of the LDR-FLIP error (as NVIDIA's FLIP tool prints).", ""},
        {"flip_max", "FLIP max", "", Improves::kLower, kSignificantDigits, "Largest per-pixel LDR-FLIP error.", ""}},
       &ComputeFlipMetric}};
}

}  // namespace aalab
