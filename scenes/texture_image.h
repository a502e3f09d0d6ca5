/// Image textures as a GPU samples them: a mip chain stored as a GPU stores it (RGBA8 sRGB or
/// linear, or RGBA half for 16-bit and float sources; float only for derived chains), bilinear
/// taps with the sampler's wrap modes, trilinear filtering with the level chosen from the UV
/// derivatives of the pixel footprint (the OpenGL 4.6 / Vulkan level-of-detail rule), and an
/// optional anisotropic filter (up to 16 probes along the footprint's major axis).
/// docs/real-content.md "Texture sampling" states what the truth is and why.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace aalab {

/// How a texture coordinate outside [0, 1) is folded back (glTF sampler wrapS / wrapT).
enum class WrapMode { kRepeat, kClampToEdge, kMirroredRepeat };

/// How a level's texels are stored (what a GPU texture format would hold).
enum class TexelFormat {
  kFloat,   ///< RGBA float32 in `texels` (derived chains such as Toksvig's, tests)
  kSrgb8,   ///< RGBA8 in `bytes`: RGB sRGB-encoded, decoded on fetch by a 256-entry table; alpha linear
  kUnorm8,  ///< RGBA8 in `bytes`, linear (k/255 on fetch, by a 256-entry table)
  kHalf,    ///< RGBA IEEE half in `halves` (16-bit and float sources), linear
};

/// One level of a mip chain: width × height RGBA texels, row-major, row 0 at v = 0, in one
/// of the formats above. Fetch returns a texel as linear RGBA float whatever the format.
struct MipLevel {
  int width = 0, height = 0;
  TexelFormat format = TexelFormat::kFloat;
  std::vector<glm::vec4> texels;  ///< kFloat
  std::vector<uint8_t> bytes;     ///< kSrgb8, kUnorm8: 4 a texel
  std::vector<uint16_t> halves;   ///< kHalf: 4 a texel
  /// Texel i (row-major) as linear RGBA.
  glm::vec4 Fetch(size_t i) const;
  /// Bytes of the texels as stored.
  size_t Bytes() const;
};

/// Linear value of an 8-bit code: the same float OpenImageIO returns when it reads that code
/// as FLOAT (so an RGBA8 level fetches the bits a float decode of the same image would hold),
/// without (Unorm8Table) or with (Srgb8Table) the sRGB decode.
const float* Unorm8Table();
const float* Srgb8Table();
/// IEEE half (round to nearest even, as OpenEXR's half) to float and back.
float HalfToFloat(uint16_t h);
uint16_t FloatToHalf(float f);

inline glm::vec4 MipLevel::Fetch(size_t i) const {
  switch (format) {
    case TexelFormat::kFloat: return texels[i];
    case TexelFormat::kSrgb8: {
      const uint8_t* p = &bytes[4 * i];
      const float* s = Srgb8Table();
      return {s[p[0]], s[p[1]], s[p[2]], Unorm8Table()[p[3]]};
    }
    case TexelFormat::kUnorm8: {
      const uint8_t* p = &bytes[4 * i];
      const float* u = Unorm8Table();
      return {u[p[0]], u[p[1]], u[p[2]], u[p[3]]};
    }
    case TexelFormat::kHalf: {
      const uint16_t* p = &halves[4 * i];
      return {HalfToFloat(p[0]), HalfToFloat(p[1]), HalfToFloat(p[2]), HalfToFloat(p[3])};
    }
  }
  return glm::vec4(0.0f);
}

/// Level `l` converted to kFloat (what Fetch returns for each texel). Pure.
MipLevel ToFloatLevel(const MipLevel& l);

/// A decoded texture image with its full mip chain (level 0 = the image, each next level
/// half the size, rounded down, at least 1, down to 1 × 1). Colour is filtered in linear
/// light (as a GPU's *_SRGB formats filter); alpha is straight (not premultiplied).
struct MipChain {
  std::string name;  ///< where it came from, for messages and the report
  std::vector<MipLevel> levels;
  /// Bytes of the chain as stored here (4 a texel for RGBA8, 8 for half, 16 for float).
  size_t Bytes() const;
  /// Bytes of the same chain in an RGBA8 GPU texture (4 bytes a texel).
  size_t Bytes8() const;
};

/// Builds the mip chain of `level0` by 2 × 2 box averages (an odd size folds its last row or
/// column into the last texel of the next level, so every texel contributes), each level
/// from the one above as stored and in level 0's format, as glGenerateMipmap does (engines
/// store RGBA8 mips): kSrgb8 colour averaged in linear light (double) and stored as the
/// nearest sRGB code (the code whose encoded interval holds the mean), kUnorm8 channels and
/// kSrgb8 alpha as the mean of the codes rounded half up, kHalf and kFloat averaged in double
/// and rounded to the format. Pure.
MipChain BuildMipChain(MipLevel level0, std::string name);

/// Largest texture edge aalab accepts (a bigger declared size is refused before decoding).
inline constexpr int kMaxTextureSize = 16384;

/// Decodes an image (PNG, JPEG, any format OpenImageIO reads) from a file or from memory
/// (`data` non-null: `size` bytes, `hint` the format's extension, e.g. "png") into RGBA level
/// 0. An 8-bit image stays 8-bit (kSrgb8 with `srgb`, else kUnorm8: decoded on fetch); any
/// other (16-bit, half, float) is read as float, its RGB sRGB-decoded with `srgb`, and
/// stored as kHalf. Grey images replicate into RGB; images without alpha get 1.
/// Throws UserError naming `name` for undecodable data, a zero or larger than
/// kMaxTextureSize size, or more than 4 channels.
/// With `charged`, the caller has charged the image's pixels to io's decode budget already
/// (ChargeDecodeBudget, in file order: the same refusal at any thread count).
MipLevel DecodeTextureImage(const std::string& name, const std::string& path, const uint8_t* data, size_t size,
                            const std::string& hint, bool srgb, bool charged = false);

/// What an image's header declares, read before any texel is decoded.
struct TextureHeader {
  int width = 0, height = 0, channels = 0;
  /// Bytes of its RGBA8 mip chain (4 bytes a texel, about 4/3 of level 0).
  size_t Bytes8Chain() const;
};

/// Opens the image (file, or memory as DecodeTextureImage) and reads its header only; throws
/// UserError naming `name` for an unreadable header, a size outside 1..kMaxTextureSize or
/// more than 4 channels. The one place the header rules live (issue #39's image decode
/// budget replaces its body when it lands).
TextureHeader ProbeTextureImage(const std::string& name, const std::string& path, const uint8_t* data, size_t size,
                                const std::string& hint);

/// UV derivatives of one shading sample: how far (u, v) moves for one footprint step along
/// image x and along image y.
struct UvDerivs {
  glm::vec2 dx{0.0f}, dy{0.0f};
};

/// std::hypot(a, b) of two floats, its bits: with glibc 2.35 or later, finite arguments take
/// that library's own arithmetic inline (the double square root of the squares' double sum,
/// rounded to float); the rest, and other C libraries, call std::hypot.
float HypotF(float a, float b);

/// The level of detail λ = log2(ρ), ρ = max(|∂(u·W, v·H)/∂x|, |∂(u·W, v·H)/∂y|) for a
/// level-0 size W × H (OpenGL 4.6 §8.14.1, equation 8.7 with the "max of the two lengths"
/// choice, which Vulkan and D3D allow). −inf when both derivatives are zero.
float MipLambda(const UvDerivs& d, int width, int height);

/// Folds the integer texel index i into [0, n) with the wrap mode.
int WrapIndex(int i, int n, WrapMode mode);

/// Bilinear tap of one level at (u, v): texel centres at ((i + 0.5)/W, (j + 0.5)/H). An
/// 8-bit level's tap runs in SSE registers (SampleBilinearBatch's arithmetic), every other
/// one (and a non-finite or far-off uv) as SampleBilinearScalar: the same bits either way.
glm::vec4 SampleBilinear(const MipLevel& level, glm::vec2 uv, WrapMode wrap_s, WrapMode wrap_t);

/// SampleBilinear texel by texel in float and double scalars (FoldCoord, floor, WrapIndex,
/// glm's vec4 blend): the reference the SSE taps are tested against.
glm::vec4 SampleBilinearScalar(const MipLevel& level, glm::vec2 uv, WrapMode wrap_s, WrapMode wrap_t);

/// SampleBilinear of each uv[k] into out[k], k < n, with the same bits: the batch form the
/// reference's level-0 texture fetches take over a packet of samples: the format and tables
/// decided once per batch, a sample's texel x and y in the two lanes of an SSE2 double
/// register, each texel's four channels decoded (sRGB colour by table, unorm codes by
/// conversion and k · (1/255.0f), Unorm8Table's own operation) and blended in one SSE
/// register, with the same operations in the same order as SampleBilinearScalar.
void SampleBilinearBatch(const MipLevel& level, const glm::vec2* uv, int n, WrapMode wrap_s, WrapMode wrap_t,
                         glm::vec4* out);

/// A glTF sampler's filters (OpenGL enums): magFilter NEAREST 9728 / LINEAR 9729; minFilter
/// NEAREST 9728, LINEAR 9729, NEAREST_MIPMAP_NEAREST 9984, LINEAR_MIPMAP_NEAREST 9985,
/// NEAREST_MIPMAP_LINEAR 9986, LINEAR_MIPMAP_LINEAR 9987 (the default when absent, as engines
/// choose). Sampled as the OpenGL 4.6 §8.14–8.15 rules define each.
struct SamplerFilter {
  bool mag_nearest = false;  ///< magnification: nearest texel (else bilinear)
  bool min_nearest = false;  ///< minification within a level: nearest texel (else bilinear)
  enum class Mip { kNone, kNearest, kLinear } mip = Mip::kLinear;  ///< between levels
  bool operator==(const SamplerFilter&) const = default;
};

/// The filter of glTF minFilter / magFilter values (already checked to be valid enums).
SamplerFilter SamplerFilterOf(int mag, int min);

/// How a texture sample filters.
struct TextureFilter {
  bool level0_only = false;  ///< bilinear on level 0 at every sample (the reference's truth)
  int max_aniso = 1;         ///< 1: isotropic trilinear; 2..16: anisotropic probes
};

/// Trilinear (and, with max_aniso > 1, anisotropic) sample of the chain at uv with the
/// footprint d: λ from MipLambda (anisotropic: from the minor axis, at most max_aniso probes
/// spaced along the major axis, averaged), clamped to [0, last level]; λ ≤ 0 is
/// magnification (bilinear on level 0). With filter.level0_only: bilinear on level 0.
glm::vec4 SampleTexture(const MipChain& chain, glm::vec2 uv, const UvDerivs& d, WrapMode wrap_s, WrapMode wrap_t,
                        const TextureFilter& filter);

/// SampleTexture under a glTF sampler's filters: the default filter (LINEAR / trilinear)
/// is exactly SampleTexture. Otherwise λ decides magnification (λ ≤ 0: magFilter on level 0)
/// or minification (minFilter: within a level nearest or bilinear; mip none = level 0,
/// nearest = level round(λ), linear = lerp of ⌊λ⌋ and ⌊λ⌋ + 1). With filter.level0_only
/// (the reference's truth), level 0 with the magnification filter at every sample: what a
/// supersampled GPU converges to for that sampler.
glm::vec4 SampleTextureFiltered(const MipChain& chain, glm::vec2 uv, const UvDerivs& d, WrapMode wrap_s,
                                WrapMode wrap_t, const SamplerFilter& sampler, const TextureFilter& filter);

/// Nearest-texel tap of one level at (u, v) (OpenGL: texel ⌊u·W⌋, ⌊v·H⌋, wrapped).
glm::vec4 SampleNearest(const MipLevel& level, glm::vec2 uv, WrapMode wrap_s, WrapMode wrap_t);

}  // namespace aalab
