// The glTF texture footprint's on-plane coordinates in vector lanes (UvOnPlaneLanes): where
// the camera ray and its two offset rays meet the hit triangle's plane, as texture coordinates
// in double, the three rays in the lanes of one register with the operations of the ray-by-ray
// path (UvOnPlaneScalar in tracer_gltf.cpp) in its order: the same bits. HitUvDerivs' path.
#include <cstdint>

#include "scenes/tracer_internal.h"

namespace aalab::tracer_detail {

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_GLTF_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define AALAB_GLTF_CLONES
#endif

namespace {

/// Four double lanes (GCC vector: one AVX2 register, two SSE2 ones in the default clone)
/// and their lane-wise compare masks (all bits set: true).
typedef double F64x4 __attribute__((vector_size(32)));
typedef int64_t M64x4 __attribute__((vector_size(32)));

/// The lanes of rays 0, 1, 2 (and 0 again) of component c (macros, not functions: a vector
/// passed or returned by value across a function boundary changes the ABI between clones).
#define AALAB_LANES(a, c) \
  F64x4 { a[0].c, a[1].c, a[2].c, a[0].c }
/// Finite lanes: x − x is +0 exactly for finite x, NaN for ±inf and NaN.
#define AALAB_FINITE(x) (((x) - (x)) == 0.0)

}  // namespace

AALAB_GLTF_CLONES
PlaneUvs UvOnPlaneLanes(const glm::vec3 p[3], const glm::vec2 t[3], const glm::vec3 o[3], const glm::vec3 d[3]) {
  // The plane and its Gram terms: PlaneOf's operations, once for the three rays.
  const glm::dvec3 p0(p[0]);
  const glm::dvec3 e1 = glm::dvec3(p[1]) - p0, e2 = glm::dvec3(p[2]) - p0;
  const glm::dvec3 n = glm::cross(e1, e2);
  const double d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
  const double den = d00 * d11 - d01 * d01;
  const glm::dvec2 uv0(t[0]);
  const glm::dvec2 du1 = glm::dvec2(t[1]) - uv0, du2 = glm::dvec2(t[2]) - uv0;
  // BaryOnPlane and UvOnPlane in the lanes (ray k in lane k, lane 3 repeats ray 0): every
  // operation of theirs, in their order (glm's dot is (x·x' + y·y') + z·z'), with the tests
  // that end them early folded into one mask; a failed lane's values are never read.
  const F64x4 ox = AALAB_LANES(o, x), oy = AALAB_LANES(o, y), oz = AALAB_LANES(o, z);
  const F64x4 dx = AALAB_LANES(d, x), dy = AALAB_LANES(d, y), dz = AALAB_LANES(d, z);
  const F64x4 denom = (n.x * dx + n.y * dy) + n.z * dz;
  M64x4 ok = (denom > 1e-300) | (denom < -1e-300);  // |denom| > 1e-300 (false for NaN)
  const F64x4 num = (n.x * (p0.x - ox) + n.y * (p0.y - oy)) + n.z * (p0.z - oz);
  const F64x4 tt = num / denom;
  ok &= (tt > 0.0) & AALAB_FINITE(tt);
  const F64x4 qx = (ox + dx * tt) - p0.x, qy = (oy + dy * tt) - p0.y, qz = (oz + dz * tt) - p0.z;
  const F64x4 d20 = (qx * e1.x + qy * e1.y) + qz * e1.z;
  const F64x4 d21 = (qx * e2.x + qy * e2.y) + qz * e2.z;
  const F64x4 w1 = (d11 * d20 - d01 * d21) / den;
  const F64x4 w2 = (d00 * d21 - d01 * d20) / den;
  ok &= AALAB_FINITE(w1) & AALAB_FINITE(w2);
  const F64x4 u = (uv0.x + w1 * du1.x) + w2 * du2.x;
  const F64x4 v = (uv0.y + w1 * du1.y) + w2 * du2.y;
  ok &= AALAB_FINITE(u) & AALAB_FINITE(v);
  PlaneUvs r;
  for (int k = 0; k < 3; ++k) {
    r.uv[k] = glm::dvec2(u[k], v[k]);
    r.ok[k] = den > 0.0 && ok[k] != 0;
  }
  return r;
}

#undef AALAB_LANES
#undef AALAB_FINITE

}  // namespace aalab::tracer_detail
