// Image-texture sampling (scenes/texture_image.h) and the texture footprint of the renders,
// against values worked out by hand: wrap modes, box mip chains, bilinear taps, the level of
// detail; the level the 1x frame picks on a perspective ground plane from the derivative
// derived in closed form; the reference of a grazing checker against its analytic box
// integral.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/color.h"
#include "core/parallel.h"
#include "scenes/render.h"
#include "scenes/specular_aa.h"
#include "scenes/texture_image.h"
#include "scenes/tracer.h"

namespace aalab {
namespace {

MipLevel Level(int w, int h, const std::vector<float>& grey) {
  MipLevel l;
  l.width = w;
  l.height = h;
  for (float g : grey) l.texels.emplace_back(g, g, g, 1.0f);
  return l;
}

TEST(TextureWrap, FoldsIndicesAsTheGltfSamplerSays) {
  EXPECT_EQ(WrapIndex(-1, 4, WrapMode::kRepeat), 3);
  EXPECT_EQ(WrapIndex(9, 4, WrapMode::kRepeat), 1);
  EXPECT_EQ(WrapIndex(-1, 4, WrapMode::kClampToEdge), 0);
  EXPECT_EQ(WrapIndex(7, 4, WrapMode::kClampToEdge), 3);
  // Mirrored repeat over 0 1 2 3 | 3 2 1 0 | 0 1 ...
  EXPECT_EQ(WrapIndex(4, 4, WrapMode::kMirroredRepeat), 3);
  EXPECT_EQ(WrapIndex(5, 4, WrapMode::kMirroredRepeat), 2);
  EXPECT_EQ(WrapIndex(-1, 4, WrapMode::kMirroredRepeat), 0);
  EXPECT_EQ(WrapIndex(-2, 4, WrapMode::kMirroredRepeat), 1);
  EXPECT_EQ(WrapIndex(8, 4, WrapMode::kMirroredRepeat), 0);
}

TEST(TextureMips, BoxChainAveragesAndKeepsTheMeanOfOddSizes) {
  // 4x4 ramp 0..15: level 1 texel (0,0) = mean(0,1,4,5) = 2.5; level 2 = mean of all = 7.5.
  std::vector<float> v;
  for (int i = 0; i < 16; ++i) v.push_back(static_cast<float>(i));
  const MipChain c = BuildMipChain(Level(4, 4, v), "ramp");
  ASSERT_EQ(c.levels.size(), 3u);
  EXPECT_FLOAT_EQ(c.levels[1].texels[0].x, 2.5f);
  EXPECT_FLOAT_EQ(c.levels[1].texels[3].x, 12.5f);
  EXPECT_FLOAT_EQ(c.levels[2].texels[0].x, 7.5f);
  // 5x3: level 1 is 2x1; its second texel folds columns 2..4 of all 3 rows.
  const MipChain o = BuildMipChain(Level(5, 3, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14}), "odd");
  ASSERT_EQ(o.levels[1].width, 2);
  ASSERT_EQ(o.levels[1].height, 1);
  EXPECT_FLOAT_EQ(o.levels[1].texels[0].x, (0 + 1 + 5 + 6 + 10 + 11) / 6.0f);
  EXPECT_FLOAT_EQ(o.levels[1].texels[1].x, (2 + 3 + 4 + 7 + 8 + 9 + 12 + 13 + 14) / 9.0f);
  EXPECT_EQ(o.levels.back().width, 1);
  EXPECT_EQ(c.Bytes(), (16u + 4u + 1u) * 16u);
}

TEST(TextureBilinear, TexelCentresAreExactAndMidpointsAverage) {
  const MipLevel l = Level(4, 1, {0.0f, 1.0f, 2.0f, 3.0f});
  // Texel i's centre is u = (i + 0.5) / 4.
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.375f, 0.5f}, WrapMode::kRepeat, WrapMode::kRepeat).x, 1.0f);
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.5f, 0.5f}, WrapMode::kRepeat, WrapMode::kRepeat).x, 1.5f);
  // u = 0 lies halfway between texel 3 (wrapped) and texel 0 under repeat; clamp holds texel 0.
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.0f, 0.5f}, WrapMode::kRepeat, WrapMode::kRepeat).x, 1.5f);
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.0f, 0.5f}, WrapMode::kClampToEdge, WrapMode::kRepeat).x, 0.0f);
  EXPECT_FLOAT_EQ(SampleBilinear(l, {-0.125f, 0.5f}, WrapMode::kMirroredRepeat, WrapMode::kRepeat).x, 0.0f);
}

// The t axis and its own wrap mode, on a 3 × 4 texture whose texel (x, y) holds x + 10·y
// (width ≠ height, rows distinguishable from columns), worked by hand. Texel space:
// u·3 − 0.5 and v·4 − 0.5.
TEST(TextureBilinear, TheTAxisWrapsByItsOwnModeOnANonSquareTexture) {
  std::vector<float> v;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 3; ++x) v.push_back(static_cast<float>(x + 10 * y));
  }
  const MipLevel l = Level(3, 4, v);
  const WrapMode rep = WrapMode::kRepeat, clamp = WrapMode::kClampToEdge, mirror = WrapMode::kMirroredRepeat;
  // A texel centre on both axes: (5/6, 7/8) -> texel (2, 3) = 32.
  EXPECT_FLOAT_EQ(SampleBilinear(l, {5.0f / 6.0f, 7.0f / 8.0f}, rep, rep).x, 32.0f);
  // v = 0: halfway between row -1 and row 0, at column 1 (u = 0.5 -> x = 1 exactly).
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.5f, 0.0f}, rep, rep).x, 0.5f * 31.0f + 0.5f * 1.0f);  // row -1 = row 3
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.5f, 0.0f}, rep, clamp).x, 1.0f);                      // row -1 = row 0
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.5f, 0.0f}, rep, mirror).x, 1.0f);                     // row -1 = row 0
  // v = 1: halfway between row 3 and row 4.
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.5f, 1.0f}, rep, rep).x, 0.5f * 31.0f + 0.5f * 1.0f);  // row 4 = row 0
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.5f, 1.0f}, rep, mirror).x, 31.0f);                    // row 4 = row 3
  // Different modes on the two axes, at the corner (0, 0): s clamps (columns -1, 0 -> 0),
  // t repeats (rows 3 and 0): 0.5·30 + 0.5·0 = 15. With the modes swapped: s repeats
  // (columns 2 and 0: 1 on average), t clamps (row 0): 1.
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.0f, 0.0f}, clamp, rep).x, 15.0f);
  EXPECT_FLOAT_EQ(SampleBilinear(l, {0.0f, 0.0f}, rep, clamp).x, 1.0f);
}

TEST(TextureLod, LambdaIsLog2OfTheLongerFootprintEdgeInTexels) {
  UvDerivs d;
  d.dx = {1.0f / 64.0f, 0.0f};   // 4 texels of a 256 texture per step
  d.dy = {0.0f, 1.0f / 128.0f};  // 2 texels
  EXPECT_FLOAT_EQ(MipLambda(d, 256, 256), 2.0f);
  d.dx = {3.0f / 256.0f, 4.0f / 256.0f};  // length 5 texels
  d.dy = {0.0f, 0.0f};
  EXPECT_FLOAT_EQ(MipLambda(d, 256, 256), std::log2(5.0f));
  // Non-square: du scales with the width, dv with the height.
  d.dx = {0.0f, 1.0f / 16.0f};
  EXPECT_FLOAT_EQ(MipLambda(d, 256, 64), 2.0f);
}

TEST(TextureLod, TrilinearBlendsTheTwoLevelsAroundLambda) {
  // Levels of constant value k: a trilinear fetch returns λ itself between levels.
  MipChain c;
  for (int k = 0, n = 8; n >= 1; ++k, n /= 2) c.levels.push_back(Level(n, n, std::vector<float>(n * n, float(k))));
  UvDerivs d;
  d.dx = {std::exp2(1.5f) / 8.0f, 0.0f};  // ρ = 2^1.5 texels
  EXPECT_NEAR(SampleTexture(c, {0.3f, 0.6f}, d, WrapMode::kRepeat, WrapMode::kRepeat, {}).x, 1.5f, 1e-5f);
  d.dx = {0.5f / 8.0f, 0.0f};  // magnification: level 0
  EXPECT_FLOAT_EQ(SampleTexture(c, {0.3f, 0.6f}, d, WrapMode::kRepeat, WrapMode::kRepeat, {}).x, 0.0f);
  d.dx = {64.0f, 0.0f};  // beyond the chain: the last level
  EXPECT_FLOAT_EQ(SampleTexture(c, {0.3f, 0.6f}, d, WrapMode::kRepeat, WrapMode::kRepeat, {}).x, 3.0f);
  TextureFilter ref;
  ref.level0_only = true;
  EXPECT_FLOAT_EQ(SampleTexture(c, {0.3f, 0.6f}, d, WrapMode::kRepeat, WrapMode::kRepeat, ref).x, 0.0f);
  // Anisotropic 8x on a footprint 8 texels long and 1 wide: λ = log2(8 / 8) = 0.
  TextureFilter an;
  an.max_aniso = 8;
  d.dx = {1.0f, 0.0f};  // 8 texels of the 8-texel level 0
  d.dy = {0.0f, 1.0f / 8.0f};
  EXPECT_FLOAT_EQ(SampleTexture(c, {0.3f, 0.6f}, d, WrapMode::kRepeat, WrapMode::kRepeat, an).x, 0.0f);
}

/// A scene of one textured unlit glTF-material triangle soup (`positions`, `uvs`, two
/// triangles a quad) with the given texture; display none (linear values in [0, 1] pass).
Scene TexturedQuadScene(const std::vector<glm::vec3>& p, const std::vector<glm::vec2>& uv, MipChain chain,
                        const Camera& cam) {
  Scene s;
  s.name = "textured";
  s.effects[static_cast<int>(Effect::kUnlit)] = true;
  s.effects[static_cast<int>(Effect::kTextures)] = true;
  s.camera = cam;
  Material m;
  m.name = "t";
  m.shading = Shading::kUnlit;
  GltfMaterial g;
  g.base_tex.image = 0;
  m.gltf = g;
  s.materials.push_back(m);
  Shape sh;
  sh.kind = ShapeKind::kTriangles;
  sh.source = "gltf";
  sh.positions = p;
  sh.uvs = uv;
  sh.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.shapes.push_back(sh);
  s.images.push_back(std::make_shared<const MipChain>(std::move(chain)));
  return s;
}

TEST(TextureFootprint, OneXFramePicksTheLevelOfTheHandDerivedDerivative) {
  // Camera at height h = 1 looking along −z, level; ground y = 0 with u = x·s, v = −z·s.
  // A pixel row whose ray descends b = ny·tan(fov/2) per unit of −z hits z = −h / b; the row
  // below descends b' = b + 2·tan(fov/2)/H and hits z' = −h / b'. The 1x frame's derivatives
  // are these one-pixel differences: dv/dy = s·h·(1/b − 1/b'), du/dx = s·(2·tan·aspect/W)·h/b
  // (the same x step at the same depth). λ = log2(max(|du|, |dv|)·N) for an N-texel texture
  // whose level k holds the value k/16: the frame shows λ/16 directly.
  const int W = 64, H = 64, N = 256;
  const float s = 1.0f, h = 1.0f, fov = 60.0f;
  MipChain c;
  for (int k = 0, n = N; n >= 1; ++k, n /= 2) {
    c.levels.push_back(Level(n, n, std::vector<float>(static_cast<size_t>(n) * n, k / 16.0f)));
  }
  Camera cam;
  cam.type = CameraType::kPerspective;
  cam.position = {0, h, 0};
  cam.look_at = {0, h, -1};
  cam.fov_y_deg = fov;
  const float big = 1000.0f;
  const Scene sc =
      TexturedQuadScene({{-big, 0, 0}, {big, 0, 0}, {big, 0, -big}, {-big, 0, -big}},
                        {{-big * s, 0}, {big * s, 0}, {big * s, big * s}, {-big * s, big * s}}, std::move(c), cam);
  Tracer tracer(sc);
  const ImageF img = RenderFrameLinear(tracer, W, H, RenderSpec{}, 1, nullptr);
  const double t = std::tan(fov * 0.5 * 3.14159265358979 / 180.0);
  int checked = 0;
  for (int y = H / 2 + 1; y < H; y += 3) {
    const double ny = 1.0 - 2.0 * (y + 0.5) / H;  // negative below the horizon
    const double b = -ny * t, b2 = b + 2.0 * t / H;
    const double dv = s * h * (1.0 / b - 1.0 / b2);
    const double du = s * (2.0 * t / W) * h / b;
    const double lambda = std::log2(std::max(std::fabs(du), std::fabs(dv)) * N);
    const double expect = std::clamp(lambda, 0.0, 8.0) / 16.0;
    EXPECT_NEAR(img.At(W / 2, y, 0), expect, 2e-4) << "row " << y << " lambda " << lambda;
    ++checked;
  }
  EXPECT_GE(checked, 8);
}

/// Antiderivative of the triangle wave g that linearly interpolates (−1)^i at integers.
double TriangleWaveIntegral(double x) {
  const double f = std::floor(x), r = x - f;
  const double sign = std::fmod(std::fabs(f), 2.0) == 0.0 ? 1.0 : -1.0;
  return sign * r * (1.0 - r);
}

TEST(TextureReference, GrazingCheckerConvergesToItsBoxIntegral) {
  // An N×N one-texel checker, c(i, j) = (i + j) mod 2, repeated K times over a unit quad tilted
  // 75° about x, seen by an orthographic camera: pixel x maps linearly to u, pixel y to v, so
  // each pixel's footprint is an axis-aligned uv rectangle (0.71 × 2.75 texels). The bilinear
  // reconstruction is f = 1/2 − 1/2·g(X)·g(Y) (X = u·N − 1/2, g the triangle wave through
  // (−1)^i), whose box mean over [X0, X1] × [Y0, Y1] is
  // 1/2 − 1/2 · (G(X1) − G(X0))/(X1 − X0) · (G(Y1) − G(Y0))/(Y1 − Y0) with G(x) = ±r(1 − r).
  // The reference (level 0 bilinear per sub-sample) must match it within its noise floor.
  const int W = 32, H = 32, N = 8;
  const double K = 11.0, theta = 75.0 * 3.14159265358979 / 180.0;
  std::vector<float> tex;
  for (int j = 0; j < N; ++j) {
    for (int i = 0; i < N; ++i) tex.push_back(static_cast<float>((i + j) % 2));
  }
  MipChain chain = BuildMipChain(Level(N, N, tex), "checker");
  const float c = static_cast<float>(std::cos(theta)), sn = static_cast<float>(std::sin(theta));
  // Quad x ∈ [−1, 1], local y ∈ [−1, 1] → world (x, y·cos, y·sin); u = (x + 1)/2·K, v = (1 − y)/2·K.
  const std::vector<glm::vec3> p = {{-1, c, sn}, {1, c, sn}, {1, -c, -sn}, {-1, -c, -sn}};
  const float k = static_cast<float>(K);
  const std::vector<glm::vec2> uv = {{0, 0}, {k, 0}, {k, k}, {0, k}};
  Camera cam;
  cam.type = CameraType::kOrthographic;
  cam.position = {0, 0, 5};
  cam.look_at = {0, 0, 0};
  const double hc = 2.0 * std::cos(theta);
  cam.height = static_cast<float>(hc);
  const Scene sc = TexturedQuadScene(p, uv, std::move(chain), cam);
  Tracer tracer(sc);
  const Reference ref = RenderReference(tracer, W, H, 16, 7, nullptr);
  double err2 = 0.0, noise2 = 0.0;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const double wx0 = -hc / 2 + x * hc / W, wx1 = wx0 + hc / W;
      const double wy0 = hc / 2 - y * hc / H, wy1 = wy0 - hc / H;  // world y' at the pixel's top and bottom
      const double X0 = (wx0 + 1) / 2 * K * N - 0.5, X1 = (wx1 + 1) / 2 * K * N - 0.5;
      const double Y0 = (1 - wy0 / std::cos(theta)) / 2 * K * N - 0.5,
                   Y1 = (1 - wy1 / std::cos(theta)) / 2 * K * N - 0.5;
      const double gx = (TriangleWaveIntegral(X1) - TriangleWaveIntegral(X0)) / (X1 - X0);
      const double gy = (TriangleWaveIntegral(Y1) - TriangleWaveIntegral(Y0)) / (Y1 - Y0);
      const double exact = 0.5 - 0.5 * gx * gy;
      const double got = SrgbDecode(ref.image.At(x, y, 0));
      const double a = SrgbDecode(ref.half_a.At(x, y, 0)), b = SrgbDecode(ref.half_b.At(x, y, 0));
      err2 += (got - exact) * (got - exact);
      noise2 += 0.25 * (a - b) * (a - b);  // the full mean's variance, from the halves' difference
    }
  }
  const double rms_err = std::sqrt(err2 / (W * H)), rms_noise = std::sqrt(noise2 / (W * H));
  EXPECT_LT(rms_err, 2.0 * rms_noise + 1e-4) << "rms error " << rms_err << " noise " << rms_noise;
  std::printf("grazing checker: rms error %.3g, rms noise %.3g\n", rms_err, rms_noise);
  EXPECT_GT(rms_noise, 0.0);  // the texture varies inside pixels: the test is not trivially exact
}

TEST(SpecularAa, RoughnessWideningByHand) {
  const float s2 = 0.15915494f, k = 0.18f;
  // |dN/dx|² + |dN/dy|² = 0.01 + 0.04 = 0.05; σ²·0.05 = 0.0079577.
  EXPECT_NEAR(FilteredAlpha2(0.01f, {0.1f, 0, 0}, {0, 0.2f, 0}, s2, k), 0.01f + 0.15915494f * 0.05f, 1e-7f);
  // A kernel of σ²·4 = 0.64 is clamped to κ.
  EXPECT_FLOAT_EQ(FilteredAlpha2(0.01f, {2.0f, 0, 0}, {0, 0, 0}, s2, k), 0.19f);
  // Never above 1; a constant normal changes nothing.
  EXPECT_FLOAT_EQ(FilteredAlpha2(0.95f, {2.0f, 0, 0}, {0, 0, 0}, s2, k), 1.0f);
  EXPECT_FLOAT_EQ(FilteredAlpha2(0.3f, {0, 0, 0}, {0, 0, 0}, s2, k), 0.3f);
}

/// A full-view unlit glTF quad of constant alpha `a` (MASK) over a black background.
Scene AlphaQuadScene(float a) {
  Scene s;
  s.name = "alpha";
  s.effects[static_cast<int>(Effect::kUnlit)] = true;
  s.effects[static_cast<int>(Effect::kAlphaTest)] = true;
  s.camera.type = CameraType::kOrthographic;
  s.camera.position = {0, 0, 5};
  s.camera.look_at = {0, 0, 0};
  s.camera.height = 2.0f;
  Material m;
  m.name = "a";
  m.shading = Shading::kUnlit;
  m.alpha_cutoff = 0.5f;
  GltfMaterial g;
  g.base_factor = {1.0f, 1.0f, 1.0f, a};
  g.alpha_mode = AlphaMode::kMask;
  m.gltf = g;
  s.materials.push_back(m);
  Shape sh;
  sh.kind = ShapeKind::kTriangles;
  sh.source = "gltf";
  sh.positions = {{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}};
  sh.uvs.assign(4, glm::vec2(0.0f));
  sh.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.shapes.push_back(sh);
  return s;
}

TEST(AlphaToCoverage, MaskCountsByHand) {
  // k = ⌊α·N + d⌋, d = (Bayer + 0.5)/16: α = 0.5, N = 4 keeps 2 samples at every phase.
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) EXPECT_EQ(AlphaToCoverageMask(0.5f, 4, x, y), 0x3u);
  }
  EXPECT_EQ(AlphaToCoverageMask(0.0f, 4, 3, 3), 0x0u);
  EXPECT_EQ(AlphaToCoverageMask(1.0f, 4, 3, 3), 0xFu);
  // α·N = 1.2: the phases with d ≥ 0.8 (Bayer 13, 14, 15) keep 2 samples, the other 13 keep 1:
  // 19 samples over a 4×4 block, 16·1.2 = 19.2 rounded.
  int total = 0;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) total += __builtin_popcount(AlphaToCoverageMask(0.3f, 4, x, y));
  }
  EXPECT_EQ(total, 19);
}

// The dither per pixel, not as a tile's sum (a transposed or shifted matrix keeps every
// tile's sum): with one sample, α = k/16 keeps it iff (b + 0.5)/16 ≥ 1 − k/16, i.e. k ≥ 16 − b,
// so the smallest k that keeps it gives the pixel's Bayer index b = 16 − k. Expected: Bayer's
// 4×4 index matrix as published (B. E. Bayer, ICC 1973; row = y mod 4, column = x mod 4),
// read at pixels (x, y) = (5..8, 2..5), a window that starts off the tile on both axes.
TEST(AlphaToCoverage, EachPixelTakesItsOwnBayerThreshold) {
  const int bayer[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
  for (int y = 2; y < 6; ++y) {
    for (int x = 5; x < 9; ++x) {
      int k = 0;
      while (k <= 16 && AlphaToCoverageMask(static_cast<float>(k) / 16.0f, 1, x, y) == 0u) ++k;
      EXPECT_EQ(16 - k, bayer[y % 4][x % 4]) << "pixel (" << x << ", " << y << ")";
    }
  }
  // With 4 samples, α·N = 1.2 keeps 2 samples exactly at the indices 13, 14, 15: pixels
  // (2, 3), (2, 1), (0, 3) of each tile, here (6, 7), (10, 5), (4, 3).
  EXPECT_EQ(AlphaToCoverageMask(0.3f, 4, 6, 7), 0x3u);
  EXPECT_EQ(AlphaToCoverageMask(0.3f, 4, 10, 5), 0x3u);
  EXPECT_EQ(AlphaToCoverageMask(0.3f, 4, 4, 3), 0x3u);
  EXPECT_EQ(AlphaToCoverageMask(0.3f, 4, 7, 6),
            0x1u);  // (6, 7) transposed: index 9 (a transposed matrix reads 13 there)
}

TEST(AlphaToCoverage, MsaaCoverageFollowsAlphaWhileTheAlphaTestIsAllOrNothing) {
  RenderSpec a2c;
  a2c.msaa.samples = 4;
  a2c.msaa.alpha_test = MsaaAlphaTest::kCoverage;
  RenderSpec shade = a2c;
  shade.msaa.alpha_test = MsaaAlphaTest::kShade;
  {  // α = 0.3 < cutoff: the alpha test drops the quad, A2C keeps 19 of 64 samples per 4×4 block.
    const Scene sc = AlphaQuadScene(0.3f);
    Tracer tracer(sc);
    const ImageF img = RenderFrameLinear(tracer, 8, 8, a2c, 1, nullptr);
    double block = 0.0;
    for (int y = 0; y < 4; ++y) {
      for (int x = 0; x < 4; ++x) block += img.At(x, y, 0);
    }
    EXPECT_NEAR(block / 16.0, 19.0 / 64.0, 1e-6);
    const ImageF test = RenderFrameLinear(tracer, 8, 8, shade, 1, nullptr);
    EXPECT_EQ(test.At(3, 3, 0), 0.0f);
  }
  {  // α = 0.5: two of four samples in every pixel; the alpha test (α ≥ cutoff) keeps all.
    const Scene sc = AlphaQuadScene(0.5f);
    Tracer tracer(sc);
    const ImageF img = RenderFrameLinear(tracer, 8, 8, a2c, 1, nullptr);
    for (int y = 0; y < 8; ++y) {
      for (int x = 0; x < 8; ++x) EXPECT_FLOAT_EQ(img.At(x, y, 0), 0.5f);
    }
    EXPECT_EQ(RenderFrameLinear(tracer, 8, 8, shade, 1, nullptr).At(5, 2, 0), 1.0f);
  }
}

TEST(TextureDeterminism, SameBitsAtOneAndTwoThreads) {
  std::vector<float> tex;
  for (int i = 0; i < 64; ++i) tex.push_back(static_cast<float>((i * 37) % 11) / 10.0f);
  Camera cam;
  cam.position = {0, 1, 0};
  cam.look_at = {0, 0.8f, -1};
  cam.fov_y_deg = 50;
  const Scene sc = TexturedQuadScene({{-50, 0, 0}, {50, 0, 0}, {50, 0, -50}, {-50, 0, -50}},
                                     {{0, 0}, {40, 0}, {40, 40}, {0, 40}}, BuildMipChain(Level(8, 8, tex), "n"), cam);
  Tracer tracer(sc);
  RenderSpec spec;
  SetThreadCount(1);
  const ImageF a = RenderFrameLinear(tracer, 40, 30, spec, 1, nullptr);
  const Reference ra = RenderReference(tracer, 40, 30, 4, 1, nullptr);
  SetThreadCount(2);
  const ImageF b = RenderFrameLinear(tracer, 40, 30, spec, 1, nullptr);
  const Reference rb = RenderReference(tracer, 40, 30, 4, 1, nullptr);
  SetThreadCount(0);
  EXPECT_TRUE(a == b);
  EXPECT_TRUE(ra.image == rb.image);
}

}  // namespace
}  // namespace aalab
