// Internals shared by the tracer's files; not part of the public interface (only the scenes
// library includes it, the one place that knows Embree):
//   tracer.cpp        BVH build, packets, visibility (closest hits through cut-outs),
//                     Tracer::Trace (one shading per sample), BareTrace
//   tracer_camera.cpp camera rays, and camera rays traced in packets filled in place (for
//                     unlit and plain lambert scenes also shaded in place; tracer_lit.h)
//   tracer_shade.cpp  surface attributes, shadow rays and shading of a list of hits
//   tracer_msaa.cpp   Tracer::TraceMsaa: coverage samples, one shading per primitive
//   tracer_gltf.cpp   image textures (footprints, mip-mapped fetches), glTF alpha and the
//                     metallic-roughness BRDF
//   tracer_plane_uv.cpp the footprint's three rays on the hit triangle's plane, in vector lanes
#pragma once
#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "scenes/toksvig.h"
#include "scenes/tracer.h"

namespace aalab {

struct Tracer::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string error;
  bool any_alpha = false;
  bool any_blend = false;
  bool any_cull = false;            // a single-sided glTF material: camera rays skip its back faces
  bool any_gltf = false;            // a glTF material (its shading reads every surface attribute)
  bool any_vertex_normals = false;  // a triangle mesh with vertex normals (n differs from ng)
  ToksvigChains toksvig;            // unit-normal chains of the normal maps, built when specular AA asks
  // camera basis
  glm::vec3 origin{0.0f}, forward{0.0f}, right{0.0f}, up{0.0f};
  float half_h = 0.0f;  // tan(fov_y / 2) (perspective) or height / 2 (orthographic)

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace tracer_detail {

constexpr int kPacket = 16;
constexpr int kMaxAlphaLayers = 256;  // continuation rounds through cut-outs before giving up

/// The packet's inputs Embree never writes (time 0, every mask bit, id = lane, no flags):
/// set once per batch of packets.
inline void InitPacketConstants(RTCRayHit16& rh) {
  for (int k = 0; k < kPacket; ++k) {
    rh.ray.time[k] = 0.0f;
    rh.ray.mask[k] = 0xFFFFFFFFu;
    rh.ray.id[k] = static_cast<unsigned>(k);
    rh.ray.flags[k] = 0;
  }
}

/// An intersect context for Embree's packet calls, flagged coherent when the packet's rays
/// start close together in similar directions (camera rays, a light's shadow rays).
inline RTCIntersectContext PacketContext(bool coherent) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  if (coherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  return ctx;
}

/// A ray's closest hit (shape == -1: nothing).
struct Hit {
  float t = std::numeric_limits<float>::infinity();
  int shape = -1;
  unsigned prim = 0;
  float u = 0, v = 0;
  glm::vec3 ng{0.0f};
};

/// Hit k of a traced 16-ray packet, branch-free: a miss or an invalid lane (`valid` false) is
/// Hit{} (t = inf, shape = -1, the rest 0). The one read-out of IntersectRays and the camera
/// packets.
inline Hit PacketHit(const RTCRayHit16& rh, int k, bool valid = true) {
  const bool hit = valid && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
  Hit h;
  h.t = hit ? rh.ray.tfar[k] : std::numeric_limits<float>::infinity();
  h.shape = hit ? static_cast<int>(rh.hit.geomID[k]) : -1;
  h.prim = hit ? rh.hit.primID[k] : 0u;
  h.u = hit ? rh.hit.u[k] : 0.0f;
  h.v = hit ? rh.hit.v[k] : 0.0f;
  h.ng = hit ? glm::vec3(rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]) : glm::vec3(0.0f);
  return h;
}

/// Surface attributes at a hit.
struct Surface {
  glm::vec3 p{0.0f};
  glm::vec3 n{0.0f};   // shading normal, facing the ray
  glm::vec3 ng{0.0f};  // geometric normal, facing the ray
  glm::vec2 uv{0.0f};
};

/// The texture footprint of a batch of camera rays on a width × height image plane.
struct Footprint {
  int width = 1, height = 1;
  TextureFootprint tex;    ///< tex.px == 0: level 0 bilinear (also used for shadow rays)
  bool hit_points = true;  ///< ShadeHits writes SampleResult::t and position (SampleFields::kAll)
};

/// Where a ray continues after rejecting a hit at distance t (just past it).
inline float ContinuePast(float t) { return t + std::max(t * 2e-6f, 1e-6f); }

/// Grows v to at least n elements (never shrinks) and returns its data.
template <typename T>
T* Sized(std::vector<T>& v, size_t n) {
  if (v.size() < n) v.resize(n);
  return v.data();
}

/// Closest hits for n rays, in 16-wide packets. Ray k of the batch is ray idx[k] of the
/// arrays (idx == nullptr: ray k itself); hits[k] receives its hit. Rays with tnear >= tfar
/// are skipped. The packets hold the same rays, in the same lanes, whether or not an index
/// list is used, so the result never depends on how the caller stores its rays.
void IntersectRays(RTCScene scene, const glm::vec3* org, const glm::vec3* dir, const float* tnear, const float* tfar,
                   const int* idx, int n, Hit* hits, bool coherent);

/// Whether each of n rays (tnear[i] < tfar[i]) meets anything in [tnear, tfar], in 16-wide
/// packets (rtcOccluded16): occluded[i] = 1 or 0. The same answer as "IntersectRays finds a
/// hit" (the same primitive tests; Embree only stops at the first hit it meets), without
/// the search for the closest one; for shadow rays that need no alpha test.
void OccludedRays(RTCScene scene, const glm::vec3* org, const glm::vec3* dir, const float* tnear, const float* tfar,
                  int n, uint8_t* occluded);

/// Camera rays through `count` continuous pixel positions of a width × height image plane.
void CameraRays(const Tracer::Impl& im, const Camera& cam, const SamplePos* pos, int count, int width, int height,
                glm::vec3* org, glm::vec3* dir);

/// Closest hits of `count` camera rays through continuous pixel positions (tnear 0, tfar ∞,
/// no alpha test): the same rays as CameraRays into org/dir and the same hits as
/// IntersectRays of those rays (the same packets), each packet filled straight from the
/// positions. Counts nothing.
void TraceCameraRays(const Tracer::Impl& im, const Camera& cam, const SamplePos* pos, int count, int width, int height,
                     glm::vec3* org, glm::vec3* dir, Hit* hits);

/// What the alpha test of a kept glTF cut-out fetched at a camera ray's final hit: the base
/// texel and the UV derivatives of its coordinate set. The shading of the same hit fetches
/// exactly these (the same hit, ray and footprint), so it reuses them instead.
struct KeptTexel {
  bool valid = false;
  int set = 0;
  UvDerivs d;
  glm::vec4 base{0.0f};
};

/// Working memory of the continuation loops, reused from call to call.
struct LayerScratch {
  std::vector<Hit> layer_hits;
  std::vector<int> active, next;
};

/// Closest hits of `count` camera rays (tnear 0, tfar ∞) that pass the alpha test at their
/// own position: with `alpha`, a ray whose hit is cut out continues just past it (a new packet
/// round) up to kMaxAlphaLayers rounds; so does a ray that meets the back of a single-sided
/// glTF material (always: a rasterizer culls at coverage). Adds the rays to counters.primary_rays and
/// counters.coverage_rays, the alpha lookups to counters.texture_lookups. With `kept` (count
/// entries), kept[i] receives the texel of ray i's final hit's alpha test (valid only where
/// a glTF cut-out with a base texture was tested and kept).
void ClosestVisibleHits(const Tracer::Impl& im, const Scene& sc, bool alpha, const glm::vec3* org, const glm::vec3* dir,
                        int count, float* tnear, float* tfar, Hit* hits, LayerScratch& ls, TraceCounters& counters,
                        const Footprint& fp, KeptTexel* kept = nullptr);

/// ClosestVisibleHits after its first round: `hits` holds the first hits of the count rays
/// (tnear 0, tfar ∞ in tnear/tfar); cut-out and culled hits continue from there. Nothing
/// happens without `alpha` in a scene without culled materials.
void ContinueVisibleHits(const Tracer::Impl& im, const Scene& sc, bool alpha, const glm::vec3* org,
                         const glm::vec3* dir, int count, float* tnear, float* tfar, Hit* hits, LayerScratch& ls,
                         TraceCounters& counters, const Footprint& fp, KeptTexel* kept = nullptr);

/// True when the cut-out material `m` keeps the hit h (procedural pattern t >= cutoff, or glTF
/// MASK alpha >= alphaCutoff, the alpha filtered with the ray's footprint). Reads srf.uv only.
/// With `fetched`, a glTF base-texture fetch is recorded there (valid set true).
bool CutoutKeeps(const Tracer::Impl& im, const Scene& sc, const Material& m, const Hit& h, const Surface& srf,
                 glm::vec3 org, glm::vec3 dir, const Footprint& fp, KeptTexel* fetched = nullptr);

/// The continuous alpha of a cut-out material at a hit (procedural: the pattern value t; glTF
/// MASK: baseColorFactor.a × the filtered texture alpha), for alpha-to-coverage.
float CutoutAlpha(const Tracer::Impl& im, const Scene& sc, const Material& m, const Hit& h, const Surface& srf,
                  glm::vec3 org, glm::vec3 dir, const Footprint& fp);

/// True when camera rays skip this hit: a single-sided glTF material (doubleSided false) seen
/// from the back (the triangle's counter-clockwise normal faces away from the ray's origin).
bool BackFaceCulled(const Scene& sc, const Material& m, const Hit& h, glm::vec3 dir);

/// UV derivatives of a camera ray's hit on a triangle shape (Footprint's rule; zero with
/// fp.tex.px == 0; huge when an offset ray misses the triangle's plane).
/// `set`: the texture coordinate set (0: Shape::uvs, 1: Shape::uvs1).
UvDerivs HitUvDerivs(const Tracer::Impl& im, const Scene& sc, const Hit& h, glm::vec3 org, glm::vec3 dir,
                     const Footprint& fp, int set = 0);

/// Where three rays (o[k], d[k]) meet the plane of the triangle with corners p and texture
/// coordinates t, as texture coordinates extrapolated over the plane (in double): ok[k] false
/// where ray k is (nearly) parallel to the plane, meets it behind its origin, or the triangle
/// is degenerate or a value is not finite; uv[k] is then unspecified.
struct PlaneUvs {
  glm::dvec2 uv[3];
  bool ok[3];
};

/// PlaneUvs of the camera ray and its two offset rays, the three evaluated in vector lanes
/// with the same per-lane operations as UvOnPlaneScalar (the same bits; HitUvDerivs' path).
PlaneUvs UvOnPlaneLanes(const glm::vec3 p[3], const glm::vec2 t[3], const glm::vec3 o[3], const glm::vec3 d[3]);

/// PlaneUvs ray by ray (the plane's terms once, then a ray's barycentrics and uv in double):
/// the reference UvOnPlaneLanes is tested against.
PlaneUvs UvOnPlaneScalar(const glm::vec3 p[3], const glm::vec2 t[3], const glm::vec3 o[3], const glm::vec3 d[3]);

/// A texture fetch of material texture `t` at uv with derivatives d (of t's coordinate set,
/// before its KHR_texture_transform, which is applied here), with t's sampler filters and
/// Footprint's filter.
glm::vec4 FetchTexture(const Scene& sc, const TextureRef& t, glm::vec2 uv, const UvDerivs& d, const Footprint& fp);

/// Texture fetches of one hit: the coordinates and footprint of each set, computed once.
struct HitTextures {
  HitTextures(const Tracer::Impl& im_, const Scene& sc_, const Hit& h_, const Surface& srf_, glm::vec3 org_,
              glm::vec3 dir_, const Footprint& fp_, bool footprint_ = true)
      : im(im_), sc(sc_), h(h_), srf(srf_), org(org_), dir(dir_), fp(fp_), footprint(footprint_) {}
  const Tracer::Impl& im;
  const Scene& sc;
  const Hit& h;
  const Surface& srf;
  glm::vec3 org, dir;
  const Footprint& fp;
  bool footprint = true;  ///< false: zero derivatives (level 0), as ShadeGltf without textures
  bool derivs[2] = {false, false};
  UvDerivs d[2];
  bool uv1_done = false;
  glm::vec2 uv1{0.0f};
  /// Fetches material texture t at this hit.
  glm::vec4 Fetch(const TextureRef& t);
};

/// Texels of one hit fetched ahead of ShadeGltf (ShadeHits batches the reference's level-0
/// fetches over the whole packet): slot k (PrefetchSlot) is valid when bit k of `mask` is set,
/// and holds exactly what ShadeGltf's own fetch of that texture would return.
enum PrefetchSlot { kSlotBase, kSlotMr, kSlotOcclusion, kSlotNormal, kSlotEmissive, kSlots };
struct PrefetchedTexels {
  unsigned mask = 0;
  glm::vec4 texel[kSlots];
};

/// Radiance of a glTF material (unlit or the metallic-roughness BRDF) at a camera-ray hit,
/// with `blocked` the shadowed-light bits. Adds its texture fetches to counters. `kept` (may be
/// null): the alpha test's fetch at this very hit (ClosestVisibleHits), reused when valid;
/// `pre` (may be null): texels fetched ahead (the same values), used where its mask says.
glm::vec3 ShadeGltf(const Tracer::Impl& im, const Scene& sc, const Material& m, const Hit& h, const Surface& srf,
                    glm::vec3 org, glm::vec3 dir, uint32_t blocked, const Footprint& fp, TraceCounters& counters,
                    const KeptTexel* kept = nullptr, const PrefetchedTexels* pre = nullptr);

/// Deepest chain of blended (glTF BLEND) surfaces composited along one ray; the last one
/// is drawn opaque.
constexpr int kMaxBlendLayers = 16;

/// glTF BLEND, as an engine draws transparent surfaces after the opaque ones, sorted and
/// over-composited: for every out[i] whose hit is a blended material, the ray continues past
/// the hit (cut-outs and culling as for camera rays), what it sees is shaded (recursively
/// composited, up to kMaxBlendLayers) and out[i].rgb = a · front + (1 − a) · behind, a the
/// material's alpha (baseColorFactor.a × the base texture's alpha, filtered with the
/// footprint). out[i]'s surface, depth and position stay the front surface's. Nothing
/// happens in a scene without blended materials.
void CompositeBlended(const Tracer::Impl& im, const Scene& sc, bool alpha, const Hit* hits, const glm::vec3* org,
                      const glm::vec3* dir, int n, SampleResult* out, TraceCounters& counters, const Footprint& fp,
                      int depth = 0);

/// Surface attributes of a hit on the ray (org, dir). With `uv` false the texture
/// coordinates are left at 0, with `normals` false n and ng are left at 0 (what a caller
/// that never reads them skips: a sphere's uv costs an atan2 and an acos); every attribute
/// that is computed has the same bits either way.
Surface SurfaceAt(const Scene& scene, const Hit& h, const glm::vec3& org, const glm::vec3& dir, bool uv = true,
                  bool normals = true);

/// EvaluatePattern's checker at uv = (x, y), branch-free so that loops of it vectorise: the
/// same test (|a| < 2^24 and odd; from 2^24 on every float is even, as are inf and NaN).
inline __attribute__((always_inline)) float CheckerValue(float scale, float x, float y) {
  const float a = std::fabs(std::floor(x * scale) + std::floor(y * scale));
  const bool small = a < 16777216.0f;
  const int32_t ai = static_cast<int32_t>(small ? a : 0.0f);
  return small && (ai & 1) ? 1.0f : 0.0f;
}

/// EvaluatePattern's noise at uv = (x, y), seed_hi = seed << 32: the same operations, written
/// so that loops of it vectorise (64-bit lanes). float → int64 of a value out of range (or NaN)
/// gives INT64_MIN in the scalar (cvttss2si) and the vector (vcvttps2qq) instruction alike.
inline __attribute__((always_inline)) float NoiseValue(float scale, uint64_t seed_hi, float x, float y) {
  const auto cx = static_cast<int64_t>(std::floor(x * scale));
  const auto cy = static_cast<int64_t>(std::floor(y * scale));
  uint64_t h = static_cast<uint64_t>(cx) * 0x9e3779b97f4a7c15ULL ^
               (static_cast<uint64_t>(cy) + 0x632be59bd9b4e019ULL) * 0xbf58476d1ce4e5b9ULL ^ seed_hi;
  h ^= h >> 31;
  h *= 0x94d049bb133111ebULL;
  h ^= h >> 29;
  return static_cast<float>(h >> 40) * (1.0f / 16777216.0f);
}

/// EvaluatePattern(tex, uv[k]) into t[k] for n points (the same values), vectorised for the
/// checker and the noise.
void EvaluatePatternBatch(const Texture& tex, const glm::vec2* uv, int n, float* t);

/// EvaluatePatternBatch of the points (x[k], y[k]), from separate arrays (t not aliasing them).
void EvaluatePatternLanes(const Texture& tex, const float* x, const float* y, int n, float* t);

/// Working memory of ShadeHits, reused from call to call.
struct ShadeScratch {
  std::vector<Surface> surf;
  std::vector<uint32_t> blocked;
  std::vector<int> who_sample, who_light;
  std::vector<glm::vec3> so, sd;
  std::vector<float> stn, stf;
  std::vector<uint8_t> occluded;
  LayerScratch layers;
  std::vector<PrefetchedTexels> pre;  // the batched level-0 texels (PrefetchTexels)
  std::vector<unsigned> mat_slots, want;
  std::vector<int> job_hit;
  std::vector<glm::vec2> job_uv;
  std::vector<glm::vec4> job_out;
  std::vector<const Texture*> pattern_tex;  // the unlit path's textured hits (ShadeUnlit)
  std::vector<float> pattern_t;
  std::vector<glm::vec3> lit_c0, lit_terms;  // the lit packets' colour terms (LitShading)
  std::vector<uint32_t> lit_mask;
};

/// The shading of hits in a scene without lighting, shadows or glTF materials (every hit shows
/// its material's colour or procedural texture), one sample at a time: what ShadeUnlit does for
/// a Hit array and the camera packets' fused path (TraceCameraRaysUnlit) for a packet's lanes,
/// in one place. Background() and Shade() write out[i]'s rgb, surface and shadowed (a textured
/// hit's rgb after Finish()); Finish() evaluates the queued textured hits' patterns in batches
/// per run of hits that share a texture (EvaluatePatternBatch) and writes their colours.
/// tan(fov_y / 2) for a perspective camera, height / 2 for an orthographic one: the image
/// plane's half height at distance 1, in float, as every camera ray is formed from it.
inline float CameraHalfHeight(const Camera& c) {
  return c.type == CameraType::kPerspective ? std::tan(glm::radians(c.fov_y_deg) * 0.5f) : c.height * 0.5f;
}

/// A sample that saw nothing: no surface, not shadowed, the scene's background colour.
inline void WriteBackground(const Scene& sc, SampleResult& r) {
  r.surface = -1;
  r.shadowed = 0;
  r.rgb[0] = sc.background.x;
  r.rgb[1] = sc.background.y;
  r.rgb[2] = sc.background.z;
}

class UnlitShading {
 public:
  UnlitShading(const Scene& sc, bool textures, ShadeScratch& S, int n, SampleResult* out, TraceCounters& local);

  /// Sample i saw nothing.
  void Background(int i) { WriteBackground(sc_, out_[i]); }

  /// Sample i hit shape `shape_id` (primitive prim, barycentrics u, v). `curved_uv()` returns
  /// the hit's uv for shapes that are not triangle meshes (FillSurface's), called only there.
  template <typename CurvedUv>
  void Shade(int i, int shape_id, unsigned prim, float u, float v, const CurvedUv& curved_uv) {
    SampleResult& r = out_[i];
    r.surface = shape_id;
    r.shadowed = 0;
    ++evals_;
    if (shape_id != cur_shape_) {  // consecutive hits mostly see the same shape
      cur_shape_ = shape_id;
      shape_ = &sc_.shapes[static_cast<size_t>(shape_id)];
      mat_ = &sc_.materials[shape_->material];
      texture_ = textures_ && mat_->texture ? &*mat_->texture : nullptr;
    }
    if (texture_) {
      ++lookups_;
      if (shape_->kind == ShapeKind::kTriangles) {  // FillSurface's uv, operation for operation
        const glm::uvec3 tri = shape_->triangles[prim];
        const float w = 1.0f - u - v;
        uv_[m_] = shape_->uvs[tri.x] * w + shape_->uvs[tri.y] * u + shape_->uvs[tri.z] * v;
      } else {
        uv_[m_] = curved_uv();
      }
      who_[m_] = i;
      tex_[m_] = texture_;
      ++m_;
      return;
    }
    r.rgb[0] = mat_->color.x;
    r.rgb[1] = mat_->color.y;
    r.rgb[2] = mat_->color.z;
  }

  /// Shade(base + k, …) for the m lanes of a camera packet (Embree's geomID, primID, u, v
  /// arrays) when every lane hit the same shape and that shape is an untextured one or a
  /// textured triangle mesh: the same outputs, in loops over the lanes without the per-lane
  /// branch on the shape; a texture's colours are written here, not queued for Finish
  /// (TexturedTriangleLanes). A packet spread over several triangles still loads their
  /// corner uvs one lane at a time: explicit AVX-512/AVX2 gathers were measured slower here
  /// (s8-trace2 in docs/performance.md).
  /// Returns false, having written nothing, for any other packet (then call Shade per lane).
  inline __attribute__((always_inline)) bool ShadeUniformPacket(int base, int m, const unsigned* geom,
                                                                const unsigned* prim, const float* u, const float* v) {
    const unsigned g = geom[0];
    unsigned diff = 0;
    for (int k = 1; k < m; ++k) diff |= geom[k] ^ g;
    if (diff != 0 || g == RTC_INVALID_GEOMETRY_ID) return false;
    const int shape_id = static_cast<int>(g);
    if (shape_id != cur_shape_) {  // as Shade
      cur_shape_ = shape_id;
      shape_ = &sc_.shapes[static_cast<size_t>(shape_id)];
      mat_ = &sc_.materials[shape_->material];
      texture_ = textures_ && mat_->texture ? &*mat_->texture : nullptr;
    }
    if (texture_ && shape_->kind != ShapeKind::kTriangles) return false;
    SampleResult* r = out_ + base;
    for (int k = 0; k < m; ++k) {
      r[k].surface = shape_id;
      r[k].shadowed = 0;
    }
    evals_ += static_cast<uint64_t>(m);
    if (!texture_) {
      const glm::vec3 c = mat_->color;
      for (int k = 0; k < m; ++k) {
        r[k].rgb[0] = c.x;
        r[k].rgb[1] = c.y;
        r[k].rgb[2] = c.z;
      }
      return true;
    }
    lookups_ += static_cast<uint64_t>(m);
    if (m == kPacket) {  // the reference's packets are whole: loops of a constant count
      TexturedTriangleLanes<kPacket>(base, m, prim, u, v);
    } else {
      TexturedTriangleLanes<0>(base, m, prim, u, v);
    }
    return true;
  }

  /// The textured hits' colours (after the last Shade()); adds the shading evaluations and
  /// texture lookups to the counters. (Counted here, and the object best kept a local of the
  /// loop that calls Shade(): its members then stay in registers, not reloaded after every
  /// store to out.)
  void Finish();

 private:
  /// ShadeUniformPacket's lanes on a textured triangle mesh (m = kCount when kCount > 0): the
  /// lanes' uvs with FillSurface's operations in its order, (uv_a·w + uv_b·u) + uv_c·v,
  /// w = (1 − u) − v (a packet on one triangle, the usual case, loads its corners once); then
  /// the pattern (EvaluatePatternLanes: EvaluatePattern's values) and Finish's colour,
  /// color_a + (color_b − color_a)·t, written straight to the lanes' samples.
  template <int kCount>
  inline __attribute__((always_inline)) void TexturedTriangleLanes(int base, int m_in, const unsigned* prim,
                                                                   const float* u, const float* v) {
    const int m = kCount > 0 ? kCount : m_in;
    const glm::uvec3* tris = shape_->triangles.data();
    const glm::vec2* uvs = shape_->uvs.data();
    float ux[16], uy[16];  // m ≤ 16: one packet
    unsigned other = 0;
    for (int k = 1; k < m; ++k) other |= prim[k] ^ prim[0];
    if (other == 0) {
      const glm::uvec3 tri = tris[prim[0]];
      const glm::vec2 a = uvs[tri.x], b = uvs[tri.y], c = uvs[tri.z];
      for (int k = 0; k < m; ++k) {
        const float w = 1.0f - u[k] - v[k];
        ux[k] = a.x * w + b.x * u[k] + c.x * v[k];
        uy[k] = a.y * w + b.y * u[k] + c.y * v[k];
      }
    } else {
      for (int k = 0; k < m; ++k) {
        const glm::uvec3 tri = tris[prim[k]];
        const float w = 1.0f - u[k] - v[k];
        ux[k] = uvs[tri.x].x * w + uvs[tri.y].x * u[k] + uvs[tri.z].x * v[k];
        uy[k] = uvs[tri.x].y * w + uvs[tri.y].y * u[k] + uvs[tri.z].y * v[k];
      }
    }
    const Texture& tex = *texture_;
    float t[16];
    EvaluatePatternLanes(tex, ux, uy, m, t);
    const glm::vec3 ca = tex.color_a, cab = tex.color_b - tex.color_a;  // Finish's values
    SampleResult* r = out_ + base;
    for (int k = 0; k < m; ++k) {
      r[k].rgb[0] = ca.x + cab.x * t[k];
      r[k].rgb[1] = ca.y + cab.y * t[k];
      r[k].rgb[2] = ca.z + cab.z * t[k];
    }
  }

  const Scene& sc_;
  bool textures_;
  SampleResult* out_;
  TraceCounters& local_;
  glm::vec2* uv_;
  int* who_;
  const Texture** tex_;
  float* tv_;
  int m_ = 0;
  int cur_shape_ = -1;
  uint64_t evals_ = 0, lookups_ = 0;
  const Shape* shape_ = nullptr;
  const Material* mat_ = nullptr;
  const Texture* texture_ = nullptr;
};

/// TraceCameraRays and ShadeHits' unlit shading fused, for a scene without lighting, shadows,
/// glTF materials or an active alpha test, when the caller reads rgb, surface and shadowed only
/// (SampleFields::kShading): the same packets, and each packet's lanes shaded straight from
/// Embree's layout (no org/dir/Hit arrays). out[i] gets what Trace's general path writes.
/// Counts the shading and texture lookups (not the rays).
void TraceCameraRaysUnlit(const Tracer::Impl& im, const Scene& sc, const SamplePos* pos, int count, int width,
                          int height, ShadeScratch& S, SampleResult* out, TraceCounters& local);

/// The level-0 texture fetches ShadeGltf would make for n hits of a reference render
/// (fp.tex.px == 0), batched per slot and texture over the packet (SampleBilinearBatch) into
/// S.pre: the same texels, fetched with the same uv, wrap and filter. Hits that are not glTF
/// get an empty mask; so do slots whose sampler is NEAREST (fetched one by one as before).
void PrefetchTexels(const Scene& sc, const Hit* hits, const Surface* surf, int n, const KeptTexel* kept,
                    ShadeScratch& S);

/// Shades n hits seen along the rays (org[i], dir[i]) with the scene's declared effects:
/// surface attributes, shadow rays (alpha-tested when `alpha`), lambert, specular and
/// textures. out[i] receives radiance, the surface index and the shadowed-light bits;
/// hits with shape < 0 get the background. Adds shadow rays and colour lookups to counters.
/// `kept` (n entries, may be null): ClosestVisibleHits' record of the same hits.
void ShadeHits(const Tracer::Impl& im, const Scene& sc, bool alpha, const Hit* hits, const glm::vec3* org,
               const glm::vec3* dir, int n, ShadeScratch& scratch, SampleResult* out, TraceCounters& counters,
               const Footprint& fp, const KeptTexel* kept = nullptr);

}  // namespace tracer_detail
}  // namespace aalab
