// Embree tracer: BVH build, 16-wide packet traversal (camera rays: tracer_camera.cpp) and alpha-test
// continuation; Tracer::Trace shades every camera sample (tracer_shade.cpp shades, and
// tracer_msaa.cpp holds MSAA's coverage/shading split).
//
// Rays are traced in packets of 16 (rtcIntersect16 / rtcOccluded16). Alpha cut-outs are
// handled by continuing the ray past a rejected hit (a new packet round), not by an Embree
// filter callback: the set of alpha lookups is then a function of the ray alone (never of the
// BVH's traversal order), so counters and images are identical at any thread count.
#include "scenes/tracer.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "scenes/tracer_internal.h"
#include "scenes/tracer_lit.h"

namespace aalab {

using namespace tracer_detail;

namespace {

void DeviceError(void* user, RTCError code, const char* str) {
  auto* msg = static_cast<std::string*>(user);
  *msg = "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (str ? str : "");
}

}  // namespace

float EvaluatePattern(const Texture& tex, glm::vec2 uv) {
  switch (tex.pattern) {
    case TexturePattern::kChecker: {
      // a is an integer (or ±inf, NaN): fmod(|a|, 2) >= 1 exactly when |a| is odd, and every
      // float from 2^24 on is even (fmod 0), as are inf and NaN (fmod NaN): no fmod call.
      const float a = std::fabs(std::floor(uv.x * tex.scale) + std::floor(uv.y * tex.scale));
      return a < 16777216.0f && (static_cast<int32_t>(a) & 1) ? 1.0f : 0.0f;
    }
    case TexturePattern::kStripes: {
      const float ang = glm::radians(tex.angle_deg);
      const float d = (uv.x * std::cos(ang) + uv.y * std::sin(ang)) * tex.scale;
      return (d - std::floor(d)) < tex.duty ? 1.0f : 0.0f;
    }
    case TexturePattern::kNoise: {
      const auto cx = static_cast<int64_t>(std::floor(uv.x * tex.scale));
      const auto cy = static_cast<int64_t>(std::floor(uv.y * tex.scale));
      uint64_t h = static_cast<uint64_t>(cx) * 0x9e3779b97f4a7c15ULL ^
                   (static_cast<uint64_t>(cy) + 0x632be59bd9b4e019ULL) * 0xbf58476d1ce4e5b9ULL ^
                   (static_cast<uint64_t>(tex.seed) << 32);
      h ^= h >> 31;
      h *= 0x94d049bb133111ebULL;
      h ^= h >> 29;
      return static_cast<float>(h >> 40) * (1.0f / 16777216.0f);
    }
  }
  return 0.0f;
}

namespace {

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_PATTERN_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define AALAB_PATTERN_CLONES
#endif

/// EvaluatePattern's noise over n points (NoiseValue: the same operations per point).
AALAB_PATTERN_CLONES
void NoiseBatch(float scale, uint64_t seed_hi, const glm::vec2* uv, int n, float* t) {
  for (int k = 0; k < n; ++k) t[k] = NoiseValue(scale, seed_hi, uv[k].x, uv[k].y);
}

/// EvaluatePattern's checker over n points (CheckerValue: the same test per point).
AALAB_PATTERN_CLONES
void CheckerBatch(float scale, const glm::vec2* uv, int n, float* t) {
  for (int k = 0; k < n; ++k) t[k] = CheckerValue(scale, uv[k].x, uv[k].y);
}

typedef float F32x8 __attribute__((vector_size(32)));
typedef int32_t I32x8 __attribute__((vector_size(32)));
typedef int64_t I64x8 __attribute__((vector_size(64)));
typedef uint64_t U64x8 __attribute__((vector_size(64)));

/// static_cast<int64_t>(std::floor(v)) in 8 lanes, as cvttss2si gives it: the truncation
/// (INT64_MIN for NaN, ±inf and |v| ≥ 2^63, where the scalar code gets INT64_MIN too) less one
/// where v lies below it (an in-range truncation converts back to float exactly).
inline __attribute__((always_inline)) void FloorToInt64Lanes(const F32x8& v, U64x8& out) {
  const I64x8 c = __builtin_convertvector(v, I64x8);
  const I64x8 below = __builtin_convertvector(v < __builtin_convertvector(c, F32x8), I64x8);  // 0 or −1
  out = reinterpret_cast<U64x8>(c + (below & (c != std::numeric_limits<int64_t>::min())));
}

/// std::floor(v) in 8 lanes: |v| < 2^23 (NaN excluded) through the int32 truncation less one
/// where v lies below it (−0 and −0.x give +0 and −1: the checker takes |a| of a sum of these,
/// so the sign of a zero never shows); any other v is an integer, ±inf or NaN, its own floor.
inline __attribute__((always_inline)) void FloorLanes(const F32x8& v, F32x8& out) {
  const I32x8 c = __builtin_convertvector(v, I32x8);
  const F32x8 fc = __builtin_convertvector(c, F32x8);
  const F32x8 fl = fc - __builtin_convertvector(-(v < fc), F32x8);
  const F32x8 mag = v < 0.0f ? -v : v;
  out = mag < 8388608.0f ? fl : v;
}

/// NoiseValue over separate x and y arrays, 8 points at a time in vector lanes (the same
/// integer operations; the floor by FloorToInt64Lanes; h >> 40 < 2^24 converts exactly).
AALAB_PATTERN_CLONES
void NoiseLanes(float scale, uint64_t seed_hi, const float* x, const float* y, int n, float* t) {
  int k = 0;
  for (; k + 8 <= n; k += 8) {
    F32x8 fx, fy;
    std::memcpy(&fx, x + k, sizeof fx);
    std::memcpy(&fy, y + k, sizeof fy);
    U64x8 cx, cy;
    FloorToInt64Lanes(fx * scale, cx);
    FloorToInt64Lanes(fy * scale, cy);
    U64x8 h = cx * 0x9e3779b97f4a7c15ULL ^ (cy + 0x632be59bd9b4e019ULL) * 0xbf58476d1ce4e5b9ULL ^ seed_hi;
    h ^= h >> 31;
    h *= 0x94d049bb133111ebULL;
    h ^= h >> 29;
    const F32x8 r = __builtin_convertvector(__builtin_convertvector(h >> 40, I32x8), F32x8) * (1.0f / 16777216.0f);
    std::memcpy(t + k, &r, sizeof r);
  }
  for (; k < n; ++k) t[k] = NoiseValue(scale, seed_hi, x[k], y[k]);
}

/// CheckerValue over separate x and y arrays, 8 points at a time in vector lanes (the floor by
/// FloorLanes; then CheckerValue's test).
AALAB_PATTERN_CLONES
void CheckerLanes(float scale, const float* x, const float* y, int n, float* t) {
  int k = 0;
  for (; k + 8 <= n; k += 8) {
    F32x8 fx, fy;
    std::memcpy(&fx, x + k, sizeof fx);
    std::memcpy(&fy, y + k, sizeof fy);
    F32x8 gx, gy;
    FloorLanes(fx * scale, gx);
    FloorLanes(fy * scale, gy);
    const F32x8 sum = gx + gy;
    const F32x8 a = sum < 0.0f ? -sum : sum;
    const I32x8 small = a < 16777216.0f;
    const I32x8 ai = __builtin_convertvector(small ? a : F32x8{}, I32x8);
    const F32x8 r = (small & (ai & 1)) != 0 ? F32x8{} + 1.0f : F32x8{};
    std::memcpy(t + k, &r, sizeof r);
  }
  for (; k < n; ++k) t[k] = CheckerValue(scale, x[k], y[k]);
}

}  // namespace

void tracer_detail::EvaluatePatternLanes(const Texture& tex, const float* x, const float* y, int n, float* t) {
  switch (tex.pattern) {
    case TexturePattern::kChecker: CheckerLanes(tex.scale, x, y, n, t); return;
    case TexturePattern::kNoise: NoiseLanes(tex.scale, static_cast<uint64_t>(tex.seed) << 32, x, y, n, t); return;
    case TexturePattern::kStripes: break;
  }
  for (int k = 0; k < n; ++k) t[k] = EvaluatePattern(tex, glm::vec2(x[k], y[k]));
}

void tracer_detail::EvaluatePatternBatch(const Texture& tex, const glm::vec2* uv, int n, float* t) {
  switch (tex.pattern) {
    case TexturePattern::kChecker: CheckerBatch(tex.scale, uv, n, t); return;
    case TexturePattern::kNoise: NoiseBatch(tex.scale, static_cast<uint64_t>(tex.seed) << 32, uv, n, t); return;
    case TexturePattern::kStripes: break;
  }
  for (int k = 0; k < n; ++k) t[k] = EvaluatePattern(tex, uv[k]);
}

Tracer::Tracer(const Scene& scene) : scene_(scene), impl_(std::make_unique<Impl>()) {
  Impl& im = *impl_;
  im.device = rtcNewDevice("verbose=0");
  if (!im.device) throw InternalError("cannot create the Embree device");
  rtcSetDeviceErrorFunction(im.device, DeviceError, &im.error);
  im.scene = rtcNewScene(im.device);
  rtcSetSceneFlags(im.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(im.scene, RTC_BUILD_QUALITY_HIGH);
  for (size_t i = 0; i < scene.shapes.size(); ++i) {
    const Shape& s = scene.shapes[i];
    if (scene.materials[s.material].CutOut()) im.any_alpha = true;
    if (scene.materials[s.material].Blended()) im.any_blend = true;
    if (scene.materials[s.material].gltf && !scene.materials[s.material].gltf->double_sided) im.any_cull = true;
    if (scene.materials[s.material].gltf) im.any_gltf = true;
    if (s.kind == ShapeKind::kTriangles && !s.normals.empty()) im.any_vertex_normals = true;
    RTCGeometry g = nullptr;
    switch (s.kind) {
      case ShapeKind::kTriangles: {
        g = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), s.positions.size()));
        for (size_t k = 0; k < s.positions.size(); ++k) {
          v[3 * k] = s.positions[k].x;
          v[3 * k + 1] = s.positions[k].y;
          v[3 * k + 2] = s.positions[k].z;
        }
        auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), s.triangles.size()));
        for (size_t k = 0; k < s.triangles.size(); ++k) {
          idx[3 * k] = s.triangles[k].x;
          idx[3 * k + 1] = s.triangles[k].y;
          idx[3 * k + 2] = s.triangles[k].z;
        }
        break;
      }
      case ShapeKind::kSphere:
      case ShapeKind::kDisk: {
        g = rtcNewGeometry(im.device, s.kind == ShapeKind::kSphere ? RTC_GEOMETRY_TYPE_SPHERE_POINT
                                                                   : RTC_GEOMETRY_TYPE_ORIENTED_DISC_POINT);
        auto* v = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
        v[0] = s.center.x;
        v[1] = s.center.y;
        v[2] = s.center.z;
        v[3] = s.radius;
        if (s.kind == ShapeKind::kDisk) {
          auto* n = static_cast<float*>(
              rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 1));
          n[0] = s.normal.x;
          n[1] = s.normal.y;
          n[2] = s.normal.z;
        }
        break;
      }
      case ShapeKind::kCapsule:
      case ShapeKind::kCylinder: {
        g = rtcNewGeometry(im.device, s.kind == ShapeKind::kCapsule ? RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE
                                                                    : RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE);
        auto* v = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 2));
        v[0] = s.p0.x;
        v[1] = s.p0.y;
        v[2] = s.p0.z;
        v[3] = s.radius;
        v[4] = s.p1.x;
        v[5] = s.p1.y;
        v[6] = s.p1.z;
        v[7] = s.radius;
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), 1));
        idx[0] = 0;
        auto* flags =
            static_cast<unsigned char*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, 1, 1));
        flags[0] = 0;  // a single segment: no neighbours, so both ends are capped
        break;
      }
    }
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(im.scene, g);
    AALAB_CHECK(id == i, "Embree geometry ids must equal shape indices");
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(im.scene);
  if (!im.error.empty()) throw InternalError("building the BVH failed: " + im.error);

  const Camera& c = scene.camera;
  const CameraBasis basis = CameraBasisOf(c);
  im.origin = c.position;
  im.forward = basis.forward;
  im.right = basis.right;
  im.up = basis.up;
  im.half_h = CameraHalfHeight(c);
}

Tracer::~Tracer() = default;

void tracer_detail::IntersectRays(RTCScene scene, const glm::vec3* org, const glm::vec3* dir, const float* tnear,
                                  const float* tfar, const int* idx, int n, Hit* hits, bool coherent) {
  RTCIntersectContext ctx = PacketContext(coherent);
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[kPacket];
  InitPacketConstants(rh);
  for (int base = 0; base < n; base += kPacket) {
    // A full packet of consecutive rays, all with tnear < tfar (camera rays): the same lanes
    // as the general loop below, filled without its per-lane selects.
    bool plain = !idx && base + kPacket <= n;
    for (int k = 0; plain && k < kPacket; ++k) plain = tnear[base + k] < tfar[base + k];
    if (plain) {
      const glm::vec3* o = org + base;
      const glm::vec3* d = dir + base;
      for (int k = 0; k < kPacket; ++k) {
        valid[k] = -1;
        rh.ray.org_x[k] = o[k].x;
        rh.ray.org_y[k] = o[k].y;
        rh.ray.org_z[k] = o[k].z;
        rh.ray.dir_x[k] = d[k].x;
        rh.ray.dir_y[k] = d[k].y;
        rh.ray.dir_z[k] = d[k].z;
        rh.ray.tnear[k] = tnear[base + k];
        rh.ray.tfar[k] = tfar[base + k];
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
    }
    for (int k = 0; !plain && k < kPacket; ++k) {
      const int i = base + k;
      const int ri = i < n ? (idx ? idx[i] : i) : 0;
      const bool on = i < n && tnear[ri] < tfar[ri];
      valid[k] = on ? -1 : 0;
      const int j = on ? ri : (idx ? idx[base] : base);
      rh.ray.org_x[k] = org[j].x;
      rh.ray.org_y[k] = org[j].y;
      rh.ray.org_z[k] = org[j].z;
      rh.ray.dir_x[k] = dir[j].x;
      rh.ray.dir_y[k] = dir[j].y;
      rh.ray.dir_z[k] = dir[j].z;
      rh.ray.tnear[k] = on ? tnear[j] : 0.0f;
      rh.ray.tfar[k] = on ? tfar[j] : 0.0f;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, scene, &ctx, &rh);
    const int lanes = std::min(kPacket, n - base);
    for (int k = 0; k < lanes; ++k) hits[base + k] = PacketHit(rh, k, valid[k] != 0);
  }
}

void tracer_detail::OccludedRays(RTCScene scene, const glm::vec3* org, const glm::vec3* dir, const float* tnear,
                                 const float* tfar, int n, uint8_t* occluded) {
  // Shadow rays of neighbouring samples start close together toward the same light: coherent
  // (a traversal hint only; a yes/no answer cannot depend on it).
  RTCIntersectContext ctx = PacketContext(true);
  alignas(64) RTCRay16 ray;
  alignas(64) int valid[kPacket];
  for (int k = 0; k < kPacket; ++k) {
    ray.time[k] = 0.0f;
    ray.mask[k] = 0xFFFFFFFFu;
    ray.id[k] = static_cast<unsigned>(k);
    ray.flags[k] = 0;
  }
  for (int base = 0; base < n; base += kPacket) {
    for (int k = 0; k < kPacket; ++k) {
      const int i = base + k;
      const bool on = i < n && tnear[i] < tfar[i];
      valid[k] = on ? -1 : 0;
      const int j = on ? i : base;
      ray.org_x[k] = org[j].x;
      ray.org_y[k] = org[j].y;
      ray.org_z[k] = org[j].z;
      ray.dir_x[k] = dir[j].x;
      ray.dir_y[k] = dir[j].y;
      ray.dir_z[k] = dir[j].z;
      ray.tnear[k] = on ? tnear[j] : 0.0f;
      ray.tfar[k] = on ? tfar[j] : 0.0f;
    }
    rtcOccluded16(valid, scene, &ctx, &ray);
    for (int k = 0; k < kPacket && base + k < n; ++k) {
      // Embree sets tfar to -inf on an occluded ray.
      occluded[base + k] = valid[k] && ray.tfar[k] == -std::numeric_limits<float>::infinity() ? 1 : 0;
    }
  }
}

void tracer_detail::ClosestVisibleHits(const Tracer::Impl& im, const Scene& sc, bool alpha, const glm::vec3* org,
                                       const glm::vec3* dir, int count, float* tnear, float* tfar, Hit* hits,
                                       LayerScratch& ls, TraceCounters& local, const Footprint& fp, KeptTexel* kept) {
  // Layer 0 holds every ray in order: trace straight into `hits` (same packets as a copy).
  IntersectRays(im.scene, org, dir, tnear, tfar, nullptr, count, hits, true);
  local.primary_rays += static_cast<uint64_t>(count);
  local.coverage_rays += static_cast<uint64_t>(count);
  ContinueVisibleHits(im, sc, alpha, org, dir, count, tnear, tfar, hits, ls, local, fp, kept);
}

void tracer_detail::ContinueVisibleHits(const Tracer::Impl& im, const Scene& sc, bool alpha, const glm::vec3* org,
                                        const glm::vec3* dir, int count, float* tnear, float* tfar, Hit* hits,
                                        LayerScratch& ls, TraceCounters& local, const Footprint& fp, KeptTexel* kept) {
  if (!alpha && !im.any_cull) return;
  if (kept) std::fill(kept, kept + count, KeptTexel{});
  std::vector<int>& active = ls.active;
  std::vector<int>& next = ls.next;
  active.clear();
  // Layer 0's rejected hits, then further layers through the cut-outs.
  auto alpha_pass = [&](int layer, int n, const int* who, const Hit* h) {
    next.clear();
    for (int k = 0; k < n; ++k) {
      const int i = who ? who[k] : k;
      const Hit hk = h[k];  // h may alias hits (layer 0)
      hits[i] = hk;
      if (hk.shape < 0) continue;
      const Material& m = sc.materials[sc.shapes[hk.shape].material];
      const bool culled = im.any_cull && BackFaceCulled(sc, m, hk, dir[i]);
      if (!culled) {
        if (!alpha || !m.CutOut()) continue;
        const Surface srf = SurfaceAt(sc, hk, org[i], dir[i], true, false);  // the test reads uv only
        ++local.texture_lookups;
        KeptTexel fetched;
        if (CutoutKeeps(im, sc, m, hk, srf, org[i], dir[i], fp, kept ? &fetched : nullptr)) {
          if (kept) kept[i] = fetched;
          continue;
        }
      }
      // Rejected: continue just past this hit.
      hits[i] = Hit{};
      tnear[i] = ContinuePast(hk.t);
      if (layer + 1 < kMaxAlphaLayers) next.push_back(i);
    }
    active.swap(next);
  };
  alpha_pass(0, count, nullptr, hits);
  for (int layer = 1; !active.empty(); ++layer) {
    const int n = static_cast<int>(active.size());
    Hit* h = Sized(ls.layer_hits, static_cast<size_t>(n));
    IntersectRays(im.scene, org, dir, tnear, tfar, active.data(), n, h, false);
    local.primary_rays += static_cast<uint64_t>(n);
    local.coverage_rays += static_cast<uint64_t>(n);
    alpha_pass(layer, n, active.data(), h);
  }
}

namespace {

/// Per-thread working memory of Trace, reused from call to call: a call allocates nothing
/// once its thread has seen a batch of that size (vectors only grow).
struct TraceScratch {
  std::vector<glm::vec3> org, dir;
  std::vector<float> tnear, tfar;
  std::vector<Hit> hits;
  std::vector<KeptTexel> kept;
  LayerScratch layers;
  ShadeScratch shade;
};

}  // namespace

void Tracer::Trace(const SamplePos* pos, int count, int width, int height, SampleResult* out, TraceCounters* counters,
                   TextureFootprint footprint, SampleFields fields) const {
  const Impl& im = *impl_;
  const Scene& sc = scene_;
  TraceCounters local;
  local.samples = static_cast<uint64_t>(count);
  if (count <= 0) {
    if (counters) *counters += local;
    return;
  }
  thread_local TraceScratch scratch;
  TraceScratch& S = scratch;
  const size_t n_all = static_cast<size_t>(count);
  const bool alpha = sc.Has(Effect::kAlphaTest) && im.any_alpha;

  // An unlit scene (ShadeHits' unlit path) without cut-outs to continue through, culled or
  // blended materials, for a caller that reads the shading only: the packets shaded in place.
  const bool unlit = !sc.Has(Effect::kLambert) && !sc.Has(Effect::kShadows) && !im.any_gltf;
  if (unlit && !alpha && !im.any_cull && !im.any_blend && fields == SampleFields::kShading) {
    TraceCameraRaysUnlit(im, sc, pos, count, width, height, S.shade, out, local);
    local.primary_rays += static_cast<uint64_t>(count);
    local.coverage_rays += static_cast<uint64_t>(count);
    if (counters) *counters += local;
    return;
  }

  // A lambert scene without textures, specular, glTF or an environment, for a caller that
  // reads the shading only: the packets shaded in place, shadow rays packed straight.
  if (LitPacketsApply(im, sc, alpha, fields)) {
    TraceCameraRaysLit(im, sc, pos, count, width, height, S.shade, out, local);
    local.primary_rays += static_cast<uint64_t>(count);
    local.coverage_rays += static_cast<uint64_t>(count);
    if (counters) *counters += local;
    return;
  }

  // 1. Camera rays, traced in packets filled straight from the positions.
  glm::vec3* org = Sized(S.org, n_all);
  glm::vec3* dir = Sized(S.dir, n_all);
  Hit* hits = Sized(S.hits, n_all);
  TraceCameraRays(im, sc.camera, pos, count, width, height, org, dir, hits);
  local.primary_rays += static_cast<uint64_t>(count);
  local.coverage_rays += static_cast<uint64_t>(count);

  // 2. Closest hits, continuing through alpha cut-outs (only with `alpha_test`) and past
  // culled back faces: ClosestVisibleHits after its first round.
  const Footprint fp{width, height, footprint, fields == SampleFields::kAll};
  // With glTF cut-outs, the alpha test's base texel and footprint go on to the shading.
  KeptTexel* kept = alpha && im.any_gltf ? Sized(S.kept, n_all) : nullptr;
  if (alpha || im.any_cull) {
    float* tnear = Sized(S.tnear, n_all);
    float* tfar = Sized(S.tfar, n_all);
    std::fill(tnear, tnear + count, 0.0f);
    std::fill(tfar, tfar + count, std::numeric_limits<float>::infinity());
    ContinueVisibleHits(im, sc, alpha, org, dir, count, tnear, tfar, hits, S.layers, local, fp, kept);
  }

  // 3. One shading per sample.
  ShadeHits(im, sc, alpha, hits, org, dir, count, S.shade, out, local, fp, kept);
  CompositeBlended(im, sc, alpha, hits, org, dir, count, out, local, fp);
  if (counters) *counters += local;
}

uint64_t Tracer::BareTrace(int width, int height, int grid) const {
  const Impl& im = *impl_;
  const Camera& cam = scene_.camera;
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const float half_h = CameraHalfHeight(cam);
  const bool persp = cam.type == CameraType::kPerspective;
  constexpr int kTileSize = 8;
  const int tiles_x = (width + kTileSize - 1) / kTileSize;
  const int tiles_y = (height + kTileSize - 1) / kTileSize;
  std::vector<uint64_t> hits(static_cast<size_t>(tiles_x) * tiles_y, 0);
  ParallelForChunks(tiles_x * tiles_y, 1, [&](int begin, int end) {
    RTCIntersectContext ctx = PacketContext(true);
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[kPacket];
    InitPacketConstants(rh);
    for (int t = begin; t < end; ++t) {
      const int x0 = (t % tiles_x) * kTileSize, y0 = (t / tiles_x) * kTileSize;
      const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, height);
      uint64_t n_hit = 0;
      int lane = 0;
      auto flush = [&]() {
        for (int k = 0; k < kPacket; ++k) valid[k] = k < lane ? -1 : 0;
        rtcIntersect16(valid, im.scene, &ctx, &rh);
        for (int k = 0; k < lane; ++k) n_hit += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        lane = 0;
      };
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          for (int j = 0; j < grid; ++j) {
            for (int i = 0; i < grid; ++i) {
              const float px = static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / static_cast<float>(grid);
              const float py = static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / static_cast<float>(grid);
              const float nx = 2.0f * px / static_cast<float>(width) - 1.0f;
              const float ny = 1.0f - 2.0f * py / static_cast<float>(height);
              const glm::vec3 offset = im.right * (nx * half_h * aspect) + im.up * (ny * half_h);
              const glm::vec3 o = persp ? im.origin : im.origin + offset;
              const glm::vec3 d = persp ? glm::normalize(im.forward + offset) : im.forward;
              rh.ray.org_x[lane] = o.x;
              rh.ray.org_y[lane] = o.y;
              rh.ray.org_z[lane] = o.z;
              rh.ray.dir_x[lane] = d.x;
              rh.ray.dir_y[lane] = d.y;
              rh.ray.dir_z[lane] = d.z;
              rh.ray.tnear[lane] = 0.0f;
              rh.ray.tfar[lane] = std::numeric_limits<float>::infinity();
              rh.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
              rh.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
              if (++lane == kPacket) flush();
            }
          }
        }
      }
      if (lane > 0) flush();
      hits[static_cast<size_t>(t)] = n_hit;
    }
  });
  uint64_t total = 0;
  for (uint64_t h : hits) total += h;
  return total;
}

}  // namespace aalab
