// SSIM's float32 production path (metrics/ssim_float.cpp) held to its derived bound, pixel by
// pixel, against an accurate double map (tests/metrics/ssim_bound.h), on adversarial inputs:
// flat images, 0/1 extremes, sharp edges inside a tile (flat windows far from the tile's
// centre: the bound's worst case), a constant offset of 1000, tiny and odd sizes, images that
// cross tile boundaries, 3 and 4 channels, both argument orders. Planted drift (no centring,
// a dropped tap, float map arithmetic) fails these: the bound scales with each window's
// spread about its tile centre, not with the values.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/parallel.h"
#include "metrics/ssim.h"
#include "tests/metrics/ssim_bound.h"
#include "tests/metrics/test_images.h"

namespace aalab {
namespace {

// Every pixel of every channel within its bound; the means too.
void ExpectWithinBound(const ImageF& a, const ImageF& b, const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    const testssim::Drift d = testssim::MeasureDrift(a, b, c);
    if (std::getenv("SSIM_DRIFT_PRINT"))
      std::printf("DRIFT %s c%d worst_abs %.3g worst_ratio %.3g mean_abs %.3g mean_bound %.3g\n", what.c_str(), c,
                  d.worst_abs, d.worst_ratio, d.mean_abs, d.mean_bound);
    EXPECT_LE(d.worst_ratio, 1.0) << what << " channel " << c << ": worst |Δ| " << d.worst_abs;
    EXPECT_LE(d.mean_abs, d.mean_bound) << what << " channel " << c;
  }
}

ImageF Random(int w, int h, int channels, uint32_t seed, float lo, float hi) {
  ImageF img(w, h, channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c)
        img.At(x, y, c) =
            lo +
            (hi - lo) * static_cast<float>(testimg::Hash32(seed * 7777u + x + 4099u * y + 131u * c) % 1000u) / 999.0f;
  return img;
}

// Two flat regions split by a slanted edge: windows far from the edge are flat at 0.02 or
// 0.98 while the tile's centre lies between them.
ImageF Edge(int w, int h, int channels, float lo, float hi, int slope) {
  ImageF img(w, h, channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) img.At(x, y, c) = (3 * x + slope * y + 17 * c) % 200 < 100 ? lo : hi;
  return img;
}

TEST(SsimPrecision, TestPairsWithinBound) {
  for (auto [w, h, seed] : {std::tuple{48, 40, 1u}, std::tuple{33, 21, 2u}, std::tuple{40, 30, 7u},
                            std::tuple{160, 120, 11u}, std::tuple{300, 80, 3u}}) {
    const auto [a, b] = testimg::MakePair(w, h, seed);
    ExpectWithinBound(a, b, "MakePair " + std::to_string(w) + "x" + std::to_string(h));
    ExpectWithinBound(b, a, "MakePair reversed");
  }
}

TEST(SsimPrecision, FlatImages) {
  for (auto [va, vb] : {std::pair{0.3f, 0.7f}, std::pair{0.0f, 1.0f}, std::pair{0.98f, 0.97f}, std::pair{0.5f, 0.5f}}) {
    const ImageF a(40, 23, 3, va), b(40, 23, 3, vb);
    ExpectWithinBound(a, b, "flat");
    // Flat windows: σ = 0, so Eq. (13) is (2μxμy + C1)/(μx² + μy² + C1); the float sums of a
    // flat tile are d·Σw with d = 0 exactly (the centre is the value), so this is exact too.
    const double c1 = kSsimK1 * kSsimK1;
    const double expected = (2.0 * va * vb + c1) / (static_cast<double>(va) * va + static_cast<double>(vb) * vb + c1);
    EXPECT_NEAR(*ComputeSsim(a, b).ssim, expected, 1e-15) << va << " " << vb;
  }
}

TEST(SsimPrecision, ExtremesAndSharpEdgesWithinBound) {
  ExpectWithinBound(Random(70, 50, 3, 1, 0.0f, 1.0f), Random(70, 50, 3, 2, 0.0f, 1.0f), "random [0,1]");
  // 0/1 only (8-bit 0 and 255).
  ImageF bin_a = Random(64, 64, 3, 3, 0.0f, 1.0f), bin_b = Random(64, 64, 3, 4, 0.0f, 1.0f);
  for (float& v : bin_a.Data()) v = v < 0.5f ? 0.0f : 1.0f;
  for (float& v : bin_b.Data()) v = v < 0.9f ? 0.0f : 1.0f;
  ExpectWithinBound(bin_a, bin_b, "0/1");
  // Sharp edges: flat windows 0.48 away from their tile's centre, in both images.
  ExpectWithinBound(Edge(120, 90, 3, 0.02f, 0.98f, 2), Edge(120, 90, 3, 0.02f, 0.98f, 3), "edges");
  ExpectWithinBound(Edge(120, 90, 3, 0.0f, 1.0f, 2), Edge(120, 90, 3, 0.0f, 0.999f, 2), "edges, one level apart");
}

TEST(SsimPrecision, HugeConstantOffsetWithinBound) {
  // x + 1000: the centre takes the offset out (x − c is exact within a factor 2 of c), so
  // the bound is that of the unshifted content; the separable double reference itself loses
  // ~1e-6 here (E[x²] ≈ 1e6), the accurate map does not.
  ImageF a = Random(60, 40, 3, 5, 0.0f, 1.0f), b = Random(60, 40, 3, 6, 0.0f, 1.0f);
  for (float& v : a.Data()) v += 1000.0f;
  for (float& v : b.Data()) v += 1000.0f;
  ExpectWithinBound(a, b, "offset 1000");
}

TEST(SsimPrecision, TinyOddSizesAndTileBoundariesWithinBound) {
  // 11 wide or high (one valid row or column), odd sizes, and 267 × 85 / 523 × 11: valid
  // regions of 257 × 75 and 513 × 1 cross the 256-column strips and the 64-row chunks.
  for (auto [w, h] : {std::pair{11, 11}, std::pair{12, 30}, std::pair{31, 11}, std::pair{17, 13}, std::pair{267, 85},
                      std::pair{523, 11}}) {
    const ImageF a = Random(w, h, 3, 7 + w, 0.0f, 1.0f), b = Random(w, h, 3, 9 + h, 0.2f, 0.6f);
    ExpectWithinBound(a, b, std::to_string(w) + "x" + std::to_string(h));
  }
}

TEST(SsimPrecision, FourChannelsAndBothOrders) {
  // RGBA: the alpha channel is ignored; the result equals the RGB image's bit for bit.
  const ImageF a4 = Random(50, 31, 4, 11, 0.0f, 1.0f), b4 = Random(50, 31, 4, 12, 0.0f, 1.0f);
  ImageF a3(50, 31, 3), b3(50, 31, 3);
  for (int y = 0; y < 31; ++y)
    for (int x = 0; x < 50; ++x)
      for (int c = 0; c < 3; ++c) a3.At(x, y, c) = a4.At(x, y, c), b3.At(x, y, c) = b4.At(x, y, c);
  ExpectWithinBound(a4, b4, "RGBA");
  EXPECT_EQ(ComputeSsim(a4, b4).per_channel, ComputeSsim(a3, b3).per_channel);
  EXPECT_EQ(*ComputeSsim(a4, b4).ssim, *ComputeSsim(b4, a4).ssim);
  EXPECT_EQ(*ComputeSsim(a4, *PrepareSsimReference(b4)).ssim, *ComputeSsim(a4, b4).ssim);
  // Channels swapped (R ↔ B) in both images: the per-channel values swap bit for bit.
  ImageF as = a3, bs = b3;
  for (int y = 0; y < 31; ++y)
    for (int x = 0; x < 50; ++x) std::swap(as.At(x, y, 0), as.At(x, y, 2)), std::swap(bs.At(x, y, 0), bs.At(x, y, 2));
  const SsimResult r = ComputeSsim(a3, b3), s = ComputeSsim(as, bs);
  EXPECT_EQ(r.per_channel[0], s.per_channel[2]);
  EXPECT_EQ(r.per_channel[2], s.per_channel[0]);
}

// The production map is the one ComputeSsim averages, and the reference's map is the
// double definition: the two means agree with ComputeSsim / ComputeSsimReference.
TEST(SsimPrecision, MapsAreTheAveragedMaps) {
  const auto [a, b] = testimg::MakePair(300, 80, 3);
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> m = SsimMap(a, b, c), r = SsimMapReference(a, b, c);
    ASSERT_EQ(m.size(), static_cast<size_t>(290 * 70));
    double sm = 0.0, sr = 0.0;
    for (size_t i = 0; i < m.size(); ++i) sm += m[i], sr += r[i];
    EXPECT_NEAR(sm / m.size(), ComputeSsim(a, b).per_channel[c], 1e-14);
    EXPECT_NEAR(sr / r.size(), ComputeSsimReference(a, b).per_channel[c], 1e-14);
  }
  EXPECT_TRUE(SsimMap(ImageF(10, 30, 3), ImageF(10, 30, 3), 0).empty());
  EXPECT_THROW(SsimMap(a, b, 3), UserError);
}

TEST(SsimPrecision, SameBitsAtOneAndTwoThreads) {
  const ImageF a = Random(300, 150, 3, 21, 0.0f, 1.0f), b = Random(300, 150, 3, 22, 0.0f, 1.0f);
  SetThreadCount(1);
  const SsimResult one = ComputeSsim(a, b);
  const std::vector<double> map_one = SsimMap(a, b, 1);
  SetThreadCount(2);
  const SsimResult two = ComputeSsim(a, b);
  const SsimResult two_prepared = ComputeSsim(a, *PrepareSsimReference(b));
  const std::vector<double> map_two = SsimMap(a, b, 1);
  SetThreadCount(0);
  EXPECT_EQ(one.per_channel, two.per_channel);
  EXPECT_EQ(one.per_channel, two_prepared.per_channel);
  EXPECT_EQ(map_one, map_two);
}

}  // namespace
}  // namespace aalab
