// SMAA's two precomputed textures, generated at first use from the published algorithm
// (iryoku/smaa Scripts/AreaTex.py and Scripts/SearchTex.py; read for the definitions, this
// is our own code). Both scripts compute in Python floats (IEEE double); so do we, with the
// same operations in the same order, so ties (points exactly on a line in the diagonal
// brute force) fall the same way. Values are then stored as the shipped 8-bit textures:
// int(255·v) (the scripts' bytes(): truncation toward zero), read back as k/255 by the
// sampler, because the GPU running the reference shader sees exactly those quantised values.
//
// Area texture, 160×560, two channels (r, g of an RGBA8 image here):
//   x 0..79    orthogonal areas: a 5×5 grid of 16×16 tiles; tile (i, j) holds the crossing-
//              edge pattern whose rounded bilinear codes (0, 1, 3, 4 of round(4·e)) are
//              (i, j); inside a tile, texel (l, r) holds the area for distances (l², r²)
//              (quadratic compression, looked up with sqrt(d)).
//   x 80..159  diagonal areas: a 4×4 grid of 20×20 tiles, texel (l, r) = distances (l, r).
//   rows       one 80-row band per subsample offset; SMAA 1x reads band 0 (offset 0 /
//              (0, 0)). Only band 0 is generated; the other bands stay 0 (T2x/S2x/4x only).
// Search texture, 64×16, one channel: for the bilinear "pseudo gather" values (e_left,
//   e_top) = (k/32, m/32), 127 × the extra distance (0, 1, 2) to add after the search's last
//   step, left half for searches to the left/up, right half (x + 33) for right/down; the
//   66×33 table is cropped to rows 17..32, columns 0..63 and flipped vertically.
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "methods/smaa.h"

namespace aalab {

namespace {

using D2 = std::pair<double, double>;

constexpr int kSizeOrtho = 16;               // SIZE_ORTHO
constexpr int kSizeDiag = 20;                // SIZE_DIAG
constexpr int kSamplesDiag = 30;             // SAMPLES_DIAG
constexpr double kSmoothMaxDistance = 32.0;  // SMOOTH_MAX_DISTANCE

// Tile (column, row) of each pattern in its block (the script's edgesortho / edgesdiag).
// Orthogonal: the tile is the pair of rounded crossing-edge codes round(4·e1), round(4·e2)
// that SMAAArea looks up (codes 0, 1, 3, 4); diagonal: the pair of codes 2·c.x + c.y.
constexpr std::array<std::array<int, 2>, 16> kTileOrtho = {{{0, 0},
                                                            {3, 0},
                                                            {0, 3},
                                                            {3, 3},
                                                            {1, 0},
                                                            {4, 0},
                                                            {1, 3},
                                                            {4, 3},
                                                            {0, 1},
                                                            {3, 1},
                                                            {0, 4},
                                                            {3, 4},
                                                            {1, 1},
                                                            {4, 1},
                                                            {1, 4},
                                                            {4, 4}}};
constexpr std::array<std::array<int, 2>, 16> kTileDiag = {{{0, 0},
                                                           {1, 0},
                                                           {0, 2},
                                                           {1, 2},
                                                           {2, 0},
                                                           {3, 0},
                                                           {2, 2},
                                                           {3, 2},
                                                           {0, 1},
                                                           {1, 1},
                                                           {0, 3},
                                                           {1, 3},
                                                           {2, 1},
                                                           {3, 1},
                                                           {2, 3},
                                                           {3, 3}}};

// Area under the segment p1→p2 within the pixel column [x, x+1], split by the side of the
// edge it lies on: (area below, area above) as the script's inner area().
D2 SegmentArea(D2 p1, D2 p2, double x) {
  const double dx = p2.first - p1.first;
  const double dy = p2.second - p1.second;
  const double x1 = x;
  const double x2 = x + 1.0;
  const double y1 = p1.second + dy * (x1 - p1.first) / dx;
  const double y2 = p1.second + dy * (x2 - p1.first) / dx;
  const bool inside = (x1 >= p1.first && x1 < p2.first) || (x2 > p1.first && x2 <= p2.first);
  if (!inside) return {0.0, 0.0};
  const bool trapezoid =
      std::copysign(1.0, y1) == std::copysign(1.0, y2) || std::fabs(y1) < 1e-4 || std::fabs(y2) < 1e-4;
  if (trapezoid) {
    const double a = (y1 + y2) / 2.0;
    return a < 0.0 ? D2{std::fabs(a), 0.0} : D2{0.0, std::fabs(a)};
  }
  // Two triangles either side of the crossing point xc.
  const double xc = -p1.second * dx / dy + p1.first;
  double int_part = 0.0;
  const double frac = std::modf(xc, &int_part);
  const double a1 = xc > p1.first ? y1 * frac / 2.0 : 0.0;
  const double a2 = xc < p2.first ? y2 * (1.0 - frac) / 2.0 : 0.0;
  const double a = std::fabs(a1) > std::fabs(a2) ? a1 : -a2;
  return a < 0.0 ? D2{std::fabs(a1), std::fabs(a2)} : D2{std::fabs(a2), std::fabs(a1)};
}

D2 Add(D2 a, D2 b) { return {a.first + b.first, a.second + b.second}; }

// The script's smootharea for U shapes: blends sqrt(2a)/2 toward a with distance.
std::pair<D2, D2> SmoothArea(double d, D2 a1, D2 a2) {
  const D2 b1{std::sqrt(a1.first * 2.0) * 0.5, std::sqrt(a1.second * 2.0) * 0.5};
  const D2 b2{std::sqrt(a2.first * 2.0) * 0.5, std::sqrt(a2.second * 2.0) * 0.5};
  const double p = std::min(std::max(d / kSmoothMaxDistance, 0.0), 1.0);
  auto lerp = [p](double a, double b) { return a + (b - a) * p; };
  return {D2{lerp(b1.first, a1.first), lerp(b1.second, a1.second)},
          D2{lerp(b2.first, a2.first), lerp(b2.second, a2.second)}};
}

// Fraction of the unit square at p (sampled on a 30×30 lattice including both borders) on
// the positive side of the line p1→p2 (the whole square when p1 == p2): area1 of areadiag.
double BruteForceArea(D2 p1, D2 p2, D2 p) {
  const bool degenerate = p1 == p2;
  const double xm = (p1.first + p2.first) / 2.0;
  const double ym = (p1.second + p2.second) / 2.0;
  const double a = p2.second - p1.second;
  const double b = p1.first - p2.first;
  double count = 0.0;
  for (int i = 0; i < kSamplesDiag; ++i) {
    for (int j = 0; j < kSamplesDiag; ++j) {
      const double sx = p.first + static_cast<double>(i) / static_cast<double>(kSamplesDiag - 1);
      const double sy = p.second + static_cast<double>(j) / static_cast<double>(kSamplesDiag - 1);
      bool in = true;
      if (!degenerate) in = a * (sx - xm) + b * (sy - ym) > 0.0;
      if (in) count += 1.0;
    }
  }
  return count / static_cast<double>(kSamplesDiag * kSamplesDiag);
}

}  // namespace

std::pair<double, double> SmaaAreaOrtho(int pattern, int left, int right, double offset) {
  AALAB_CHECK(pattern >= 0 && pattern < 16, "SMAA orthogonal pattern out of range");
  const double d = static_cast<double>(left + right + 1);
  const double o1 = 0.5 + offset;
  const double o2 = 0.5 + offset - 1.0;
  const double l = static_cast<double>(left);
  const double half = d / 2.0;
  auto area = [l](D2 p1, D2 p2) { return SegmentArea(p1, p2, l); };
  switch (pattern) {
    case 0: return {0.0, 0.0};
    case 1: return left <= right ? area({0.0, o2}, {half, 0.0}) : D2{0.0, 0.0};
    case 2: return left >= right ? area({half, 0.0}, {d, o2}) : D2{0.0, 0.0};
    case 3: {
      const auto [a1, a2] = SmoothArea(d, area({0.0, o2}, {half, 0.0}), area({half, 0.0}, {d, o2}));
      return Add(a1, a2);
    }
    case 4: return left <= right ? area({0.0, o1}, {half, 0.0}) : D2{0.0, 0.0};
    case 5: return {0.0, 0.0};
    case 6:
      if (std::fabs(offset) > 0.0) {
        const D2 a1 = area({0.0, o1}, {d, o2});
        const D2 a2 = Add(area({0.0, o1}, {half, 0.0}), area({half, 0.0}, {d, o2}));
        const D2 s = Add(a1, a2);
        return {s.first / 2.0, s.second / 2.0};
      }
      return area({0.0, o1}, {d, o2});
    case 7: return area({0.0, o1}, {d, o2});
    case 8: return left >= right ? area({half, 0.0}, {d, o1}) : D2{0.0, 0.0};
    case 9:
      if (std::fabs(offset) > 0.0) {
        const D2 a1 = area({0.0, o2}, {d, o1});
        const D2 a2 = Add(area({0.0, o2}, {half, 0.0}), area({half, 0.0}, {d, o1}));
        const D2 s = Add(a1, a2);
        return {s.first / 2.0, s.second / 2.0};
      }
      return area({0.0, o2}, {d, o1});
    case 10: return {0.0, 0.0};
    case 11: return area({0.0, o2}, {d, o1});
    case 12: {
      const auto [a1, a2] = SmoothArea(d, area({0.0, o1}, {half, 0.0}), area({half, 0.0}, {d, o1}));
      return Add(a1, a2);
    }
    case 13: return area({0.0, o2}, {d, o1});
    case 14: return area({0.0, o1}, {d, o2});
    default: return {0.0, 0.0};  // 15: crossing edges on both sides at both ends
  }
}

std::pair<double, double> SmaaAreaDiag(int pattern, int left, int right, double ox, double oy) {
  AALAB_CHECK(pattern >= 0 && pattern < 16, "SMAA diagonal pattern out of range");
  const double d = static_cast<double>(left + right + 1);  // the line's length; `right` enters only here
  const double l = static_cast<double>(left);
  const int e1 = kTileDiag[static_cast<size_t>(pattern)][0];
  const int e2 = kTileDiag[static_cast<size_t>(pattern)][1];
  // Area of the line p1→p2 (ends shifted by the subsample offset where that end has a
  // crossing edge) in the pixel and in its opposite: (1 − area at (1,0)+l, area at (1,1)+l).
  auto area = [&](D2 p1, D2 p2) {
    if (e1 > 0) p1 = {p1.first + ox, p1.second + oy};
    if (e2 > 0) p2 = {p2.first + ox, p2.second + oy};
    const double a1 = BruteForceArea(p1, p2, {1.0 + l, 0.0 + l});
    const double a2 = BruteForceArea(p1, p2, {1.0 + l, 1.0 + l});
    return D2{1.0 - a1, a2};
  };
  auto blend = [](D2 a, D2 b) { return D2{(a.first + b.first) / 2.0, (a.second + b.second) / 2.0}; };
  auto end = [d](double x, double y) { return D2{x + d, y + d}; };
  switch (pattern) {
    case 0: return blend(area({1.0, 1.0}, end(1.0, 1.0)), area({1.0, 0.0}, end(1.0, 0.0)));
    case 1: return blend(area({1.0, 0.0}, end(0.0, 0.0)), area({1.0, 0.0}, end(1.0, 0.0)));
    case 2: return blend(area({0.0, 0.0}, end(1.0, 0.0)), area({1.0, 0.0}, end(1.0, 0.0)));
    case 3: return area({1.0, 0.0}, end(1.0, 0.0));
    case 4: return blend(area({1.0, 1.0}, end(0.0, 0.0)), area({1.0, 1.0}, end(1.0, 0.0)));
    case 5: return blend(area({1.0, 1.0}, end(0.0, 0.0)), area({1.0, 0.0}, end(1.0, 0.0)));
    case 6: return area({1.0, 1.0}, end(1.0, 0.0));
    case 7: return blend(area({1.0, 1.0}, end(1.0, 0.0)), area({1.0, 0.0}, end(1.0, 0.0)));
    case 8: return blend(area({0.0, 0.0}, end(1.0, 1.0)), area({1.0, 0.0}, end(1.0, 1.0)));
    case 9: return area({1.0, 0.0}, end(1.0, 1.0));
    case 10: return blend(area({0.0, 0.0}, end(1.0, 1.0)), area({1.0, 0.0}, end(1.0, 0.0)));
    case 11: return blend(area({1.0, 0.0}, end(1.0, 1.0)), area({1.0, 0.0}, end(1.0, 0.0)));
    case 12: return area({1.0, 1.0}, end(1.0, 1.0));
    case 13: return blend(area({1.0, 1.0}, end(1.0, 1.0)), area({1.0, 0.0}, end(1.0, 1.0)));
    case 14: return blend(area({1.0, 1.0}, end(1.0, 1.0)), area({1.0, 1.0}, end(1.0, 0.0)));
    default: return blend(area({1.0, 1.0}, end(1.0, 1.0)), area({1.0, 0.0}, end(1.0, 0.0)));  // 15
  }
}

namespace {

// The script's bytes(): int(255·v), truncation toward zero; values stay in [0, 1].
uint8_t TextureByte(double v) {
  const double t = std::trunc(255.0 * v);
  return static_cast<uint8_t>(std::min(std::max(t, 0.0), 255.0));
}

}  // namespace

const Image8& SmaaAreaTexture() {
  static const Image8 tex = [] {
    Image8 t(160, 560, 4, 0);
    for (int p = 0; p < 16; ++p) {
      const int tx = kTileOrtho[static_cast<size_t>(p)][0] * kSizeOrtho;
      const int ty = kTileOrtho[static_cast<size_t>(p)][1] * kSizeOrtho;
      for (int l = 0; l < kSizeOrtho; ++l) {
        for (int r = 0; r < kSizeOrtho; ++r) {
          const D2 a = SmaaAreaOrtho(p, l * l, r * r, 0.0);
          uint8_t* px = t.Pixel(tx + l, ty + r);
          px[0] = TextureByte(a.first);
          px[1] = TextureByte(a.second);
        }
      }
    }
    for (int p = 0; p < 16; ++p) {
      const int tx = 5 * kSizeOrtho + kTileDiag[static_cast<size_t>(p)][0] * kSizeDiag;
      const int ty = kTileDiag[static_cast<size_t>(p)][1] * kSizeDiag;
      for (int l = 0; l < kSizeDiag; ++l) {
        for (int r = 0; r < kSizeDiag; ++r) {
          const D2 a = SmaaAreaDiag(p, l, r, 0.0, 0.0);
          uint8_t* px = t.Pixel(tx + l, ty + r);
          px[0] = TextureByte(a.first);
          px[1] = TextureByte(a.second);
        }
      }
    }
    return t;
  }();
  return tex;
}

namespace {

// The bilinear "pseudo gather" value of four edges at the search's sample position
// (-0.25, -0.125): e[0] e[1] on the row above, e[2] e[3] on the current row.
double GatherValue(const std::array<int, 4>& e) {
  auto lerp = [](double a, double b, double p) { return a + (b - a) * p; };
  const double a = lerp(e[0], e[1], 1.0 - 0.25);
  const double b = lerp(e[2], e[3], 1.0 - 0.25);
  return lerp(a, b, 1.0 - 0.125);
}

// The inverse of GatherValue over the 16 edge combinations; false when v is none of them.
bool DecodeGather(double v, std::array<int, 4>* e) {
  for (int bits = 0; bits < 16; ++bits) {
    const std::array<int, 4> c = {(bits >> 3) & 1, (bits >> 2) & 1, (bits >> 1) & 1, bits & 1};
    if (GatherValue(c) == v) {
      *e = c;
      return true;
    }
  }
  return false;
}

}  // namespace

int SmaaSearchDelta(bool right, double e_left, double e_top) {
  std::array<int, 4> l{}, t{};
  if (!DecodeGather(e_left, &l) || !DecodeGather(e_top, &t)) return -1;
  int d = 0;
  if (!right) {
    // Continue over an edge on the current pixel's top; once more over the next one when no
    // crossing edge breaks the line.
    if (t[3] == 1) d += 1;
    if (d == 1 && t[2] == 1 && l[1] != 1 && l[3] != 1) d += 1;
  } else {
    if (t[3] == 1 && l[1] != 1 && l[3] != 1) d += 1;
    if (d == 1 && t[2] == 1 && l[0] != 1 && l[2] != 1) d += 1;
  }
  return d;
}

const Image8& SmaaSearchTexture() {
  static const Image8 tex = [] {
    // The full 66×33 table, then the crop and the flip.
    std::array<std::array<uint8_t, 66>, 33> full{};
    for (int x = 0; x < 33; ++x) {
      for (int y = 0; y < 33; ++y) {
        const double ex = 0.03125 * x, ey = 0.03125 * y;
        const int dl = SmaaSearchDelta(false, ex, ey);
        const int dr = SmaaSearchDelta(true, ex, ey);
        if (dl >= 0) full[static_cast<size_t>(y)][static_cast<size_t>(x)] = static_cast<uint8_t>(127 * dl);
        if (dr >= 0) full[static_cast<size_t>(y)][static_cast<size_t>(33 + x)] = static_cast<uint8_t>(127 * dr);
      }
    }
    Image8 t(64, 16, 4, 0);
    for (int r = 0; r < 16; ++r) {
      for (int x = 0; x < 64; ++x) t.Pixel(x, r)[0] = full[static_cast<size_t>(32 - r)][static_cast<size_t>(x)];
    }
    return t;
  }();
  return tex;
}

}  // namespace aalab
