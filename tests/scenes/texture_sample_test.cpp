// The fast texture taps (scenes/texture_sample.cpp) against the scalar reference, bit for bit:
// the unorm decode by conversion against Unorm8Table for every code, the SSE taps' wrap (one
// division, or a mask on power-of-two sizes) against SampleBilinearScalar's WrapIndex in every
// wrap mode and on sizes of 1 to 16 texels a side, far-off and non-finite coordinates, the
// trilinear blend in SSE lanes against glm's blend of two scalar taps at every kind of λ
// (magnification, NaN, whole, fractional, last level and beyond), and HypotF against
// std::hypot.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "scenes/texture_image.h"

namespace aalab {
namespace {

bool SameBits(const glm::vec4& a, const glm::vec4& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

MipLevel Rgba8(int w, int h, TexelFormat f, const std::vector<uint8_t>& b) { return MipLevel{w, h, f, {}, b, {}}; }

std::vector<uint8_t> RandomCodes(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint8_t> b(n);
  for (uint8_t& v : b) v = static_cast<uint8_t>(rng() & 0xFF);
  return b;
}

constexpr WrapMode kModes[3] = {WrapMode::kRepeat, WrapMode::kClampToEdge, WrapMode::kMirroredRepeat};

TEST(TextureSampleFast, UnormDecodeIsTheTableForEveryCode) {
  // Texel k of a 256 x 1 level holds codes (k, 255 − k, 7k mod 256, 13k + 5 mod 256); a tap at
  // texel k's centre has weights exactly 1 and 0, so it returns texel k's decode itself.
  std::vector<uint8_t> b(256 * 4);
  for (int k = 0; k < 256; ++k) {
    b[4 * k + 0] = static_cast<uint8_t>(k);
    b[4 * k + 1] = static_cast<uint8_t>(255 - k);
    b[4 * k + 2] = static_cast<uint8_t>((7 * k) % 256);
    b[4 * k + 3] = static_cast<uint8_t>((13 * k + 5) % 256);
  }
  for (TexelFormat f : {TexelFormat::kUnorm8, TexelFormat::kSrgb8}) {
    const MipLevel l = Rgba8(256, 1, f, b);
    const float* rgb = f == TexelFormat::kSrgb8 ? Srgb8Table() : Unorm8Table();
    for (int k = 0; k < 256; ++k) {
      const glm::vec2 uv((static_cast<float>(k) + 0.5f) / 256.0f, 0.5f);
      const glm::vec4 got = SampleBilinear(l, uv, WrapMode::kRepeat, WrapMode::kRepeat);
      const uint8_t* p = &b[4 * static_cast<size_t>(k)];
      const glm::vec4 want(rgb[p[0]], rgb[p[1]], rgb[p[2]], Unorm8Table()[p[3]]);
      EXPECT_TRUE(SameBits(got, want)) << "texel " << k;
      EXPECT_TRUE(SameBits(got, SampleBilinearScalar(l, uv, WrapMode::kRepeat, WrapMode::kRepeat))) << k;
    }
  }
}

TEST(TextureSampleFast, TapsAreTheScalarTapsInEveryWrapModeAndSize) {
  const int sizes[][2] = {{1, 1}, {2, 1}, {1, 2}, {2, 2}, {4, 8}, {8, 4}, {16, 16}, {3, 5}, {5, 3}, {6, 7}, {7, 6}};
  const float inf = std::numeric_limits<float>::infinity();
  for (const auto& sz : sizes) {
    const int w = sz[0], h = sz[1];
    std::vector<glm::vec2> uv;
    for (int j = -23; j <= 23; ++j) {
      for (int i = -31; i <= 31; ++i) uv.push_back({0.0731f * static_cast<float>(i), 0.0917f * static_cast<float>(j)});
    }
    // Whole periods and texel edges far out (both signs), where the index folds by the
    // division or the mask, and past 1e8 texels (FoldCoord: the scalar path) and non-finite.
    for (float m : {-1e6f, -4096.0f, -1000.0f, -3.0f, -1.0f, 0.0f, 1.0f, 2.0f, 3.0f, 1000.0f, 4097.0f, 1e6f}) {
      for (float e : {-0.5f, -0.25f, 0.0f, 0.125f, 0.5f, 0.75f}) {
        uv.push_back({m + e / static_cast<float>(w), m - e / static_cast<float>(h)});
      }
    }
    for (glm::vec2 e :
         {glm::vec2(9.9e7f / static_cast<float>(w), 0.3f), glm::vec2(0.3f, -9.9e7f / static_cast<float>(h)),
          glm::vec2(2e8f, 0.2f), glm::vec2(0.3f, -5e8f), glm::vec2(inf, 0.5f), glm::vec2(0.5f, -inf),
          glm::vec2(0.5f, std::nanf("")), glm::vec2(3e38f, -3e38f)}) {
      uv.push_back(e);
    }
    for (TexelFormat f : {TexelFormat::kSrgb8, TexelFormat::kUnorm8}) {
      const MipLevel l = Rgba8(w, h, f, RandomCodes(static_cast<size_t>(4 * w * h), static_cast<uint32_t>(w * 31 + h)));
      for (WrapMode ws : kModes) {
        for (WrapMode wt : kModes) {
          std::vector<glm::vec4> batch(uv.size());
          SampleBilinearBatch(l, uv.data(), static_cast<int>(uv.size()), ws, wt, batch.data());
          for (size_t k = 0; k < uv.size(); ++k) {
            const glm::vec4 want = SampleBilinearScalar(l, uv[k], ws, wt);
            EXPECT_TRUE(SameBits(SampleBilinear(l, uv[k], ws, wt), want))
                << w << "x" << h << " uv " << uv[k].x << "," << uv[k].y;
            EXPECT_TRUE(SameBits(batch[k], want)) << w << "x" << h << " uv " << uv[k].x << "," << uv[k].y;
          }
        }
      }
    }
  }
}

/// The trilinear tap as it was written before the SSE blend: scalar taps, glm's vec4 blend.
glm::vec4 LerpReference(const MipChain& chain, glm::vec2 uv, float lambda, WrapMode ws, WrapMode wt) {
  const int last = static_cast<int>(chain.levels.size()) - 1;
  if (!(lambda > 0.0f)) return SampleBilinearScalar(chain.levels[0], uv, ws, wt);
  if (lambda >= static_cast<float>(last)) return SampleBilinearScalar(chain.levels[last], uv, ws, wt);
  const int l0 = static_cast<int>(std::floor(lambda));
  const float f = lambda - static_cast<float>(l0);
  const glm::vec4 a = SampleBilinearScalar(chain.levels[l0], uv, ws, wt);
  if (f == 0.0f) return a;
  const glm::vec4 b = SampleBilinearScalar(chain.levels[l0 + 1], uv, ws, wt);
  return a * (1.0f - f) + b * f;
}

TEST(TextureSampleFast, TrilinearIsTheScalarBlendAtEveryKindOfLambda) {
  // Level-0 footprints (texels a pixel along x) giving λ < 0, 0, fractional, whole, the last
  // level exactly, beyond it, and NaN / inf derivatives.
  const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  const float texels[] = {0.25f, 1.0f, 1.5f, 2.0f, 2.7f, 4.0f, 5.9f, 8.0f, 16.0f, 1e3f, 1e30f, nan, inf, 0.0f};
  for (const auto& sz : {std::pair{16, 8}, std::pair{5, 3}, std::pair{1, 1}}) {
    const int w = sz.first, h = sz.second;
    for (TexelFormat f : {TexelFormat::kSrgb8, TexelFormat::kUnorm8}) {
      const MipChain c =
          BuildMipChain(Rgba8(w, h, f, RandomCodes(static_cast<size_t>(4 * w * h), static_cast<uint32_t>(w + 7))), "t");
      for (float t : texels) {
        UvDerivs d;
        d.dx = glm::vec2(t / static_cast<float>(w), 0.0f);
        d.dy = glm::vec2(0.0f, 0.5f * t / static_cast<float>(h));
        const float lambda = MipLambda(d, w, h);
        for (WrapMode ws : kModes) {
          for (WrapMode wt : kModes) {
            for (int k = -7; k <= 7; ++k) {
              const glm::vec2 uv(0.173f * static_cast<float>(k), -0.291f * static_cast<float>(k) + 0.05f);
              const glm::vec4 got = SampleTexture(c, uv, d, ws, wt, TextureFilter{});
              EXPECT_TRUE(SameBits(got, LerpReference(c, uv, lambda, ws, wt)))
                  << w << "x" << h << " lambda " << lambda << " uv " << uv.x << "," << uv.y;
            }
          }
        }
      }
    }
  }
}

TEST(TextureSampleFast, HypotIsStdHypot) {
  const float inf = std::numeric_limits<float>::infinity(), big = std::numeric_limits<float>::max();
  const float tiny = std::numeric_limits<float>::denorm_min(), small = std::numeric_limits<float>::min();
  const std::vector<float> edge = {0.0f,  -0.0f, tiny,   -tiny, small, 1.0f, -1.0f, 3.0f,          4.0f,
                                   1e19f, 1e20f, -1e20f, big,   -big,  inf,  -inf,  std::nanf(""), 1e-20f};
  auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (float a : edge) {
    for (float b : edge) EXPECT_TRUE(same(HypotF(a, b), std::hypot(a, b))) << a << " " << b;
  }
  // Random bit patterns (every exponent, both signs, subnormals, the odd NaN and inf).
  std::mt19937 rng(41);
  for (int k = 0; k < 2000000; ++k) {
    const uint32_t ba = rng(), bb = rng();
    float a, b;
    std::memcpy(&a, &ba, sizeof a);
    std::memcpy(&b, &bb, sizeof b);
    ASSERT_TRUE(same(HypotF(a, b), std::hypot(a, b))) << ba << " " << bb;
  }
  // Near-equal magnitudes of the size footprints have (where rounding ties are likeliest).
  std::uniform_real_distribution<float> u(0.0f, 4096.0f);
  for (int k = 0; k < 1000000; ++k) {
    const float a = u(rng), b = u(rng);
    ASSERT_TRUE(same(HypotF(a, b), std::hypot(a, b))) << a << " " << b;
  }
}

}  // namespace
}  // namespace aalab
