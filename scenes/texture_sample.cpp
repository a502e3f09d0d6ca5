// Sampling of the mip-mapped image textures (scenes/texture_image.h): wrap modes, the level
// of detail, bilinear taps of one level (8-bit levels in SSE registers, every format in
// scalars as the reference), trilinear and anisotropic filtering, and the glTF sampler's
// NEAREST / mip-mode variants (OpenGL 4.6 §8.14–8.15).
#include "scenes/texture_image.h"

#include <emmintrin.h>

#include <algorithm>
#include <cmath>

namespace aalab {

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
