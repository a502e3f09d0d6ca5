// FXAA and SMAA on rendered library scenes: every preset must improve edge quality over
// `none` (error measured on the reference's geometric edge mask), and the longer-reaching
// FXAA 1.0 presets must beat the short ones on near-horizontal edges.
#include <gtest/gtest.h>

#include "metrics/metric.h"
#include "methods/registry.h"
#include "methods/rescale.h"
#include "scenes/library.h"
#include "scenes/render.h"

namespace aalab {
namespace {

struct Rendered {
  Reference ref;
  Image8 none;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<Tracer> tracer;
};

Rendered Render(Scene scene, int w, int h) {
  Rendered r;
  r.scene = std::make_unique<Scene>(std::move(scene));
  r.tracer = std::make_unique<Tracer>(*r.scene);
  r.ref = RenderReference(*r.tracer, w, h, 8, 1, nullptr);
  r.none = RenderFrame(*r.tracer, w, h, RenderSpec{}, 1, nullptr);
  return r;
}

double EdgeMse(const Rendered& r, const Image8& img) {
  return MeanSquaredError(ToFloat(img), r.ref.image, &r.ref.edge_mask).mse;
}

Image8 RunPlan(const Rendered& r, const MethodPlan& plan) {
  const int W = r.none.Width(), H = r.none.Height();
  Image8 frame = r.none;
  if (!plan.IsPostOnly()) {
    const int rw = static_cast<int>(std::lround(plan.render.scale * W));
    const int rh = static_cast<int>(std::lround(plan.render.scale * H));
    frame = RenderFrame(*r.tracer, rw, rh, plan.render, 1, nullptr);
  }
  if (plan.post) frame = plan.post(frame, PostOptions{}, nullptr);
  if (plan.rescale != Rescale::kNone) frame = RescaleFrame(frame, W, H, plan.rescale, nullptr);
  return frame;
}

TEST(FxaaOnScenes, EveryPostFilterImprovesEdgesOnWedgesAndCircle) {
  // Every registered post filter (FXAA 1.0, FXAA 3.11, SMAA, and any family added later: the
  // registry's post-only rows, not a list of names).
  int filters = 0;
  for (const char* scene : {"wedges", "circle"}) {
    const Rendered r = Render(LoadScene(scene), 192, 108);
    const double none = EdgeMse(r, r.none);
    for (const auto& e : MethodRegistry()) {
      const MethodPlan plan = MakeMethod(e.name);
      if (!plan.IsPostOnly()) continue;
      // FSR 1's `rcas` is a sharpener, not an AA filter: it moves edge pixels away from the
      // box-filtered coverage by design (docs/fsr1.md); tests/methods/fsr1_test.cpp checks it.
      if (plan.family == "fsr1") continue;
      ++filters;
      const double m = EdgeMse(r, RunPlan(r, plan));
      EXPECT_LT(m, none) << scene << " " << e.name;
    }
  }
  EXPECT_GE(filters, 2 * (6 + 21 + 4));  // fxaa1-p0..p5, 21 FXAA 3.11 rows, 4 SMAA presets
}

TEST(SmaaOnScenes, EverySmaaPresetImprovesEdgesOnWedgesAndCircle) {
  // The same bar as FXAA's above, for every registered SMAA preset (low, medium, high, ultra):
  // a morphological filter that blends across the detected edges must bring the edge pixels
  // closer to the box-filtered coverage than the 1x frame's 0/1 steps.
  int presets = 0;
  for (const char* scene : {"wedges", "circle"}) {
    const Rendered r = Render(LoadScene(scene), 192, 108);
    const double none = EdgeMse(r, r.none);
    for (const auto& e : MethodRegistry()) {
      if (e.family != "smaa") continue;
      ++presets;
      const double m = EdgeMse(r, RunPlan(r, MakeMethod(e.name)));
      EXPECT_LT(m, none) << scene << " " << e.name;
    }
  }
  EXPECT_EQ(presets, 2 * 4);
}

TEST(FxaaOnScenes, LongSearchPresetsBeatShortOnNearHorizontalEdges) {
  // One white quad whose top edge runs at 1.2°: a staircase with ~48 px treads at this size.
  const std::string json = R"({"name": "near-horizontal", "effects": ["unlit"],
    "camera": {"type": "orthographic", "position": [0,0,10], "look_at": [0,0,0], "height": 9},
    "materials": {"w": {"shading": "unlit", "color": [0.9,0.9,0.9]}},
    "objects": [{"shape": "quad", "size": [30, 8], "material": "w",
                 "transform": {"translate": [0,-4,0], "rotate": [0,0,1.2]}}]})";
  const Rendered r = Render(ParseScene(json, "test", "."), 320, 90);
  auto err = [&](const char* spec) { return EdgeMse(r, RunPlan(r, MakeMethod(spec))); };
  const double p0 = err("fxaa1-p0"), p1 = err("fxaa1-p1"), p3 = err("fxaa1-p3"), p4 = err("fxaa1-p4");
  EXPECT_LT(p3, p0);
  EXPECT_LT(p3, p1);
  EXPECT_LT(p4, p0);
  EXPECT_LT(p4, p1);
}

TEST(FxaaOnScenes, RenderScalePlusFxaaBeatsNoneAndScaleAlone) {
  const Rendered r = Render(LoadScene("wedges"), 192, 108);
  const double none = EdgeMse(r, r.none);
  const double scale = EdgeMse(r, RunPlan(r, MakeMethod("scale43")));
  for (const char* spec : {"scale43-fxaa-high", "scale43-fxaa-high:rescale=bicubic"}) {
    const double both = EdgeMse(r, RunPlan(r, MakeMethod(spec)));
    EXPECT_LT(both, none) << spec;
    EXPECT_LT(both, scale) << spec;
  }
}

}  // namespace
}  // namespace aalab
