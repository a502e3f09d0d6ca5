// Image textures: decoding through io (io/image_io.h: ReadTexturePixels, straight alpha,
// the reader's checks and decode budget), compact storage (RGBA8 sRGB / linear with
// 256-entry decode tables, half for 16-bit and float images), box-filtered mip chains built
// in the stored format as glGenerateMipmap does (scenes/texture_image.h). Wrap modes and
// bilinear / trilinear / anisotropic sampling: scenes/texture_sample.cpp. The RGBA8 tables
// hold OpenImageIO's own UINT8 -> FLOAT conversion, so an 8-bit level 0 fetches the same
// floats the float decode before issue #35 stored (the mips differ: they are 8-bit now, as
// engines store them).
#include "scenes/texture_image.h"

#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/color.h"
#include "core/error.h"
#include "io/image_io.h"

namespace aalab {

const float* Unorm8Table() { return Unorm8FloatTable(); }

const float* Srgb8Table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (size_t i = 0; i < 256; ++i) t[i] = SrgbDecode(Unorm8Table()[i]);
    return t;
  }();
  return table.data();
}

float HalfToFloat(uint16_t h) {
  Imath::half v;
  v.setBits(h);
  return static_cast<float>(v);
}

uint16_t FloatToHalf(float f) { return Imath::half(f).bits(); }

size_t MipLevel::Bytes() const {
  return texels.size() * sizeof(glm::vec4) + bytes.size() + halves.size() * sizeof(uint16_t);
}

MipLevel ToFloatLevel(const MipLevel& l) {
  MipLevel f;
  f.width = l.width;
  f.height = l.height;
  f.texels.resize(static_cast<size_t>(l.width) * l.height);
  for (size_t i = 0; i < f.texels.size(); ++i) f.texels[i] = l.Fetch(i);
  return f;
}

size_t MipChain::Bytes() const {
  size_t n = 0;
  for (const MipLevel& l : levels) n += l.Bytes();
  return n;
}

size_t MipChain::Bytes8() const {
  size_t n = 0;
  for (const MipLevel& l : levels) n += static_cast<size_t>(l.width) * l.height * 4;
  return n;
}

namespace {

/// A level of `format` with room for w × h texels.
MipLevel EmptyLevel(int w, int h, TexelFormat format) {
  MipLevel l;
  l.width = w;
  l.height = h;
  l.format = format;
  const size_t n = static_cast<size_t>(w) * h;
  switch (format) {
    case TexelFormat::kFloat: l.texels.assign(n, glm::vec4(0.0f)); break;
    case TexelFormat::kSrgb8:
    case TexelFormat::kUnorm8: l.bytes.assign(4 * n, 0); break;
    case TexelFormat::kHalf: l.halves.assign(4 * n, 0); break;
  }
  return l;
}

/// The 8-bit sRGB code of a linear value: the code whose encoded interval holds it, i.e. the
/// number of code midpoints SrgbDecode((k + ½)/255), k = 0..254, at or below v (the code
/// rounding SrgbEncode(v)·255 to nearest gives, up to float rounding at a midpoint), found
/// without a pow: a 4096-bucket table gives the code at the bucket's low end, and the
/// midpoints inside the bucket (at most a few) are stepped over.
uint8_t EncodeSrgb8(float v) {
  struct Tables {
    std::array<float, 256> mid{};  // mid[255] = +inf: no code above 255
    std::array<uint8_t, 4097> start{};
  };
  static const Tables t = [] {
    Tables r;
    for (size_t k = 0; k < 255; ++k) r.mid[k] = SrgbDecode((static_cast<float>(k) + 0.5f) / 255.0f);
    r.mid[255] = std::numeric_limits<float>::infinity();
    for (size_t b = 0; b <= 4096; ++b) {
      const float lo = static_cast<float>(b) / 4096.0f;
      r.start[b] = static_cast<uint8_t>(std::upper_bound(r.mid.begin(), r.mid.begin() + 255, lo) - r.mid.begin());
    }
    return r;
  }();
  if (!(v > 0.0f)) return 0;  // also NaN
  if (v >= 1.0f) return 255;
  // b/4096 <= v for b = floor(v·4096) (exact in float), so start[b] <= the answer.
  unsigned code = t.start[static_cast<size_t>(v * 4096.0f)];
  while (t.mid[code] <= v) ++code;
  return static_cast<uint8_t>(code);
}

/// Texel i of a float or half level (MipLevel::Fetch, unswitched).
template <TexelFormat F>
glm::dvec4 FetchAs(const MipLevel& l, size_t i) {
  if constexpr (F == TexelFormat::kFloat) {
    return glm::dvec4(l.texels[i]);
  } else {
    const uint16_t* p = &l.halves[4 * i];
    return {HalfToFloat(p[0]), HalfToFloat(p[1]), HalfToFloat(p[2]), HalfToFloat(p[3])};
  }
}

/// Stores the linear texel v at i of a float (as is) or half (rounded to nearest) level.
template <TexelFormat F>
void StoreAs(MipLevel& l, size_t i, const glm::dvec4& v) {
  if constexpr (F == TexelFormat::kFloat) {
    l.texels[i] = glm::vec4(v);
  } else {
    for (int c = 0; c < 4; ++c) l.halves[4 * i + c] = FloatToHalf(static_cast<float>(v[c]));
  }
}

/// Source rows (or columns) of destination index y: 2y and 2y + 1, plus the odd last one on
/// the last destination index, so every source texel contributes.
std::pair<int, int> SourceSpan(int y, int dst_n, int src_n) {
  const int y0 = std::min(2 * y, src_n - 1);
  const int y1 = (y == dst_n - 1) ? src_n - 1 : std::min(2 * y + 1, src_n - 1);
  return {y0, y1};
}

/// The next level of `src`: 2 × 2 box averages, odd last rows and columns folded in.
template <TexelFormat F>
MipLevel Downsample(const MipLevel& src) {
  MipLevel dst = EmptyLevel(std::max(1, src.width / 2), std::max(1, src.height / 2), F);
  for (int y = 0; y < dst.height; ++y) {
    const auto [y0, y1] = SourceSpan(y, dst.height, src.height);
    for (int x = 0; x < dst.width; ++x) {
      const auto [x0, x1] = SourceSpan(x, dst.width, src.width);
      const size_t o = static_cast<size_t>(y) * dst.width + x;
      if constexpr (F == TexelFormat::kUnorm8 || F == TexelFormat::kSrgb8) {
        // Linear 8-bit channels (all four of kUnorm8, alpha of kSrgb8): the mean of the
        // codes rounded half up, in integers. sRGB colour: the mean in linear light (double),
        // encoded by EncodeSrgb8.
        const float* lin = Srgb8Table();
        unsigned isum[4] = {0, 0, 0, 0};
        double lsum[3] = {0.0, 0.0, 0.0};
        unsigned n = 0;
        for (int sy = y0; sy <= y1; ++sy) {
          const uint8_t* row = &src.bytes[4 * (static_cast<size_t>(sy) * src.width)];
          for (int sx = x0; sx <= x1; ++sx) {
            const uint8_t* p = row + 4 * static_cast<size_t>(sx);
            for (int c = 0; c < 4; ++c) isum[c] += p[c];
            if constexpr (F == TexelFormat::kSrgb8) {
              for (int c = 0; c < 3; ++c) lsum[c] += lin[p[c]];
            }
            ++n;
          }
        }
        for (int c = 0; c < 4; ++c) {
          uint8_t v = static_cast<uint8_t>((2 * isum[c] + n) / (2 * n));
          if (F == TexelFormat::kSrgb8 && c < 3) v = EncodeSrgb8(static_cast<float>(lsum[c] / n));
          dst.bytes[4 * o + static_cast<size_t>(c)] = v;
        }
      } else {
        glm::dvec4 sum(0.0);
        int n = 0;
        for (int sy = y0; sy <= y1; ++sy) {
          for (int sx = x0; sx <= x1; ++sx) {
            sum += FetchAs<F>(src, static_cast<size_t>(sy) * src.width + sx);
            ++n;
          }
        }
        StoreAs<F>(dst, o, sum / static_cast<double>(n));
      }
    }
  }
  return dst;
}

}  // namespace

MipChain BuildMipChain(MipLevel level0, std::string name) {
  MipChain chain;
  chain.name = std::move(name);
  chain.levels.push_back(std::move(level0));
  while (chain.levels.back().width > 1 || chain.levels.back().height > 1) {
    const MipLevel& src = chain.levels.back();
    MipLevel dst;
    switch (src.format) {
      case TexelFormat::kFloat: dst = Downsample<TexelFormat::kFloat>(src); break;
      case TexelFormat::kSrgb8: dst = Downsample<TexelFormat::kSrgb8>(src); break;
      case TexelFormat::kUnorm8: dst = Downsample<TexelFormat::kUnorm8>(src); break;
      case TexelFormat::kHalf: dst = Downsample<TexelFormat::kHalf>(src); break;
    }
    chain.levels.push_back(std::move(dst));
  }
  return chain;
}

namespace {

/// Where the bytes are, for io: a file, or memory read by the reader `hint` names.
ImageSource Source(const std::string& name, const std::string& path, const uint8_t* data, size_t size,
                   const std::string& hint) {
  if (!data) return {path, nullptr, 0, ""};
  return {name, data, size, "." + (hint.empty() ? std::string("png") : hint)};
}

/// io's message, prefixed with the texture it is about.
[[noreturn]] void Undecodable(const std::string& name, const UserError& e) {
  throw UserError("texture " + name + " cannot be decoded: " + e.what());
}

/// The header rules (size, channel count), checked before any texel is read.
void CheckHeader(const ImageHeader& h, const std::string& name) {
  if (h.width <= 0 || h.height <= 0 || h.width > kMaxTextureSize || h.height > kMaxTextureSize) {
    throw UserError("texture " + name + " has size " + std::to_string(h.width) + "x" + std::to_string(h.height) +
                    " (allowed: 1 to " + std::to_string(kMaxTextureSize) + " texels a side)");
  }
  if (h.channels < 1 || h.channels > 4) {
    throw UserError("texture " + name + " has " + std::to_string(h.channels) + " channels (allowed: 1 to 4)");
  }
}

}  // namespace

size_t TextureHeader::Bytes8Chain() const {
  size_t n = 0;
  for (int w = width, h = height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
    n += static_cast<size_t>(w) * static_cast<size_t>(h) * 4;
    if (w == 1 && h == 1) break;
  }
  return n;
}

TextureHeader ProbeTextureImage(const std::string& name, const std::string& path, const uint8_t* data, size_t size,
                                const std::string& hint) {
  ImageHeader h;
  try {
    h = ReadImageHeader(Source(name, path, data, size, hint));
  } catch (const UserError& e) {
    Undecodable(name, e);
  }
  CheckHeader(h, name);
  return {h.width, h.height, h.channels};
}

MipLevel DecodeTextureImage(const std::string& name, const std::string& path, const uint8_t* data, size_t size,
                            const std::string& hint, bool srgb, bool charged) {
  ProbeTextureImage(name, path, data, size, hint);  // the header rules before any texel
  TexturePixels px;
  try {
    px = ReadTexturePixels(Source(name, path, data, size, hint), kMaxImagePixels, charged);
  } catch (const UserError& e) {
    Undecodable(name, e);
  }
  MipLevel level;
  level.width = px.width;
  level.height = px.height;
  if (px.is8) {
    // 8-bit stays 8-bit: the codes as stored, decoded on fetch (MipLevel::Fetch).
    level.format = srgb ? TexelFormat::kSrgb8 : TexelFormat::kUnorm8;
    level.bytes = std::move(px.rgba8);
    return level;
  }
  level.format = TexelFormat::kHalf;
  level.halves.resize(px.rgba.size());
  for (size_t i = 0; i < px.rgba.size(); ++i) {
    float v = px.rgba[i];
    if (srgb && i % 4 < 3) v = SrgbDecode(v);
    level.halves[i] = FloatToHalf(v);
  }
  return level;
}

}  // namespace aalab
