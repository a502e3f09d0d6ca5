// Sampling of the mip-mapped image textures (scenes/texture_image.h): wrap modes, the level
// of detail, bilinear taps of one level (8-bit levels in SSE registers, every format in
// scalars as the reference), trilinear and anisotropic filtering, and the glTF sampler's
// NEAREST / mip-mode variants (OpenGL 4.6 §8.14–8.15).
#include "scenes/texture_image.h"

#include <emmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace aalab {

float HypotF(float a, float b) {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35))
  // glibc 2.35's hypotf for finite arguments (sysdeps/ieee754/flt-32/e_hypotf.c): the squares
  // are exact in double, one rounded sum, IEEE square root, one rounding to float.
  constexpr float kMax = 3.40282347e38f;  // FLT_MAX; NaN fails both compares
  if (std::fabs(a) <= kMax && std::fabs(b) <= kMax) {
    const double x = a, y = b;
    return static_cast<float>(std::sqrt(x * x + y * y));
  }
#endif
  return std::hypot(a, b);
}

float MipLambda(const UvDerivs& d, int width, int height) {
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  const float lx = HypotF(d.dx.x * w, d.dx.y * h);
  const float ly = HypotF(d.dy.x * w, d.dy.y * h);
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

/// WrapPair with at most one integer division (WrapPair's out-of-range case takes two): the
/// index of x0 + 1 is the successor of x0's index in the period (n, or 2n mirrored), back to
/// 0 past its end, then mirrored as WrapIndex mirrors; a power-of-two period folds by a mask
/// (x & (m − 1) is x mod m in [0, m) for every int x in two's complement).
inline void WrapPairFast(int x0, int n, WrapMode mode, int* i0, int* i1) {
  if (x0 >= 0 && x0 < n - 1) {
    *i0 = x0;
    *i1 = x0 + 1;
    return;
  }
  if (mode == WrapMode::kClampToEdge) {
    *i0 = std::clamp(x0, 0, n - 1);
    *i1 = std::clamp(x0 + 1, 0, n - 1);
    return;
  }
  const int period = mode == WrapMode::kMirroredRepeat ? 2 * n : n;
  int r = 0;
  if ((period & (period - 1)) == 0) {
    r = x0 & (period - 1);
  } else {
    r = x0 % period;
    if (r < 0) r += period;
  }
  const int r1 = r + 1 == period ? 0 : r + 1;
  if (mode != WrapMode::kMirroredRepeat) {
    *i0 = r;
    *i1 = r1;
    return;
  }
  *i0 = r < n ? r : period - 1 - r;
  *i1 = r1 < n ? r1 : period - 1 - r1;
}

/// Blend4 in one SSE register per texel (lanes = the four channels): per channel the same
/// products and sums in the same order as glm's vec4 operators, so the same bits.
inline __m128 Blend4Sse(__m128 t00, __m128 t10, __m128 t01, __m128 t11, float ax, float ay) {
  const __m128 wx = _mm_set1_ps(ax), wx1 = _mm_set1_ps(1.0f - ax);
  const __m128 wy = _mm_set1_ps(ay), wy1 = _mm_set1_ps(1.0f - ay);
  const __m128 top = _mm_add_ps(_mm_mul_ps(t00, wx1), _mm_mul_ps(t10, wx));
  const __m128 bot = _mm_add_ps(_mm_mul_ps(t01, wx1), _mm_mul_ps(t11, wx));
  return _mm_add_ps(_mm_mul_ps(top, wy1), _mm_mul_ps(bot, wy));
}

/// The 8-bit decode tables, looked up once (a guarded static, not two calls a tap).
struct Tables8 {
  const float* srgb;
  const float* unorm;
};
inline const Tables8& Tables() {
  static const Tables8 t{Srgb8Table(), Unorm8Table()};
  return t;
}

/// Texel i of an 8-bit level as its four linear channels. sRGB: colour through Srgb8Table,
/// alpha through Unorm8Table. Unorm: the four codes widened to int32 lanes, converted
/// (exactly) and multiplied by 1/255 in float, which is how Unorm8Table's entries are made
/// (k · (1.0f / 255.0f), io/image_read.cpp): the same operation, the same floats.
template <bool kSrgb>
inline __m128 Texel8(const uint8_t* bytes, size_t i, const Tables8& t) {
  const uint8_t* p = bytes + 4 * i;
  if constexpr (kSrgb) {
    return _mm_setr_ps(t.srgb[p[0]], t.srgb[p[1]], t.srgb[p[2]], t.unorm[p[3]]);
  } else {
    int32_t v;
    std::memcpy(&v, p, sizeof v);
    const __m128i z = _mm_setzero_si128();
    const __m128i codes = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(v), z), z);
    return _mm_mul_ps(_mm_cvtepi32_ps(codes), _mm_set1_ps(1.0f / 255.0f));
  }
}

/// SampleBilinear of an 8-bit level (kSrgb: kSrgb8, else kUnorm8; tb: the decode tables) at uv
/// into *out, in SSE2 registers; false, having written nothing, where SampleBilinearScalar
/// must answer (a non-finite uv, a coordinate FoldCoord would fold).
template <bool kSrgb>
inline __attribute__((always_inline)) bool Bilinear8(const MipLevel& level, const glm::vec2& uv, WrapMode wrap_s,
                                                     WrapMode wrap_t, const Tables8& tb, __m128* out) {
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
  WrapPairFast(x0, level.width, wrap_s, &i0, &i1);
  WrapPairFast(y0, level.height, wrap_t, &j0, &j1);
  const size_t w = static_cast<size_t>(level.width);
  const size_t r0 = static_cast<size_t>(j0) * w, r1 = static_cast<size_t>(j1) * w;
  const uint8_t* bytes = level.bytes.data();
  *out = Blend4Sse(
      Texel8<kSrgb>(bytes, r0 + static_cast<size_t>(i0), tb), Texel8<kSrgb>(bytes, r0 + static_cast<size_t>(i1), tb),
      Texel8<kSrgb>(bytes, r1 + static_cast<size_t>(i0), tb), Texel8<kSrgb>(bytes, r1 + static_cast<size_t>(i1), tb),
      _mm_cvtss_f32(a), _mm_cvtss_f32(_mm_shuffle_ps(a, a, 1)));
  return true;
}

/// SampleBilinear's value in an SSE register (the SSE tap of an 8-bit level, else the scalar).
inline __m128 Tap(const MipLevel& level, const glm::vec2& uv, WrapMode wrap_s, WrapMode wrap_t) {
  __m128 r;
  if (level.format == TexelFormat::kSrgb8) {
    if (Bilinear8<true>(level, uv, wrap_s, wrap_t, Tables(), &r)) return r;
  } else if (level.format == TexelFormat::kUnorm8) {
    if (Bilinear8<false>(level, uv, wrap_s, wrap_t, Tables(), &r)) return r;
  }
  const glm::vec4 v = SampleBilinearScalar(level, uv, wrap_s, wrap_t);
  return _mm_loadu_ps(&v.x);
}

inline glm::vec4 ToVec4(__m128 v) {
  glm::vec4 r;
  _mm_storeu_ps(&r.x, v);
  return r;
}

/// SampleBilinearBatch for one 8-bit format.
template <bool kSrgb>
void Batch8(const MipLevel& level, const glm::vec2* uv, int n, WrapMode wrap_s, WrapMode wrap_t, glm::vec4* out) {
  const Tables8& tb = Tables();
  for (int k = 0; k < n; ++k) {
    __m128 r;
    if (Bilinear8<kSrgb>(level, uv[k], wrap_s, wrap_t, tb, &r)) {
      _mm_storeu_ps(&out[k].x, r);
    } else {
      out[k] = SampleBilinearScalar(level, uv[k], wrap_s, wrap_t);
    }
  }
}

}  // namespace

glm::vec4 SampleBilinear(const MipLevel& level, glm::vec2 uv, WrapMode wrap_s, WrapMode wrap_t) {
  return ToVec4(Tap(level, uv, wrap_s, wrap_t));
}

void SampleBilinearBatch(const MipLevel& level, const glm::vec2* uv, int n, WrapMode wrap_s, WrapMode wrap_t,
                         glm::vec4* out) {
  switch (level.format) {
    case TexelFormat::kSrgb8: Batch8<true>(level, uv, n, wrap_s, wrap_t, out); return;
    case TexelFormat::kUnorm8: Batch8<false>(level, uv, n, wrap_s, wrap_t, out); return;
    default:
      for (int k = 0; k < n; ++k) out[k] = SampleBilinearScalar(level, uv[k], wrap_s, wrap_t);
  }
}

namespace {

/// The trilinear tap at λ: level 0 when magnifying (and for NaN), the last level beyond it,
/// else the two levels around λ blended a · (1 − f) + b · f per channel (glm's vec4
/// operators' products and sum, in SSE lanes), or level ⌊λ⌋ alone where f is 0.
glm::vec4 SampleLevelLerp(const MipChain& chain, glm::vec2 uv, float lambda, WrapMode ws, WrapMode wt) {
  const int last = static_cast<int>(chain.levels.size()) - 1;
  int l0 = 0;
  float f = 0.0f;
  if (!(lambda > 0.0f)) {
    l0 = 0;
  } else if (lambda >= static_cast<float>(last)) {
    l0 = last;
  } else {
    l0 = static_cast<int>(std::floor(lambda));
    f = lambda - static_cast<float>(l0);
  }
  const __m128 a = Tap(chain.levels[static_cast<size_t>(l0)], uv, ws, wt);
  if (f == 0.0f) return ToVec4(a);
  const __m128 b = Tap(chain.levels[static_cast<size_t>(l0) + 1], uv, ws, wt);
  return ToVec4(_mm_add_ps(_mm_mul_ps(a, _mm_set1_ps(1.0f - f)), _mm_mul_ps(b, _mm_set1_ps(f))));
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
  const float lx = HypotF(d.dx.x * w, d.dx.y * h);
  const float ly = HypotF(d.dy.x * w, d.dy.y * h);
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
