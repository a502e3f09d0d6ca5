/// Image textures as a GPU samples them: a mip chain of linear RGBA float texels, bilinear
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

/// One level of a mip chain: width × height RGBA texels, row-major, row 0 at v = 0.
struct MipLevel {
  int width = 0, height = 0;
  std::vector<glm::vec4> texels;
};

/// A decoded texture image with its full mip chain (level 0 = the image, each next level
/// half the size, rounded down, at least 1, down to 1 × 1). Colour texels are linear: an
/// sRGB image is decoded to linear before the chain is built (as a GPU's *_SRGB formats
/// filter in linear light); alpha is straight (not premultiplied).
struct MipChain {
  std::string name;  ///< where it came from, for messages and the report
  std::vector<MipLevel> levels;
  /// Bytes of the chain as stored here (16 bytes a texel).
  size_t Bytes() const;
  /// Bytes of the same chain in an RGBA8 GPU texture (4 bytes a texel).
  size_t Bytes8() const;
};

/// Builds the mip chain of `level0` by 2 × 2 box averages (an odd size folds its last row or
/// column into the last texel of the next level, so every texel contributes). Pure.
MipChain BuildMipChain(MipLevel level0, std::string name);

/// Largest texture edge aalab accepts (a bigger declared size is refused before decoding).
inline constexpr int kMaxTextureSize = 16384;

/// Decodes an image (PNG, JPEG, any format OpenImageIO reads) from a file or from memory
/// (`data` non-null: `size` bytes, `hint` the format's extension, e.g. "png") into RGBA level
/// 0. `srgb`: the RGB channels are sRGB-encoded and are decoded to linear; else they are
/// used as stored (k/255). Grey images replicate into RGB; images without alpha get 1.
/// Throws UserError naming `name` for undecodable data, a zero or larger than
/// kMaxTextureSize size, or more than 4 channels.
MipLevel DecodeTextureImage(const std::string& name, const std::string& path, const uint8_t* data, size_t size,
                            const std::string& hint, bool srgb);

/// UV derivatives of one shading sample: how far (u, v) moves for one footprint step along
/// image x and along image y.
struct UvDerivs {
  glm::vec2 dx{0.0f}, dy{0.0f};
};

/// The level of detail λ = log2(ρ), ρ = max(|∂(u·W, v·H)/∂x|, |∂(u·W, v·H)/∂y|) for a
/// level-0 size W × H (OpenGL 4.6 §8.14.1, equation 8.7 with the "max of the two lengths"
/// choice, which Vulkan and D3D allow). −inf when both derivatives are zero.
float MipLambda(const UvDerivs& d, int width, int height);

/// Folds the integer texel index i into [0, n) with the wrap mode.
int WrapIndex(int i, int n, WrapMode mode);

/// Bilinear tap of one level at (u, v): texel centres at ((i + 0.5)/W, (j + 0.5)/H).
glm::vec4 SampleBilinear(const MipLevel& level, glm::vec2 uv, WrapMode wrap_s, WrapMode wrap_t);

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

}  // namespace aalab
