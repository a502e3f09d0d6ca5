// Image textures: decoding through io (io/image_io.h: ReadTexturePixels, straight alpha,
// the reader's checks and decode budget), compact storage (RGBA8 sRGB / linear with
// 256-entry decode tables, half for 16-bit and float images), box-filtered mip chains built
// in the stored format as glGenerateMipmap does, wrap modes, bilinear / trilinear /
// anisotropic sampling (scenes/texture_image.h). The RGBA8 tables hold OpenImageIO's own
// UINT8 -> FLOAT conversion, so an 8-bit level 0 fetches the same floats the float decode
// before issue #35 stored (the mips differ: they are 8-bit now, as engines store them).
#include "scenes/texture_image.h"

#include <Imath/half.h>
#include <emmintrin.h>

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

float MipLambda(const UvDerivs& d, int width, int height) {
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  const float lx = std::hypot(d.dx.x * w, d.dx.y * h);
  const float ly = std::hypot(d.dy.x * w, d.dy.y * h);
  const float rho = std::max(lx, ly);
  return std::log2(rho);
}

int WrapIndex(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::kRepeat: {
      const int r = i % n;
      return r < 0 ? r + n : r;
    }
    case WrapMode::kClampToEdge: return std::clamp(i, 0, n - 1);
    case WrapMode::kMirroredRepeat: {
      const int period = 2 * n;
      int r = i % period;
      if (r < 0) r += period;
      return r < n ? r : period - 1 - r;
    }
  }
  return 0;
}

namespace {

/// A texel coordinate far outside the texture would overflow int: fold it into one repeat
/// period (or clamp) in double first, which changes no texel it selects.
double FoldCoord(double x, int n, WrapMode mode) {
  if (std::fabs(x) < 1e8) return x;
  if (mode == WrapMode::kClampToEdge) return x < 0 ? -1.0 : static_cast<double>(n);
  const double period = mode == WrapMode::kRepeat ? n : 2.0 * n;
  return x - std::floor(x / period) * period;
}

}  // namespace

namespace {

/// WrapIndex of x0 and x0 + 1: an in-range pair maps to itself in every wrap mode, so the
/// common case needs no integer division.
inline void WrapPair(int x0, int n, WrapMode mode, int* i0, int* i1) {
  if (x0 >= 0 && x0 < n - 1) {
    *i0 = x0;
    *i1 = x0 + 1;
    return;
  }
  *i0 = WrapIndex(x0, n, mode);
  *i1 = WrapIndex(x0 + 1, n, mode);
}

/// The bilinear blend of the four taps `at(i, j)`, in the one order every format shares.
template <typename At>
inline glm::vec4 Blend4(const At& at, int i0, int i1, int j0, int j1, float ax, float ay) {
  const glm::vec4 top = at(i0, j0) * (1.0f - ax) + at(i1, j0) * ax;
  const glm::vec4 bot = at(i0, j1) * (1.0f - ax) + at(i1, j1) * ax;
  return top * (1.0f - ay) + bot * ay;
}

}  // namespace

glm::vec4 SampleBilinearScalar(const MipLevel& level, glm::vec2 uv, WrapMode wrap_s, WrapMode wrap_t) {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return level.Fetch(0);
  const double x = FoldCoord(static_cast<double>(uv.x) * level.width - 0.5, level.width, wrap_s);
  const double y = FoldCoord(static_cast<double>(uv.y) * level.height - 0.5, level.height, wrap_t);
  const double fx = std::floor(x), fy = std::floor(y);
  const float ax = static_cast<float>(x - fx), ay = static_cast<float>(y - fy);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  int i0, i1, j0, j1;
  WrapPair(x0, level.width, wrap_s, &i0, &i1);
  WrapPair(y0, level.height, wrap_t, &j0, &j1);
  const size_t w = static_cast<size_t>(level.width);
  // The 8-bit formats decode by table with the tables and the format looked up once per
  // tap group, not per texel (MipLevel::Fetch's values, the same blend: the same bits).
  switch (level.format) {
    case TexelFormat::kSrgb8: {
      const uint8_t* b = level.bytes.data();
      const float* s = Srgb8Table();
      const float* u = Unorm8Table();
      return Blend4(
          [&](int i, int j) {
            const uint8_t* p = b + 4 * (static_cast<size_t>(j) * w + static_cast<size_t>(i));
            return glm::vec4(s[p[0]], s[p[1]], s[p[2]], u[p[3]]);
          },
          i0, i1, j0, j1, ax, ay);
    }
    case TexelFormat::kUnorm8: {
      const uint8_t* b = level.bytes.data();
      const float* u = Unorm8Table();
      return Blend4(
          [&](int i, int j) {
            const uint8_t* p = b + 4 * (static_cast<size_t>(j) * w + static_cast<size_t>(i));
            return glm::vec4(u[p[0]], u[p[1]], u[p[2]], u[p[3]]);
          },
          i0, i1, j0, j1, ax, ay);
    }
    default:
      return Blend4([&](int i, int j) { return level.Fetch(static_cast<size_t>(j) * w + static_cast<size_t>(i)); }, i0,
                    i1, j0, j1, ax, ay);
  }
}

namespace {

/// Blend4 in one SSE register per texel (lanes = the four channels): per channel the same
/// products and sums in the same order as glm's vec4 operators, so the same bits.
inline __m128 Blend4Sse(__m128 t00, __m128 t10, __m128 t01, __m128 t11, float ax, float ay) {
  const __m128 wx = _mm_set1_ps(ax), wx1 = _mm_set1_ps(1.0f - ax);
  const __m128 wy = _mm_set1_ps(ay), wy1 = _mm_set1_ps(1.0f - ay);
  const __m128 top = _mm_add_ps(_mm_mul_ps(t00, wx1), _mm_mul_ps(t10, wx));
  const __m128 bot = _mm_add_ps(_mm_mul_ps(t01, wx1), _mm_mul_ps(t11, wx));
  return _mm_add_ps(_mm_mul_ps(top, wy1), _mm_mul_ps(bot, wy));
}

/// The four channels of texel i of an 8-bit level through its decode tables (rgb, alpha).
inline __m128 Texel8(const uint8_t* bytes, size_t i, const float* rgb, const float* alpha) {
  const uint8_t* p = bytes + 4 * i;
  return _mm_setr_ps(rgb[p[0]], rgb[p[1]], rgb[p[2]], alpha[p[3]]);
}

/// SampleBilinear of an 8-bit level at uv into *out (rgb, alpha: its decode tables), in SSE2
/// registers; false, having written nothing, where SampleBilinearScalar must answer (a
/// non-finite uv, a coordinate FoldCoord would fold).
inline __attribute__((always_inline)) bool Bilinear8(const MipLevel& level, const glm::vec2& uv, WrapMode wrap_s,
                                                     WrapMode wrap_t, const float* rgb, const float* alpha,
                                                     float* out) {
  static_assert(sizeof(glm::vec2) == 8 && sizeof(glm::vec4) == 16, "glm vectors must be packed floats");
  const __m128d size = _mm_setr_pd(static_cast<double>(level.width), static_cast<double>(level.height));
  // (x, y) in the two lanes of an SSE2 double register: x = u·W − ½ in double, floor by
  // truncation (exact: |x| < 1e8 < 2^31) minus one where that rounded up, the fraction
  // x − ⌊x⌋ (exact in double) rounded to float: SampleBilinearScalar's arithmetic.
  const __m128d c =
      _mm_sub_pd(_mm_mul_pd(_mm_cvtps_pd(_mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(&uv)))), size),
                 _mm_set1_pd(0.5));
  // Non-finite uv (NaN fails the compare) or a coordinate FoldCoord would fold.
  const __m128d abs_mask = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
  if (_mm_movemask_pd(_mm_cmplt_pd(_mm_and_pd(c, abs_mask), _mm_set1_pd(1e8))) != 3) return false;
  const __m128d t = _mm_cvtepi32_pd(_mm_cvttpd_epi32(c));
  const __m128d f = _mm_sub_pd(t, _mm_and_pd(_mm_cmpgt_pd(t, c), _mm_set1_pd(1.0)));
  const __m128i fi = _mm_cvttpd_epi32(f);
  const __m128 a = _mm_cvtpd_ps(_mm_sub_pd(c, f));
  const int x0 = _mm_cvtsi128_si32(fi), y0 = _mm_cvtsi128_si32(_mm_shuffle_epi32(fi, 1));
  int i0, i1, j0, j1;
  WrapPair(x0, level.width, wrap_s, &i0, &i1);
  WrapPair(y0, level.height, wrap_t, &j0, &j1);
  const size_t w = static_cast<size_t>(level.width);
  const size_t r0 = static_cast<size_t>(j0) * w, r1 = static_cast<size_t>(j1) * w;
  const uint8_t* bytes = level.bytes.data();
  const __m128 v = Blend4Sse(
      Texel8(bytes, r0 + static_cast<size_t>(i0), rgb, alpha), Texel8(bytes, r0 + static_cast<size_t>(i1), rgb, alpha),
      Texel8(bytes, r1 + static_cast<size_t>(i0), rgb, alpha), Texel8(bytes, r1 + static_cast<size_t>(i1), rgb, alpha),
      _mm_cvtss_f32(a), _mm_cvtss_f32(_mm_shuffle_ps(a, a, 1)));
  _mm_storeu_ps(out, v);
  return true;
}

}  // namespace

glm::vec4 SampleBilinear(const MipLevel& level, glm::vec2 uv, WrapMode wrap_s, WrapMode wrap_t) {
  if (level.format == TexelFormat::kSrgb8 || level.format == TexelFormat::kUnorm8) {
    glm::vec4 r;
    if (Bilinear8(level, uv, wrap_s, wrap_t, level.format == TexelFormat::kSrgb8 ? Srgb8Table() : Unorm8Table(),
                  Unorm8Table(), &r.x)) {
      return r;
    }
  }
  return SampleBilinearScalar(level, uv, wrap_s, wrap_t);
}

void SampleBilinearBatch(const MipLevel& level, const glm::vec2* uv, int n, WrapMode wrap_s, WrapMode wrap_t,
                         glm::vec4* out) {
  const bool is8 = level.format == TexelFormat::kSrgb8 || level.format == TexelFormat::kUnorm8;
  const float* rgb = level.format == TexelFormat::kSrgb8 ? Srgb8Table() : Unorm8Table();
  const float* alpha = Unorm8Table();
  for (int k = 0; k < n; ++k) {
    if (!is8 || !Bilinear8(level, uv[k], wrap_s, wrap_t, rgb, alpha, &out[k].x)) {
      out[k] = SampleBilinearScalar(level, uv[k], wrap_s, wrap_t);
    }
  }
}

namespace {

glm::vec4 SampleLevelLerp(const MipChain& chain, glm::vec2 uv, float lambda, WrapMode ws, WrapMode wt) {
  const int last = static_cast<int>(chain.levels.size()) - 1;
  if (!(lambda > 0.0f)) return SampleBilinear(chain.levels[0], uv, ws, wt);  // magnification, NaN
  if (lambda >= static_cast<float>(last)) return SampleBilinear(chain.levels[last], uv, ws, wt);
  const int l0 = static_cast<int>(std::floor(lambda));
  const float f = lambda - static_cast<float>(l0);
  const glm::vec4 a = SampleBilinear(chain.levels[l0], uv, ws, wt);
  if (f == 0.0f) return a;
  const glm::vec4 b = SampleBilinear(chain.levels[l0 + 1], uv, ws, wt);
  return a * (1.0f - f) + b * f;
}

}  // namespace

glm::vec4 SampleTexture(const MipChain& chain, glm::vec2 uv, const UvDerivs& d, WrapMode wrap_s, WrapMode wrap_t,
                        const TextureFilter& filter) {
  if (filter.level0_only) return SampleBilinear(chain.levels[0], uv, wrap_s, wrap_t);
  const MipLevel& l0 = chain.levels[0];
  if (filter.max_aniso <= 1) return SampleLevelLerp(chain, uv, MipLambda(d, l0.width, l0.height), wrap_s, wrap_t);
  // Anisotropic: N probes along the major axis, each with the level of the minor axis
  // stretched so that N probes cover the major one (the EXT_texture_filter_anisotropic rule).
  const float w = static_cast<float>(l0.width), h = static_cast<float>(l0.height);
  const float lx = std::hypot(d.dx.x * w, d.dx.y * h);
  const float ly = std::hypot(d.dy.x * w, d.dy.y * h);
  const float pmax = std::max(lx, ly), pmin = std::min(lx, ly);
  if (!(pmax > 0.0f) || !std::isfinite(pmax))
    return SampleLevelLerp(chain, uv, MipLambda(d, l0.width, l0.height), wrap_s, wrap_t);
  const float ratio = pmin > 0.0f ? pmax / pmin : static_cast<float>(filter.max_aniso);
  const int n = std::clamp(static_cast<int>(std::ceil(ratio)), 1, filter.max_aniso);
  const float lambda = std::log2(pmax / static_cast<float>(n));
  const glm::vec2 major = lx >= ly ? d.dx : d.dy;
  glm::vec4 sum(0.0f);
  for (int k = 0; k < n; ++k) {
    const float t = (static_cast<float>(k) + 0.5f) / static_cast<float>(n) - 0.5f;
    sum += SampleLevelLerp(chain, uv + major * t, lambda, wrap_s, wrap_t);
  }
  return sum / static_cast<float>(n);
}

SamplerFilter SamplerFilterOf(int mag, int min) {
  SamplerFilter f;
  f.mag_nearest = mag == 9728;
  f.min_nearest = min == 9728 || min == 9984 || min == 9986;
  f.mip = (min == 9728 || min == 9729)   ? SamplerFilter::Mip::kNone
          : (min == 9984 || min == 9985) ? SamplerFilter::Mip::kNearest
                                         : SamplerFilter::Mip::kLinear;
  return f;
}

glm::vec4 SampleNearest(const MipLevel& level, glm::vec2 uv, WrapMode wrap_s, WrapMode wrap_t) {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return level.Fetch(0);
  const double x = FoldCoord(static_cast<double>(uv.x) * level.width, level.width, wrap_s);
  const double y = FoldCoord(static_cast<double>(uv.y) * level.height, level.height, wrap_t);
  const int i = WrapIndex(static_cast<int>(std::floor(x)), level.width, wrap_s);
  const int j = WrapIndex(static_cast<int>(std::floor(y)), level.height, wrap_t);
  return level.Fetch(static_cast<size_t>(j) * level.width + i);
}

glm::vec4 SampleTextureFiltered(const MipChain& chain, glm::vec2 uv, const UvDerivs& d, WrapMode wrap_s,
                                WrapMode wrap_t, const SamplerFilter& sampler, const TextureFilter& filter) {
  if (sampler == SamplerFilter{}) return SampleTexture(chain, uv, d, wrap_s, wrap_t, filter);
  auto tap = [&](const MipLevel& l, bool nearest) {
    return nearest ? SampleNearest(l, uv, wrap_s, wrap_t) : SampleBilinear(l, uv, wrap_s, wrap_t);
  };
  if (filter.level0_only) return tap(chain.levels[0], sampler.mag_nearest);
  const MipLevel& l0 = chain.levels[0];
  const float lambda = MipLambda(d, l0.width, l0.height);
  if (!(lambda > 0.0f)) return tap(l0, sampler.mag_nearest);  // magnification (and NaN)
  const int last = static_cast<int>(chain.levels.size()) - 1;
  switch (sampler.mip) {
    case SamplerFilter::Mip::kNone: return tap(l0, sampler.min_nearest);
    case SamplerFilter::Mip::kNearest: {
      // OpenGL 4.6 eq. 8.13: level ⌈λ + ½⌉ − 1 (round half down), clamped to the chain.
      const int k = std::clamp(static_cast<int>(std::ceil(lambda + 0.5f)) - 1, 0, last);
      return tap(chain.levels[static_cast<size_t>(k)], sampler.min_nearest);
    }
    case SamplerFilter::Mip::kLinear: break;
  }
  if (lambda >= static_cast<float>(last)) return tap(chain.levels[static_cast<size_t>(last)], sampler.min_nearest);
  const int k = static_cast<int>(std::floor(lambda));
  const float f = lambda - static_cast<float>(k);
  const glm::vec4 a = tap(chain.levels[static_cast<size_t>(k)], sampler.min_nearest);
  if (f == 0.0f) return a;
  return a * (1.0f - f) + tap(chain.levels[static_cast<size_t>(k) + 1], sampler.min_nearest) * f;
}

}  // namespace aalab
