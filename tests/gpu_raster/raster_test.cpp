// The raster path (gpu/raster, docs/gpu.md "The raster path") against aalab's own renderer,
// on whatever OpenGL 4.5 EGL gives here (Mesa's llvmpipe in CI):
//  - the 1× frame (and TAA's jittered frame) equals aalab's 8-bit frame within 1 code per
//    channel, except at pixels whose centre lies within the rasteriser's vertex snapping
//    distance of a projected triangle edge, where coverage may legitimately flip;
//  - MSAA 2/4/8×: glGetMultisamplefv's positions equal the standard D3D11 / Vulkan table
//    (../shared/notes/msaa-and-analytic-aa.md §1, core/render_spec.h) and the shape seen by
//    every sample equals the one aalab's MSAA simulation (Tracer::TraceMsaa) sees, again
//    except within the snapping distance of an edge;
//  - MSAA 4× and SSAA 2×2 resolved frames equal aalab's within 1 code away from edges.
// Without a context the tests skip, and fail under CI (tests/skip_or_fail.h).
#include <gtest/gtest.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "core/raster_geometry.h"
#include "core/render_spec.h"
#include "gpu/raster/egl_context.h"
#include "gpu/raster/raster_renderer.h"
#include "methods/registry.h"
#include "scenes/library.h"
#include "scenes/motion_render.h"
#include "scenes/raster_export.h"
#include "scenes/render.h"
#include "scenes/tracer.h"
#include "tests/gpu_raster/raster_gltf_rule.h"
#include "tests/gpu_raster/raster_rule.h"
#include "tests/skip_or_fail.h"

namespace aalab {
namespace {

using raster::RasterMethod;

/// One context for the whole test program ("" when made, else why not).
const std::string& ContextError() {
  static const std::string why = [] {
    raster::GlDeviceInfo info;
    const std::string r = raster::MakeHeadlessGlContext(raster::EglPlatform::kAuto, &info);
    if (r.empty())
      std::printf("raster tests on %s (%s) via %s\n", info.renderer.c_str(), info.version.c_str(),
                  info.platform.c_str());
    return r;
  }();
  return why;
}

#define REQUIRE_GL()                                                                                                  \
  do {                                                                                                                \
    if (!ContextError().empty()) AALAB_SKIP_OR_FAIL_UNDER_CI("no OpenGL 4.5 context through EGL: " + ContextError()); \
  } while (0)

struct Loaded {
  Scene scene;
  RasterScene raster;
  std::unique_ptr<Tracer> tracer;
};

std::unique_ptr<Loaded> Load(const std::string& name) {
  auto l = std::make_unique<Loaded>();
  l->scene = LoadScene(name);
  l->raster = RasterSceneOf(l->scene);
  l->tracer = std::make_unique<Tracer>(l->scene);
  return l;
}

/// GL_MAX_SAMPLES of the context (Mesa 22's llvmpipe: 4).
int MaxSamples() {
  GLint n = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &n);
  return n;
}

RasterMethod Method(const std::string& spec) {
  RasterMethod m;
  std::string why;
  EXPECT_TRUE(raster::ParseRasterMethod(spec, &m, &why)) << why;
  return m;
}

// The 1× frame: one sample at each pixel centre, the same shading and display transform.
// wedges (orthographic, unlit, 9 rotated quads) and mesh (perspective, lambert, 3200 flat
// triangles, a directional light) at 320×180, both target formats.
TEST(RasterPath, OneXFrameMatchesAalab) {
  REQUIRE_GL();
  for (const std::string name : {"wedges", "mesh"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    const Image8 ref = RenderFrame(*l->tracer, w, h, RenderSpec{}, 1, nullptr);
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    for (auto fmt : {raster::TargetFormat::kRgba16f, raster::TargetFormat::kRgba32f}) {
      r.Configure(Method("none"), w, h, fmt, raster::ResolveKind::kShader);
      r.RenderFrame();
      const FrameDiff d = Compare(ref, r.ReadRgb8(), edges, SnapDistance(r), w, h);
      std::printf(
          "%s 1x %s: %d pixel(s) 1 code apart, %d >1 code apart (max %d), all within %.4f px of an edge (snap %.4f)\n",
          name.c_str(), fmt == raster::TargetFormat::kRgba16f ? "rgba16f" : "rgba32f", d.one_code, d.near_edge_flips,
          d.max_any, d.worst_distance, SnapDistance(r));
      EXPECT_EQ(d.unexplained, 0) << name << ": pixels away from every edge differ by up to " << d.max_off_edge;
      EXPECT_LE(d.near_edge_flips, 8) << name;
    }
  }
}

// TAA's jittered frame 1 (Halton(2,3) point 2: (0, −1/6) px) against aalab's render of the
// same jitter (FrameJitterAt of taa's own jitter spec; what `aalab export-frames
// --taa-frames` writes as taa-f1).
TEST(RasterPath, TaaJitteredFrameMatchesAalab) {
  REQUIRE_GL();
  auto l = Load("mesh");
  const int w = 320, h = 180;
  const FrameJitter j = FrameJitterAt(MakeMethod("taa").render.jitter, 1);
  const RasterMethod m = Method("taa");
  EXPECT_FLOAT_EQ(m.jx, j.x);
  EXPECT_FLOAT_EQ(m.jy, j.y);
  const SurfaceFrame sf = RenderSurfaceFrame(*l->tracer, w, h, j, nullptr);
  RasterRenderer r(l->raster);
  r.Configure(m, w, h, raster::TargetFormat::kRgba16f, raster::ResolveKind::kShader);
  r.RenderFrame();
  // The edges move with the jitter: the geometry is shifted by −jitter under the centre sample.
  Edges edges = ProjectEdges(l->raster, w, h);
  for (auto& s : edges.seg) {
    s[0] -= j.x, s[2] -= j.x;
    s[1] -= j.y, s[3] -= j.y;
  }
  const FrameDiff d = Compare(sf.image, r.ReadRgb8(), edges, SnapDistance(r), w, h);
  std::printf("mesh taa-f1: %d pixel(s) 1 code apart, %d >1 code apart (max %d), all within %.4f px of an edge\n",
              d.one_code, d.near_edge_flips, d.max_any, d.worst_distance);
  EXPECT_EQ(d.unexplained, 0);
  EXPECT_LE(d.near_edge_flips, 8);
}

// MSAA's sample positions as the GL reports them: the standard table, in the raster path's
// image-aligned window coordinates (x right, y down), i.e. (8 + o)/16 of the table's 1/16 px
// offsets from the centre.
TEST(RasterPath, MsaaSamplePositionsAreTheStandardOnes) {
  REQUIRE_GL();
  auto l = Load("wedges");
  RasterRenderer r(l->raster);
  for (int want : {2, 4, 8, 16}) {
    if (want > MaxSamples()) {
      std::printf("msaa-%dx: this GL allows %d samples (GL_MAX_SAMPLES); not checked here\n", want, MaxSamples());
      continue;
    }
    r.Configure(Method("msaa-" + std::to_string(want) + "x"), 64, 36, raster::TargetFormat::kRgba16f,
                raster::ResolveKind::kShader);
    // A GL may allocate more samples than asked; the positions are then the larger pattern's.
    const int n = r.Samples();
    if (n != want) std::printf("msaa-%dx: this GL allocates %d samples; checking the %d-sample pattern\n", want, n, n);
    ASSERT_GE(n, want);
    const std::vector<float> pos = r.SamplePositions();
    const auto& table = StandardSamplePositions(n);
    ASSERT_EQ(pos.size(), 2 * table.size());
    for (int s = 0; s < n; ++s) {
      EXPECT_FLOAT_EQ(pos[2 * s], (8 + table[s].x) / 16.0f) << n << "x sample " << s << " x";
      EXPECT_FLOAT_EQ(pos[2 * s + 1], (8 + table[s].y) / 16.0f) << n << "x sample " << s << " y";
    }
  }
}

// Coverage sample for sample on wedges (edges at 0.5° to 89.6°) and sdf-circles (85 disk
// impostors, their coverage per sample from gl_SampleMask): the shape each hardware
// sample sees (an ID pass into an R32UI multisample target) against the shape aalab's MSAA
// simulation traces at that sample (Tracer::TraceMsaa with the standard positions, as
// RenderFrame builds them). Differences only within the snapping distance of an edge.
TEST(RasterPath, MsaaCoverageMatchesAalabSampleForSample) {
  REQUIRE_GL();
  for (const std::string name : {"wedges", "sdf-circles"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    const SurfaceCells cells{l->raster, Cam(l->raster, w, h)};
    int disk_exempt = 0;
    for (int want : {2, 4, 8, 16}) {
      if (want > MaxSamples()) continue;
      r.Configure(Method("msaa-" + std::to_string(want) + "x"), w, h, raster::TargetFormat::kRgba16f,
                  raster::ResolveKind::kShader);
      const int n = r.Samples();  // what the GL allocated (≥ want), compared with aalab's n-sample MSAA
      const std::vector<int32_t> gl = r.SampleShapes();
      const auto& table = StandardSamplePositions(n);
      std::vector<SamplePos> pos, centres;
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          centres.push_back({x + 0.5f, y + 0.5f});
          for (const auto& o : table) {
            pos.push_back({static_cast<float>(x) + static_cast<float>(8 + o.x) / 16.0f,
                           static_cast<float>(y) + static_cast<float>(8 + o.y) / 16.0f});
          }
        }
      }
      MsaaSpec spec;
      spec.samples = n;
      std::vector<SampleResult> out(pos.size());
      TraceCounters counters;
      l->tracer->TraceMsaa(pos.data(), centres.data(), w * h, spec, w, h, out.data(), nullptr, &counters);
      ASSERT_EQ(gl.size(), out.size());
      int covered = 0, near_edge = 0, unexplained = 0;
      double worst = 0;
      for (size_t i = 0; i < out.size(); ++i) {
        covered += out[i].surface >= 0;
        if (gl[i] == out[i].surface) continue;
        const double dist = edges.Nearest(pos[i].x, pos[i].y);
        if (dist <= SnapDistance(r)) {
          ++near_edge;
          worst = std::max(worst, dist);
        } else if (cells.NearBoundary(pos[i].x, pos[i].y, SnapDistance(r))) {
          ++disk_exempt;  // within the float slack of a disk's outline (SurfaceCells)
        } else if (++unexplained <= 5) {
          ADD_FAILURE() << n << "x: sample " << i % n << " of pixel " << i / n << " at (" << pos[i].x << ", "
                        << pos[i].y << "): GL sees shape " << gl[i] << ", aalab " << out[i].surface << ", " << dist
                        << " px from the nearest edge";
        }
      }
      std::printf(
          "%s msaa-%dx (%d samples allocated): %zu samples (%d on a shape), %d differ within %.5f px of "
          "an edge (snap %.5f), %d at a disk's outline\n",
          name.c_str(), want, n, out.size(), covered, near_edge, worst, SnapDistance(r), disk_exempt);
      EXPECT_EQ(unexplained, 0) << name;
      EXPECT_GT(covered, static_cast<int>(out.size() / 10));  // the fixture has real coverage
      EXPECT_LE(near_edge + disk_exempt, static_cast<int>(out.size() / 2000)) << name;
    }
  }
}

// Resolved frames: MSAA 4× (both resolves) and SSAA 2×2 against aalab's msaa-4x and
// ssaa-2x2 frames (display transform per sample, box average in linear light).
TEST(RasterPath, ResolvedFramesMatchAalab) {
  REQUIRE_GL();
  for (const std::string name : {"wedges", "mesh"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    for (const std::string spec : {"msaa-4x", "ssaa-2x2"}) {
      const Image8 ref = RenderFrame(*l->tracer, w, h, MakeMethod(spec).render, 1, nullptr);
      for (auto res : {raster::ResolveKind::kShader, raster::ResolveKind::kBlit}) {
        if (spec == "ssaa-2x2" && res == raster::ResolveKind::kBlit) continue;
        r.Configure(Method(spec), w, h, raster::TargetFormat::kRgba32f, res);
        r.RenderFrame();
        // A resolved pixel on an edge averages samples near it: one flipped sample of n
        // moves it by up to 255/n codes, so the edge test asks for the pixel's whole
        // footprint (centre ± 0.5 px, the farthest sample ≤ 0.71 px away) near an edge.
        const FrameDiff d = Compare(ref, r.ReadRgb8(), edges, 0.7072 + SnapDistance(r), w, h);
        std::printf("%s %s (%s resolve): %d pixel(s) 1 code apart, %d edge pixel(s) >1 code apart (max %d)\n",
                    name.c_str(), spec.c_str(), res == raster::ResolveKind::kBlit ? "blit" : "shader", d.one_code,
                    d.near_edge_flips, d.max_any);
        EXPECT_EQ(d.unexplained, 0) << name << " " << spec;
        EXPECT_LE(d.near_edge_flips, 24) << name << " " << spec;
      }
    }
  }
}

// Procedural textures (checker-plane: a checker ground plane to the horizon, perspective,
// clipped by the near plane; detail-texture: hashed noise, one texel per pixel at 960×540,
// orthographic): the pattern functions ported to GLSL operation for operation, point-sampled
// at the perspective-correct uv. 1× (both formats), TAA's jittered frame 2 (frame 1's jitter
// (0, −1/6) px puts every sample of detail-texture at 320×180 exactly on a texel boundary,
// 3 texels to a pixel: a tie on every pixel, which the rule exempts and so checks nothing),
// MSAA 4× (one
// texture lookup per primitive and pixel, at the centre, on both sides) and SSAA 2×2 against
// aalab's frames; pixels over 1 code apart only near a geometric edge or where the exact uv
// lies within the stated slack of a cell boundary (SurfaceCells).
TEST(RasterPath, ProceduralTexturesMatchAalab) {
  REQUIRE_GL();
  for (const std::string name : {"checker-plane", "detail-texture"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    for (const std::string spec : {"none", "taa@2", "msaa-4x", "ssaa-2x2"}) {
      const RasterMethod m = Method(spec);
      Image8 ref;
      if (spec == "taa@2") {
        const FrameJitter j = FrameJitterAt(MakeMethod("taa").render.jitter, 2);
        EXPECT_FLOAT_EQ(m.jx, j.x);
        EXPECT_FLOAT_EQ(m.jy, j.y);
        ref = RenderSurfaceFrame(*l->tracer, w, h, j, nullptr).image;
      } else {
        ref = RenderFrame(*l->tracer, w, h, MakeMethod(spec).render, 1, nullptr);
      }
      const int grid = m.kind == RasterMethod::Kind::kSsaa ? m.grid : 1;
      for (auto fmt : {raster::TargetFormat::kRgba16f, raster::TargetFormat::kRgba32f}) {
        if (spec != "none" && fmt == raster::TargetFormat::kRgba32f) continue;
        r.Configure(m, w, h, fmt, raster::ResolveKind::kShader);
        r.RenderFrame();
        Edges moved = edges;
        for (auto& sg : moved.seg) {
          sg[0] -= m.jx, sg[2] -= m.jx;
          sg[1] -= m.jy, sg[3] -= m.jy;
        }
        const SurfaceCells cells{l->raster, Cam(l->raster, w, h)};
        // Resolved frames: a flipped sample anywhere in the pixel's footprint counts.
        const double reach = m.kind == RasterMethod::Kind::kMsaa || grid > 1 ? 0.7072 : 0.0;
        const FrameDiff d = Compare(ref, r.ReadRgb8(), moved, reach + SnapDistance(r), w, h, &cells, grid, m.jx, m.jy);
        std::printf(
            "%s %s %s: %d pixel(s) identical, %d 1 code apart, %d >1 code apart near an edge, %d near a texture "
            "cell boundary (max %d)\n",
            name.c_str(), spec.c_str(), fmt == raster::TargetFormat::kRgba16f ? "rgba16f" : "rgba32f",
            w * h - d.one_code - d.near_edge_flips - d.texture_flips - d.unexplained, d.one_code, d.near_edge_flips,
            d.texture_flips, d.max_any);
        EXPECT_EQ(d.unexplained, 0) << name << " " << spec << ": pixels differ by up to " << d.max_off_edge;
        // The fixture has structure: the checker reaches the horizon, the noise is non-constant.
        EXPECT_LE(d.near_edge_flips + d.texture_flips, w * h / 50) << name << " " << spec;
      }
    }
  }
}

// Disks as impostors (circle: one lambert disk under a point light; hdr-edges: quads and a
// disk through ACES; sdf-circles: 85 disks over two quads) and shadow rays in the fragment
// shader (shadow-stipple: 18 thin boxes casting a stipple of shadows on a lambert plane):
// 1×, TAA's frame 1, MSAA 4× and SSAA 2×2 against aalab's frames, under the same rule
// (triangle edges, disk outlines, shadow boundaries).
TEST(RasterPath, DiskAndShadowScenesMatchAalab) {
  REQUIRE_GL();
  for (const std::string name : {"circle", "hdr-edges", "sdf-circles", "shadow-stipple"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    for (const std::string spec : {"none", "taa", "msaa-4x", "ssaa-2x2"}) {
      const RasterMethod m = Method(spec);
      const Image8 ref =
          spec == "taa"
              ? RenderSurfaceFrame(*l->tracer, w, h, FrameJitterAt(MakeMethod("taa").render.jitter, 1), nullptr).image
              : RenderFrame(*l->tracer, w, h, MakeMethod(spec).render, 1, nullptr);
      const int grid = m.kind == RasterMethod::Kind::kSsaa ? m.grid : 1;
      r.Configure(m, w, h, raster::TargetFormat::kRgba16f, raster::ResolveKind::kShader);
      r.RenderFrame();
      Edges moved = edges;
      for (auto& sg : moved.seg) {
        sg[0] -= m.jx, sg[2] -= m.jx;
        sg[1] -= m.jy, sg[3] -= m.jy;
      }
      const SurfaceCells cells{l->raster, Cam(l->raster, w, h)};
      const double reach = m.kind == RasterMethod::Kind::kMsaa ? 0.7072 : 0.0;
      const FrameDiff d = Compare(ref, r.ReadRgb8(), moved, reach + SnapDistance(r), w, h, &cells,
                                  m.kind == RasterMethod::Kind::kMsaa ? -r.Samples() : grid, m.jx, m.jy);
      std::printf(
          "%s %s: %d pixel(s) identical, %d 1 code apart, %d >1 code apart near an edge, %d at a disk's outline "
          "or shadow boundary (max %d)\n",
          name.c_str(), spec.c_str(), w * h - d.one_code - d.near_edge_flips - d.texture_flips - d.unexplained,
          d.one_code, d.near_edge_flips, d.texture_flips, d.max_any);
      EXPECT_EQ(d.unexplained, 0) << name << " " << spec << ": pixels differ by up to " << d.max_off_edge;
      EXPECT_LE(d.near_edge_flips + d.texture_flips, w * h / 200) << name << " " << spec;
    }
    if (l->raster.shadows) {
      // The fixture's shadows matter: without the shadow rays the frame is another one.
      RasterScene unshadowed = l->raster;
      unshadowed.shadows = false;
      RasterRenderer u(unshadowed);
      u.Configure(Method("none"), w, h, raster::TargetFormat::kRgba16f, raster::ResolveKind::kShader);
      u.RenderFrame();
      const FrameDiff d =
          Compare(RenderFrame(*l->tracer, w, h, RenderSpec{}, 1, nullptr), u.ReadRgb8(), edges, SnapDistance(r), w, h);
      std::printf("%s without shadow rays: %d pixel(s) over 1 code apart\n", name.c_str(), d.unexplained);
      EXPECT_GT(d.unexplained, w * h / 20) << name;
    }
  }
}

// The default suite's glTF scenes (docs/gpu.md "The default suite's glTF scenes"): their 1×,
// TAA frame 1, MSAA 4× and SSAA 2×2 frames against aalab's at 320×180 under the rule of raster_gltf_rule.h (triangle
// edges within the snap distance; alpha-test and shadow decisions within the worked-out slack). real-glossy: a
// normal-mapped GGX floor at roughness 0.18 under the sun (no cut-outs: every pixel within 1 code); real-fence: a
// single-sided MASK chain-link fence; real-foliage: MASK leaves casting shadows through their cut-outs. Each fixture's
// feature matters: without it the frame is another one (the normal map, the alpha test, the shadow rays).
TEST(RasterPath, GltfScenesMatchAalab) {
  REQUIRE_GL();
  for (const std::string name : {"real-glossy", "real-fence", "real-foliage"}) {
    auto l = Load(name);
    const int w = 320, h = 180;
    const Image8 ref = RenderFrame(*l->tracer, w, h, RenderSpec{}, 1, nullptr);
    RasterRenderer r(l->raster);
    const Edges edges = ProjectEdges(l->raster, w, h);
    for (const std::string spec : {"none", "taa", "msaa-4x", "ssaa-2x2"}) {
      const RasterMethod m = Method(spec);
      const Image8 mref =
          spec == "none" ? ref
          : spec == "taa"
              ? RenderSurfaceFrame(*l->tracer, w, h, FrameJitterAt(MakeMethod("taa").render.jitter, 1), nullptr).image
              : RenderFrame(*l->tracer, w, h, MakeMethod(spec).render, 1, nullptr);
      r.Configure(m, w, h, raster::TargetFormat::kRgba16f, raster::ResolveKind::kShader);
      r.RenderFrame();
      Edges moved = edges;
      for (auto& sg : moved.seg) {
        sg[0] -= m.jx, sg[2] -= m.jx;
        sg[1] -= m.jy, sg[3] -= m.jy;
      }
      const int grid = m.kind == RasterMethod::Kind::kSsaa ? m.grid : 1;
      const GltfCells cells(l->raster, w, h, SnapDistance(r));
      const double reach = m.kind == RasterMethod::Kind::kMsaa ? 0.7072 : 0.0;
      const FrameDiff d = Compare(mref, r.ReadRgb8(), moved, reach + SnapDistance(r), w, h, &cells,
                                  m.kind == RasterMethod::Kind::kMsaa ? -r.Samples() : grid, m.jx, m.jy);
      std::printf(
          "%s %s: %d pixel(s) identical, %d 1 code apart, %d >1 code apart near an edge, %d at a surface, "
          "alpha-test or shadow boundary (max %d)\n",
          name.c_str(), spec.c_str(), w * h - d.one_code - d.near_edge_flips - d.texture_flips - d.unexplained,
          d.one_code, d.near_edge_flips, d.texture_flips, d.max_any);
      EXPECT_EQ(d.unexplained, 0) << name << " " << spec << ": pixels differ by up to " << d.max_off_edge;
      EXPECT_LE(d.near_edge_flips + d.texture_flips, w * h / 1000) << name << " " << spec;
    }
    r.Configure(Method("none"), w, h, raster::TargetFormat::kRgba16f, raster::ResolveKind::kShader);
    // Without the scene's distinguishing feature the GPU's frame is far from aalab's.
    RasterScene planted = l->raster;
    if (name == "real-glossy") planted.normal_map = false;
    if (name == "real-fence") planted.alpha_test = false;
    if (name == "real-foliage") planted.shadows = false;
    RasterRenderer u(planted);
    u.Configure(Method("none"), w, h, raster::TargetFormat::kRgba16f, raster::ResolveKind::kShader);
    u.RenderFrame();
    const FrameDiff p = Compare(ref, u.ReadRgb8(), edges, SnapDistance(r), w, h);
    std::printf("%s without its feature: %d pixel(s) over 1 code apart away from edges\n", name.c_str(), p.unexplained);
    EXPECT_GT(p.unexplained, w * h / 100) << name;
  }
}

// Timing (issue #37's timing bug: on the H100 some frames came back as 0 ms, and medians of
// frames with and without a result shuffled the stages). The frame counts under a GPU-time
// budget, worked by hand from the rule in raster_renderer.h: budget 1000 ms, probe 4 ms →
// ⌊1000/4⌋ = 250 timed frames, capped at repeat 200; warm-up ⌊500/4⌋ = 125 of 200. Probe
// 30 ms → 33 timed, 16 warm-up. Probe 2500 ms (shadow-stipple's 4K ssaa-4x4 at its 1080p
// cost × 64) → min_repeat 5 and 1 warm-up frame. No budget → exactly warmup / repeat.
TEST(RasterTiming, FrameCountsFollowTheBudget) {
  raster::TimingPlan plan;
  plan.warmup = 200;
  plan.repeat = 200;
  plan.min_repeat = 5;
  plan.budget_ms = 1000;
  EXPECT_EQ(raster::PlanFrames(plan, 4.0).repeat, 200);
  EXPECT_EQ(raster::PlanFrames(plan, 4.0).warmup, 125);
  EXPECT_EQ(raster::PlanFrames(plan, 30.0).repeat, 33);
  EXPECT_EQ(raster::PlanFrames(plan, 30.0).warmup, 16);
  EXPECT_EQ(raster::PlanFrames(plan, 2500.0).repeat, 5);
  EXPECT_EQ(raster::PlanFrames(plan, 2500.0).warmup, 1);
  plan.repeat = 3;  // min_repeat never raises the count past --repeat
  EXPECT_EQ(raster::PlanFrames(plan, 2500.0).repeat, 3);
  plan.warmup = 0;
  EXPECT_EQ(raster::PlanFrames(plan, 2500.0).warmup, 0);
  plan.budget_ms = 0;
  plan.warmup = 7;
  EXPECT_EQ(raster::PlanFrames(plan, 2500.0).repeat, 3);
  EXPECT_EQ(raster::PlanFrames(plan, 2500.0).warmup, 7);
}

// A frame's query results are checked before they become a time: 0 ns for a stage that
// drew, a result not available, or more than 100 s is refused with the stage named; a
// method without a resolve reports its resolve as 0 whatever its (empty) query says.
TEST(RasterTiming, ZeroOrMissingResultsAreRefused) {
  const bool all[3] = {true, true, true};
  const uint64_t good[3] = {2000000, 500000, 250000};
  const raster::StageTimes t = raster::CheckedStageTimes(good, all, true);
  EXPECT_DOUBLE_EQ(t.draw, 2.0);
  EXPECT_DOUBLE_EQ(t.resolve, 0.5);
  EXPECT_DOUBLE_EQ(t.encode, 0.25);
  const uint64_t no_resolve[3] = {2000000, 0, 250000};
  EXPECT_DOUBLE_EQ(raster::CheckedStageTimes(no_resolve, all, false).resolve, 0.0);
  const uint64_t stray[3] = {2000000, 3000, 250000};  // an empty stage's query overhead
  EXPECT_DOUBLE_EQ(raster::CheckedStageTimes(stray, all, false).resolve, 0.0);
  auto why = [](const uint64_t ns[3], const bool avail[3], bool resolve) -> std::string {
    try {
      raster::CheckedStageTimes(ns, avail, resolve);
    } catch (const raster::TimingError& e) {
      EXPECT_FALSE(e.context_lost);
      return e.what();
    }
    return "";
  };
  EXPECT_NE(why(no_resolve, all, true).find("resolve stage"), std::string::npos);
  const uint64_t zero_draw[3] = {0, 500000, 250000};
  EXPECT_NE(why(zero_draw, all, true).find("draw stage's GL_TIME_ELAPSED query returned 0 ns"), std::string::npos);
  const uint64_t zero_encode[3] = {2000000, 0, 0};
  EXPECT_NE(why(zero_encode, all, false).find("encode stage"), std::string::npos);
  const bool encode_missing[3] = {true, true, false};
  EXPECT_NE(why(good, encode_missing, true).find("encode stage's GL_TIME_ELAPSED query has no result"),
            std::string::npos);
  const uint64_t huge[3] = {200000000000ull, 500000, 250000};
  EXPECT_NE(why(huge, all, true).find("not a plausible time"), std::string::npos);
}

// On the GL here: every timed frame has a draw and an encode time above 0, a resolve above 0
// exactly when the method resolves and 0 otherwise, the frame counts the plan asked for, and
// stages in their places: ssaa-4x4's draw fills 16× the encode's pixels with the scene's
// shading, so its median is larger than the encode's (stages read from another frame's or
// stage's query, as in the H100 run's shuffled row, would break that or the zeros).
TEST(RasterTiming, EveryTimedFrameHasItsOwnStageTimes) {
  REQUIRE_GL();
  auto l = Load("wedges");
  RasterRenderer r(l->raster);
  raster::TimingPlan plan;
  plan.warmup = 2;
  plan.repeat = 7;  // more frames than the ring's 3 slots: every slot is reused
  for (const std::string spec : {"none", "msaa-4x", "ssaa-4x4"}) {
    r.Configure(Method(spec), 160, 90, raster::TargetFormat::kRgba16f, raster::ResolveKind::kShader);
    const raster::TimedFrames t = r.TimeFrames(plan);
    ASSERT_EQ(t.frames.size(), 7u) << spec;
    EXPECT_EQ(t.warmup, 2);
    std::vector<double> draw, encode;
    for (const auto& f : t.frames) {
      EXPECT_GT(f.draw, 0.0) << spec;
      EXPECT_GT(f.encode, 0.0) << spec;
      if (spec == "none")
        EXPECT_EQ(f.resolve, 0.0);
      else
        EXPECT_GT(f.resolve, 0.0) << spec;
      draw.push_back(f.draw);
      encode.push_back(f.encode);
    }
    if (spec == "ssaa-4x4") {
      std::sort(draw.begin(), draw.end());
      std::sort(encode.begin(), encode.end());
      EXPECT_GT(draw[3], encode[3]) << "ssaa-4x4's draw (640×360 shaded) vs its encode (160×90)";
    }
  }
  // Under a budget far below one frame: one probe, then 1 warm-up and min_repeat frames.
  plan.budget_ms = 1e-6;
  plan.min_repeat = 4;
  const raster::TimedFrames b = r.TimeFrames(plan);
  EXPECT_EQ(b.frames.size(), 4u);
  EXPECT_EQ(b.warmup, 1);
  EXPECT_GT(b.probe_ms, 0.0);
}

}  // namespace
}  // namespace aalab
