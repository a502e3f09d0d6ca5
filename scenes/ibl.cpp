// Image-based lighting: the equirectangular map, its SH9 irradiance, its GGX prefilter levels
// and the split-sum BRDF table.
//
// Sources:
//   B. Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013 Physically Based Shading course:
//     the split-sum approximation ∫ L f cos ≈ (∫ L D cos / ∫ D cos) · ∫ f cos, the first factor
//     prefiltered per roughness under the n = v = r assumption, the second a 2D table of
//     (N·V, roughness) → (A, B) with ∫ f cos = F0·A + B, integrated by GGX importance sampling.
//   R. Ramamoorthi and P. Hanrahan, "An Efficient Representation for Irradiance Environment
//     Maps", SIGGRAPH 2001: irradiance from the first nine SH coefficients of the radiance,
//     E(n) = Σ Â_l L_lm Y_lm(n) with Â_0 = π, Â_1 = 2π/3, Â_2 = π/4 (their equations 8, 12, 13).
// Determinism: every sum runs in a fixed order in double; the prefilter is parallel over output
// rows only (each row written by one task), the table is computed once with a fixed sample set.
// Safe choices: the GGX alpha is floored at 1e-3 (as the tracer's BRDF); N·V is floored at 1e-4;
// SH9 irradiance, which can ring below zero for a small bright source, is clamped at 0.
#include "scenes/ibl.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "core/error.h"
#include "core/parallel.h"
#include "io/image_io.h"

namespace aalab {

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kPi = 3.14159265358979f;

float Smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

/// The nine real SH basis functions at unit d (x, y, z), bands 0-2 in the usual order
/// (Y00; Y1-1 ∝ y, Y10 ∝ z, Y11 ∝ x; Y2-2 ∝ xy, Y2-1 ∝ yz, Y20 ∝ 3z² − 1, Y21 ∝ xz,
/// Y22 ∝ x² − y²). aalab's "up" is +Y, which makes no difference to the projection.
std::array<double, 9> ShBasis(glm::dvec3 d) {
  return {0.282094791773878,
          0.488602511902920 * d.y,
          0.488602511902920 * d.z,
          0.488602511902920 * d.x,
          1.092548430592079 * d.x * d.y,
          1.092548430592079 * d.y * d.z,
          0.315391565252520 * (3.0 * d.z * d.z - 1.0),
          1.092548430592079 * d.x * d.z,
          0.546274215296040 * (d.x * d.x - d.y * d.y)};
}

/// 2 × 2 box average (width and height even).
EquirectMap Halve(const EquirectMap& m) {
  EquirectMap o;
  o.width = m.width / 2;
  o.height = m.height / 2;
  o.texels.resize(static_cast<size_t>(o.width) * o.height);
  for (int j = 0; j < o.height; ++j) {
    for (int i = 0; i < o.width; ++i) {
      auto at = [&](int x, int y) { return m.texels[static_cast<size_t>(y) * m.width + x]; };
      o.texels[static_cast<size_t>(j) * o.width + i] =
          (at(2 * i, 2 * j) + at(2 * i + 1, 2 * j) + at(2 * i, 2 * j + 1) + at(2 * i + 1, 2 * j + 1)) * 0.25f;
    }
  }
  return o;
}

/// Radical inverse in base 2 (Hammersley's second coordinate).
float RadicalInverse2(uint32_t b) {
  b = (b << 16u) | (b >> 16u);
  b = ((b & 0x55555555u) << 1u) | ((b & 0xAAAAAAAAu) >> 1u);
  b = ((b & 0x33333333u) << 2u) | ((b & 0xCCCCCCCCu) >> 2u);
  b = ((b & 0x0F0F0F0Fu) << 4u) | ((b & 0xF0F0F0F0u) >> 4u);
  b = ((b & 0x00FF00FFu) << 8u) | ((b & 0xFF00FF00u) >> 8u);
  return static_cast<float>(static_cast<double>(b) * 2.3283064365386963e-10);
}

}  // namespace

glm::vec3 EquirectDirection(float u, float v) {
  const float theta = v * kPi, phi = u * 2.0f * kPi;
  const float st = std::sin(theta);
  return {st * std::sin(phi), std::cos(theta), -st * std::cos(phi)};
}

glm::vec2 EquirectUv(glm::vec3 d) {
  float u = std::atan2(d.x, -d.z) * (0.5f / kPi);
  if (u < 0.0f) u += 1.0f;
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
  return {u, v};
}

glm::vec3 SampleEquirect(const EquirectMap& m, glm::vec3 d) {
  const glm::vec2 uv = EquirectUv(d);
  const float x = uv.x * static_cast<float>(m.width) - 0.5f;
  const float y = std::clamp(uv.y * static_cast<float>(m.height) - 0.5f, 0.0f, static_cast<float>(m.height - 1));
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  int x0 = static_cast<int>(fx) % m.width;
  if (x0 < 0) x0 += m.width;
  const int x1 = (x0 + 1) % m.width;
  const int y0 = static_cast<int>(fy), y1 = std::min(y0 + 1, m.height - 1);
  auto at = [&](int i, int j) { return m.texels[static_cast<size_t>(j) * m.width + i]; };
  const glm::vec3 a = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * tx;
  const glm::vec3 b = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * tx;
  return a + (b - a) * ty;
}

EquirectMap StudioEnvironment() {
  EquirectMap m;
  m.width = 512;
  m.height = 256;
  m.texels.resize(static_cast<size_t>(m.width) * m.height);
  struct Box {
    glm::vec3 dir;
    float radius_deg;
    glm::vec3 radiance;
  };
  // Key (warm, upper left in front of a camera looking down −Z), fill (cool, right), and a
  // rim light behind; soft edges over 2° so a mirror's reflection of them is smooth.
  const Box boxes[] = {{glm::normalize(glm::vec3(-0.55f, 0.65f, 0.55f)), 14.0f, {12.0f, 11.4f, 10.6f}},
                       {glm::normalize(glm::vec3(0.75f, 0.25f, 0.45f)), 20.0f, {2.6f, 2.8f, 3.1f}},
                       {glm::normalize(glm::vec3(0.1f, 0.45f, -1.0f)), 10.0f, {6.0f, 6.0f, 6.0f}}};
  for (int j = 0; j < m.height; ++j) {
    for (int i = 0; i < m.width; ++i) {
      const glm::vec3 d = EquirectDirection((static_cast<float>(i) + 0.5f) / static_cast<float>(m.width),
                                            (static_cast<float>(j) + 0.5f) / static_cast<float>(m.height));
      // Floor 0.18, walls 0.45 at the horizon, ceiling 0.8: a neutral grey room.
      const float wall = 0.18f + 0.27f * Smoothstep(-0.25f, 0.0f, d.y);
      glm::vec3 c(wall + 0.35f * Smoothstep(0.0f, 0.8f, d.y));
      for (const Box& b : boxes) {
        const float ang = std::acos(std::clamp(glm::dot(d, b.dir), -1.0f, 1.0f)) * (180.0f / kPi);
        c += b.radiance * (1.0f - Smoothstep(b.radius_deg - 2.0f, b.radius_deg, ang));
      }
      m.texels[static_cast<size_t>(j) * m.width + i] = c;
    }
  }
  return m;
}

std::array<glm::vec3, 9> ProjectSh9(const EquirectMap& m) {
  // Each texel is taken as constant radiance over its patch of the sphere, and every basis
  // function (a polynomial of degree <= 2 in x = sinθ sinφ, y = cosθ, z = −sinθ cosφ) is
  // integrated over the patch in closed form (μ = cos θ, dΩ = dμ dφ): exact for the map as a
  // piecewise-constant function (a uniform map gives exactly L·√(4π) in band 0 and 0 above).
  std::array<glm::dvec3, 9> acc{};
  const double dphi = 2.0 * kPiD / m.width;
  // Antiderivatives in μ of 1, μ, μ², √(1 − μ²), μ√(1 − μ²), 1 − μ².
  auto s_of = [](double mu) { return std::sqrt(std::max(0.0, 1.0 - mu * mu)); };
  auto i_sin = [&](double mu) { return 0.5 * (mu * s_of(mu) + std::asin(std::clamp(mu, -1.0, 1.0))); };
  auto i_musin = [&](double mu) { return -std::pow(s_of(mu), 3.0) / 3.0; };
  std::vector<std::array<double, 6>> col(static_cast<size_t>(m.width));  // ∫ 1, sin, cos, sin², cos², sin·cos dφ
  for (int i = 0; i < m.width; ++i) {
    const double a = i * dphi, b = (i + 1) * dphi;
    col[i] = {b - a,
              std::cos(a) - std::cos(b),
              std::sin(b) - std::sin(a),
              0.5 * (b - a) - 0.25 * (std::sin(2.0 * b) - std::sin(2.0 * a)),
              0.5 * (b - a) + 0.25 * (std::sin(2.0 * b) - std::sin(2.0 * a)),
              0.5 * (std::sin(b) * std::sin(b) - std::sin(a) * std::sin(a))};
  }
  for (int j = 0; j < m.height; ++j) {
    const double mt = std::cos(j * kPiD / m.height), mb = std::cos((j + 1) * kPiD / m.height);
    const double r1 = mt - mb, rmu = 0.5 * (mt * mt - mb * mb), rmu2 = (mt * mt * mt - mb * mb * mb) / 3.0;
    const double rsin = i_sin(mt) - i_sin(mb), rmusin = i_musin(mt) - i_musin(mb), rsin2 = r1 - rmu2;
    for (int i = 0; i < m.width; ++i) {
      const std::array<double, 6>& c = col[i];
      const double w[9] = {0.282094791773878 * c[0] * r1,
                           0.488602511902920 * c[0] * rmu,                        // y
                           0.488602511902920 * -c[2] * rsin,                      // z = −sinθ cosφ
                           0.488602511902920 * c[1] * rsin,                       // x = sinθ sinφ
                           1.092548430592079 * c[1] * rmusin,                     // xy
                           1.092548430592079 * -c[2] * rmusin,                    // yz
                           0.315391565252520 * (3.0 * c[4] * rsin2 - c[0] * r1),  // 3z² − 1
                           1.092548430592079 * -c[5] * rsin2,                     // xz
                           0.546274215296040 * (c[3] * rsin2 - c[0] * rmu2)};     // x² − y²
      const glm::dvec3 l(m.texels[static_cast<size_t>(j) * m.width + i]);
      for (int k = 0; k < 9; ++k) acc[k] += l * w[k];
    }
  }
  std::array<glm::vec3, 9> out;
  for (int k = 0; k < 9; ++k) out[k] = glm::vec3(acc[k]);
  return out;
}

glm::vec3 Sh9Irradiance(const std::array<glm::vec3, 9>& sh, glm::vec3 n) {
  const std::array<double, 9> y = ShBasis(glm::dvec3(n));
  const double band[9] = {kPiD,       2.0 * kPiD / 3.0, 2.0 * kPiD / 3.0, 2.0 * kPiD / 3.0, kPiD / 4.0,
                          kPiD / 4.0, kPiD / 4.0,       kPiD / 4.0,       kPiD / 4.0};
  glm::dvec3 e(0.0);
  for (int k = 0; k < 9; ++k) e += glm::dvec3(sh[k]) * (band[k] * y[k]);
  return glm::max(glm::vec3(e), glm::vec3(0.0f));
}

EquirectMap PrefilterGgx(const EquirectMap& src, float alpha, int out_w, int out_h) {
  const double a2 = std::max(static_cast<double>(alpha) * alpha, 1e-6);
  // D(h)/D_max >= 1e-4  <=>  (r·h)² >= (1 − 100α²)/(1 − α²); the lobe's l then lies within
  // cos θ_l >= 2(r·h)² − 1 of r (and in r's hemisphere).
  const double nh2_min = a2 >= 0.01 ? 0.0 : (1.0 - 100.0 * a2) / (1.0 - a2);
  const double cos_l_min = std::max(0.0, 2.0 * nh2_min - 1.0);
  const double cone = std::acos(cos_l_min);
  // Source texel directions and solid angles, once.
  const int sw = src.width, sh = src.height;
  std::vector<glm::dvec3> dirs(static_cast<size_t>(sw) * sh);
  std::vector<double> solid(static_cast<size_t>(sh));
  for (int j = 0; j < sh; ++j) {
    const double theta = (j + 0.5) * kPiD / sh;
    solid[j] = (2.0 * kPiD / sw) * (kPiD / sh) * std::sin(theta);
    for (int i = 0; i < sw; ++i) {
      const double phi = (i + 0.5) * 2.0 * kPiD / sw;
      dirs[static_cast<size_t>(j) * sw + i] =
          glm::dvec3(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
    }
  }
  EquirectMap out;
  out.width = out_w;
  out.height = out_h;
  out.texels.resize(static_cast<size_t>(out_w) * out_h);
  ParallelFor(out_h, [&](int oj) {
    const double theta_r = (oj + 0.5) * kPiD / out_h;
    const int j0 = std::max(0, static_cast<int>(std::floor((theta_r - cone) / kPiD * sh)) - 1);
    const int j1 = std::min(sh - 1, static_cast<int>(std::ceil((theta_r + cone) / kPiD * sh)) + 1);
    for (int oi = 0; oi < out_w; ++oi) {
      const double phi_r = (oi + 0.5) * 2.0 * kPiD / out_w;
      const glm::dvec3 r(std::sin(theta_r) * std::sin(phi_r), std::cos(theta_r), -std::sin(theta_r) * std::cos(phi_r));
      glm::dvec3 sum(0.0);
      double wsum = 0.0;
      for (int j = j0; j <= j1; ++j) {
        for (int i = 0; i < sw; ++i) {
          const size_t idx = static_cast<size_t>(j) * sw + i;
          const glm::dvec3& l = dirs[idx];
          const double rl = glm::dot(r, l);
          if (rl < cos_l_min || rl <= 0.0) continue;
          // With n = v = r: r·h = sqrt((1 + r·l)/2).
          const double nh2 = 0.5 * (1.0 + rl);
          const double dd = nh2 * (a2 - 1.0) + 1.0;
          const double w = a2 / (kPiD * dd * dd) * rl * solid[j];
          sum += glm::dvec3(src.texels[idx]) * w;
          wsum += w;
        }
      }
      // wsum > 0 always (r's own texel neighbourhood lies in the lobe); guard anyway.
      out.texels[static_cast<size_t>(oj) * out_w + oi] =
          wsum > 0.0 ? glm::vec3(sum / wsum) : SampleEquirect(src, glm::vec3(r));
    }
  });
  return out;
}

glm::vec2 IntegrateBrdf(float nv, float roughness, int samples) {
  const double alpha = std::max(static_cast<double>(roughness) * roughness, 1e-3);
  const double a2 = alpha * alpha;
  const double cv = std::max(static_cast<double>(nv), 1e-4);
  const glm::dvec3 v(std::sqrt(std::max(0.0, 1.0 - cv * cv)), 0.0, cv);
  const double vis_v = cv + std::sqrt(a2 + (1.0 - a2) * cv * cv);
  double a = 0.0, b = 0.0;
  for (int i = 0; i < samples; ++i) {
    const double xi1 = (i + 0.5) / samples, xi2 = RadicalInverse2(static_cast<uint32_t>(i));
    const double phi = 2.0 * kPiD * xi2;
    const double ct = std::sqrt((1.0 - xi1) / (1.0 + (a2 - 1.0) * xi1));
    const double st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
    const glm::dvec3 h(st * std::cos(phi), st * std::sin(phi), ct);
    const double vh = glm::dot(v, h);
    const glm::dvec3 l = 2.0 * vh * h - v;
    const double nl = l.z, nh = h.z;
    if (nl <= 0.0 || vh <= 0.0) continue;
    // f·cos / pdf with pdf(l) = D·(n·h)/(4 v·h) and f = F·D·V: 4·V·(n·l)(v·h)/(n·h).
    const double vis = 1.0 / ((nl + std::sqrt(a2 + (1.0 - a2) * nl * nl)) * vis_v);
    const double g = 4.0 * vis * nl * vh / nh;
    const double fc = std::pow(1.0 - vh, 5.0);
    a += (1.0 - fc) * g;
    b += fc * g;
  }
  return {static_cast<float>(a / samples), static_cast<float>(b / samples)};
}

glm::vec2 BrdfLut(float nv, float roughness) {
  static const std::vector<glm::vec2> table = [] {
    std::vector<glm::vec2> t(static_cast<size_t>(kBrdfLutSize) * kBrdfLutSize);
    for (int j = 0; j < kBrdfLutSize; ++j) {
      for (int i = 0; i < kBrdfLutSize; ++i) {
        t[static_cast<size_t>(j) * kBrdfLutSize + i] =
            IntegrateBrdf((i + 0.5f) / kBrdfLutSize, (j + 0.5f) / kBrdfLutSize, 512);
      }
    }
    return t;
  }();
  const float n = static_cast<float>(kBrdfLutSize);
  const float x = std::clamp(nv * n - 0.5f, 0.0f, n - 1.0f), y = std::clamp(roughness * n - 0.5f, 0.0f, n - 1.0f);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const int x1 = std::min(x0 + 1, kBrdfLutSize - 1), y1 = std::min(y0 + 1, kBrdfLutSize - 1);
  const float tx = x - static_cast<float>(x0), ty = y - static_cast<float>(y0);
  auto at = [&](int i, int j) { return table[static_cast<size_t>(j) * kBrdfLutSize + i]; };
  const glm::vec2 a = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * tx;
  const glm::vec2 b = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * tx;
  return a + (b - a) * ty;
}

glm::vec3 Environment::ToMap(glm::vec3 d) const {
  // Rotating the map by +θ about +Y is looking it up at the direction rotated by −θ.
  return {cos_rot * d.x - sin_rot * d.z, d.y, sin_rot * d.x + cos_rot * d.z};
}

glm::vec3 Environment::Diffuse(glm::vec3 n) const { return Sh9Irradiance(sh, ToMap(n)) * (intensity / kPi); }

glm::vec3 Environment::Specular(glm::vec3 r, float roughness) const {
  const glm::vec3 d = ToMap(r);
  const float f = std::clamp(roughness, 0.0f, 1.0f) * static_cast<float>(kIblLevels - 1);
  const int k0 = std::min(static_cast<int>(f), kIblLevels - 2);
  const float t = f - static_cast<float>(k0);
  const glm::vec3 a = SampleEquirect(specular[static_cast<size_t>(k0)], d);
  const glm::vec3 b = SampleEquirect(specular[static_cast<size_t>(k0) + 1], d);
  return (a + (b - a) * t) * intensity;
}

std::shared_ptr<const Environment> MakeEnvironment(EquirectMap map, std::string name, float intensity,
                                                   float rotation_deg) {
  auto env = std::make_shared<Environment>();
  env->name = std::move(name);
  env->intensity = intensity;
  env->rotation_deg = rotation_deg;
  const double rad = static_cast<double>(rotation_deg) * kPiD / 180.0;
  env->cos_rot = static_cast<float>(std::cos(rad));
  env->sin_rot = static_cast<float>(std::sin(rad));
  env->sh = ProjectSh9(map);
  // Box-downsampled copies: pyramid[p] has height map.height / 2^p (halving while even and
  // above 16 texels).
  std::vector<EquirectMap> pyramid{map};
  while (pyramid.back().height % 2 == 0 && pyramid.back().height > 16 && pyramid.back().width % 2 == 0) {
    pyramid.push_back(Halve(pyramid.back()));
  }
  env->specular.push_back(std::move(map));
  for (int k = 1; k < kIblLevels; ++k) {
    const float r = static_cast<float>(k) / static_cast<float>(kIblLevels - 1);
    const float alpha = r * r;
    // The coarsest copy whose texels (π/H radians) are no wider than α, the lobe's angular
    // scale; output at half its size (at least 32 × 16 unless the map is smaller).
    size_t p = 0;
    while (p + 1 < pyramid.size() && kPi / static_cast<float>(pyramid[p + 1].height) <= alpha) ++p;
    const EquirectMap& src = pyramid[p];
    const int oh = std::min(src.height, std::max(16, src.height / 2));
    env->specular.push_back(PrefilterGgx(src, alpha, 2 * oh, oh));
  }
  return env;
}

std::shared_ptr<const Environment> StudioEnvironmentShared(float intensity, float rotation_deg) {
  static std::mutex mu;
  static std::shared_ptr<const Environment> base;
  {
    std::lock_guard<std::mutex> lock(mu);
    if (!base) base = MakeEnvironment(StudioEnvironment(), "studio", 1.0f, 0.0f);
  }
  auto env = std::make_shared<Environment>(*base);
  env->intensity = intensity;
  env->rotation_deg = rotation_deg;
  const double rad = static_cast<double>(rotation_deg) * kPiD / 180.0;
  env->cos_rot = static_cast<float>(std::cos(rad));
  env->sin_rot = static_cast<float>(std::sin(rad));
  return env;
}

EquirectMap ReadEquirect(const std::string& path) {
  // Through io's reader (its checks, the decode budget, values as stored); the shape rules
  // are checked on the header, before any pixel is decoded.
  const auto unreadable = [&path](const UserError& e) {
    return UserError("environment map '" + path + "' could not be read: " + e.what() +
                     " (expected an equirectangular HDR or EXR image)");
  };
  ImageHeader head;
  try {
    head = ReadImageHeader({path, nullptr, 0, ""});
  } catch (const UserError& e) {
    throw unreadable(e);
  }
  const int w = head.width, h = head.height;
  if (!(w == 2 * h) || h < 2) {
    throw UserError("environment map '" + path + "' is " + std::to_string(w) + " x " + std::to_string(h) +
                    ": an equirectangular map is twice as wide as high (e.g. 2048 x 1024)");
  }
  if (h > 8192) throw UserError("environment map '" + path + "' is larger than the allowed 16384 x 8192");
  LoadedImage img;
  try {
    img = ReadImage(path);
  } catch (const UserError& e) {
    throw unreadable(e);
  }
  const int nc = img.pixels.Channels();  // 3 or 4: grey is expanded to RGB
  EquirectMap m;
  m.width = w;
  m.height = h;
  m.texels.resize(static_cast<size_t>(w) * h);
  for (size_t t = 0; t < m.texels.size(); ++t) {
    const float* px = &img.pixels.Data()[t * nc];
    const glm::vec3 c(px[0], px[1], px[2]);
    if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) {
      throw UserError("environment map '" + path + "' has a negative texel at (" + std::to_string(t % w) + ", " +
                      std::to_string(t / w) + "): radiance must be finite and >= 0");
    }
    m.texels[t] = c;
  }
  return m;
}

glm::vec3 IblShadePbr(const Environment& env, glm::vec3 n, glm::vec3 v, float nv, glm::vec3 c_diff, glm::vec3 f0,
                      float roughness) {
  const glm::vec3 r = n * (2.0f * glm::dot(n, v)) - v;
  const glm::vec2 ab = BrdfLut(nv, roughness);
  return c_diff * env.Diffuse(n) + env.Specular(r, roughness) * (f0 * ab.x + glm::vec3(ab.y));
}

}  // namespace aalab
