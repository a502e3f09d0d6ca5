// Shading of a list of hits: surface attributes, shadow rays (through alpha cut-outs) and
// the scene's declared effects only. Tracer::Trace shades every camera sample with it,
// Tracer::TraceMsaa one shading point per primitive and pixel.
#include <cmath>

#include "scenes/ibl.h"
#include "scenes/light_eval.h"
#include "scenes/tracer_internal.h"
#include "scenes/tracer_lit.h"

namespace aalab::tracer_detail {

namespace {

/// Shadow rays from every lambert hit to every shadow-casting light; sets blocked[i] bit l
/// when light l is blocked at hit i. Any hit that survives the alpha test blocks the light.
void ShadowRays(const Tracer::Impl& im, const Scene& sc, bool alpha, const Hit* hits, int n, ShadeScratch& S,
                TraceCounters& local) {
  const Surface* surf = S.surf.data();
  uint32_t* blocked = S.blocked.data();
  // At most one ray per hit and shadow-casting light: the arrays are sized once and filled
  // through a count (no per-ray push_back).
  const size_t n_lights = std::min<size_t>(sc.lights.size(), 32);
  const size_t cap = static_cast<size_t>(n) * n_lights;
  int* who_sample = Sized(S.who_sample, cap);
  int* who_light = Sized(S.who_light, cap);
  glm::vec3* so = Sized(S.so, cap);
  glm::vec3* sd = Sized(S.sd, cap);
  float* stn = Sized(S.stn, cap);
  float* stf = Sized(S.stf, cap);
  int m = 0;
  for (int i = 0; i < n; ++i) {
    if (hits[i].shape < 0) continue;
    if (sc.materials[sc.shapes[hits[i].shape].material].shading == Shading::kUnlit) continue;
    const Surface& sf = surf[i];
    for (size_t l = 0; l < n_lights; ++l) {
      const Light& light = sc.lights[l];
      if (!light.shadows) continue;
      if (!ShadowRayTo(light, sf.p, sf.ng, sf.n, &so[m], &sd[m], &stf[m])) continue;
      stn[m] = 0.0f;
      who_sample[m] = i;
      who_light[m] = static_cast<int>(l);
      ++m;
    }
  }
  if (!alpha) {
    // No alpha test: any hit blocks the light, so whether there is one is all that counts
    // (the same answer as the closest hit's existence below, without searching for it).
    uint8_t* occ = Sized(S.occluded, static_cast<size_t>(m));
    OccludedRays(im.scene, so, sd, stn, stf, m, occ);
    local.shadow_rays += static_cast<uint64_t>(m);
    for (int k = 0; k < m; ++k) {
      if (occ[k]) blocked[who_sample[k]] |= 1u << who_light[k];
    }
    return;
  }
  std::vector<int>& act = S.layers.active;
  std::vector<int>& next = S.layers.next;
  act.resize(static_cast<size_t>(m));
  for (int k = 0; k < m; ++k) act[static_cast<size_t>(k)] = k;
  for (int layer = 0; !act.empty() && layer < kMaxAlphaLayers; ++layer) {
    const int count = static_cast<int>(act.size());
    Hit* h = Sized(S.layers.layer_hits, static_cast<size_t>(count));
    // Layer 0 traces every shadow ray in order (no index list needed).
    IntersectRays(im.scene, so, sd, stn, stf, layer == 0 ? nullptr : act.data(), count, h, false);
    local.shadow_rays += static_cast<uint64_t>(count);
    next.clear();
    for (int k = 0; k < count; ++k) {
      const int r = act[k];
      if (h[k].shape < 0) continue;
      const Material& mat = sc.materials[sc.shapes[h[k].shape].material];
      if (alpha && mat.CutOut()) {
        const Surface srf = SurfaceAt(sc, h[k], so[r], sd[r], true, false);  // the test reads uv only
        ++local.texture_lookups;
        if (!CutoutKeeps(im, sc, mat, h[k], srf, so[r], sd[r], Footprint{1, 1, {0.0f, 1}})) {
          stn[r] = ContinuePast(h[k].t);
          next.push_back(r);
          continue;
        }
      }
      blocked[who_sample[r]] |= 1u << who_light[r];
    }
    act.swap(next);
  }
}

}  // namespace

namespace {

/// The texture coordinates of a non-triangle shape's hit at out.p (triangles: SurfaceAt).
void CurvedSurfaceUv(const Shape& s, const Hit& h, Surface& out) {
  switch (s.kind) {
    case ShapeKind::kTriangles: break;
    case ShapeKind::kSphere: {
      const glm::vec3 d = out.p - s.center;
      const float len = glm::length(d);
      const glm::vec3 q = len > 0.0f ? d / len : glm::vec3(0, 1, 0);
      out.uv = {std::atan2(q.z, q.x) * 0.15915494f + 0.5f, std::acos(std::clamp(q.y, -1.0f, 1.0f)) * 0.31830989f};
      out.uv *= 2.0f * 3.14159265f * s.radius;  // uv in world units along the surface
      break;
    }
    case ShapeKind::kDisk: {
      const glm::vec3 d = out.p - s.center;
      const glm::vec3 b = glm::cross(s.normal, s.tangent);
      out.uv = {glm::dot(d, s.tangent), glm::dot(d, b)};
      break;
    }
    case ShapeKind::kCapsule:
    case ShapeKind::kCylinder: {
      const glm::vec3 axis = s.p1 - s.p0;
      out.uv = {h.u * glm::length(axis), 0.0f};
      break;
    }
  }
}

}  // namespace

namespace {

/// SurfaceAt, writing into `out` in place (a returned Surface copied into the caller's array
/// stalled on store forwarding: the per-sample loop spent more time copying than computing).
inline __attribute__((always_inline)) void FillSurface(const Scene& scene, const Hit& h, const glm::vec3& org,
                                                       const glm::vec3& dir, bool uv, bool normals, Surface& out) {
  const Shape& s = scene.shapes[h.shape];
  out.p = org + dir * h.t;
  out.uv = glm::vec2(0.0f);
  glm::vec3 ng = h.ng;
  glm::vec3 n = ng;
  // Vertex normals interpolated: n differs from ng. Without them n is ng itself, and its
  // normalisation and flip below are ng's (the same vector, the same operations, ng's
  // fallback), so they are not done twice.
  const bool vertex_normals = normals && s.kind == ShapeKind::kTriangles && !s.normals.empty();
  if (s.kind == ShapeKind::kTriangles) {
    const glm::uvec3 tri = s.triangles[h.prim];
    const float w = 1.0f - h.u - h.v;
    if (uv) out.uv = s.uvs[tri.x] * w + s.uvs[tri.y] * h.u + s.uvs[tri.z] * h.v;
    if (vertex_normals) n = s.normals[tri.x] * w + s.normals[tri.y] * h.u + s.normals[tri.z] * h.v;
  } else if (uv) {
    CurvedSurfaceUv(s, h, out);
  }
  if (!normals) {
    out.ng = glm::vec3(0.0f);
    out.n = glm::vec3(0.0f);
    return;
  }
  auto safe_normalize = [](glm::vec3 v, glm::vec3 fallback) {
    const float len = glm::length(v);
    return (len > 0.0f && std::isfinite(len)) ? v / len : fallback;
  };
  ng = safe_normalize(ng, -dir);
  if (vertex_normals) n = safe_normalize(n, ng);  // the fallback: ng before its flip
  if (glm::dot(ng, dir) > 0.0f) ng = -ng;
  out.ng = ng;
  if (!vertex_normals) {
    out.n = ng;
    return;
  }
  if (glm::dot(n, dir) > 0.0f) n = -n;
  out.n = n;
}

}  // namespace

Surface SurfaceAt(const Scene& scene, const Hit& h, const glm::vec3& org, const glm::vec3& dir, bool uv, bool normals) {
  Surface out;
  FillSurface(scene, h, org, dir, uv, normals, out);
  return out;
}

namespace {

/// ShadeHits for a scene without lighting, shadows or glTF materials (every hit shows its
/// material's colour or procedural texture): the same outputs, with the pattern values of
/// the textured hits evaluated in batches per run of hits that share a texture
/// (UnlitShading) instead of one call a hit.
void ShadeUnlit(const Scene& sc, bool textures, const Hit* hits, const glm::vec3* org, const glm::vec3* dir, int n,
                ShadeScratch& S, SampleResult* out, TraceCounters& local, bool hit_points) {
  UnlitShading shading(sc, textures, S, n, out, local);
  for (int i = 0; i < n; ++i) {
    const Hit& h = hits[i];
    SampleResult& r = out[i];
    if (hit_points) {
      r.t = h.t;
      if (h.shape < 0) {
        r.position[0] = r.position[1] = r.position[2] = 0.0f;
      } else {
        const glm::vec3 p = org[i] + dir[i] * h.t;  // FillSurface's point
        r.position[0] = p.x;
        r.position[1] = p.y;
        r.position[2] = p.z;
      }
    }
    if (h.shape < 0) {
      shading.Background(i);
      continue;
    }
    shading.Shade(i, h.shape, h.prim, h.u, h.v, [&] {
      Surface sf;
      FillSurface(sc, h, org[i], dir[i], true, false, sf);
      return sf.uv;
    });
  }
  shading.Finish();
}

}  // namespace

UnlitShading::UnlitShading(const Scene& sc, bool textures, ShadeScratch& S, int n, SampleResult* out,
                           TraceCounters& local)
    : sc_(sc), textures_(textures), out_(out), local_(local) {
  const size_t n_all = static_cast<size_t>(n);
  uv_ = Sized(S.job_uv, n_all);
  who_ = Sized(S.job_hit, n_all);
  tex_ = Sized(S.pattern_tex, n_all);
  tv_ = Sized(S.pattern_t, n_all);
}

void UnlitShading::Finish() {
  local_.shading_evals += evals_;
  local_.texture_lookups += lookups_;
  for (int k = 0; k < m_;) {
    int e = k + 1;
    while (e < m_ && tex_[e] == tex_[k]) ++e;
    const Texture& t = *tex_[k];
    EvaluatePatternBatch(t, uv_ + k, e - k, tv_ + k);
    const glm::vec3 a = t.color_a, ab = t.color_b - t.color_a;  // per run: the same values
    for (int j = k; j < e; ++j) {
      const glm::vec3 base = a + ab * tv_[j];
      SampleResult& r = out_[who_[j]];
      r.rgb[0] = base.x;
      r.rgb[1] = base.y;
      r.rgb[2] = base.z;
    }
    k = e;
  }
}

void LitShading::Flush() {
  if (lanes_ == 0) return;
  RTCIntersectContext ctx = PacketContext(true);
  alignas(64) int valid[kPacket];
  for (int k = 0; k < kPacket; ++k) valid[k] = k < lanes_ && ray_.tnear[k] < ray_.tfar[k] ? -1 : 0;
  for (int k = 0; k < kPacket; ++k) {
    if (valid[k]) continue;
    ray_.org_x[k] = ray_.org_x[0];  // OccludedRays' idle lane: the packet's first ray, empty
    ray_.org_y[k] = ray_.org_y[0];
    ray_.org_z[k] = ray_.org_z[0];
    ray_.dir_x[k] = ray_.dir_x[0];
    ray_.dir_y[k] = ray_.dir_y[0];
    ray_.dir_z[k] = ray_.dir_z[0];
    ray_.tnear[k] = 0.0f;
    ray_.tfar[k] = 0.0f;
  }
  rtcOccluded16(valid, scene_, &ctx, &ray_);
  for (int k = 0; k < lanes_; ++k) {
    // Embree sets tfar to -inf on an occluded ray.
    if (!(valid[k] && ray_.tfar[k] == -std::numeric_limits<float>::infinity())) continue;
    SampleResult& r = out_[who_sample_[k]];
    if (r.shadowed == 0) redo_[n_redo_++] = who_sample_[k];
    r.shadowed |= 1u << who_light_[k];
  }
  lanes_ = 0;
}

void LitShading::Finish() {
  Flush();
  local_.shading_evals += evals_;
  local_.shadow_rays += shadow_rays_;
  if (!lambert_) return;               // the colour is the material's, shadowed or not
  for (int j = 0; j < n_redo_; ++j) {  // ShadeHits' sum without the blocked lights
    const int i = redo_[j];
    SampleResult& r = out_[i];
    const glm::vec3* term = terms_ + static_cast<size_t>(i) * n_lights_;
    glm::vec3 c = c0_[i];
    for (size_t l = 0; l < n_lights_; ++l) {
      if (((mask_[i] & ~r.shadowed) >> l) & 1u) c += term[l];
    }
    r.rgb[0] = c.x;
    r.rgb[1] = c.y;
    r.rgb[2] = c.z;
  }
}

void ShadeHits(const Tracer::Impl& im, const Scene& sc, bool alpha, const Hit* hits, const glm::vec3* org,
               const glm::vec3* dir, int n, ShadeScratch& S, SampleResult* out, TraceCounters& local,
               const Footprint& fp, const KeptTexel* kept) {
  const bool lambert = sc.Has(Effect::kLambert);
  const bool shadows = sc.Has(Effect::kShadows);
  const bool specular = sc.Has(Effect::kSpecular);
  const bool textures = sc.Has(Effect::kTextures);
  if (!lambert && !shadows && !im.any_gltf) {
    ShadeUnlit(sc, textures, hits, org, dir, n, S, out, local, fp.hit_points);
    return;
  }
  const size_t n_all = static_cast<size_t>(n);
  // Surface attributes feed only lighting, shadows and textures: unlit untextured scenes
  // never read them, so they are not computed there.
  Surface* surf = Sized(S.surf, n_all);
  // Texture coordinates feed only textures (and glTF shading), the normals only lighting and
  // shadows (and glTF shading): each is computed only where it is read.
  const bool need_uv = textures || im.any_gltf;
  const bool need_normals = lambert || shadows || im.any_gltf;
  if (lambert || shadows || textures) {
    for (int i = 0; i < n; ++i) {
      if (hits[i].shape >= 0) FillSurface(sc, hits[i], org[i], dir[i], need_uv, need_normals, surf[i]);
    }
  }
  uint32_t* blocked = Sized(S.blocked, n_all);
  std::fill(blocked, blocked + n, 0u);
  // Shadow rays only with `shadows`, only for shadow-casting lights.
  if (shadows) ShadowRays(im, sc, alpha, hits, n, S, local);

  // The reference (level 0 only) fetches its glTF texels batched over the whole packet.
  const PrefetchedTexels* pre = nullptr;
  if (im.any_gltf && !(fp.tex.px > 0.0f)) {
    PrefetchTexels(sc, hits, surf, n, kept, S);
    pre = S.pre.data();
  }

  for (int i = 0; i < n; ++i) {
    SampleResult& r = out[i];
    r.surface = hits[i].shape;
    r.shadowed = blocked[i];
    if (fp.hit_points) {
      r.t = hits[i].t;
      // The hit point, for exact motion vectors (scenes/motion_render.h); 0 for the background.
      const glm::vec3 p = hits[i].shape >= 0 ? org[i] + dir[i] * hits[i].t : glm::vec3(0.0f);
      r.position[0] = p.x;
      r.position[1] = p.y;
      r.position[2] = p.z;
    }
    glm::vec3 c = sc.background;
    if (hits[i].shape >= 0) {
      ++local.shading_evals;
      const Material& m = sc.materials[sc.shapes[hits[i].shape].material];
      if (m.gltf) {
        c = ShadeGltf(im, sc, m, hits[i], surf[i], org[i], dir[i], blocked[i], fp, local, kept ? kept + i : nullptr,
                      pre ? pre + i : nullptr);
        r.rgb[0] = c.x;
        r.rgb[1] = c.y;
        r.rgb[2] = c.z;
        continue;
      }
      glm::vec3 base = m.color;
      if (textures && m.texture) {
        ++local.texture_lookups;
        const float t = EvaluatePattern(*m.texture, surf[i].uv);
        base = m.texture->color_a + (m.texture->color_b - m.texture->color_a) * t;
      }
      if (m.shading == Shading::kUnlit || !lambert) {
        c = base;
      } else {
        c = sc.ambient * base;
        // Image-based diffuse: the environment's irradiance / π (scenes/ibl.h).
        if (sc.environment) c += base * sc.environment->Diffuse(surf[i].n);
        for (size_t l = 0; l < sc.lights.size(); ++l) {
          const Light& light = sc.lights[l];
          glm::vec3 L;
          float falloff = 1.0f;
          if (!LightIncidence(light, surf[i].p, &L, &falloff)) continue;
          const float ndotl = glm::dot(surf[i].n, L);
          if (ndotl <= 0.0f) continue;
          if (l < 32 && (blocked[i] >> l) & 1u) continue;
          const glm::vec3 e = light.color * (light.intensity * falloff);
          c += base * e * ndotl;
          if (specular && m.specular != glm::vec3(0.0f)) {
            const glm::vec3 hv = glm::normalize(L - dir[i]);
            const float nh = std::max(0.0f, glm::dot(surf[i].n, hv));
            c += m.specular * e * std::pow(nh, m.shininess);
          }
        }
      }
    }
    r.rgb[0] = c.x;
    r.rgb[1] = c.y;
    r.rgb[2] = c.z;
  }
}

}  // namespace aalab::tracer_detail
