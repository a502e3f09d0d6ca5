// Hard cases stay numerically stable: every method on every scene of the `hard` suite, and on
// degenerate frame sizes, gives finite metrics (or null with a reason) and a valid report.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/run/pipeline.h"
#include "methods/registry.h"
#include "reports/report_json.h"
#include "scenes/library.h"

namespace aalab {
namespace {

void ExpectStable(const MethodOutput& mo, const std::string& where) {
  for (const auto& m : mo.row.metrics) {
    if (m.value) {
      EXPECT_TRUE(std::isfinite(*m.value)) << where << " " << m.name;
    } else {
      EXPECT_FALSE(m.null_reason.empty()) << where << " " << m.name << " is null without a reason";
    }
  }
  for (const auto& t : {mo.row.render, mo.row.post, mo.row.resample, mo.row.total}) {
    EXPECT_TRUE(std::isfinite(t.median_ms) && t.median_ms >= 0) << where;
  }
}

TEST(HardSuite, EveryMethodOnEveryHardSceneIsFiniteOrNullWithReason) {
  const auto names = SuiteScenes("hard");
  ASSERT_EQ(names.size(), 8u);
  std::vector<std::string> specs = MethodNames();
  const auto plans = ResolveMethods(specs);
  Report report;
  for (const auto& name : names) {
    auto prepared = PrepareScene(std::make_unique<Scene>(LoadScene(name)), 64, 36, 4, 1, 1);
    report.scenes.push_back(prepared->info);
    for (const auto& plan : plans) {
      MethodOutput mo = RunMethod(*prepared, plan, MethodRunSettings{1, 1});
      ExpectStable(mo, name + " " + plan.spec);
      EXPECT_EQ(mo.output.Width(), 64);
      EXPECT_EQ(mo.output.Height(), 36);
      report.rows.push_back(mo.row);
    }
  }
  // The whole report serialises without a single non-finite number (ReportToJson checks).
  const std::string text = ReportToJson(report).dump();
  EXPECT_EQ(text.find("NaN"), std::string::npos);
  EXPECT_EQ(text.find("Infinity"), std::string::npos);
}

TEST(HardSuite, DegenerateFrameSizesForEveryMethod) {
  const auto plans = ResolveMethods(MethodNames());
  for (auto [w, h] : std::vector<std::pair<int, int>>{{1, 1}, {1, 7}, {7, 1}, {3, 3}, {2, 2}, {17, 9}, {5, 13}}) {
    auto prepared = PrepareScene(std::make_unique<Scene>(LoadScene("wedges")), w, h, 2, 1, 1);
    for (const auto& plan : plans) {
      const std::string where = std::to_string(w) + "x" + std::to_string(h) + " " + plan.spec;
      MethodOutput mo = RunMethod(*prepared, plan, MethodRunSettings{1, 1});
      ExpectStable(mo, where);
      EXPECT_EQ(mo.output.Width(), w) << where;
      EXPECT_EQ(mo.output.Height(), h) << where;
    }
  }
}

TEST(HardSuite, HugeCoordinatesStillRenderTheWedges) {
  // Translating the scene by 1e6 costs float precision (spacing 0.0625) but must not lose
  // the geometry: the frame still differs from an empty background in a comparable share of
  // pixels to the original wedges.
  auto near = PrepareScene(std::make_unique<Scene>(LoadScene("wedges")), 96, 54, 2, 1, 1);
  auto far = PrepareScene(std::make_unique<Scene>(LoadScene("hard-huge-coords")), 96, 54, 2, 1, 1);
  auto lit = [](const Image8& img) {
    int n = 0;
    for (int y = 0; y < img.Height(); ++y) {
      for (int x = 0; x < img.Width(); ++x) n += img.At(x, y, 1) > 40 ? 1 : 0;
    }
    return n;
  };
  const int a = lit(near->frame1x), b = lit(far->frame1x);
  EXPECT_GT(a, 200);
  EXPECT_NEAR(static_cast<double>(b), static_cast<double>(a), 0.25 * a);
}

}  // namespace
}  // namespace aalab
