// Camera rays: the perspective and orthographic rays of continuous pixel positions
// (CameraRays, vectorised in blocks of 16 with the scalar glm arithmetic's roundings), and the
// camera rays traced in 16-wide packets filled straight from the positions (TraceCameraRays,
// what Tracer::Trace uses: no vec3 arrays read back and repacked), and for unlit scenes whose
// caller reads the shading only (the reference) the same packets shaded in place
// (TraceCameraRaysUnlit: no org/dir/Hit arrays at all), and so are plain lambert scenes'
// (TraceCameraRaysLit: LitShading, tracer_lit.h, with the shadow rays packed straight).
#include <cmath>

#include "scenes/tracer_internal.h"
#include "scenes/tracer_lit.h"

namespace aalab {

using namespace tracer_detail;

namespace {

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define AALAB_SIMD_CLONES
#endif

/// The x and y of m ≤ 16 sample positions into separate arrays; lanes past m repeat the
/// last position (their rays are computed, never stored). Branch-free loads of a whole block
/// (scalar stores under a per-lane condition, read back as one vector, stalled on store
/// forwarding).
inline __attribute__((always_inline)) void LoadBlock(const SamplePos* pos, int m, float* px, float* py) {
  if (m == 16) {
    for (int k = 0; k < 16; ++k) {
      px[k] = pos[k].x;
      py[k] = pos[k].y;
    }
    return;
  }
  for (int k = 0; k < 16; ++k) {
    const int i = std::min(k, m - 1);
    px[k] = pos[i].x;
    py[k] = pos[i].y;
  }
}

/// Where the rays of a block of 16 go: six component arrays (a packet's, or a block's before
/// its vec3 stores).
struct RayLanes {
  float *ox, *oy, *oz, *dx, *dy, *dz;
};

/// What a camera ray of a continuous pixel position needs, formed once a call (CameraViewOf):
/// the projection, the frame's size, the camera's half height and aspect, and its basis.
struct CameraView {
  bool persp;
  float width, height, half_h, aspect;
  glm::vec3 origin, fwd, right, up;
};

/// The camera rays of 16 positions (px, py) component by component, so the loop vectorises:
/// perspective, exactly glm's `normalize(forward + right·(nx·half_h·aspect) + up·(ny·half_h))`
/// — normalize(v) = v · (1 / sqrt((x·x + y·y) + z·z)) — from `origin`; orthographic, from
/// `origin + (right·(nx·half_h·aspect) + up·(ny·half_h))` along `forward`. The same roundings
/// as the scalar glm code (IEEE divide and sqrt, no contraction), so the same bits.
template <bool persp>
inline __attribute__((always_inline)) void CameraBlock(const float* px, const float* py, CameraView v, RayLanes o) {
  const float width = v.width, height = v.height, half_h = v.half_h, aspect = v.aspect;
  const glm::vec3 origin = v.origin, fwd = v.fwd, right = v.right, up = v.up;
  for (int k = 0; k < 16; ++k) {
    const float nx = 2.0f * px[k] / width - 1.0f;
    const float ny = 1.0f - 2.0f * py[k] / height;
    const float a = nx * half_h * aspect;
    const float b = ny * half_h;
    if constexpr (persp) {
      const float vx = fwd.x + (right.x * a + up.x * b);
      const float vy = fwd.y + (right.y * a + up.y * b);
      const float vz = fwd.z + (right.z * a + up.z * b);
      const float inv = 1.0f / std::sqrt((vx * vx + vy * vy) + vz * vz);
      o.ox[k] = origin.x;
      o.oy[k] = origin.y;
      o.oz[k] = origin.z;
      o.dx[k] = vx * inv;
      o.dy[k] = vy * inv;
      o.dz[k] = vz * inv;
    } else {
      o.ox[k] = origin.x + (right.x * a + up.x * b);
      o.oy[k] = origin.y + (right.y * a + up.y * b);
      o.oz[k] = origin.z + (right.z * a + up.z * b);
      o.dx[k] = fwd.x;
      o.dy[k] = fwd.y;
      o.dz[k] = fwd.z;
    }
  }
}

/// CameraBlock over `count` positions into vec3 arrays, in blocks of 16 (the arithmetic on
/// separate x, y, z lanes, vectorised; the vec3 stores after it: a vec3 array's 12-byte stride
/// kept the one-loop form scalar).
template <bool persp>
inline __attribute__((always_inline)) void CameraRayArrays(const SamplePos* pos, int count, CameraView v,
                                                           glm::vec3* org, glm::vec3* dir) {
  constexpr int kBlock = 16;
  for (int base = 0; base < count; base += kBlock) {
    const int m = std::min(kBlock, count - base);
    float px[kBlock], py[kBlock], ox[kBlock], oy[kBlock], oz[kBlock], dx[kBlock], dy[kBlock], dz[kBlock];
    LoadBlock(pos + base, m, px, py);
    CameraBlock<persp>(px, py, v, {ox, oy, oz, dx, dy, dz});
    for (int k = 0; k < m; ++k) {
      org[base + k] = glm::vec3(ox[k], oy[k], oz[k]);
      dir[base + k] = glm::vec3(dx[k], dy[k], dz[k]);
    }
  }
}

/// Perspective camera rays (CameraBlock<true>: the same bits as the scalar glm code).
AALAB_SIMD_CLONES
void PerspectiveRays(const SamplePos* pos, int count, CameraView v, glm::vec3* org, glm::vec3* dir) {
  CameraRayArrays<true>(pos, count, v, org, dir);
}

/// Orthographic camera rays (CameraBlock<false>: the same bits as the scalar glm code).
AALAB_SIMD_CLONES
void OrthographicRays(const SamplePos* pos, int count, CameraView v, glm::vec3* org, glm::vec3* dir) {
  CameraRayArrays<false>(pos, count, v, org, dir);
}

/// Fills the packet with the camera rays of m ≤ 16 positions, with PerspectiveRays' or
/// OrthographicRays' arithmetic (the same bits), tnear 0 and tfar ∞; a partial packet's idle
/// lanes hold its first ray with tnear = tfar = 0 (the packets CameraRays + IntersectRays build).
inline __attribute__((always_inline)) void FillCameraPacket(CameraView v, const SamplePos* pos, int m, RTCRayHit16& rh,
                                                            int* valid) {
  const float inf = std::numeric_limits<float>::infinity();
  float px[kPacket], py[kPacket];
  LoadBlock(pos, m, px, py);
  const RayLanes lanes{rh.ray.org_x, rh.ray.org_y, rh.ray.org_z, rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z};
  if (v.persp) {
    CameraBlock<true>(px, py, v, lanes);
  } else {
    CameraBlock<false>(px, py, v, lanes);
  }
  for (int k = 0; k < kPacket; ++k) {
    valid[k] = -1;
    rh.ray.tnear[k] = 0.0f;
    rh.ray.tfar[k] = inf;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  for (int k = m; k < kPacket; ++k) {  // a partial packet's idle lanes: its first ray, empty
    valid[k] = 0;
    rh.ray.org_x[k] = rh.ray.org_x[0];
    rh.ray.org_y[k] = rh.ray.org_y[0];
    rh.ray.org_z[k] = rh.ray.org_z[0];
    rh.ray.dir_x[k] = rh.ray.dir_x[0];
    rh.ray.dir_y[k] = rh.ray.dir_y[0];
    rh.ray.dir_z[k] = rh.ray.dir_z[0];
    rh.ray.tfar[k] = 0.0f;
  }
}

/// Camera rays of `count` positions traced in 16-wide packets filled straight from the
/// positions (FillCameraPacket), traced (rtcIntersect16, coherent) and read out as
/// IntersectRays does; org/dir receive the same rays for the shading. The packets are the
/// ones CameraRays + IntersectRays build, without the vec3 arrays read back and repacked.
AALAB_SIMD_CLONES
void CameraPackets(RTCScene scene, CameraView v, const SamplePos* pos, int count, glm::vec3* org, glm::vec3* dir,
                   Hit* hits) {
  RTCIntersectContext ctx = PacketContext(true);
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[kPacket];
  InitPacketConstants(rh);
  for (int base = 0; base < count; base += kPacket) {
    const int m = std::min(kPacket, count - base);
    FillCameraPacket(v, pos + base, m, rh, valid);
    for (int k = 0; k < m; ++k) {
      org[base + k] = glm::vec3(rh.ray.org_x[k], rh.ray.org_y[k], rh.ray.org_z[k]);
      dir[base + k] = glm::vec3(rh.ray.dir_x[k], rh.ray.dir_y[k], rh.ray.dir_z[k]);
    }
    rtcIntersect16(valid, scene, &ctx, &rh);
    for (int k = 0; k < m; ++k) hits[base + k] = PacketHit(rh, k);
  }
}

/// CameraPackets with each packet's lanes shaded straight from the packet (UnlitShading):
/// the rays and hits never leave Embree's layout. A curved shape's uv (FillSurface's) takes the
/// lane's ray and hit as CameraPackets would have stored them.
AALAB_SIMD_CLONES
void CameraPacketsUnlit(RTCScene scene, CameraView v, const SamplePos* pos, int count, const Scene& sc, ShadeScratch& S,
                        SampleResult* out, TraceCounters& local) {
  UnlitShading shading(sc, sc.Has(Effect::kTextures), S, count, out, local);  // a local: in registers
  RTCIntersectContext ctx = PacketContext(true);
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[kPacket];
  InitPacketConstants(rh);
  for (int base = 0; base < count; base += kPacket) {
    const int m = std::min(kPacket, count - base);
    FillCameraPacket(v, pos + base, m, rh, valid);
    rtcIntersect16(valid, scene, &ctx, &rh);
    if (shading.ShadeUniformPacket(base, m, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v)) continue;
    for (int k = 0; k < m; ++k) {
      const unsigned geom = rh.hit.geomID[k];
      if (geom == RTC_INVALID_GEOMETRY_ID) {
        shading.Background(base + k);
        continue;
      }
      shading.Shade(base + k, static_cast<int>(geom), rh.hit.primID[k], rh.hit.u[k], rh.hit.v[k], [&] {
        const glm::vec3 o(rh.ray.org_x[k], rh.ray.org_y[k], rh.ray.org_z[k]);
        const glm::vec3 d(rh.ray.dir_x[k], rh.ray.dir_y[k], rh.ray.dir_z[k]);
        return SurfaceAt(sc, PacketHit(rh, k), o, d, true, false).uv;
      });
    }
  }
  shading.Finish();
}

/// CameraPackets with each packet's lanes shaded straight from the packet (LitShading): the
/// camera rays and hits never leave Embree's layout, the shadow rays go straight into their
/// own packets.
AALAB_SIMD_CLONES
void CameraPacketsLit(RTCScene scene, CameraView v, const SamplePos* pos, int count, const Scene& sc, ShadeScratch& S,
                      SampleResult* out, TraceCounters& local) {
  LitShading shading(sc, scene, S, count, out, local);
  RTCIntersectContext ctx = PacketContext(true);
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[kPacket];
  InitPacketConstants(rh);
  for (int base = 0; base < count; base += kPacket) {
    const int m = std::min(kPacket, count - base);
    FillCameraPacket(v, pos + base, m, rh, valid);
    rtcIntersect16(valid, scene, &ctx, &rh);
    if (shading.ShadeUniformPacket(base, m, rh)) continue;
    for (int k = 0; k < m; ++k) {
      const unsigned geom = rh.hit.geomID[k];
      if (geom == RTC_INVALID_GEOMETRY_ID) {
        shading.Background(base + k);
        continue;
      }
      shading.Shade(base + k, static_cast<int>(geom), glm::vec3(rh.ray.org_x[k], rh.ray.org_y[k], rh.ray.org_z[k]),
                    glm::vec3(rh.ray.dir_x[k], rh.ray.dir_y[k], rh.ray.dir_z[k]), rh.ray.tfar[k],
                    glm::vec3(rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]));
    }
  }
  shading.Finish();
}

/// The view of `cam` over a width × height frame.
CameraView CameraViewOf(const Tracer::Impl& im, const Camera& cam, int width, int height) {
  return {cam.type == CameraType::kPerspective,
          static_cast<float>(width),
          static_cast<float>(height),
          CameraHalfHeight(cam),
          static_cast<float>(width) / static_cast<float>(height),
          im.origin,
          im.forward,
          im.right,
          im.up};
}

}  // namespace

void tracer_detail::CameraRays(const Tracer::Impl& im, const Camera& cam, const SamplePos* pos, int count, int width,
                               int height, glm::vec3* org, glm::vec3* dir) {
  const CameraView v = CameraViewOf(im, cam, width, height);
  if (v.persp) {
    PerspectiveRays(pos, count, v, org, dir);
  } else {
    OrthographicRays(pos, count, v, org, dir);
  }
}

void tracer_detail::TraceCameraRays(const Tracer::Impl& im, const Camera& cam, const SamplePos* pos, int count,
                                    int width, int height, glm::vec3* org, glm::vec3* dir, Hit* hits) {
  CameraPackets(im.scene, CameraViewOf(im, cam, width, height), pos, count, org, dir, hits);
}

void tracer_detail::TraceCameraRaysUnlit(const Tracer::Impl& im, const Scene& sc, const SamplePos* pos, int count,
                                         int width, int height, ShadeScratch& S, SampleResult* out,
                                         TraceCounters& local) {
  CameraPacketsUnlit(im.scene, CameraViewOf(im, sc.camera, width, height), pos, count, sc, S, out, local);
}

void tracer_detail::TraceCameraRaysLit(const Tracer::Impl& im, const Scene& sc, const SamplePos* pos, int count,
                                       int width, int height, ShadeScratch& S, SampleResult* out,
                                       TraceCounters& local) {
  CameraPacketsLit(im.scene, CameraViewOf(im, sc.camera, width, height), pos, count, sc, S, out, local);
}

}  // namespace aalab
