// The per-scene verdict (reports/verdict.h) on hand-made rows: a clear win on each axis with
// the axes disagreeing, ties within the display precision, null metrics, a scene with only none.
#include "reports/verdict.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

namespace aalab {
namespace {

ResultRow Row(const std::string& scene, const std::string& spec, std::optional<double> edge, std::optional<double> flip,
              double ms) {
  ResultRow r;
  r.scene = scene;
  r.method = r.spec = spec;
  r.total.samples_ms = {ms, ms + 0.2, ms - 0.1};  // median ms
  r.total.Summarize();
  r.metrics = {{"psnr_db", 20.0, ""},
               {"edge_psnr_db", edge, edge ? "" : "no edge pixels"},
               {"flip_mean", flip, flip ? "" : "not computed"}};
  return r;
}

TEST(Verdict, WinnersByHowMuchAtWhatCostAndDisagreement) {
  // Rows of another scene, listed first, must not leak in.
  const std::vector<ResultRow> rows = {Row("other", "ssaa16", 60.0, 0.0, 50.0), Row("a", "none", 30.0, 0.10, 1.0),
                                       Row("a", "fxaa", 33.0, 0.08, 1.5), Row("a", "ssaa4", 36.5, 0.09, 4.0)};
  const SceneVerdict v = VerdictForScene(rows, "a");
  ASSERT_TRUE(v.edge_psnr && v.flip);
  EXPECT_EQ(v.edge_psnr->winner, "ssaa4");
  EXPECT_DOUBLE_EQ(v.edge_psnr->value - *v.edge_psnr->none_value, 6.5);
  EXPECT_DOUBLE_EQ(v.edge_psnr->time_ms, 4.0);
  EXPECT_EQ(v.flip->winner, "fxaa");
  EXPECT_TRUE(v.disagree);
  EXPECT_EQ(v.line,
            "edge PSNR → ssaa4 36.50 dB (+6.50 dB over none, 4.00 ms, +3.00 ms over none); "
            "FLIP → fxaa 0.0800 (-0.0200 vs none, 1.50 ms, +0.500 ms over none); "
            "the axes disagree: edge PSNR picks ssaa4, FLIP picks fxaa (look at both images)");
}

TEST(Verdict, TiesWithinDisplayPrecisionAgree) {
  // 35.004 is within 0.005 dB of 35.000: a tie, the first in report order named the winner.
  // 35.010 on a third row is the best value, so the tie is measured from it: 35.004 ties, 35.000 does not.
  std::vector<ResultRow> rows = {Row("t", "none", 30.0, 0.1, 1.0), Row("t", "x", 35.000, 0.05, 2.0),
                                 Row("t", "y", 35.004, 0.05002, 3.0)};
  SceneVerdict v = VerdictForScene(rows, "t");
  ASSERT_TRUE(v.edge_psnr && v.flip);
  EXPECT_EQ(v.edge_psnr->winner, "x");
  EXPECT_EQ(v.edge_psnr->tied, std::vector<std::string>{"y"});
  EXPECT_EQ(v.flip->winner, "x");
  EXPECT_EQ(v.flip->tied, std::vector<std::string>{"y"});
  EXPECT_FALSE(v.disagree);
  EXPECT_NE(v.line.find("edge PSNR → x (tied with y) 35.00 dB"), std::string::npos) << v.line;
  EXPECT_NE(v.line.find("; both axes agree"), std::string::npos) << v.line;

  rows.push_back(Row("t", "z", 35.008, 0.2, 9.0));
  v = VerdictForScene(rows, "t");
  EXPECT_EQ(v.edge_psnr->winner, "y");
  EXPECT_EQ(v.edge_psnr->tied, std::vector<std::string>{"z"});
  // FLIP still picks x (tied with y); y wins edge PSNR too, so the axes agree through the tie.
  EXPECT_FALSE(v.disagree);
}

TEST(Verdict, NullMetricsAndNotApplicableRows) {
  std::vector<ResultRow> rows = {Row("n", "none", std::nullopt, 0.10, 1.0), Row("n", "smaa", 34.0, std::nullopt, 2.0),
                                 Row("n", "fxaa", 31.0, 0.12, 1.25)};
  ResultRow na = Row("n", "msaa4", 99.0, 0.0, 0.0);
  na.not_applicable = "renders; this is an image scene";
  rows.push_back(na);
  const SceneVerdict v = VerdictForScene(rows, "n");
  ASSERT_TRUE(v.edge_psnr && v.flip);
  EXPECT_EQ(v.edge_psnr->winner, "smaa");
  EXPECT_FALSE(v.edge_psnr->none_value);
  EXPECT_EQ(v.flip->winner, "none");
  EXPECT_TRUE(v.disagree);
  EXPECT_EQ(v.line,
            "edge PSNR → smaa 34.00 dB (none has no value, 2.00 ms, +1.00 ms over none); "
            "FLIP → none 0.1000 (no method beats none); "
            "the axes disagree: edge PSNR picks smaa, FLIP picks none (look at both images)");

  // No FLIP anywhere, and no none row.
  const std::vector<ResultRow> nf = {Row("f", "fxaa", 31.0, std::nullopt, 1.25),
                                     Row("f", "smaa", 32.0, std::nullopt, 2.0)};
  const SceneVerdict w = VerdictForScene(nf, "f");
  EXPECT_FALSE(w.flip);
  EXPECT_FALSE(w.disagree);
  EXPECT_EQ(w.line, "edge PSNR → smaa 32.00 dB (no none row, 2.00 ms); FLIP: no values");
}

TEST(Verdict, OnlyNoneAndNoRows) {
  const std::vector<ResultRow> rows = {Row("o", "none", 30.0, 0.1, 1.0)};
  SceneVerdict v = VerdictForScene(rows, "o");
  EXPECT_FALSE(v.edge_psnr);
  EXPECT_EQ(v.line, "only none ran: nothing to compare");
  v = VerdictForScene(rows, "missing");
  EXPECT_EQ(v.line, "no method ran on this scene");

  Report r;
  r.scenes.resize(2);
  r.scenes[0].name = "o";
  r.scenes[1].name = "missing";
  r.rows = rows;
  EXPECT_EQ(FormatVerdicts(Verdicts(r)),
            "verdict (edge PSNR higher is better, FLIP lower is better; times are median ms per frame):\n"
            "  o: only none ran: nothing to compare\n"
            "  missing: no method ran on this scene\n");
}

}  // namespace
}  // namespace aalab
