// Compact texture storage (scenes/texture_image.h, issue #35): 8-bit images stay RGBA8 and
// fetch exactly the floats a float decode of the same file gives (read here through
// OpenImageIO's FLOAT path, independently of the RGBA8 tables); 16-bit images become half;
// RGBA8 mips average colour in linear light and alpha in codes, with the codes worked out by
// hand below; byte counts per format.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "core/color.h"
#include "scenes/texture_image.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

/// Writes a PNG of w × h × nc channels of type T (UINT8 or UINT16) to a fresh temp file.
/// The samples are written as given (alpha straight: OpenImageIO's PNG writer would otherwise
/// divide colour by alpha on the way out).
template <typename T>
std::string WritePng(const std::string& stem, int w, int h, int nc, const std::vector<T>& px) {
  const fs::path p = fs::temp_directory_path() / ("aalab_texstore_" + stem + ".png");
  auto out = OIIO::ImageOutput::create(p.string());
  const OIIO::TypeDesc t = sizeof(T) == 1 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
  OIIO::ImageSpec spec(w, h, nc, t);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  EXPECT_TRUE(out && out->open(p.string(), spec) && out->write_image(t, px.data()) && out->close());
  return p.string();
}

/// The file read as FLOAT by OpenImageIO (the pre-#35 decode path).
std::vector<float> ReadFloat(const std::string& path, int* nc) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in);
  const OIIO::ImageSpec& s = in->spec();
  *nc = s.nchannels;
  std::vector<float> v(static_cast<size_t>(s.width) * s.height * s.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, v.data()));
  return v;
}

bool SameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(TextureStorage, EightBitRgbStaysRgba8AndFetchesTheFloatDecodeBitForBit) {
  // 3 × 2 RGB, every code different, asymmetric in x and y.
  const std::vector<uint8_t> px = {0, 1, 2, 50, 104, 200, 255, 128, 7, 13, 99, 240, 60, 61, 62, 187, 188, 254};
  const std::string path = WritePng("rgb8", 3, 2, 3, px);
  int nc = 0;
  const std::vector<float> ref = ReadFloat(path, &nc);
  ASSERT_EQ(nc, 3);
  for (bool srgb : {true, false}) {
    const MipLevel l = DecodeTextureImage("t", path, nullptr, 0, "png", srgb);
    EXPECT_EQ(l.format, srgb ? TexelFormat::kSrgb8 : TexelFormat::kUnorm8);
    ASSERT_EQ(l.bytes.size(), 6u * 4u);
    EXPECT_TRUE(l.texels.empty());
    EXPECT_EQ(l.Bytes(), 24u);
    for (size_t i = 0; i < 6; ++i) {
      const glm::vec4 t = l.Fetch(i);
      for (int c = 0; c < 3; ++c) {
        const float want = srgb ? SrgbDecode(ref[i * 3 + c]) : ref[i * 3 + c];
        EXPECT_TRUE(SameBits(t[c], want)) << "texel " << i << " channel " << c << ": " << t[c] << " vs " << want;
        EXPECT_EQ(l.bytes[4 * i + c], px[i * 3 + c]);
      }
      EXPECT_EQ(t.w, 1.0f);  // no alpha channel: opaque
    }
  }
  fs::remove(path);
}

TEST(TextureStorage, EightBitGreyReplicatesIntoRgbWithOpaqueAlpha) {
  const std::vector<uint8_t> px = {10, 200, 90};  // 3 × 1 grey
  const std::string path = WritePng("g8", 3, 1, 1, px);
  const MipLevel l = DecodeTextureImage("t", path, nullptr, 0, "png", false);
  ASSERT_EQ(l.format, TexelFormat::kUnorm8);
  const std::vector<uint8_t> want = {10, 10, 10, 255, 200, 200, 200, 255, 90, 90, 90, 255};
  EXPECT_EQ(l.bytes, want);
  // Grey + alpha: grey replicated, alpha as stored (not multiplied into the grey).
  const std::string ga = WritePng("ga8", 2, 1, 2, std::vector<uint8_t>{100, 128, 30, 0});
  EXPECT_EQ(DecodeTextureImage("t", ga, nullptr, 0, "png", false).bytes,
            (std::vector<uint8_t>{100, 100, 100, 128, 30, 30, 30, 0}));
  fs::remove(path);
  fs::remove(ga);
}

TEST(TextureStorage, AlphaIsStraightAsGltfDefinesIt) {
  // glTF's alpha is unassociated: a texel's colour is the file's colour whatever its alpha.
  // 3 × 2 RGBA, asymmetric in x and y; texel (1, 1) is (200, 40, 120) at alpha 128 (0.502),
  // texel (2, 1) keeps its colour (60, 180, 90) at alpha 0. Premultiplied, they would read
  // back (100, 20, 60) and (0, 0, 0).
  const std::vector<uint8_t> px = {255, 0,  0,  255, 0,   255, 0,   255, 0,  0,   255, 255,
                                   10,  20, 30, 255, 200, 40,  120, 128, 60, 180, 90,  0};
  const std::string path = WritePng("straight", 3, 2, 4, px);
  std::ifstream f(path, std::ios::binary);
  const std::vector<uint8_t> file((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  // From the file and from memory (a .glb's embedded image): the same codes.
  for (const bool memory : {false, true}) {
    const MipLevel l = memory ? DecodeTextureImage("t", "", file.data(), file.size(), "png", false)
                              : DecodeTextureImage("t", path, nullptr, 0, "png", false);
    ASSERT_EQ(l.format, TexelFormat::kUnorm8);
    EXPECT_EQ(l.bytes, px) << (memory ? "memory" : "file");
    // Bilinear halfway between texels (1, 1) and (2, 1): u = 2/3, v = 3/4. Straight colour
    // averages the colours: R (200 + 60)/2 = 130, G (40 + 180)/2 = 110, B (120 + 90)/2 = 105,
    // A (128 + 0)/2 = 64, over 255.
    const glm::vec4 s = SampleBilinear(l, {2.0f / 3.0f, 0.75f}, WrapMode::kClampToEdge, WrapMode::kClampToEdge);
    EXPECT_NEAR(s.x, 130.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(s.y, 110.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(s.z, 105.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(s.w, 64.0f / 255.0f, 1e-6f);
  }
  // sRGB colour: texel (1, 1) alone (its centre, u = 1/2, v = 3/4) decodes code 200 to
  // ((200/255 + 0.055)/1.055)^2.4 = 0.57758 and keeps alpha 128/255.
  const MipLevel srgb = DecodeTextureImage("t", path, nullptr, 0, "png", true);
  const glm::vec4 c = SampleBilinear(srgb, {0.5f, 0.75f}, WrapMode::kClampToEdge, WrapMode::kClampToEdge);
  EXPECT_NEAR(c.x, 0.577581f, 2e-6f);
  EXPECT_NEAR(c.w, 128.0f / 255.0f, 1e-6f);
  fs::remove(path);
}

TEST(TextureStorage, SixteenBitImagesAreStoredAsHalf) {
  const std::vector<uint16_t> px = {0, 1000, 40000, 65535, 20000, 300};  // 2 × 1 RGB
  const std::string path = WritePng("rgb16", 2, 1, 3, px);
  const MipLevel lin = DecodeTextureImage("t", path, nullptr, 0, "png", false);
  ASSERT_EQ(lin.format, TexelFormat::kHalf);
  EXPECT_EQ(lin.Bytes(), 2u * 4u * 2u);
  const MipLevel srgb = DecodeTextureImage("t", path, nullptr, 0, "png", true);
  for (size_t i = 0; i < 2; ++i) {
    for (int c = 0; c < 3; ++c) {
      const double v = px[i * 3 + c] / 65535.0;
      // Half keeps 11 significant bits: relative error at most 2^-11 (normal numbers).
      EXPECT_NEAR(lin.Fetch(i)[c], v, v * std::ldexp(1.0, -11) + 1e-7) << i << " " << c;
      const double s = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
      EXPECT_NEAR(srgb.Fetch(i)[c], s, s * std::ldexp(1.0, -10) + 1e-7) << i << " " << c;
    }
    EXPECT_EQ(lin.Fetch(i).w, 1.0f);
  }
  fs::remove(path);
}

TEST(TextureStorage, HalfConversionIsIeee) {
  // IEEE 754 binary16: 1.0 = 0x3C00, 0.5 = 0x3800, -2 = 0xC000, 65504 = 0x7BFF (largest).
  EXPECT_EQ(FloatToHalf(1.0f), 0x3C00);
  EXPECT_EQ(FloatToHalf(0.5f), 0x3800);
  EXPECT_EQ(FloatToHalf(-2.0f), 0xC000);
  EXPECT_EQ(FloatToHalf(65504.0f), 0x7BFF);
  EXPECT_EQ(HalfToFloat(0x3555), 0.333251953125f);  // nearest half to 1/3
  EXPECT_EQ(FloatToHalf(1.0f / 3.0f), 0x3555);
}

/// A w × h RGBA8 level of format f holding bytes b.
MipLevel Rgba8(int w, int h, TexelFormat f, const std::vector<uint8_t>& b) { return MipLevel{w, h, f, {}, b, {}}; }

TEST(TextureStorage, Rgba8MipsAverageColourInLinearLightAndAlphaInCodes) {
  // sRGB codes 0 and 255: linear mean 0.5, sRGB-encoded 0.7354 · 255 = 187.5 -> code 188
  // (SrgbDecode(187.5/255) = 0.49993 <= 0.5 < SrgbDecode(188.5/255) = 0.50591); averaging
  // the codes instead would give 128. Alpha codes 10 and 21: mean 15.5, rounded half up 16.
  const MipChain c = BuildMipChain(Rgba8(2, 1, TexelFormat::kSrgb8, {0, 255, 0, 10, 255, 0, 255, 21}), "s");
  ASSERT_EQ(c.levels.size(), 2u);
  EXPECT_EQ(c.levels[1].format, TexelFormat::kSrgb8);
  EXPECT_EQ(c.levels[1].bytes, (std::vector<uint8_t>{188, 188, 188, 16}));
  // Odd width 3 folds into one texel: codes 0, 0, 255 -> linear mean 1/3, encoded 0.61246 ·
  // 255 = 156.2 -> 156; alpha 0, 1, 2 -> 1.
  const MipChain o = BuildMipChain(Rgba8(3, 1, TexelFormat::kSrgb8, {0, 0, 0, 0, 0, 0, 0, 1, 255, 255, 255, 2}), "o");
  ASSERT_EQ(o.levels.size(), 2u);
  EXPECT_EQ(o.levels[1].bytes, (std::vector<uint8_t>{156, 156, 156, 1}));
  // Linear RGBA8: every channel the mean of the codes, half up: (3, 6) -> 5, (0, 255) -> 128,
  // (100, 101) -> 101, (7, 7) -> 7.
  const MipChain u = BuildMipChain(Rgba8(1, 2, TexelFormat::kUnorm8, {3, 0, 100, 7, 6, 255, 101, 7}), "u");
  EXPECT_EQ(u.levels[1].format, TexelFormat::kUnorm8);
  EXPECT_EQ(u.levels[1].bytes, (std::vector<uint8_t>{5, 128, 101, 7}));
}

TEST(TextureStorage, ChainBytesCountTheStoredFormat) {
  const MipChain c = BuildMipChain(Rgba8(4, 4, TexelFormat::kSrgb8, std::vector<uint8_t>(64, 77)), "b");
  EXPECT_EQ(c.Bytes(), (16u + 4u + 1u) * 4u);
  EXPECT_EQ(c.Bytes8(), (16u + 4u + 1u) * 4u);
  const MipLevel f = ToFloatLevel(c.levels[1]);
  EXPECT_EQ(f.format, TexelFormat::kFloat);
  EXPECT_NEAR(f.texels[3].x, SrgbDecode(77 / 255.0f), 1e-7f);
}

TEST(TextureStorage, BilinearBatchFetchesSampleBilinearsBitsInEveryWrapMode) {
  // A 5 x 3 level (odd, asymmetric, both axes) of distinct codes in every channel.
  std::vector<uint8_t> b(5 * 3 * 4);
  for (size_t k = 0; k < b.size(); ++k) b[k] = static_cast<uint8_t>((k * 37 + 11) % 256);
  std::vector<glm::vec2> uv;
  for (int j = -9; j <= 9; ++j) {
    for (int i = -13; i <= 13; ++i) uv.push_back({0.137f * static_cast<float>(i), 0.211f * static_cast<float>(j)});
  }
  // Texel centres, exact edges, and the cases the scalar path keeps (|x| >= 1e8, non-finite).
  for (float v : {0.1f, 0.5f, 0.9f, 1.0f, 0.0f}) uv.push_back({v, 1.0f - v});
  const float inf = std::numeric_limits<float>::infinity();
  for (glm::vec2 e : {glm::vec2(3e7f, 0.2f), glm::vec2(0.3f, -5e8f), glm::vec2(inf, 0.5f),
                      glm::vec2(0.5f, std::nanf("")), glm::vec2(-1e6f, 2.5e6f)}) {
    uv.push_back(e);
  }
  for (TexelFormat f : {TexelFormat::kSrgb8, TexelFormat::kUnorm8}) {
    const MipLevel l = Rgba8(5, 3, f, b);
    const MipLevel half = ToFloatLevel(l);  // the float path falls back to SampleBilinear
    for (WrapMode ws : {WrapMode::kRepeat, WrapMode::kClampToEdge, WrapMode::kMirroredRepeat}) {
      for (WrapMode wt : {WrapMode::kRepeat, WrapMode::kClampToEdge, WrapMode::kMirroredRepeat}) {
        std::vector<glm::vec4> got(uv.size()), got_f(uv.size());
        SampleBilinearBatch(l, uv.data(), static_cast<int>(uv.size()), ws, wt, got.data());
        SampleBilinearBatch(half, uv.data(), static_cast<int>(uv.size()), ws, wt, got_f.data());
        for (size_t k = 0; k < uv.size(); ++k) {
          const glm::vec4 want = SampleBilinearScalar(l, uv[k], ws, wt);
          EXPECT_EQ(std::memcmp(&got[k], &want, sizeof want), 0) << "uv " << uv[k].x << "," << uv[k].y;
          // The one-tap form (SSE for 8-bit levels) too.
          const glm::vec4 one = SampleBilinear(l, uv[k], ws, wt);
          EXPECT_EQ(std::memcmp(&one, &want, sizeof want), 0) << "uv " << uv[k].x << "," << uv[k].y;
          const glm::vec4 want_f = SampleBilinearScalar(half, uv[k], ws, wt);
          EXPECT_EQ(std::memcmp(&got_f[k], &want_f, sizeof want_f), 0);
          const glm::vec4 one_f = SampleBilinear(half, uv[k], ws, wt);
          EXPECT_EQ(std::memcmp(&one_f, &want_f, sizeof want_f), 0);
        }
      }
    }
  }
  // By hand: the centre of texel (1, 2) is that texel's decoded codes (up to the float
  // rounding of the uv); halfway between
  // texels (1, 0) and (2, 0) (u = 2/5, v = 1/6) their mean, (a + b) · ½ in float.
  const MipLevel l = Rgba8(5, 3, TexelFormat::kUnorm8, b);
  const glm::vec2 pts[2] = {{1.5f / 5.0f, 2.5f / 3.0f}, {2.0f / 5.0f, 0.5f / 3.0f}};
  glm::vec4 got[2];
  SampleBilinearBatch(l, pts, 2, WrapMode::kRepeat, WrapMode::kRepeat, got);
  const size_t t12 = 4 * (2 * 5 + 1), t10 = 4 * 1, t20 = 4 * 2;
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(got[0][c], static_cast<float>(b[t12 + c]) / 255.0f, 1e-6f) << c;
    EXPECT_NEAR(got[1][c], (static_cast<float>(b[t10 + c]) + static_cast<float>(b[t20 + c])) / 510.0f, 1e-6f) << c;
  }
}

}  // namespace
}  // namespace aalab
