// The glTF footprint's on-plane texture coordinates (HitUvDerivs): the camera ray and its two
// offset rays evaluated in vector lanes (UvOnPlaneLanes) against the ray-by-ray double path
// (UvOnPlaneScalar), bit for bit, on random triangles and on the edge cases: degenerate
// triangles, rays parallel to the plane or pointing away from it, huge offsets, non-finite
// texture coordinates and directions.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "scenes/tracer_internal.h"

namespace aalab {
namespace {

using tracer_detail::PlaneUvs;
using tracer_detail::UvOnPlaneLanes;
using tracer_detail::UvOnPlaneScalar;

struct Case {
  glm::vec3 p[3];
  glm::vec2 t[3];
  glm::vec3 o[3], d[3];
};

/// Lanes and scalar agree: the same verdict per ray and, where it holds, the same bits.
void ExpectSame(const Case& c, const char* what) {
  const PlaneUvs a = UvOnPlaneLanes(c.p, c.t, c.o, c.d);
  const PlaneUvs b = UvOnPlaneScalar(c.p, c.t, c.o, c.d);
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(a.ok[k], b.ok[k]) << what << " ray " << k;
    if (b.ok[k]) {
      EXPECT_EQ(std::memcmp(&a.uv[k], &b.uv[k], sizeof a.uv[k]), 0) << what << " ray " << k;
    }
  }
}

Case Base() {
  Case c;
  c.p[0] = {-1.0f, -1.0f, 0.0f};
  c.p[1] = {1.0f, -1.0f, 0.1f};
  c.p[2] = {0.0f, 1.0f, -0.2f};
  c.t[0] = {0.0f, 0.0f};
  c.t[1] = {1.0f, 0.0f};
  c.t[2] = {0.5f, 1.0f};
  for (int k = 0; k < 3; ++k) c.o[k] = {0.0f, 0.0f, 5.0f};
  c.d[0] = glm::normalize(glm::vec3(0.01f, 0.02f, -1.0f));
  c.d[1] = glm::normalize(glm::vec3(0.013f, 0.02f, -1.0f));
  c.d[2] = glm::normalize(glm::vec3(0.01f, 0.017f, -1.0f));
  return c;
}

TEST(PlaneUv, LanesMatchScalarOnRandomTriangles) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> pos(-10.0f, 10.0f), uvd(-3.0f, 3.0f), small(-0.01f, 0.01f);
  int hits = 0;
  for (int n = 0; n < 20000; ++n) {
    Case c;
    for (int k = 0; k < 3; ++k) {
      c.p[k] = {pos(rng), pos(rng), pos(rng)};
      c.t[k] = {uvd(rng), uvd(rng)};
    }
    const glm::vec3 target = (c.p[0] + c.p[1] + c.p[2]) / 3.0f;
    const glm::vec3 o(pos(rng), pos(rng), pos(rng));
    const glm::vec3 d = glm::normalize(target - o);
    const bool persp = n % 2 == 0;  // perspective: one origin; orthographic: offset origins
    for (int k = 0; k < 3; ++k) {
      c.o[k] = persp || k == 0 ? o : o + glm::vec3(small(rng), small(rng), small(rng)) * 100.0f;
      c.d[k] = persp && k > 0 ? glm::normalize(d + glm::vec3(small(rng), small(rng), small(rng))) : d;
    }
    const PlaneUvs b = UvOnPlaneScalar(c.p, c.t, c.o, c.d);
    hits += b.ok[0] && b.ok[1] && b.ok[2];
    ExpectSame(c, "random");
  }
  EXPECT_GT(hits, 15000);  // the random rays mostly meet their planes: the values are compared
}

TEST(PlaneUv, LanesMatchScalarOnEdgeCases) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  ExpectSame(Base(), "base");
  {
    const PlaneUvs b = UvOnPlaneScalar(Base().p, Base().t, Base().o, Base().d);
    EXPECT_TRUE(b.ok[0] && b.ok[1] && b.ok[2]);
  }
  {  // degenerate triangles: coincident corners, collinear corners
    Case c = Base();
    c.p[2] = c.p[1];
    ExpectSame(c, "coincident");
    c = Base();
    c.p[2] = (c.p[0] + c.p[1]) * 0.5f;
    ExpectSame(c, "collinear");
    c = Base();
    c.p[1] = c.p[2] = c.p[0];
    ExpectSame(c, "point");
  }
  {  // a ray parallel to the plane (z = 0 plane, direction in it), one behind, one away
    Case c = Base();
    c.p[1].z = c.p[2].z = 0.0f;
    c.d[1] = {1.0f, 0.0f, 0.0f};
    c.d[2] = {0.0f, 0.0f, 1.0f};
    ExpectSame(c, "parallel / away");
    c.d[0] = {0.6f, 0.8f, 0.0f};
    ExpectSame(c, "primary parallel");
  }
  {  // huge offsets and tiny directions
    Case c = Base();
    c.o[1] = {1e30f, 0.0f, 5.0f};
    c.o[2] = {0.0f, -3e38f, 3e38f};
    ExpectSame(c, "huge origins");
    c = Base();
    c.d[1] = {1e-30f, 1e-30f, -1e-30f};
    c.d[2] = {0.0f, 0.0f, -1e-38f};
    ExpectSame(c, "tiny directions");
    c = Base();
    for (int k = 0; k < 3; ++k) c.p[k] *= 1e18f;
    ExpectSame(c, "huge triangle");
  }
  {  // non-finite texture coordinates, origins and directions
    Case c = Base();
    c.t[1].x = nan;
    ExpectSame(c, "NaN uv");
    c = Base();
    c.t[2].y = inf;
    ExpectSame(c, "inf uv");
    c = Base();
    c.t[0] = {3e38f, -3e38f};
    c.t[1] = {-3e38f, 3e38f};
    ExpectSame(c, "huge uv");
    c = Base();
    c.d[2] = {nan, 0.0f, -1.0f};
    c.o[1] = {inf, 0.0f, 5.0f};
    ExpectSame(c, "NaN direction, inf origin");
    c = Base();
    c.p[1].x = nan;
    ExpectSame(c, "NaN corner");
  }
}

}  // namespace
}  // namespace aalab
