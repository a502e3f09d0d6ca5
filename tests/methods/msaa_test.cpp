// MSAA (methods/msaa.cpp, scenes/tracer_msaa.cpp) against values worked out by hand: the
// standard sample positions are written out here independently (Vulkan's [0,1]² table), and
// each pixel's expected coverage k comes from testing those positions against the scene's
// geometry in double precision.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "methods/registry.h"
#include "metrics/metric.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/scene.h"
#include "scenes/tracer.h"

namespace aalab {
namespace {

/// Vulkan "standard sample locations" (upper-left origin, [0,1]², sample index order).
std::vector<std::pair<double, double>> VulkanPositions(int n) {
  switch (n) {
    case 2: return {{0.75, 0.75}, {0.25, 0.25}};
    case 4: return {{0.375, 0.125}, {0.875, 0.375}, {0.125, 0.625}, {0.625, 0.875}};
    case 8:
      return {{0.5625, 0.3125}, {0.4375, 0.6875}, {0.8125, 0.5625}, {0.3125, 0.1875},
              {0.1875, 0.8125}, {0.0625, 0.4375}, {0.6875, 0.9375}, {0.9375, 0.0625}};
    case 16:
      return {{0.5625, 0.5625}, {0.4375, 0.3125}, {0.3125, 0.625}, {0.75, 0.4375}, {0.1875, 0.375}, {0.625, 0.8125},
              {0.8125, 0.6875}, {0.6875, 0.1875}, {0.375, 0.875},  {0.5, 0.0625},  {0.25, 0.125},   {0.125, 0.75},
              {0.0, 0.5},       {0.9375, 0.25},   {0.875, 0.9375}, {0.0625, 0.0}};
    default: return {};
  }
}

/// An orthographic, unlit scene of W × H pixels where one world unit is one pixel: pixel
/// position (px, py) is world (px − W/2, H/2 − py). `materials` and `objects` spliced in.
Scene OrthoPixelScene(int w, int h, const std::string& effects, const std::string& materials,
                      const std::string& objects, const std::string& tonemap = "none") {
  const std::string json = R"({"name": "t", "effects": )" + effects +
                           R"(, "camera": {"type": "orthographic", "position": [0,0,10], "look_at": [0,0,0],)"
                           R"( "height": )" +
                           std::to_string(h) + R"(}, "display": {"tonemap": ")" + tonemap +
                           R"("}, "background": [0,0,0], "materials": )" + materials + R"(, "objects": )" + objects +
                           "}";
  (void)w;
  return ParseScene(json, "msaa_test.json", ".");
}

uint8_t Expected8(double linear) { return QuantizeUnorm8(SrgbEncode(static_cast<float>(linear))); }

Image8 Render(const Scene& scene, int w, int h, const std::string& method, TraceCounters* c = nullptr,
              FrameStats* stats = nullptr) {
  const Tracer tracer(scene);
  return RenderFrame(tracer, w, h, MakeMethod(method).render, 1, c, stats);
}

// The edge y_world = 0.3·x_world + 0.37: no standard position lies on it (the offsets are
// multiples of 1/16 px and 0.3·k/16 + 0.37 is never a multiple of 1/16).
constexpr double kSlope = 0.3, kOffset = 0.37;
const std::string kEdgeTriangle =
    R"([{"shape": "polygon", "points": [[-1000, -299.63, 0], [1000, 300.37, 0], [0, -5000, 0]], "material": "m"}])";

TEST(Msaa, StraightEdgeIsKOverNOfTheStandardPositions) {
  const int W = 24, H = 12;
  for (const int n : {2, 4, 8, 16}) {
    const auto pos = VulkanPositions(n);
    ASSERT_EQ(static_cast<int>(pos.size()), n);
    // White (display) and a 16x emitter under the clamp tonemap (hdr-linear) below the edge.
    const Scene white =
        OrthoPixelScene(W, H, R"(["unlit"])", R"({"m": {"shading": "unlit", "color": [1,1,1]}})", kEdgeTriangle);
    const Scene hot =
        OrthoPixelScene(W, H, R"(["unlit"])", R"({"m": {"shading": "unlit", "color": [16,16,16]}})", kEdgeTriangle);
    const std::string m = "msaa-" + std::to_string(n) + "x";
    TraceCounters c;
    const Image8 img = Render(white, W, H, m, &c);
    const Image8 hot_display = Render(hot, W, H, m);
    const Image8 hot_hdr = Render(hot, W, H, m + ":resolve=hdr-linear");
    int partial = 0, touched = 0;
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        int k = 0;
        for (const auto& [sx, sy] : pos) {
          const double wx = x + sx - W / 2.0, wy = H / 2.0 - (y + sy);
          if (wy < kSlope * wx + kOffset) ++k;
        }
        partial += k > 0 && k < n;
        touched += k > 0;
        const double f = static_cast<double>(k) / n;
        for (int ch = 0; ch < 3; ++ch) {
          ASSERT_EQ(img.At(x, y, ch), Expected8(f)) << m << " pixel " << x << "," << y << " k=" << k;
          // Each sample clamped to 1 before the average: the same k/N.
          ASSERT_EQ(hot_display.At(x, y, ch), Expected8(f)) << m << " pixel " << x << "," << y;
          // Radiance averaged first: 16·k/N, clamped once — any covered sample saturates the pixel.
          ASSERT_EQ(hot_hdr.At(x, y, ch), Expected8(std::min(1.0, 16.0 * f))) << m << " pixel " << x << "," << y;
        }
      }
    }
    EXPECT_GT(partial, W / 2) << "the edge must cross pixels";
    // One coverage ray per sample; one shading, and one pixel-centre shading ray, per pixel
    // where some sample sees the triangle (its only primitive).
    EXPECT_EQ(c.coverage_rays, static_cast<uint64_t>(W * H * n));
    EXPECT_EQ(c.primary_rays, static_cast<uint64_t>(W * H * n + touched));
    EXPECT_EQ(c.shading_evals, static_cast<uint64_t>(touched)) << m;
  }
}

TEST(Msaa, FourSamplesOnAnUnlitSceneEqualSsaaOfTheSamePositions) {
  // ssaa-rgss samples the same four positions as msaa-4x, in the same order.
  const auto rgss = MakeMethod("ssaa-rgss").render.FixedOffsets();
  const auto std4 = VulkanPositions(4);
  ASSERT_EQ(rgss.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(rgss[i].first, std4[i].first);
    EXPECT_EQ(rgss[i].second, std4[i].second);
  }
  // Unlit, untextured: a primitive's shade is its colour wherever it is evaluated.
  for (const char* name : {"wedges", "thin-wires", "hdr-edges"}) {
    const Scene scene = LoadScene(name);
    const Tracer tracer(scene);
    const Image8 msaa = RenderFrame(tracer, 67, 37, MakeMethod("msaa-4x").render, 1, nullptr);
    const Image8 ssaa = RenderFrame(tracer, 67, 37, MakeMethod("ssaa-rgss").render, 1, nullptr);
    EXPECT_TRUE(msaa == ssaa) << name;
  }
}

/// Pixels of the ground plane y = 0 whose footprint the plane's diagonal x = z (the edge
/// between its two triangles) crosses: the pixel's four corner rays, intersected with the
/// ground in double precision with the camera model of scenes/README.md, fall on both
/// sides of it (or one misses the ground: the horizon, an edge anyway).
bool DiagonalCrosses(const Camera& cam, int w, int h, int x, int y) {
  const glm::dvec3 pos(cam.position), look(cam.look_at), upv(cam.up);
  const glm::dvec3 f = glm::normalize(look - pos);
  const glm::dvec3 r = glm::normalize(glm::cross(f, upv));
  const glm::dvec3 u = glm::cross(r, f);
  const double th = std::tan(cam.fov_y_deg * 3.14159265358979323846 / 360.0);
  const double aspect = static_cast<double>(w) / h;
  int pos_side = 0, neg_side = 0;
  for (int cy = 0; cy <= 1; ++cy) {
    for (int cx = 0; cx <= 1; ++cx) {
      const double nx = 2.0 * (x + cx) / w - 1.0, ny = 1.0 - 2.0 * (y + cy) / h;
      const glm::dvec3 d = f + r * (nx * th * aspect) + u * (ny * th);
      if (!(d.y < 0.0)) return true;
      const double t = -pos.y / d.y;
      const double gx = pos.x + t * d.x, gz = pos.z + t * d.z;
      (gx - gz > 0 ? pos_side : neg_side)++;
    }
  }
  return pos_side > 0 && neg_side > 0;
}

TEST(Msaa, InteriorsShadeOncePerPixelAndAliasLikeNone) {
  const int W = 96, H = 54;
  for (const char* name : {"checker-plane", "specular-spheres"}) {
    const Scene scene = LoadScene(name);
    const Tracer tracer(scene);
    const Reference ref = RenderReference(tracer, W, H, 4, 1, nullptr);
    const Image8 none = RenderFrame(tracer, W, H, RenderSpec{}, 1, nullptr);
    // What each pixel centre sees (surface index, -1 = background).
    std::vector<SamplePos> centres;
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) centres.push_back({x + 0.5f, y + 0.5f});
    }
    std::vector<SampleResult> seen(centres.size());
    tracer.Trace(centres.data(), W * H, W, H, seen.data(), nullptr);
    for (const char* method : {"msaa-4x", "msaa-8x:shading=centroid"}) {
      FrameStats stats;
      const Image8 msaa = RenderFrame(tracer, W, H, MakeMethod(method).render, 1, nullptr, &stats);
      // Interior error (off the reference's edge mask) equals none's: MSAA does nothing there.
      const MseResult e_none = MeanSquaredError(ToFloat(none, 3), ref.image, &ref.edge_mask, true);
      const MseResult e_msaa = MeanSquaredError(ToFloat(msaa, 3), ref.image, &ref.edge_mask, true);
      ASSERT_GT(e_none.pixels, static_cast<size_t>(W * H / 2)) << name;
      EXPECT_EQ(e_msaa.mse, e_none.mse) << name << " " << method;
      EXPECT_GT(e_none.mse, 0.0) << name << ": the interior must alias for this test to mean anything";
      int interior = 0;
      for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
          if (ref.edge_mask.At(x, y, 0) > 0.5f) continue;
          const float evals = stats.shading_evals.At(x, y, 0);
          const bool surface = seen[static_cast<size_t>(y * W + x)].surface >= 0;
          if (surface && std::string(name) == "checker-plane" && DiagonalCrosses(scene.camera, W, H, x, y)) {
            EXPECT_TRUE(evals == 1.0f || evals == 2.0f) << name << " " << x << "," << y;  // one per triangle
            continue;
          }
          ++interior;
          EXPECT_EQ(evals, surface ? 1.0f : 0.0f) << name << " " << method << " pixel " << x << "," << y;
        }
      }
      EXPECT_GT(interior, W * H / 2) << name;
    }
  }
}

TEST(Msaa, AlphaTestPerSampleDiffersFromPerShadeOnlyOnCutoutEdges) {
  // A white quad cut into stripes (period 1/0.3 px along x, shifted by 0.013 px so no standard
  // position lies on a stripe boundary) over a red quad. Stripe kept where frac(0.3·u) < 0.5,
  // u = x_world − 0.013.
  const int W = 40, H = 6;
  const Scene scene = OrthoPixelScene(
      W, H, R"(["unlit", "alpha_test"])",
      R"({"front": {"shading": "unlit", "color": [1,1,1], "alpha": {"pattern": "stripes", "scale": 0.3}},
          "back": {"shading": "unlit", "color": [1,0,0]}})",
      R"([{"shape": "quad", "size": [1000,1000], "material": "front", "transform": {"translate": [0.013,0,0]}},
          {"shape": "quad", "size": [1000,1000], "material": "back", "transform": {"translate": [0,0,-1]}}])");
  auto kept = [](double wx) {
    const double d = 0.3 * (wx - 0.013);
    return d - std::floor(d) < 0.5;
  };
  const Image8 none = Render(scene, W, H, "none");
  for (const int n : {4, 16}) {
    const auto pos = VulkanPositions(n);
    const std::string m = "msaa-" + std::to_string(n) + "x";
    const Image8 shade = Render(scene, W, H, m);
    const Image8 sample = Render(scene, W, H, m + ":alpha_test=sample");
    int edges = 0;
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        int k = 0;
        for (const auto& [sx, sy] : pos) k += kept(x + sx - W / 2.0);
        const bool centre = kept(x + 0.5 - W / 2.0);
        // Per shading: the one alpha test at the centre keeps or discards every sample (the
        // samples then see the red quad), exactly like the 1x frame.
        EXPECT_EQ(shade.At(x, y, 0), 255) << m << " " << x;
        EXPECT_EQ(shade.At(x, y, 1), centre ? 255 : 0) << m << " " << x;
        EXPECT_EQ(shade.At(x, y, 1), none.At(x, y, 1)) << m << " " << x;
        // Per sample: k of N samples see white.
        EXPECT_EQ(sample.At(x, y, 0), 255) << m << " " << x;
        EXPECT_EQ(sample.At(x, y, 1), Expected8(static_cast<double>(k) / n)) << m << " " << x << " k=" << k;
        if (k == 0 || k == n) {
          EXPECT_EQ(sample.At(x, y, 1), shade.At(x, y, 1)) << m << " " << x;  // off the cut-out edges
        } else {
          ++edges;
        }
      }
    }
    EXPECT_GT(edges, 2 * H) << m;
  }
}

TEST(Msaa, CenterExtrapolatesAndCentroidTakesTheFirstCoveredSample) {
  // A textured quad whose left edge is the vertical line px = 4 + e, stripes of period 1 px
  // along x: t = 1 (green) where frac(x_world − e) < duty, else red. In pixel 4, msaa-4x covers
  // the samples with x offset > e; `center` shades at the centre (extrapolated when 0.5 < e),
  // `centroid` at the first covered sample in index order (not all four are covered).
  const int W = 8, H = 4;
  const auto pos = VulkanPositions(4);
  struct Case {
    double e, duty;
  };
  for (const Case c : {Case{0.3, 0.15}, Case{0.6, 0.5}}) {
    const std::string mat = R"({"m": {"shading": "unlit", "texture": {"pattern": "stripes", "scale": 1, "duty": )" +
                            std::to_string(c.duty) + R"(, "color_a": [1,0,0], "color_b": [0,1,0]}}})";
    const std::string quad = R"([{"shape": "quad", "size": [2000, 100], "material": "m",)"
                             R"( "transform": {"translate": [)" +
                             std::to_string(1000 + c.e) + R"(, 0, 0]}}])";
    const Scene scene = OrthoPixelScene(W, H, R"(["unlit", "textures"])", mat, quad);
    auto green = [&](double x_offset) {  // texture at x offset in pixel 4 (x_world = offset)
      const double d = x_offset - c.e;
      return d - std::floor(d) < c.duty;
    };
    int k = 0, first = -1;
    for (int s = 0; s < 4; ++s) {
      if (pos[s].first > c.e) {
        ++k;
        if (first < 0) first = s;
      }
    }
    ASSERT_GT(k, 0);
    ASSERT_LT(k, 4);
    const Image8 center = Render(scene, W, H, "msaa-4x");
    const Image8 centroid = Render(scene, W, H, "msaa-4x:shading=centroid");
    const bool g_center = green(0.5), g_centroid = green(pos[first].first);
    EXPECT_NE(g_center, g_centroid) << "the case must tell the two apart";
    const uint8_t cover = Expected8(k / 4.0);
    for (int y = 0; y < H; ++y) {
      EXPECT_EQ(center.At(4, y, 0), g_center ? 0 : cover) << c.e;
      EXPECT_EQ(center.At(4, y, 1), g_center ? cover : 0) << c.e;
      EXPECT_EQ(centroid.At(4, y, 0), g_centroid ? 0 : cover) << c.e;
      EXPECT_EQ(centroid.At(4, y, 1), g_centroid ? cover : 0) << c.e;
      for (int x = 5; x < W; ++x) {
        EXPECT_EQ(center.At(x, y, 1), centroid.At(x, y, 1)) << "fully covered: both shade at the centre";
      }
    }
  }
}

TEST(Msaa, SameBitsAndCountersAtAnyThreadCount) {
  const Scene scene = LoadScene("shadow-stipple");
  const Tracer tracer(scene);
  const RenderSpec spec = MakeMethod("msaa-8x:shading=centroid").render;
  TraceCounters c1, c2;
  SetThreadCount(1);
  const Image8 a = RenderFrame(tracer, 45, 26, spec, 1, &c1);
  SetThreadCount(2);
  const Image8 b = RenderFrame(tracer, 45, 26, spec, 1, &c2);
  SetThreadCount(0);
  EXPECT_TRUE(a == b);
  EXPECT_EQ(c1.shading_evals, c2.shading_evals);
  EXPECT_EQ(c1.shadow_rays, c2.shadow_rays);
  EXPECT_EQ(c1.primary_rays, c2.primary_rays);
  EXPECT_GT(c1.shadow_rays, 0u);
}

TEST(Msaa, BadParametersAreErrorsThatListTheChoices) {
  auto message = [](const std::string& spec) -> std::string {
    try {
      MakeMethod(spec);
    } catch (const UserError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message("msaa-4x:shading=corner").find("centroid"), std::string::npos);
  EXPECT_NE(message("msaa-4x:alpha_test=coverage").find("sample"), std::string::npos);
  EXPECT_NE(message("msaa-4x:resolve=hdr").find("hdr-linear"), std::string::npos);
  EXPECT_NE(message("msaa-4x:samples=8").find("samples"), std::string::npos);
  EXPECT_NE(message("msaa-3x").find("msaa-4x"), std::string::npos);
  // Defaults: the hardware's (centre, alpha test per shade) and the SSAA-like resolve.
  const MethodPlan p = MakeMethod("msaa-8x");
  EXPECT_EQ(p.render.msaa.samples, 8);
  EXPECT_EQ(p.render.msaa.shading, MsaaShading::kCenter);
  EXPECT_EQ(p.render.msaa.alpha_test, MsaaAlphaTest::kShade);
  EXPECT_EQ(p.render.msaa.resolve, MsaaResolve::kDisplay);
  EXPECT_EQ(p.render.SamplesPerPixel(), 8);
  EXPECT_FALSE(p.render.IsPlain1x());
}

}  // namespace
}  // namespace aalab
