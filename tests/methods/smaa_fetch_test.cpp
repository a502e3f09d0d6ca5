// The fetch shortcuts of the fused SMAA pass (methods/smaa_fast.h).
// BilinearAt8 against BilinearAt(..., SubTexel::kFixed8): the same texels and weights, and
// field for field outside x, y in (−1, 0) (its contract): every 8-bit
// rounding boundary (k + 1/512 for k/256 over [-600, 8800]) and the floats a few ulps either
// side of it, the texel edges and centres, and random floats of every magnitude below 2^22.
// DiagSurelyZero, the byte test with which the fused pass skips the diagonal search, against the shader itself
// (smaa_shader.h's WeightsShader reading the same edge bytes through PlaneEdges, 8-bit fetches): on random edge planes
// whose bytes are biased towards both bits (the diagonal staircases the test has to see through), for every pixel with
// a top edge, wherever DiagSurelyZero answers true the shader with the diagonal search on returns the bits of the
// shader with it off and makes exactly the fetches it reported more. Frame widths and heights up to 8192 (the
// coordinates' rounding grows with the size), max_search_steps_diag 1, 8, 16 and 20, with and without corners; and the
// test must answer true for most pixels (a test that never answers would pass the first part).
// PlaneEdges::Sample's and InlineSampler's 8-bit paths against BilinearSampler (kFixed8).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/sampler.h"
#include "methods/smaa.h"
#include "methods/smaa_fast.h"
#include "methods/smaa_shader.h"

namespace aalab {
namespace {

using smaa_internal::EdgePlane;
using smaa_internal::InlineSampler;
using smaa_internal::PlaneEdges;
using smaa_internal::Tex8;

bool SameBits(const Float4& a, const Float4& b) {
  return std::memcmp(&a.r, &b.r, 4) == 0 && std::memcmp(&a.g, &b.g, 4) == 0 && std::memcmp(&a.b, &b.b, 4) == 0 &&
         std::memcmp(&a.a, &b.a, 4) == 0;
}

// A w×h plane of random edge bytes: each 0..3, 3 (both bits) with probability ~ both/8.
EdgePlane RandomPlane(int w, int h, uint32_t seed, int both) {
  EdgePlane pl;
  pl.w = w, pl.h = h;
  pl.e.reset(new uint8_t[static_cast<size_t>(w) * h]);
  for (size_t i = 0; i < static_cast<size_t>(w) * h; ++i) {
    seed = seed * 1664525u + 1013904223u;
    const uint32_t r = seed >> 24;
    pl.e[i] = static_cast<uint8_t>((r & 7) < static_cast<uint32_t>(both) ? 3 : (r >> 3) & 3);
  }
  return pl;
}

// Returns {pixels with a top edge, pixels DiagSurelyZero settled}.
std::pair<long, long> Check(const EdgePlane& pl, const SmaaParams& p, const std::string& what) {
  const smaa_detail::Frame f(pl.w, pl.h);
  InlineSampler a1(Tex8(SmaaAreaTexture()), p.subtexel), s1(Tex8(SmaaSearchTexture()), p.subtexel);
  InlineSampler a2(Tex8(SmaaAreaTexture()), p.subtexel), s2(Tex8(SmaaSearchTexture()), p.subtexel);
  PlaneEdges full_reader(pl, p.subtexel), plain_reader(pl, p.subtexel);
  SmaaParams plain_params = p;
  plain_params.diag = false;
  smaa_detail::WeightsShader<PlaneEdges, InlineSampler> full(full_reader, a1, s1, p, f);
  smaa_detail::WeightsShader<PlaneEdges, InlineSampler> plain(plain_reader, a2, s2, plain_params, f);
  long top = 0, settled = 0;
  for (int y = 0; y < pl.h; ++y) {
    for (int x = 0; x < pl.w; ++x) {
      if (!(pl.Row(y)[x] & smaa_internal::kTop)) continue;
      ++top;
      int taps = -1;
      if (!smaa_internal::DiagSurelyZero(pl, x, y, &taps)) continue;
      ++settled;
      const uint64_t t0 = full_reader.Taps() + a1.Taps() + s1.Taps();
      const uint64_t u0 = plain_reader.Taps() + a2.Taps() + s2.Taps();
      const Float4 want = full.Run(x, y);
      const Float4 got = plain.Run(x, y);
      const uint64_t t = full_reader.Taps() + a1.Taps() + s1.Taps() - t0;
      const uint64_t u = plain_reader.Taps() + a2.Taps() + s2.Taps() - u0;
      EXPECT_TRUE(SameBits(want, got)) << what << " pixel " << x << "," << y;
      EXPECT_EQ(t, u + static_cast<uint64_t>(taps)) << what << " pixel " << x << "," << y;
      if (::testing::Test::HasFailure()) return {top, settled};
    }
  }
  return {top, settled};
}

// The texels an axis of a footprint reads and the weight of the second: (a, a, 0) where the
// two clamped columns coincide or the fraction is 0 (the lerp returns the first exactly).
struct Axis {
  int a, b;
  float f;
};
Axis Read(int x0, float fx, int n) {
  const int a = std::clamp(x0, 0, n - 1), b = std::clamp(x0 + 1, 0, n - 1);
  if (a == b || fx == 0.0f) return {a, a, 0.0f};
  return {a, b, fx};
}
bool SameAxis(const Axis& p, const Axis& q) { return p.a == q.a && p.b == q.b && std::memcmp(&p.f, &q.f, 4) == 0; }

// BilinearAt8's contract: the same texels with the same weights as BilinearAt; and the same
// fields wherever BilinearAt's fraction is exact (x outside (−1, 0)).
bool SameFootprint(const BilinearFootprint& a, const BilinearFootprint& b, float u, float v, int w, int h) {
  if (!SameAxis(Read(a.x0, a.fx, w), Read(b.x0, b.fx, w)) || !SameAxis(Read(a.y0, a.fy, h), Read(b.y0, b.fy, h)))
    return false;
  const bool x_exact = !(u - 0.5f > -1.0f && u - 0.5f < 0.0f), y_exact = !(v - 0.5f > -1.0f && v - 0.5f < 0.0f);
  return (!x_exact || (a.x0 == b.x0 && std::memcmp(&a.fx, &b.fx, 4) == 0)) &&
         (!y_exact || (a.y0 == b.y0 && std::memcmp(&a.fy, &b.fy, 4) == 0));
}

TEST(SmaaFetch, BilinearAt8IsBilinearAtFixed8) {
  const int w = 8192, h = 4099;
  long checked = 0;
  auto check = [&](float u, float v) {
    const BilinearFootprint want = BilinearAt(u, v, w, h, SubTexel::kFixed8);
    const BilinearFootprint got = smaa_internal::BilinearAt8(u, v, w, h);
    ++checked;
    return SameFootprint(want, got, u, v, w, h);
  };
  for (int i = -600 * 512; i < 8800 * 512; ++i) {
    const float c = static_cast<float>(i) / 512.0f;  // texel edges and centres, 8-bit boundaries (odd i)
    float up = c, down = c;
    for (int k = 0; k < 4; ++k) {
      ASSERT_TRUE(check(up, 0.5f) && check(down, 7.25f) && check(3.0f, up) && check(-1.5f, down)) << up << " " << down;
      up = std::nextafter(up, 1e9f);
      down = std::nextafter(down, -1e9f);
    }
  }
  uint32_t seed = 99;
  for (int i = 0; i < 2000000; ++i) {
    seed = seed * 1664525u + 1013904223u;
    const uint32_t a = seed;
    seed = seed * 1664525u + 1013904223u;
    float u, v;
    const uint32_t ub = (a & 0x807fffffu) | (((a >> 23) % 149u) << 23);  // exponents up to 2^21
    const uint32_t vb = (seed & 0x807fffffu) | (((seed >> 23) % 149u) << 23);
    std::memcpy(&u, &ub, 4);
    std::memcpy(&v, &vb, 4);
    ASSERT_TRUE(check(u, v)) << u << " " << v;
  }
  EXPECT_GT(checked, 30000000);
}

TEST(SmaaFetch, DiagSurelyZeroMatchesTheDiagonalSearch) {
  struct Size {
    int w, h;
  };
  uint32_t seed = 7;
  for (const Size s : {Size{5, 4}, Size{64, 48}, Size{1920, 6}, Size{6, 1080}, Size{8192, 3}, Size{3, 8192},
                       Size{7919, 5}, Size{4, 6007}}) {
    for (int both : {0, 1, 3}) {
      const EdgePlane pl = RandomPlane(s.w, s.h, seed += 101, both);
      for (int steps : {1, 8, 16, 20}) {
        for (bool corner : {true, false}) {
          SmaaParams p = SmaaPreset("ultra");
          p.max_search_steps_diag = steps;
          p.corner = corner;
          const std::string what = std::to_string(s.w) + "x" + std::to_string(s.h) + " both " + std::to_string(both) +
                                   " steps " + std::to_string(steps) + (corner ? " corner" : "");
          const auto [top, settled] = Check(pl, p, what);
          ASSERT_FALSE(::testing::Test::HasFailure()) << what;
          if (s.w >= 5 && s.h >= 4 && both == 0) {
            EXPECT_GT(settled, top / 10) << what;
          }
        }
      }
    }
  }
}

// PlaneEdges::Sample with 8-bit fractions (its one-address read inside the plane, its clamps at
// the border) against the reference path's fetch: BilinearSampler(kFixed8) on the RGBA8 edge
// texture (r = 255 for bit 0, g = 255 for bit 1), r and g bit for bit. Planes from 1×1 to
// 67×33 (one-texel rows and columns, where no footprint lies inside); every coordinate on a
// 1/1024 grid over [−3, size + 3] and a few ulps either side of it, paired with random
// coordinates on the other axis, then random pairs.
TEST(SmaaFetch, PlaneEdgesFixed8IsTheSamplerOnTheEdgeTexture) {
  const int sizes[][2] = {{1, 1}, {1, 6}, {6, 1}, {2, 2}, {7, 5}, {67, 33}};
  uint32_t seed = 12345;
  auto rnd = [&seed](float lo, float hi) {
    seed = seed * 1664525u + 1013904223u;
    return lo + (hi - lo) * static_cast<float>(seed >> 8) / 16777216.0f;
  };
  for (const auto& sz : sizes) {
    const int w = sz[0], h = sz[1];
    const EdgePlane pl = RandomPlane(w, h, static_cast<uint32_t>(w * 131 + h), 2);
    Image8 tex(w, h, 4);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const uint8_t e = pl.Row(y)[x];
        uint8_t* t = tex.Row(y) + 4 * x;
        t[0] = e & 1 ? 255 : 0, t[1] = e & 2 ? 255 : 0, t[2] = 0, t[3] = 0;
      }
    }
    BilinearSampler ref(tex, SubTexel::kFixed8);
    PlaneEdges fast(pl, SubTexel::kFixed8);
    long n = 0, bad = 0;
    auto check = [&](float u, float v) {
      const Float4 r = ref.Sample(u, v);
      const smaa_detail::F2 f = fast.Sample(u, v);
      ++n;
      if (std::memcmp(&r.r, &f.x, 4) != 0 || std::memcmp(&r.g, &f.y, 4) != 0) {
        if (++bad < 5) ADD_FAILURE() << w << "x" << h << " at (" << u << ", " << v << "): " << f.x << ", " << f.y;
      }
    };
    for (int axis = 0; axis < 2; ++axis) {
      const int size = axis == 0 ? w : h;
      for (int k = -3 * 1024; k <= (size + 3) * 1024; ++k) {
        float c = static_cast<float>(k) / 1024.0f;
        for (int ulp = 0; ulp < 3; ++ulp, c = std::nextafter(c, -1e9f)) {
          const float o = axis == 0 ? rnd(-3.0f, h + 3.0f) : rnd(-3.0f, w + 3.0f);
          if (axis == 0) check(c, o), check(std::nextafter(c, 1e9f), o);
          if (axis == 1) check(o, c), check(o, std::nextafter(c, 1e9f));
        }
      }
    }
    for (int i = 0; i < 200000; ++i) check(rnd(-3.0f, w + 3.0f), rnd(-3.0f, h + 3.0f));
    EXPECT_EQ(bad, 0) << w << "x" << h << ", " << n << " fetches";
    EXPECT_EQ(fast.Taps(), static_cast<uint64_t>(n));
  }
}

// InlineSampler::SampleNormalized with 8-bit fractions against BilinearSampler(kFixed8)'s, on
// random RGBA8 textures from 1×1 to 67×33: all four channels bit for bit, at normalised
// coordinates over [−0.2, 1.2] on a fine grid of each axis and at random.
TEST(SmaaFetch, InlineSamplerFixed8IsTheBilinearSampler) {
  const int sizes[][2] = {{1, 1}, {1, 6}, {6, 1}, {2, 2}, {7, 5}, {67, 33}};
  uint32_t seed = 777;
  auto next = [&seed] { return seed = seed * 1664525u + 1013904223u; };
  auto rnd = [&next](float lo, float hi) { return lo + (hi - lo) * static_cast<float>(next() >> 8) / 16777216.0f; };
  for (const auto& sz : sizes) {
    const int w = sz[0], h = sz[1];
    Image8 tex(w, h, 4);
    for (int y = 0; y < h; ++y) {
      for (int i = 0; i < 4 * w; ++i) tex.Row(y)[i] = static_cast<uint8_t>(next() >> 24);
    }
    BilinearSampler ref(tex, SubTexel::kFixed8);
    InlineSampler fast(Tex8(tex), SubTexel::kFixed8);
    long n = 0, bad = 0;
    auto check = [&](float s, float t) {
      const Float4 r = ref.SampleNormalized(s, t);
      const Float4 f = fast.SampleNormalized(s, t);
      ++n;
      if (!SameBits(r, f) && ++bad < 5) ADD_FAILURE() << w << "x" << h << " at (" << s << ", " << t << ")";
    };
    for (int k = -2048; k <= 12288; ++k) {
      const float c = static_cast<float>(k) / 10240.0f;
      check(c, rnd(-0.2f, 1.2f)), check(rnd(-0.2f, 1.2f), c);
    }
    for (int i = 0; i < 200000; ++i) check(rnd(-0.2f, 1.2f), rnd(-0.2f, 1.2f));
    EXPECT_EQ(bad, 0) << w << "x" << h << ", " << n << " fetches";
    EXPECT_EQ(fast.Taps(), static_cast<uint64_t>(n));
  }
}

}  // namespace
}  // namespace aalab
