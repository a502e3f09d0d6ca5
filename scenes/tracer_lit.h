// The lit camera packets (TraceCameraRaysLit, tracer_camera.cpp): a lambert scene's camera
// packets shaded straight from Embree's lanes, the shadow rays written straight into
// RTCRay16 packets. Internal to the tracer (only the scenes library includes it).
//   ShadowRayTo   one hit's shadow ray toward one light: ShadowRays' and the packets' one rule
//   LitShading    per-lane lambert shading and the shadow packets of one Trace call
#pragma once
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "scenes/light_eval.h"
#include "scenes/tracer_internal.h"

namespace aalab::tracer_detail {

/// Offset for secondary rays: relative to the magnitude of the position (float spacing).
inline float RayEpsilon(glm::vec3 p) {
  const float m = std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
  return 1e-4f + m * 1e-6f;
}

/// The shadow ray of a hit at p (unit geometric normal ng and shading normal n, both facing the
/// camera ray) toward `light`: origin *o (p pushed off the surface on the light's side), unit
/// direction *d, tnear 0 and *tfar (∞ for a directional light, just short of a point or spot
/// light). False where no ray is cast: p on the light, or the light behind both normals.
inline bool ShadowRayTo(const Light& light, glm::vec3 p, glm::vec3 ng, glm::vec3 n, glm::vec3* o, glm::vec3* d,
                        float* tfar) {
  const float inf = std::numeric_limits<float>::infinity();
  glm::vec3 L;
  float dist;
  if (light.type == LightType::kDirectional) {
    L = -light.direction;
    dist = inf;
  } else {
    L = light.position - p;
    dist = glm::length(L);
    if (!(dist > 0.0f)) return false;
    L /= dist;
  }
  if (glm::dot(ng, L) <= 0.0f && glm::dot(n, L) <= 0.0f) return false;
  const float eps = RayEpsilon(p);
  const glm::vec3 side = glm::dot(ng, L) > 0.0f ? ng : -ng;
  *o = p + side * eps;
  *d = L;
  *tfar = light.type == LightType::kDirectional ? inf : dist * (1.0f - 1e-5f);
  return true;
}

/// Most lights the lit packets take (each lit sample keeps one term per light).
constexpr size_t kLitMaxLights = 8;

/// Whether Trace may take the lit packets (TraceCameraRaysLit) for this call: lambert and/or
/// shadows, for a caller that reads the shading only; no glTF materials, alpha test, culled or
/// blended materials, specular, textures, environment or vertex normals; at most
/// kLitMaxLights lights. Everything else takes the general path (ShadeHits).
inline bool LitPacketsApply(const Tracer::Impl& im, const Scene& sc, bool alpha, SampleFields fields) {
  return (sc.Has(Effect::kLambert) || sc.Has(Effect::kShadows)) && fields == SampleFields::kShading && !im.any_gltf &&
         !alpha && !im.any_cull && !im.any_blend && !im.any_vertex_normals && !sc.Has(Effect::kSpecular) &&
         !sc.Has(Effect::kTextures) && !sc.environment && sc.lights.size() <= kLitMaxLights;
}

/// ShadeHits' outputs for the hits of one Trace call in a scene LitPacketsApply accepts, one
/// lane at a time from the camera packets (no Hit, org, dir or Surface arrays): the surface
/// (FillSurface's p, ng and n = ng), the shadow rays (ShadowRays' rays in its order: sample by
/// sample, light by light, packed 16 at a time across the call as OccludedRays packs them, so
/// the same packets and answers) and the lambert colour (ShadeHits' sum in light order).
/// A sample's colour is written unshadowed at once, its terms kept; Finish() traces the last
/// shadow packet and re-sums, skipping the blocked lights, the samples a shadow ray found
/// blocked.
class LitShading {
 public:
  LitShading(const Scene& sc, RTCScene scene, ShadeScratch& S, int n, SampleResult* out, TraceCounters& local)
      : sc_(sc),
        scene_(scene),
        out_(out),
        local_(local),
        lambert_(sc.Has(Effect::kLambert)),
        shadows_(sc.Has(Effect::kShadows)),
        n_lights_(sc.lights.size()) {
    keep_ = lambert_ && shadows_;  // only a shadowed sample is re-summed
    lanes_ok_ = lambert_;
    for (const Light& light : sc.lights) {
      lanes_ok_ = lanes_ok_ &&
                  (light.type == LightType::kDirectional || (light.type == LightType::kPoint && !(light.range > 0.0f)));
    }
    const size_t n_all = static_cast<size_t>(n);
    c0_ = Sized(S.lit_c0, n_all);
    terms_ = Sized(S.lit_terms, n_all * (n_lights_ > 0 ? n_lights_ : 1));
    mask_ = Sized(S.lit_mask, n_all);
    redo_ = Sized(S.job_hit, n_all);
    for (int k = 0; k < kPacket; ++k) {  // OccludedRays' constants
      ray_.time[k] = 0.0f;
      ray_.mask[k] = 0xFFFFFFFFu;
      ray_.id[k] = static_cast<unsigned>(k);
      ray_.flags[k] = 0;
    }
  }

  /// Sample i saw nothing.
  void Background(int i) { WriteBackground(sc_, out_[i]); }

  /// Sample i's ray (o, d) hit shape `shape_id` at distance t, Embree's geometric normal hng.
  inline __attribute__((always_inline)) void Shade(int i, int shape_id, glm::vec3 o, glm::vec3 d, float t,
                                                   glm::vec3 hng) {
    SampleResult& r = out_[i];
    r.surface = shape_id;
    r.shadowed = 0;
    ++evals_;
    if (shape_id != cur_shape_) {
      cur_shape_ = shape_id;
      mat_ = &sc_.materials[sc_.shapes[static_cast<size_t>(shape_id)].material];
    }
    const glm::vec3 base = mat_->color;
    if (mat_->shading == Shading::kUnlit) {
      r.rgb[0] = base.x;
      r.rgb[1] = base.y;
      r.rgb[2] = base.z;
      return;
    }
    // FillSurface without uv or vertex normals: p, ng normalised (fallback −d), flipped to
    // face the ray; n = ng.
    const glm::vec3 p = o + d * t;
    glm::vec3 ng = hng;
    const float len = glm::length(ng);
    ng = (len > 0.0f && std::isfinite(len)) ? ng / len : -d;
    if (glm::dot(ng, d) > 0.0f) ng = -ng;
    glm::vec3 c = base;
    uint32_t mask = 0;
    if (lambert_) {  // ShadeHits' loop, each light's term kept for a re-sum
      c = sc_.ambient * base;
      if (keep_) c0_[i] = c;
      glm::vec3* term = terms_ + static_cast<size_t>(i) * n_lights_;
      for (size_t l = 0; l < n_lights_; ++l) {
        const Light& light = sc_.lights[l];
        glm::vec3 L;
        float falloff = 1.0f;
        if (!LightIncidence(light, p, &L, &falloff)) continue;
        const float ndotl = glm::dot(ng, L);
        if (ndotl <= 0.0f) continue;
        const glm::vec3 e = light.color * (light.intensity * falloff);
        const glm::vec3 tl = base * e * ndotl;
        if (keep_) term[l] = tl;
        mask |= 1u << l;
        c += tl;
      }
    }
    if (keep_) mask_[i] = mask;
    r.rgb[0] = c.x;
    r.rgb[1] = c.y;
    r.rgb[2] = c.z;
    if (!shadows_) return;
    for (size_t l = 0; l < n_lights_; ++l) {
      const Light& light = sc_.lights[l];
      if (!light.shadows) continue;
      glm::vec3 so, sd;
      float stf;
      if (ShadowRayTo(light, p, ng, ng, &so, &sd, &stf)) AddShadowRay(i, static_cast<int>(l), so, sd, stf);
    }
  }

  /// Traces the last shadow packet, re-sums the blocked samples' colours and adds the counts.
  void Finish();

  /// Shade(base + k, …) for the m lanes of a camera packet when every lane hit the same shape,
  /// its material is lambert and every light directional or point without a range: Shade's
  /// operations in its order, in loops over the lanes (selects for its branches), then the
  /// shadow rays lane by lane, light by light. Returns false, having written nothing, for any
  /// other packet (then call Shade per lane).
  inline __attribute__((always_inline)) bool ShadeUniformPacket(int base, int m, const RTCRayHit16& rh) {
    if (!lanes_ok_) return false;
    const unsigned g = rh.hit.geomID[0];
    unsigned diff = 0;
    for (int k = 1; k < m; ++k) diff |= rh.hit.geomID[k] ^ g;
    if (diff != 0 || g == RTC_INVALID_GEOMETRY_ID) return false;
    const int shape_id = static_cast<int>(g);
    if (shape_id != cur_shape_) {
      cur_shape_ = shape_id;
      mat_ = &sc_.materials[sc_.shapes[static_cast<size_t>(shape_id)].material];
    }
    if (mat_->shading == Shading::kUnlit) return false;
    if (m == kPacket) {  // the reference's packets are whole: loops of a constant count
      UniformLanes<kPacket>(base, m, shape_id, rh);
    } else {
      UniformLanes<0>(base, m, shape_id, rh);
    }
    return true;
  }

 private:
  inline __attribute__((always_inline)) void AddShadowRay(int i, int l, glm::vec3 o, glm::vec3 d, float tfar) {
    const int k = lanes_;
    ray_.org_x[k] = o.x;
    ray_.org_y[k] = o.y;
    ray_.org_z[k] = o.z;
    ray_.dir_x[k] = d.x;
    ray_.dir_y[k] = d.y;
    ray_.dir_z[k] = d.z;
    ray_.tnear[k] = 0.0f;
    ray_.tfar[k] = tfar;
    who_sample_[k] = i;
    who_light_[k] = l;
    ++shadow_rays_;
    if (++lanes_ == kPacket) Flush();
  }

  /// A packet's points, normals and running colours, lane by lane (UniformLanes' arrays).
  struct LanePoints {
    const float *px, *py, *pz, *nx, *ny, *nz;
    float *cx, *cy, *cz;
  };
  /// Per light and lane: the term, whether it is added (mask bit), the shadow ray.
  struct LightLanesOut {
    float tx[kLitMaxLights][kPacket], ty[kLitMaxLights][kPacket], tz[kLitMaxLights][kPacket];
    uint32_t mask[kPacket];
    float sx[kLitMaxLights][kPacket], sy[kLitMaxLights][kPacket], sz[kLitMaxLights][kPacket];
    float lx[kLitMaxLights][kPacket], ly[kLitMaxLights][kPacket], lz[kLitMaxLights][kPacket];
    float sf[kLitMaxLights][kPacket];
    int cast[kLitMaxLights][kPacket];
  };

  /// One light l over the lanes, without branches (selects), so the loop vectorises:
  /// LightIncidence (directional, or point without range), ShadeHits' term
  /// base · e · ndotl and its sum, and with kShadow ShadowRayTo's ray (n = ng, so dot(ng, L) is
  /// ndotl).
  template <bool kDir, bool kShadow, int kCount>
  static inline __attribute__((always_inline)) void LightLanes(const Light& light, glm::vec3 b, int l, int m_in,
                                                               const LanePoints& q, LightLanesOut& o) {
    const int m = kCount > 0 ? kCount : m_in;
    const float inf = std::numeric_limits<float>::infinity();
    const glm::vec3 ld = -light.direction, lp = light.position, lc = light.color;
    const float li = light.intensity;
    const glm::vec3 be = b * (lc * (li * 1.0f));  // a directional light's base · e
    // c + (on ? a : −0) is c + a, or c itself (x + −0 = x for every x): the sum without a
    // branch. The −0 is hidden from the compiler, which would fold it back into a conditional
    // addition that it does not speculate (-ftrapping-math), and leave the loop scalar.
    float neg_zero = -0.0f;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    asm("" : "+x"(neg_zero));
#endif
    for (int k = 0; k < m; ++k) {
      float Lx = ld.x, Ly = ld.y, Lz = ld.z, f = 1.0f, dist = inf;
      bool lit = true;
      if constexpr (!kDir) {
        const float vx = lp.x - q.px[k], vy = lp.y - q.py[k], vz = lp.z - q.pz[k];
        const float d2 = (vx * vx + vy * vy) + vz * vz;
        dist = std::sqrt(d2);
        lit = d2 > 0.0f;
        Lx = vx / dist;
        Ly = vy / dist;
        Lz = vz / dist;
        f = 1.0f / d2;
      }
      const float ndotl = (q.nx[k] * Lx + q.ny[k] * Ly) + q.nz[k] * Lz;
      const float ex = kDir ? be.x : b.x * (lc.x * (li * f));
      const float ey = kDir ? be.y : b.y * (lc.y * (li * f));
      const float ez = kDir ? be.z : b.z * (lc.z * (li * f));
      const float ax = ex * ndotl, ay = ey * ndotl, az = ez * ndotl;
      const bool on = lit & (ndotl > 0.0f);
      q.cx[k] = q.cx[k] + (on ? ax : neg_zero);
      q.cy[k] = q.cy[k] + (on ? ay : neg_zero);
      q.cz[k] = q.cz[k] + (on ? az : neg_zero);
      o.tx[l][k] = ax;
      o.ty[l][k] = ay;
      o.tz[l][k] = az;
      o.mask[k] |= static_cast<uint32_t>(on) << l;
      if constexpr (kShadow) {
        const float ax0 = std::fabs(q.px[k]), ay0 = std::fabs(q.py[k]), az0 = std::fabs(q.pz[k]);
        const float mx1 = ay0 < az0 ? az0 : ay0;  // RayEpsilon's std::max, in its order
        const float mx = ax0 < mx1 ? mx1 : ax0;
        const float eps = 1e-4f + mx * 1e-6f;
        const bool front = ndotl > 0.0f;
        o.sx[l][k] = q.px[k] + (front ? q.nx[k] : -q.nx[k]) * eps;
        o.sy[l][k] = q.py[k] + (front ? q.ny[k] : -q.ny[k]) * eps;
        o.sz[l][k] = q.pz[k] + (front ? q.nz[k] : -q.nz[k]) * eps;
        o.lx[l][k] = Lx;
        o.ly[l][k] = Ly;
        o.lz[l][k] = Lz;
        o.sf[l][k] = kDir ? inf : dist * (1.0f - 1e-5f);
        o.cast[l][k] = static_cast<int>((kDir | (dist > 0.0f)) & !(ndotl <= 0.0f));
      }
    }
  }

  /// ShadeUniformPacket's lanes (m = kCount when kCount > 0).
  template <int kCount>
  inline __attribute__((always_inline)) void UniformLanes(int base, int m_in, int shape_id, const RTCRayHit16& rh) {
    const int m = kCount > 0 ? kCount : m_in;
    const float inf = std::numeric_limits<float>::infinity();
    const glm::vec3 b = mat_->color;
    const glm::vec3 c0 = sc_.ambient * b;
    float px[kPacket], py[kPacket], pz[kPacket], nx[kPacket], ny[kPacket], nz[kPacket];
    float cx[kPacket], cy[kPacket], cz[kPacket];
    // FillSurface's p and ng (n = ng). The quotients g / len in a loop of their own: in the
    // loop that selects them GCC would move each division under its condition and leave the
    // loop scalar.
    float ok[kPacket];
    for (int k = 0; k < m; ++k) {
      const float dx = rh.ray.dir_x[k], dy = rh.ray.dir_y[k], dz = rh.ray.dir_z[k], t = rh.ray.tfar[k];
      px[k] = rh.ray.org_x[k] + dx * t;
      py[k] = rh.ray.org_y[k] + dy * t;
      pz[k] = rh.ray.org_z[k] + dz * t;
      const float gx = rh.hit.Ng_x[k], gy = rh.hit.Ng_y[k], gz = rh.hit.Ng_z[k];
      const float len = std::sqrt((gx * gx + gy * gy) + gz * gz);
      ok[k] = (len > 0.0f) & (len < inf) ? 1.0f : 0.0f;  // len > 0 and finite
      nx[k] = gx / len;
      ny[k] = gy / len;
      nz[k] = gz / len;
    }
    for (int k = 0; k < m; ++k) {
      const float dx = rh.ray.dir_x[k], dy = rh.ray.dir_y[k], dz = rh.ray.dir_z[k];
      const bool good = ok[k] != 0.0f;
      const float ux = good ? nx[k] : -dx, uy = good ? ny[k] : -dy, uz = good ? nz[k] : -dz;
      const bool flip = (ux * dx + uy * dy) + uz * dz > 0.0f;
      nx[k] = flip ? -ux : ux;
      ny[k] = flip ? -uy : uy;
      nz[k] = flip ? -uz : uz;
      cx[k] = c0.x;
      cy[k] = c0.y;
      cz[k] = c0.z;
    }
    // Per light: LightIncidence's L and falloff, the term, the sum; the shadow ray's set-up.
    LightLanesOut o;
    for (int k = 0; k < kPacket; ++k) o.mask[k] = 0;
    const LanePoints q{px, py, pz, nx, ny, nz, cx, cy, cz};
    for (size_t l = 0; l < n_lights_; ++l) {
      const Light& light = sc_.lights[l];
      const bool shadow = shadows_ && light.shadows;
      const int li = static_cast<int>(l);
      if (light.type == LightType::kDirectional) {
        if (shadow) {
          LightLanes<true, true, kCount>(light, b, li, m, q, o);
        } else {
          LightLanes<true, false, kCount>(light, b, li, m, q, o);
        }
      } else if (shadow) {
        LightLanes<false, true, kCount>(light, b, li, m, q, o);
      } else {
        LightLanes<false, false, kCount>(light, b, li, m, q, o);
      }
    }
    const uint32_t* mask = o.mask;
    auto& tx = o.tx;
    auto& ty = o.ty;
    auto& tz = o.tz;
    auto& sx = o.sx;
    auto& sy = o.sy;
    auto& sz = o.sz;
    auto& lx = o.lx;
    auto& ly = o.ly;
    auto& lz = o.lz;
    auto& sf = o.sf;
    auto& cast = o.cast;
    evals_ += static_cast<uint64_t>(m);
    for (int k = 0; k < m; ++k) {
      const int i = base + k;
      SampleResult& r = out_[i];
      r.surface = shape_id;
      r.shadowed = 0;
      r.rgb[0] = cx[k];
      r.rgb[1] = cy[k];
      r.rgb[2] = cz[k];
      if (!keep_) continue;
      c0_[i] = c0;
      mask_[i] = mask[k];
      glm::vec3* term = terms_ + static_cast<size_t>(i) * n_lights_;
      for (size_t l = 0; l < n_lights_; ++l) term[l] = glm::vec3(tx[l][k], ty[l][k], tz[l][k]);
    }
    if (!shadows_) return;
    for (int k = 0; k < m; ++k) {
      for (size_t l = 0; l < n_lights_; ++l) {
        if (!sc_.lights[l].shadows || !cast[l][k]) continue;
        AddShadowRay(base + k, static_cast<int>(l), glm::vec3(sx[l][k], sy[l][k], sz[l][k]),
                     glm::vec3(lx[l][k], ly[l][k], lz[l][k]), sf[l][k]);
      }
    }
  }

  /// Traces the packet of lanes_ shadow rays as OccludedRays would (lanes past lanes_ and
  /// rays with tfar ≤ 0 off, holding lane 0's ray with tnear = tfar = 0) and marks the
  /// blocked samples.
  void Flush();

  const Scene& sc_;
  RTCScene scene_;
  SampleResult* out_;
  TraceCounters& local_;
  bool lambert_, shadows_;
  bool keep_ = false;      // colour terms kept for the re-sum (lambert and shadows)
  bool lanes_ok_ = false;  // ShadeUniformPacket may run: lambert, directional and plain point lights
  size_t n_lights_;
  glm::vec3* c0_;
  glm::vec3* terms_;
  uint32_t* mask_;
  int* redo_;
  int n_redo_ = 0;
  int cur_shape_ = -1;
  const Material* mat_ = nullptr;
  uint64_t evals_ = 0, shadow_rays_ = 0;
  int lanes_ = 0;
  alignas(64) RTCRay16 ray_;
  int who_sample_[kPacket], who_light_[kPacket];
};

/// TraceCameraRays and ShadeHits fused for a scene LitPacketsApply accepts: the same camera
/// packets, each lane shaded by LitShading. out[i] gets rgb, surface and shadowed as Trace's
/// general path writes them. Counts the shading evaluations and shadow rays (not the camera rays).
void TraceCameraRaysLit(const Tracer::Impl& im, const Scene& sc, const SamplePos* pos, int count, int width, int height,
                        ShadeScratch& S, SampleResult* out, TraceCounters& local);

}  // namespace aalab::tracer_detail
