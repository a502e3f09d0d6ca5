// glTF materials in the tracer: texture footprints from the camera (the UV derivatives a GPU
// quad would compute, taken exactly on the hit triangle's plane), mip-mapped texture fetches,
// the MASK alpha test, normal mapping and the glTF 2.0 metallic-roughness BRDF (glTF 2.0
// specification, appendix B: Lambert diffuse, GGX distribution, separable Smith-GGX
// visibility, Schlick Fresnel). Only scenes with glTF materials reach this file, so the
// shading of every other scene is untouched.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "scenes/ibl.h"
#include "scenes/light_eval.h"
#include "scenes/specular_aa.h"
#include "scenes/tracer_internal.h"

namespace aalab {

uint32_t AlphaToCoverageMask(float alpha, int samples, int px, int py) {
  static const int kBayer4[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
  const float d = (static_cast<float>(kBayer4[py & 3][px & 3]) + 0.5f) / 16.0f;
  const float a = std::clamp(alpha, 0.0f, 1.0f);
  const int k = std::clamp(static_cast<int>(std::floor(a * static_cast<float>(samples) + d)), 0, samples);
  return k >= 32 ? 0xFFFFFFFFu : (1u << k) - 1u;
}

namespace tracer_detail {

namespace {

constexpr float kPi = 3.14159265358979f;

struct Ray {
  glm::vec3 o, d;
};

/// The camera rays fp.tex.px pixels to the right of and below the camera ray (org, dir).
/// False when (org, dir) does not look forward.
bool OffsetRays(const Tracer::Impl& im, const Camera& cam, glm::vec3 org, glm::vec3 dir, const Footprint& fp, Ray* rx,
                Ray* ry) {
  const bool persp = cam.type == CameraType::kPerspective;
  const float aspect = static_cast<float>(fp.width) / static_cast<float>(fp.height);
  const float half_h = im.half_h;  // the camera's, computed once (Tracer::Impl)
  const float sx = 2.0f * fp.tex.px / static_cast<float>(fp.width) * half_h * aspect;
  const float sy = 2.0f * fp.tex.px / static_cast<float>(fp.height) * half_h;
  if (!persp) {
    *rx = {org + im.right * sx, dir};
    *ry = {org - im.up * sy, dir};  // image y runs down
    return true;
  }
  const float f = glm::dot(dir, im.forward);
  if (!(f > 0.0f)) return false;
  const float a = glm::dot(dir, im.right) / f, b = glm::dot(dir, im.up) / f;
  *rx = {org, glm::normalize(im.forward + im.right * (a + sx) + im.up * b)};
  *ry = {org, glm::normalize(im.forward + im.right * a + im.up * (b - sy))};
  return true;
}

/// The plane of triangle `prim` in double, with the Gram terms every ray's barycentrics
/// share (computed once for the camera ray and its two offset rays).
struct TrianglePlane {
  glm::dvec3 p0, e1, e2, n;
  double d00, d01, d11, den;
};

TrianglePlane PlaneOf(const Shape& s, unsigned prim) {
  const glm::uvec3 tri = s.triangles[prim];
  TrianglePlane tp;
  tp.p0 = glm::dvec3(s.positions[tri.x]);
  tp.e1 = glm::dvec3(s.positions[tri.y]) - tp.p0;
  tp.e2 = glm::dvec3(s.positions[tri.z]) - tp.p0;
  tp.n = glm::cross(tp.e1, tp.e2);
  tp.d00 = glm::dot(tp.e1, tp.e1);
  tp.d01 = glm::dot(tp.e1, tp.e2);
  tp.d11 = glm::dot(tp.e2, tp.e2);
  tp.den = tp.d00 * tp.d11 - tp.d01 * tp.d01;
  return tp;
}

/// The barycentric weights (of vertices 1 and 2) where ray r meets the triangle's plane,
/// extrapolated outside the triangle as a GPU's helper lanes do, in double.
bool BaryOnPlane(const TrianglePlane& tp, const Ray& r, double* w1, double* w2) {
  const double denom = glm::dot(tp.n, glm::dvec3(r.d));
  if (!(std::fabs(denom) > 1e-300)) return false;
  const double t = glm::dot(tp.n, tp.p0 - glm::dvec3(r.o)) / denom;
  if (!(t > 0.0) || !std::isfinite(t)) return false;
  const glm::dvec3 q = glm::dvec3(r.o) + glm::dvec3(r.d) * t - tp.p0;
  const double d20 = glm::dot(q, tp.e1), d21 = glm::dot(q, tp.e2);
  if (!(tp.den > 0.0)) return false;
  *w1 = (tp.d11 * d20 - tp.d01 * d21) / tp.den;
  *w2 = (tp.d00 * d21 - tp.d01 * d20) / tp.den;
  return std::isfinite(*w1) && std::isfinite(*w2);
}

bool BaryOnPlane(const Shape& s, unsigned prim, const Ray& r, double* w1, double* w2) {
  return BaryOnPlane(PlaneOf(s, prim), r, w1, w2);
}

/// The texture coordinate where ray r meets the plane of triangle `prim` (BaryOnPlane).
bool UvOnPlane(const Shape& s, unsigned prim, const TrianglePlane& tp, const Ray& r, glm::dvec2* uv, int set = 0) {
  double b1, b2;
  if (!BaryOnPlane(tp, r, &b1, &b2)) return false;
  const glm::uvec3 tri = s.triangles[prim];
  const std::vector<glm::vec2>& uvs = set == 1 ? s.uvs1 : s.uvs;
  const glm::dvec2 uv0(uvs[tri.x]);
  *uv = uv0 + b1 * (glm::dvec2(uvs[tri.y]) - uv0) + b2 * (glm::dvec2(uvs[tri.z]) - uv0);
  return std::isfinite(uv->x) && std::isfinite(uv->y);
}

/// Tangent (xyz) and handedness (w) at a hit: interpolated vertex tangents, else the
/// triangle's dp/du from its texture coordinates.
glm::vec4 TangentAt(const Shape& s, const Hit& h) {
  const glm::uvec3 tri = s.triangles[h.prim];
  if (!s.tangents.empty()) {
    const float w = 1.0f - h.u - h.v;
    const glm::vec4 t = s.tangents[tri.x] * w + s.tangents[tri.y] * h.u + s.tangents[tri.z] * h.v;
    return glm::vec4(glm::vec3(t), s.tangents[tri.x].w < 0.0f ? -1.0f : 1.0f);
  }
  const glm::vec3 e1 = s.positions[tri.y] - s.positions[tri.x], e2 = s.positions[tri.z] - s.positions[tri.x];
  const glm::vec2 d1 = s.uvs[tri.y] - s.uvs[tri.x], d2 = s.uvs[tri.z] - s.uvs[tri.x];
  const float det = d1.x * d2.y - d2.x * d1.y;
  if (!(std::fabs(det) > 0.0f)) return glm::vec4(0.0f);
  const glm::vec3 t = (e1 * d2.y - e2 * d1.y) / det;
  const glm::vec3 b = (e2 * d1.x - e1 * d2.x) / det;
  const float w = glm::dot(glm::cross(glm::cross(e1, e2), t), b) < 0.0f ? -1.0f : 1.0f;
  return glm::vec4(t, w);
}

/// The shading normal of a normal-mapped hit: the texture's tangent-space normal (x, y scaled
/// by normalTexture.scale) in the frame (T, B = cross(N, T)·w, N) of the front face, turned to
/// the viewer's side like the unperturbed normal.
glm::vec3 NormalMapped(const Shape& s, const Hit& h, const Surface& srf, glm::vec3 tex, float scale) {
  glm::vec3 n0 = srf.n;
  if (!s.normals.empty()) {
    const glm::uvec3 tri = s.triangles[h.prim];
    const float w = 1.0f - h.u - h.v;
    n0 = s.normals[tri.x] * w + s.normals[tri.y] * h.u + s.normals[tri.z] * h.v;
  } else {
    n0 = h.ng;
  }
  const float len = glm::length(n0);
  if (!(len > 0.0f)) return srf.n;
  n0 /= len;
  const bool back = glm::dot(n0, srf.n) < 0.0f;
  const glm::vec4 t4 = TangentAt(s, h);
  glm::vec3 t = glm::vec3(t4) - n0 * glm::dot(n0, glm::vec3(t4));  // Gram-Schmidt
  const float tl = glm::length(t);
  if (!(tl > 0.0f) || !std::isfinite(tl)) return srf.n;
  t /= tl;
  const glm::vec3 b = glm::cross(n0, t) * t4.w;
  const glm::vec3 m = (tex * 2.0f - 1.0f) * glm::vec3(scale, scale, 1.0f);
  glm::vec3 n = t * m.x + b * m.y + n0 * m.z;
  const float nl = glm::length(n);
  if (!(nl > 0.0f) || !std::isfinite(nl)) return srf.n;
  n /= nl;
  return back ? -n : n;
}

/// The interpolated vertex normal (else the geometric one) at barycentrics (w1, w2).
glm::vec3 VertexNormal(const Shape& s, unsigned prim, float w1, float w2, glm::vec3 ng) {
  if (s.normals.empty()) return glm::normalize(ng);
  const glm::uvec3 tri = s.triangles[prim];
  const glm::vec3 n = s.normals[tri.x] * (1.0f - w1 - w2) + s.normals[tri.y] * w1 + s.normals[tri.z] * w2;
  const float len = glm::length(n);
  return len > 0.0f && std::isfinite(len) ? n / len : glm::normalize(ng);
}

}  // namespace

bool BackFaceCulled(const Scene& sc, const Material& m, const Hit& h, glm::vec3 dir) {
  if (!m.gltf || m.gltf->double_sided) return false;
  const Shape& s = sc.shapes[h.shape];
  if (s.kind != ShapeKind::kTriangles) return false;
  const glm::uvec3 t = s.triangles[h.prim];
  const glm::vec3 n = glm::cross(s.positions[t.y] - s.positions[t.x], s.positions[t.z] - s.positions[t.x]);
  return glm::dot(n, dir) > 0.0f;
}

PlaneUvs UvOnPlaneScalar(const glm::vec3 p[3], const glm::vec2 t[3], const glm::vec3 o[3], const glm::vec3 d[3]) {
  Shape s;
  s.positions = {p[0], p[1], p[2]};
  s.uvs = {t[0], t[1], t[2]};
  s.triangles = {glm::uvec3(0, 1, 2)};
  const TrianglePlane tp = PlaneOf(s, 0);
  PlaneUvs r;
  for (int k = 0; k < 3; ++k) r.ok[k] = UvOnPlane(s, 0, tp, {o[k], d[k]}, &r.uv[k]);
  return r;
}

UvDerivs HitUvDerivs(const Tracer::Impl& im, const Scene& sc, const Hit& h, glm::vec3 org, glm::vec3 dir,
                     const Footprint& fp, int set) {
  UvDerivs d;
  if (!(fp.tex.px > 0.0f)) return d;
  const Shape& s = sc.shapes[h.shape];
  if (s.kind != ShapeKind::kTriangles) return d;
  Ray rx, ry;
  constexpr float kHuge = 1e30f;  // an offset ray beyond the plane: the coarsest level
  if (!OffsetRays(im, sc.camera, org, dir, fp, &rx, &ry)) {
    d.dx = d.dy = glm::vec2(kHuge, 0.0f);
    return d;
  }
  // The camera ray and its two offset rays on the triangle's plane, in lanes (UvOnPlaneLanes:
  // UvOnPlane's values and verdicts for each).
  const glm::uvec3 tri = s.triangles[h.prim];
  const std::vector<glm::vec2>& uvs = set == 1 ? s.uvs1 : s.uvs;
  const glm::vec3 p[3] = {s.positions[tri.x], s.positions[tri.y], s.positions[tri.z]};
  glm::vec2 t[3] = {glm::vec2(0.0f), glm::vec2(0.0f), glm::vec2(0.0f)};
  if (!uvs.empty()) t[0] = uvs[tri.x], t[1] = uvs[tri.y], t[2] = uvs[tri.z];
  const glm::vec3 o[3] = {org, rx.o, ry.o}, dd[3] = {dir, rx.d, ry.d};
  const PlaneUvs r = UvOnPlaneLanes(p, t, o, dd);
  if (!r.ok[0]) {
    d.dx = d.dy = glm::vec2(kHuge, 0.0f);
    return d;
  }
  d.dx = r.ok[1] ? glm::vec2(r.uv[1] - r.uv[0]) : glm::vec2(kHuge, 0.0f);
  d.dy = r.ok[2] ? glm::vec2(r.uv[2] - r.uv[0]) : glm::vec2(kHuge, 0.0f);
  return d;
}

glm::vec4 FetchTexture(const Scene& sc, const TextureRef& t, glm::vec2 uv, const UvDerivs& d, const Footprint& fp) {
  TextureFilter f;
  f.level0_only = !(fp.tex.px > 0.0f);
  f.max_aniso = fp.tex.max_aniso;
  if (!t.transformed) {
    return SampleTextureFiltered(*sc.images[static_cast<size_t>(t.image)], uv, d, t.wrap_s, t.wrap_t, t.filter, f);
  }
  // KHR_texture_transform: the affine map on uv, its linear part on the derivatives.
  const glm::mat2 lin(t.uv_transform[0], t.uv_transform[1]);
  UvDerivs td;
  td.dx = lin * d.dx;
  td.dy = lin * d.dy;
  return SampleTextureFiltered(*sc.images[static_cast<size_t>(t.image)], lin * uv + t.uv_transform[2], td, t.wrap_s,
                               t.wrap_t, t.filter, f);
}

glm::vec4 HitTextures::Fetch(const TextureRef& t) {
  const int set = t.texcoord == 1 ? 1 : 0;
  if (!derivs[set]) {
    d[set] = footprint ? HitUvDerivs(im, sc, h, org, dir, fp, set) : UvDerivs{};
    derivs[set] = true;
  }
  if (set == 1 && !uv1_done) {
    const Shape& s = sc.shapes[h.shape];
    if (s.kind == ShapeKind::kTriangles && !s.uvs1.empty()) {
      const glm::uvec3 tri = s.triangles[h.prim];
      uv1 = s.uvs1[tri.x] * (1.0f - h.u - h.v) + s.uvs1[tri.y] * h.u + s.uvs1[tri.z] * h.v;
    }
    uv1_done = true;
  }
  return FetchTexture(sc, t, set == 1 ? uv1 : srf.uv, d[set], fp);
}

float CutoutAlpha(const Tracer::Impl& im, const Scene& sc, const Material& m, const Hit& h, const Surface& srf,
                  glm::vec3 org, glm::vec3 dir, const Footprint& fp) {
  if (m.alpha) return EvaluatePattern(*m.alpha, srf.uv);
  const GltfMaterial& g = *m.gltf;
  float a = g.base_factor.w;
  if (g.base_tex.Has()) a *= HitTextures(im, sc, h, srf, org, dir, fp).Fetch(g.base_tex).w;
  return a;
}

bool CutoutKeeps(const Tracer::Impl& im, const Scene& sc, const Material& m, const Hit& h, const Surface& srf,
                 glm::vec3 org, glm::vec3 dir, const Footprint& fp, KeptTexel* fetched) {
  if (m.alpha) return EvaluatePattern(*m.alpha, srf.uv) >= m.alpha_cutoff;
  const GltfMaterial& g = *m.gltf;
  float a = g.base_factor.w;
  if (g.base_tex.Has()) {
    HitTextures tex(im, sc, h, srf, org, dir, fp);
    const glm::vec4 texel = tex.Fetch(g.base_tex);
    a *= texel.w;
    if (fetched) {
      const int set = g.base_tex.texcoord == 1 ? 1 : 0;
      fetched->valid = true;
      fetched->set = set;
      fetched->d = tex.d[set];
      fetched->base = texel;
    }
  }
  return a >= m.alpha_cutoff;
}

glm::vec3 ShadeGltf(const Tracer::Impl& im, const Scene& sc, const Material& m, const Hit& h, const Surface& srf,
                    glm::vec3 org, glm::vec3 dir, uint32_t blocked, const Footprint& fp, TraceCounters& local,
                    const KeptTexel* kept, const PrefetchedTexels* pre) {
  const GltfMaterial& g = *m.gltf;
  const bool textures = sc.Has(Effect::kTextures);
  const bool any_tex = textures && (g.base_tex.Has() || g.mr_tex.Has() || g.emissive_tex.Has() ||
                                    g.occlusion_tex.Has() || g.normal_tex.Has());
  HitTextures tex(im, sc, h, srf, org, dir, fp, any_tex);
  // A prefetched texel (PrefetchTexels, level 0 only: px == 0, where the derivatives and
  // uv1 that tex.Fetch records are never read again) stands for the fetch itself.
  auto fetch = [&](PrefetchSlot slot, const TextureRef& t) {
    ++local.texture_lookups;
    if (pre && ((pre->mask >> slot) & 1u)) return pre->texel[slot];
    return tex.Fetch(t);
  };
  // The alpha test fetched the base texel with the footprint on (HitTextures' default), as
  // this fetch does whenever textures are on: the same derivatives and texel.
  const bool reuse = kept && kept->valid && textures && g.base_tex.Has();
  if (reuse) {
    tex.derivs[kept->set] = true;
    tex.d[kept->set] = kept->d;
  }
  glm::vec4 base = g.base_factor;
  if (reuse) {
    ++local.texture_lookups;
    base *= kept->base;
  } else if (textures && g.base_tex.Has()) {
    base *= fetch(kSlotBase, g.base_tex);
  }
  if (m.shading == Shading::kUnlit) return glm::vec3(base);

  float metallic = g.metallic, roughness = g.roughness, occlusion = 1.0f;
  if (textures && g.mr_tex.Has()) {
    const glm::vec4 mr = fetch(kSlotMr, g.mr_tex);
    roughness *= mr.y;
    metallic *= mr.z;
  }
  metallic = std::clamp(metallic, 0.0f, 1.0f);
  roughness = std::clamp(roughness, 0.0f, 1.0f);
  if (textures && g.occlusion_tex.Has())
    occlusion = 1.0f + g.occlusion_strength * (fetch(kSlotOcclusion, g.occlusion_tex).x - 1.0f);
  glm::vec3 n = srf.n;
  if (sc.Has(Effect::kNormalMap) && g.normal_tex.Has()) {
    n = NormalMapped(sc.shapes[h.shape], h, srf, glm::vec3(fetch(kSlotNormal, g.normal_tex)), g.normal_scale);
  }
  // α = roughness², floored so that D stays finite in float at roughness 0 (a mirror).
  const float alpha = std::max(roughness * roughness, 1e-3f);
  float a2 = alpha * alpha;
  if (fp.tex.gsaa && fp.tex.px > 0.0f) {
    // Specular AA (RenderSpec::specular_aa, methods/specular_aa.cpp). Geometric term: the
    // normal where the rays one footprint step right and down meet the triangle's plane, as a
    // pixel shader's ddx(N), ddy(N): α'² = min(1, α² + min(σ²·(|dN/dx|² + |dN/dy|²), κ))
    // (Tokuyoshi & Kaplanyan 2021, listing 5), of the interpolated vertex normal (the paper's
    // choice) or, with gsaa_mapped, of the final normal-mapped normal. Texture term: the
    // normal map's own variance over the footprint (scenes/toksvig.h), α'² += 1/(2κ_vMF).
    const Shape& shape = sc.shapes[h.shape];
    const bool mapped = sc.Has(Effect::kNormalMap) && g.normal_tex.Has();
    // The normal texture's own coordinate set and footprint, as fetched above.
    const int nset = g.normal_tex.texcoord == 1 ? 1 : 0;
    const UvDerivs d = !mapped || !any_tex ? UvDerivs{}
                       : tex.derivs[nset]  ? tex.d[nset]
                                           : HitUvDerivs(im, sc, h, org, dir, fp, nset);
    Ray rx, ry;
    if (shape.kind == ShapeKind::kTriangles && OffsetRays(im, sc.camera, org, dir, fp, &rx, &ry)) {
      const glm::vec3 n_hit = VertexNormal(shape, h.prim, h.u, h.v, h.ng);
      const bool back = glm::dot(n_hit, srf.n) < 0.0f;
      const bool use_map = mapped && fp.tex.gsaa_mapped;
      auto normal_at = [&](const Ray& r, glm::vec3* out) {
        double w1, w2;
        if (!BaryOnPlane(shape, h.prim, r, &w1, &w2)) return false;
        Hit h2 = h;
        h2.u = static_cast<float>(w1);
        h2.v = static_cast<float>(w2);
        const glm::vec3 n0 = VertexNormal(shape, h.prim, h2.u, h2.v, h.ng);
        Surface s2 = srf;
        s2.n = back ? -n0 : n0;
        if (!use_map) {
          *out = s2.n;
          return true;
        }
        const glm::uvec3 tri = shape.triangles[h.prim];
        const std::vector<glm::vec2>& uvs = g.normal_tex.texcoord == 1 ? shape.uvs1 : shape.uvs;
        s2.uv = uvs[tri.x] * (1.0f - h2.u - h2.v) + uvs[tri.y] * h2.u + uvs[tri.z] * h2.v;
        ++local.texture_lookups;
        *out = NormalMapped(shape, h2, s2, glm::vec3(FetchTexture(sc, g.normal_tex, s2.uv, d, fp)), g.normal_scale);
        return true;
      };
      glm::vec3 nx, ny;
      if (normal_at(rx, &nx) && normal_at(ry, &ny)) {
        const glm::vec3 n_base = use_map ? n : (back ? -n_hit : n_hit);
        a2 = FilteredAlpha2(a2, nx - n_base, ny - n_base, fp.tex.gsaa_sigma2, fp.tex.gsaa_kappa);
      }
    }
    if (mapped && textures && fp.tex.gsaa_toksvig > 0.0f) {
      ++local.texture_lookups;
      const MipChain& tox = im.toksvig.Get(sc, g.normal_tex.image);
      TextureFilter tf;
      tf.max_aniso = fp.tex.max_aniso;
      // The variance chain in the normal map's own coordinates (its set and KHR_texture_transform).
      glm::vec2 nuv = nset == 1 ? tex.uv1 : srf.uv;
      UvDerivs nd = d;
      if (g.normal_tex.transformed) {
        const glm::mat2 lin(g.normal_tex.uv_transform[0], g.normal_tex.uv_transform[1]);
        nuv = lin * nuv + g.normal_tex.uv_transform[2];
        nd.dx = lin * d.dx;
        nd.dy = lin * d.dy;
      }
      const float add = SampleTexture(tox, nuv, nd, g.normal_tex.wrap_s, g.normal_tex.wrap_t, tf).x;
      a2 = std::min(1.0f, a2 + std::min(fp.tex.gsaa_toksvig * add, fp.tex.gsaa_toksvig_max));
    }
  }
  const glm::vec3 base_rgb(base);
  const glm::vec3 c_diff = base_rgb * (1.0f - metallic);
  const glm::vec3 f0 = glm::vec3(0.04f) * (1.0f - metallic) + base_rgb * metallic;
  const glm::vec3 v = -dir;
  const float nv = std::max(glm::dot(n, v), 1e-4f);
  const float vis_v = nv + std::sqrt(a2 + (1.0f - a2) * nv * nv);
  glm::vec3 c = sc.ambient * (c_diff + f0) * occlusion;
  // Image-based light (scenes/ibl.h), at the roughness the specular AA left: occlusion applies
  // to it as to every indirect term (glTF 2.0 occlusionTexture).
  if (sc.environment) c += IblShadePbr(*sc.environment, n, v, nv, c_diff, f0, std::sqrt(std::sqrt(a2))) * occlusion;
  for (size_t l = 0; l < sc.lights.size(); ++l) {
    const Light& light = sc.lights[l];
    glm::vec3 L;
    float falloff = 1.0f;
    if (!LightIncidence(light, srf.p, &L, &falloff)) continue;
    const float nl = glm::dot(n, L);
    if (nl <= 0.0f || glm::dot(srf.ng, L) <= 0.0f) continue;  // below the shading or the geometric surface
    if (l < 32 && (blocked >> l) & 1u) continue;
    const glm::vec3 hv = glm::normalize(L + v);
    const float vh = std::clamp(glm::dot(v, hv), 0.0f, 1.0f);
    const float nh = std::max(glm::dot(n, hv), 0.0f);
    const float fw = std::pow(1.0f - vh, 5.0f);
    const glm::vec3 F = f0 + (glm::vec3(1.0f) - f0) * fw;
    const float dd = nh * nh * (a2 - 1.0f) + 1.0f;
    const float D = a2 / (kPi * dd * dd);
    const float vis = 1.0f / ((nl + std::sqrt(a2 + (1.0f - a2) * nl * nl)) * vis_v);
    const glm::vec3 f = (glm::vec3(1.0f) - F) * c_diff / kPi + F * (D * vis);
    // Light::intensity is the glTF value / π (scenes/scene.h), so π · f · E · (N·L) is the
    // glTF radiance f · E_gltf · (N·L): a white Lambert surface reflects E_gltf / π.
    c += kPi * f * light.color * (light.intensity * falloff) * nl;
  }
  glm::vec3 emissive = g.emissive;
  if (textures && g.emissive_tex.Has() && emissive != glm::vec3(0.0f))
    emissive *= glm::vec3(fetch(kSlotEmissive, g.emissive_tex));
  return c + emissive;
}

namespace {

/// The texture ShadeGltf fetches in `slot` at a hit of material m (null: none), by its own
/// conditions: the base colour unless the alpha test's texel is reused, and only the base
/// colour for an unlit material.
const TextureRef* SlotTexture(const Scene& sc, const Material& m, int slot, const KeptTexel* kept) {
  const GltfMaterial& g = *m.gltf;
  const bool textures = sc.Has(Effect::kTextures);
  if (slot == kSlotBase) return textures && g.base_tex.Has() && !(kept && kept->valid) ? &g.base_tex : nullptr;
  if (m.shading == Shading::kUnlit) return nullptr;
  switch (slot) {
    case kSlotMr: return textures && g.mr_tex.Has() ? &g.mr_tex : nullptr;
    case kSlotOcclusion: return textures && g.occlusion_tex.Has() ? &g.occlusion_tex : nullptr;
    case kSlotNormal: return sc.Has(Effect::kNormalMap) && g.normal_tex.Has() ? &g.normal_tex : nullptr;
    case kSlotEmissive:
      return textures && g.emissive_tex.Has() && g.emissive != glm::vec3(0.0f) ? &g.emissive_tex : nullptr;
    default: return nullptr;
  }
}

/// The coordinate HitTextures::Fetch and FetchTexture sample texture t at: its set's uv
/// (uv1 interpolated as there), through its KHR_texture_transform.
glm::vec2 SlotUv(const Scene& sc, const TextureRef& t, const Hit& h, const Surface& srf) {
  glm::vec2 uv = srf.uv;
  if (t.texcoord == 1) {
    uv = glm::vec2(0.0f);
    const Shape& s = sc.shapes[h.shape];
    if (s.kind == ShapeKind::kTriangles && !s.uvs1.empty()) {
      const glm::uvec3 tri = s.triangles[h.prim];
      uv = s.uvs1[tri.x] * (1.0f - h.u - h.v) + s.uvs1[tri.y] * h.u + s.uvs1[tri.z] * h.v;
    }
  }
  if (!t.transformed) return uv;
  const glm::mat2 lin(t.uv_transform[0], t.uv_transform[1]);
  return lin * uv + t.uv_transform[2];
}

}  // namespace

void PrefetchTexels(const Scene& sc, const Hit* hits, const Surface* surf, int n, const KeptTexel* kept,
                    ShadeScratch& S) {
  const size_t n_all = static_cast<size_t>(n);
  PrefetchedTexels* pre = Sized(S.pre, n_all);
  // Which slots each material fetches (one material lookup a hit, not one a slot), and which
  // slots each hit wants (in `want`, moved into pre[i].mask as the batches fill them).
  unsigned* mat_slots = Sized(S.mat_slots, sc.materials.size());
  for (size_t k = 0; k < sc.materials.size(); ++k) {
    mat_slots[k] = 0;
    if (!sc.materials[k].gltf) continue;
    for (int slot = 0; slot < kSlots; ++slot) {
      const TextureRef* t = SlotTexture(sc, sc.materials[k], slot, nullptr);
      // level0_only: SampleTextureFiltered taps level 0 with the magnification filter.
      if (t && !t->filter.mag_nearest) mat_slots[k] |= 1u << slot;
    }
  }
  unsigned* want = Sized(S.want, n_all);
  unsigned any = 0;
  for (int i = 0; i < n; ++i) {
    pre[i].mask = 0;
    unsigned w = hits[i].shape < 0 ? 0u : mat_slots[static_cast<size_t>(sc.shapes[hits[i].shape].material)];
    if (kept && kept[i].valid) w &= ~(1u << kSlotBase);  // ShadeGltf reuses the alpha test's texel
    want[i] = w;
    any |= w;
  }
  if (!any) return;
  int* job_hit = Sized(S.job_hit, n_all);
  glm::vec2* job_uv = Sized(S.job_uv, n_all);
  glm::vec4* job_out = Sized(S.job_out, n_all);
  for (int slot = 0; slot < kSlots; ++slot) {
    if (!((any >> slot) & 1u)) continue;
    // Runs of hits that sample the same level 0 with the same wrap modes: one batch each.
    int m = 0;
    const TextureRef* cur = nullptr;
    auto flush = [&]() {
      if (m == 0) return;
      SampleBilinearBatch(sc.images[static_cast<size_t>(cur->image)]->levels[0], job_uv, m, cur->wrap_s, cur->wrap_t,
                          job_out);
      for (int k = 0; k < m; ++k) {
        pre[job_hit[k]].texel[slot] = job_out[k];
        pre[job_hit[k]].mask |= 1u << slot;
      }
      m = 0;
    };
    for (int i = 0; i < n; ++i) {
      if (!((want[i] >> slot) & 1u)) continue;
      const TextureRef* t = SlotTexture(sc, sc.materials[sc.shapes[hits[i].shape].material], slot, nullptr);
      if (!cur || cur->image != t->image || cur->wrap_s != t->wrap_s || cur->wrap_t != t->wrap_t) {
        flush();
        cur = t;
      }
      job_uv[m] = SlotUv(sc, *t, hits[i], surf[i]);
      job_hit[m] = i;
      ++m;
    }
    flush();
  }
}

void CompositeBlended(const Tracer::Impl& im, const Scene& sc, bool alpha, const Hit* hits, const glm::vec3* org,
                      const glm::vec3* dir, int n, SampleResult* out, TraceCounters& local, const Footprint& fp,
                      int depth) {
  if (!im.any_blend || depth + 1 >= kMaxBlendLayers) return;
  std::vector<int> who;
  std::vector<float> a;
  for (int i = 0; i < n; ++i) {
    if (hits[i].shape < 0) continue;
    const Material& m = sc.materials[sc.shapes[hits[i].shape].material];
    if (!m.Blended()) continue;
    const Surface srf = SurfaceAt(sc, hits[i], org[i], dir[i]);
    float ai = m.gltf->base_factor.w;
    if (m.gltf->base_tex.Has()) {
      ++local.texture_lookups;
      ai *= HitTextures(im, sc, hits[i], srf, org[i], dir[i], fp).Fetch(m.gltf->base_tex).w;
    }
    ai = std::clamp(ai, 0.0f, 1.0f);
    if (ai >= 1.0f) continue;  // opaque where alpha is 1: nothing behind shows
    who.push_back(i);
    a.push_back(ai);
  }
  if (who.empty()) return;
  const size_t m = who.size();
  std::vector<glm::vec3> o(m), d(m);
  std::vector<float> tn(m), tf(m, std::numeric_limits<float>::infinity());
  std::vector<Hit> behind(m);
  for (size_t k = 0; k < m; ++k) {
    const int i = who[k];
    o[k] = org[i];
    d[k] = dir[i];
    tn[k] = ContinuePast(hits[i].t);
  }
  LayerScratch ls;
  ClosestVisibleHits(im, sc, alpha, o.data(), d.data(), static_cast<int>(m), tn.data(), tf.data(), behind.data(), ls,
                     local, fp);
  ShadeScratch scratch;
  std::vector<SampleResult> back(m);
  ShadeHits(im, sc, alpha, behind.data(), o.data(), d.data(), static_cast<int>(m), scratch, back.data(), local, fp);
  CompositeBlended(im, sc, alpha, behind.data(), o.data(), d.data(), static_cast<int>(m), back.data(), local, fp,
                   depth + 1);
  for (size_t k = 0; k < m; ++k) {
    SampleResult& r = out[who[k]];
    for (int c = 0; c < 3; ++c) r.rgb[c] = a[k] * r.rgb[c] + (1.0f - a[k]) * back[k].rgb[c];
  }
}

}  // namespace tracer_detail
}  // namespace aalab
