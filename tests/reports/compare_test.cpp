// compare: the rules of reports/compare.h on reports built in code with hand-picked numbers.
#include "reports/compare.h"
#include "reports/compare_export.h"
#include "reports/compare_page.h"
#include "reports/compare_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"

namespace aalab {
namespace {

Timing T(std::vector<double> samples) {
  Timing t;
  t.samples_ms = std::move(samples);
  t.Summarize();
  return t;
}

/// A post-filter row: render shared with none (its samples are ignored by MethodTime).
ResultRow Row(const std::string& scene, const std::string& spec, std::optional<double> psnr, const std::string& hash,
              std::vector<double> post = {1.0, 1.0, 1.0}) {
  ResultRow r;
  r.scene = scene;
  r.method = spec.substr(0, spec.find(':'));
  r.spec = spec;
  r.params = {{"edge_threshold", "0.125"}, {"search_steps", "16"}};
  r.render_shared = true;
  r.render = T({5.0, 5.0, 5.0});
  r.post = T(post);
  r.resample = T({0.0, 0.0, 0.0});
  r.metrics = {{"psnr_db", psnr, psnr ? "" : "identical"}, {"mse", psnr ? std::pow(10.0, -*psnr / 10.0) : 0.0, ""}};
  r.output_hash = hash;
  r.images = {{"output", "images/" + scene + "/" + spec + ".png"}};
  return r;
}

Report Rep(std::vector<ResultRow> rows) {
  Report r;
  r.context = {{"git_commit", "abc"}, {"cpu", "Test CPU"}, {"build_type", "Release"}};
  r.settings = {{"size", "48x27"}, {"ref_spp", "16"}, {"seed", "1"}, {"threads", "2"}};
  r.rows = std::move(rows);
  for (const char* s : {"wedges", "circle"}) {
    SceneResult sc;
    sc.name = s;
    sc.images = {{"reference_png", std::string("images/") + s + "/reference.png"}};
    r.scenes.push_back(sc);
  }
  return r;
}

CompareOptions NoTime() {
  CompareOptions o;
  o.check_time = false;
  return o;
}

const CompareLine* Find(const CompareResult& r, const std::string& scene, const std::string& spec,
                        const std::string& q) {
  for (const auto& l : r.lines) {
    if (l.scene == scene && l.spec == spec && l.quantity == q) return &l;
  }
  return nullptr;
}

// Directions come from the metric registry (metrics/metric.h): exact keys only, no patterns.
TEST(Compare, DirectionTableIsExplicit) {
  for (const char* m :
       {"psnr_db", "edge_psnr_db", "interior_psnr_db", "temporal_psnr_db", "ssim", "edge_error_removed"}) {
    EXPECT_EQ(MetricDirection(m), Better::kHigher) << m;
  }
  for (const char* m : {"mse", "edge_rmse", "flip_mean", "flip_max", "abs_err_p95", "abs_err_max"}) {
    EXPECT_EQ(MetricDirection(m), Better::kLower) << m;
  }
  for (const char* m :
       {"psnr", "_psnr_db", "foo_psnr_db", "flip_", "flip_foo", "ssim2", "time_ms", "area_bias_px2", ""}) {
    EXPECT_FALSE(MetricDirection(m)) << m;
  }
  EXPECT_TRUE(IsDbMetric("edge_psnr_db"));
  EXPECT_FALSE(IsDbMetric("ssim"));
  const std::string known = KnownMetricsText();
  for (const char* m : {"psnr_db", "ssim", "flip_mean", "abs_err_p95", "higher is better", "lower is better"}) {
    EXPECT_NE(known.find(m), std::string::npos) << m;
  }
}

TEST(Compare, IdenticalReportsPass) {
  const Report a = Rep({Row("wedges", "none", 21.0, "h1"), Row("wedges", "fxaa1-p3", 22.0, "h2")});
  const CompareResult r = CompareReports(a, a, CompareOptions{});
  EXPECT_EQ(r.ExitCode(), 0);
  EXPECT_EQ(r.rows.size(), 2u);
  EXPECT_TRUE(r.rows[0].bit_identical);
  EXPECT_EQ(r.metrics, std::vector<std::string>{"psnr_db"});
  EXPECT_EQ(r.lines.size(), 4u);  // psnr_db and time per row
  for (const auto& l : r.lines) EXPECT_EQ(l.verdict, Verdict::kUnchanged);
}

TEST(Compare, QualityDropBeyondThresholdIsARegression) {
  const Report a = Rep({Row("wedges", "fxaa1-p3", 30.0, "h1")});
  // -0.25 dB with the default 0.1 dB tolerance.
  CompareResult r = CompareReports(a, Rep({Row("wedges", "fxaa1-p3", 29.75, "h2")}), NoTime());
  EXPECT_EQ(r.ExitCode(), 1);
  EXPECT_EQ(r.regressions, 1);
  const CompareLine* l = Find(r, "wedges", "fxaa1-p3", "psnr_db");
  ASSERT_NE(l, nullptr);
  EXPECT_EQ(l->verdict, Verdict::kRegression);
  EXPECT_DOUBLE_EQ(*l->delta, -0.25);
  EXPECT_TRUE(r.rows[0].regression);
  // Exactly at the tolerance (exact binary fractions): not a regression ("more than").
  CompareOptions o = NoTime();
  o.max_drop_db = 0.25;
  r = CompareReports(a, Rep({Row("wedges", "fxaa1-p3", 29.75, "h2")}), o);
  EXPECT_EQ(r.ExitCode(), 0);
  // (beyond the 0.02 dB warn level: a warning, which never fails)
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "psnr_db")->verdict, Verdict::kWarning);
  // A small drop within the tolerance (a warning: beyond 0.02 dB), and an improvement.
  r = CompareReports(a, Rep({Row("wedges", "fxaa1-p3", 29.9375, "h2")}), NoTime());
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "psnr_db")->verdict, Verdict::kWarning);
  EXPECT_EQ(r.ExitCode(), 0);
  r = CompareReports(a, Rep({Row("wedges", "fxaa1-p3", 30.5, "h2")}), NoTime());
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "psnr_db")->verdict, Verdict::kImproved);
  EXPECT_EQ(r.improvements, 1);
  EXPECT_EQ(r.ExitCode(), 0);
}

TEST(Compare, BitIdenticalOutputIsUnchangedAtOnce) {
  // Same hash, different value: the reference (or the metric) changed, not the method.
  const CompareResult r = CompareReports(Rep({Row("wedges", "fxaa1-p3", 30.0, "same")}),
                                         Rep({Row("wedges", "fxaa1-p3", 25.0, "same")}), NoTime());
  EXPECT_EQ(r.ExitCode(), 0);
  EXPECT_TRUE(r.rows[0].bit_identical);
  const CompareLine* l = Find(r, "wedges", "fxaa1-p3", "psnr_db");
  EXPECT_EQ(l->verdict, Verdict::kUnchanged);
  EXPECT_NE(l->note.find("bit-identical"), std::string::npos);
  ASSERT_EQ(r.notes.size(), 2u);  // "time not compared", then the bit-identical note
  EXPECT_NE(r.notes[1].find("1 value(s) of rows with bit-identical output differ"), std::string::npos) << r.notes[1];
  EXPECT_NE(r.notes[1].find("wedges / fxaa1-p3 psnr_db 30.000 -> 25.000"), std::string::npos) << r.notes[1];
}

TEST(Compare, MissingAndExtraRowsAreListedByNameAndExit2) {
  const Report a = Rep({Row("wedges", "none", 21.0, "h1"), Row("wedges", "fxaa1-p3", 22.0, "h2"),
                        Row("circle", "fxaa1-p3", 26.0, "h3")});
  const Report b = Rep({Row("wedges", "none", 21.0, "h1"), Row("wedges", "fxaa1-p3:edge_threshold=0.5", 22.0, "h4")});
  const CompareResult r = CompareReports(a, b, NoTime());
  EXPECT_EQ(r.ExitCode(), 2);
  EXPECT_EQ(r.missing_rows, (std::vector<std::string>{"wedges / fxaa1-p3", "circle / fxaa1-p3"}));
  EXPECT_EQ(r.extra_rows, std::vector<std::string>{"wedges / fxaa1-p3:edge_threshold=0.5"});
  EXPECT_EQ(r.rows.size(), 1u);  // the matching row is still compared
  const std::string text = FormatCompareText(r, a, b, "a.json", "b.json", false);
  for (const char* s : {"missing from the current report (2 rows)", "circle / fxaa1-p3", "extra in the current report",
                        "exit 2 (could not compare)"}) {
    EXPECT_NE(text.find(s), std::string::npos) << s << "\n" << text;
  }
}

TEST(Compare, DifferentSettingsOrSchemaCannotBeCompared) {
  const Report a = Rep({Row("wedges", "none", 21.0, "h1")});
  for (const char* key : {"size", "ref_spp", "seed"}) {
    Report b = a;
    for (auto& kv : b.settings) {
      if (kv.first == key) kv.second = std::string(1, '7');  // (not `= "7"`: GCC 12 -Wrestrict false positive)
    }
    const CompareResult r = CompareReports(a, b, CompareOptions{});
    EXPECT_EQ(r.ExitCode(), 2) << key;
    ASSERT_EQ(r.cannot_compare.size(), 1u) << key;
    EXPECT_NE(r.cannot_compare[0].find(std::string("setting '") + key + "' differs"), std::string::npos)
        << r.cannot_compare[0];
    EXPECT_TRUE(r.lines.empty());
  }
  Report b = a;
  b.schema_version = 2;
  CompareResult r = CompareReports(a, b, CompareOptions{});
  EXPECT_EQ(r.ExitCode(), 2);
  EXPECT_NE(r.cannot_compare[0].find("schema_version differs"), std::string::npos);
  b = a;
  b.settings.erase(b.settings.begin());  // no size
  r = CompareReports(a, b, CompareOptions{});
  EXPECT_EQ(r.ExitCode(), 2);
  EXPECT_NE(r.cannot_compare[0].find("'size' is missing from the current report"), std::string::npos);
}

TEST(Compare, ChangedParametersOrDuplicateRowsCannotBeCompared) {
  const Report a = Rep({Row("wedges", "fxaa1-p3", 22.0, "h1")});
  Report b = a;
  b.rows[0].params[0].second = "0.1";
  CompareResult r = CompareReports(a, b, NoTime());
  EXPECT_EQ(r.ExitCode(), 2);
  ASSERT_EQ(r.cannot_compare.size(), 1u);
  EXPECT_NE(r.cannot_compare[0].find("row wedges / fxaa1-p3: resolved parameters differ (edge_threshold 0.125 -> 0.1)"),
            std::string::npos)
      << r.cannot_compare[0];
  b = a;
  b.rows.push_back(b.rows[0]);
  r = CompareReports(a, b, NoTime());
  EXPECT_EQ(r.ExitCode(), 2);
  EXPECT_NE(r.cannot_compare[0].find("holds row wedges / fxaa1-p3 twice"), std::string::npos);
}

TEST(Compare, NullIdenticalPsnrIsBetterThanAnyNumber) {
  const auto none = std::nullopt;
  // number -> identical: improved.
  CompareResult r = CompareReports(Rep({Row("wedges", "ssaa-4x4", 60.0, "h1")}),
                                   Rep({Row("wedges", "ssaa-4x4", none, "h2")}), NoTime());
  const CompareLine* l = Find(r, "wedges", "ssaa-4x4", "psnr_db");
  EXPECT_EQ(l->verdict, Verdict::kImproved);
  EXPECT_TRUE(std::isinf(*l->current));
  EXPECT_EQ(r.ExitCode(), 0);
  // identical -> any number, however high: regression.
  r = CompareReports(Rep({Row("wedges", "ssaa-4x4", none, "h1")}), Rep({Row("wedges", "ssaa-4x4", 99.0, "h2")}),
                     NoTime());
  l = Find(r, "wedges", "ssaa-4x4", "psnr_db");
  EXPECT_EQ(l->verdict, Verdict::kRegression);
  EXPECT_NE(l->note.find("identical"), std::string::npos);
  EXPECT_EQ(r.ExitCode(), 1);
  // identical -> identical (different hashes cannot both be identical in practice, but the rule holds).
  r = CompareReports(Rep({Row("wedges", "ssaa-4x4", none, "h1")}), Rep({Row("wedges", "ssaa-4x4", none, "h2")}),
                     NoTime());
  EXPECT_EQ(Find(r, "wedges", "ssaa-4x4", "psnr_db")->verdict, Verdict::kUnchanged);
}

TEST(Compare, ValueThatBecameNullForAnotherReasonIsARegression) {
  Report a = Rep({Row("wedges", "fxaa1-p3", 22.0, "h1")});
  Report b = Rep({Row("wedges", "fxaa1-p3", 22.0, "h2")});
  a.rows[0].metrics.push_back({"edge_psnr_db", 18.0, ""});
  b.rows[0].metrics.push_back({"edge_psnr_db", std::nullopt, "empty mask"});
  CompareResult r = CompareReports(a, b, NoTime());
  EXPECT_EQ(r.metrics, (std::vector<std::string>{"edge_psnr_db", "psnr_db"}));  // present in both: default
  const CompareLine* l = Find(r, "wedges", "fxaa1-p3", "edge_psnr_db");
  EXPECT_EQ(l->verdict, Verdict::kRegression);
  EXPECT_EQ(l->note, "became null: empty mask");
  EXPECT_EQ(r.ExitCode(), 1);
  // The other way round: nothing to judge, said so.
  r = CompareReports(b, a, NoTime());
  l = Find(r, "wedges", "fxaa1-p3", "edge_psnr_db");
  EXPECT_EQ(l->verdict, Verdict::kNotJudged);
  EXPECT_EQ(r.ExitCode(), 0);
}

TEST(Compare, DefaultMetricsAndMissingMetrics) {
  Report a = Rep({Row("wedges", "fxaa1-p3", 22.0, "h1")});
  Report b = a;
  b.rows[0].metrics.push_back({"edge_psnr_db", 18.0, ""});
  // edge_psnr_db only in the current report: the default falls back to psnr_db.
  CompareResult r = CompareReports(a, b, NoTime());
  EXPECT_EQ(r.metrics, std::vector<std::string>{"psnr_db"});
  EXPECT_EQ(r.ExitCode(), 0);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes[0].find("edge_psnr_db not compared: the baseline report does not have it"), std::string::npos)
      << r.notes[0];
  // Asked for explicitly: could not compare, naming the metric and a row.
  CompareOptions o = NoTime();
  o.metrics = {"edge_psnr_db"};
  ValidateCompareOptions(o);
  r = CompareReports(a, b, o);
  EXPECT_EQ(r.ExitCode(), 2);
  ASSERT_EQ(r.cannot_compare.size(), 1u);
  EXPECT_NE(r.cannot_compare[0].find("metric 'edge_psnr_db' is missing from 1 baseline row(s), e.g. wedges / fxaa1-p3"),
            std::string::npos)
      << r.cannot_compare[0];
}

TEST(Compare, NonDbMetricsNeedATolerance) {
  CompareOptions o;
  o.metrics = {"psnr_db", "mse"};
  try {
    ValidateCompareOptions(o);
    FAIL() << "mse without --max-metric-change was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-metric-change"), std::string::npos) << e.what();
  }
  o.metrics = {"psnr"};
  try {
    ValidateCompareOptions(o);
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown metric 'psnr'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("edge_psnr_db"), std::string::npos);  // lists the known ones
  }
  o.metrics = {"psnr_db", "psnr_db"};
  EXPECT_THROW(ValidateCompareOptions(o), UserError);
  o = CompareOptions{};
  o.metric_change = ParseMetricChangeOption("1%");
  EXPECT_THROW(ValidateCompareOptions(o), UserError);  // no non-dB metric to apply it to
  EXPECT_THROW(ParseMetricChangeOption("psnr_db=0.1"), UserError);
  EXPECT_THROW(ParseMetricChangeOption("nope=0.1"), UserError);
  EXPECT_THROW(ParseMetricChangeOption("ssim=0.1,ssim=0.2"), UserError);
  EXPECT_THROW(ParseMetricChangeOption("-1"), UserError);
  EXPECT_THROW(ParseMetricChangeOption("abc"), UserError);

  // mse (lower is better) with a relative 5% tolerance: +4% within, +6% regression, -6% improved.
  o = NoTime();
  o.metrics = {"mse"};
  o.metric_change = ParseMetricChangeOption("mse=5%");
  ValidateCompareOptions(o);
  auto with_mse = [](double mse, const std::string& hash) {
    Report r = Rep({Row("wedges", "fxaa1-p3", 22.0, hash)});
    r.rows[0].metrics[1].value = mse;
    return r;
  };
  auto verdict = [&](double cur) {
    return Find(CompareReports(with_mse(0.01, "a"), with_mse(cur, "b"), o), "wedges", "fxaa1-p3", "mse")->verdict;
  };
  EXPECT_EQ(verdict(0.0104), Verdict::kWarning);  // beyond half the tolerance (2.5%): a warning
  EXPECT_EQ(verdict(0.0102), Verdict::kWithin);
  EXPECT_EQ(verdict(0.0106), Verdict::kRegression);
  EXPECT_EQ(verdict(0.0094), Verdict::kImproved);
  // Absolute tolerance for every non-dB metric.
  o.metric_change = ParseMetricChangeOption("0.001");
  EXPECT_EQ(verdict(0.0109), Verdict::kWarning);
  EXPECT_EQ(verdict(0.0104), Verdict::kWithin);
  EXPECT_EQ(verdict(0.0111), Verdict::kRegression);
}

CompareOptions GateAny() {
  CompareOptions o;
  o.fail_on = CompareOptions::FailOn::kAny;
  return o;
}

TEST(Compare, TimeIncreaseWithinTheRepeatsSpreadIsNoise) {
  auto time_verdict = [](std::vector<double> base, std::vector<double> cur, CompareOptions o = GateAny()) {
    const CompareResult r = CompareReports(Rep({Row("wedges", "fxaa1-p3", 22.0, "h", base)}),
                                           Rep({Row("wedges", "fxaa1-p3", 22.0, "h", cur)}), o);
    return Find(r, "wedges", "fxaa1-p3", "time_ms")->verdict;
  };
  // Median 1.1 -> 2.05 (+0.95): beyond 10% (0.11), the spreads' sum (0.2 + 0.1) and the
  // 0.5 ms floor: regression.
  EXPECT_EQ(time_verdict({1.0, 1.1, 1.2}, {2.0, 2.05, 2.1}), Verdict::kRegression);
  // +0.25 ms is under the 0.5 ms floor however steady the runs are ...
  EXPECT_EQ(time_verdict({1.0, 1.1, 1.2}, {1.3, 1.35, 1.4}), Verdict::kWithin);
  // ... and without a floor, under the spreads' sum (0.2 + 0.1 = 0.3 ms).
  CompareOptions no_floor = GateAny();
  no_floor.time_floor_ms = 0;
  EXPECT_EQ(time_verdict({1.0, 1.1, 1.2}, {1.3, 1.35, 1.4}, no_floor), Verdict::kWithin);
  // +0.45 ms > 0.3 ms: regression without the floor.
  EXPECT_EQ(time_verdict({1.0, 1.1, 1.2}, {1.5, 1.55, 1.6}, no_floor), Verdict::kRegression);
  // Same medians, but the baseline's repeats spread over 0.6 ms (1.0..1.6): noise.
  EXPECT_EQ(time_verdict({1.0, 1.1, 1.6}, {1.5, 1.55, 1.6}, no_floor), Verdict::kWithin);
  // ... or the current run's (1.2..2.1).
  EXPECT_EQ(time_verdict({1.0, 1.1, 1.2}, {1.2, 1.55, 2.1}, no_floor), Verdict::kWithin);
  // +5% is below the 10% threshold however steady the runs are.
  EXPECT_EQ(time_verdict({10.0, 10.0, 10.0}, {10.5, 10.5, 10.5}), Verdict::kWithin);
  // Faster beyond everything: improved.
  EXPECT_EQ(time_verdict({2.0, 2.05, 2.1}, {1.0, 1.1, 1.2}), Verdict::kImproved);
  // Absolute threshold in ms.
  CompareOptions o = no_floor;
  o.time_increase = ParseTimeThreshold("0.5ms", "--max-time-increase");
  EXPECT_EQ(time_verdict({1.0, 1.1, 1.2}, {1.5, 1.55, 1.6}, o), Verdict::kWithin);
  o.time_increase = ParseTimeThreshold("0.4ms", "--max-time-increase");
  EXPECT_EQ(time_verdict({1.0, 1.1, 1.2}, {1.5, 1.55, 1.6}, o), Verdict::kRegression);
  EXPECT_THROW(ParseTimeThreshold("10", "--max-time-increase"), UserError);
  EXPECT_THROW(ParseTimeThreshold("x%", "--max-time-increase"), UserError);
  EXPECT_THROW(ParseTimeThreshold("-5%", "--max-time-increase"), UserError);
  // Bit-identical outputs: quality unchanged at once, time still checked when gated.
  const Report a = Rep({Row("wedges", "fxaa1-p3", 22.0, "same", {1.0, 1.1, 1.2})});
  const Report b = Rep({Row("wedges", "fxaa1-p3", 22.0, "same", {2.0, 2.05, 2.1})});
  CompareResult r = CompareReports(a, b, GateAny());
  EXPECT_TRUE(r.rows[0].bit_identical);
  EXPECT_EQ(r.ExitCode(), 1);
  EXPECT_EQ(r.regressions, 1);
  // The default gates quality only: the same time regression is a warning, exit 0.
  r = CompareReports(a, b, CompareOptions{});
  EXPECT_EQ(r.ExitCode(), 0);
  EXPECT_EQ(r.regressions, 0);
  EXPECT_EQ(r.warnings, 1);
  const CompareLine* l = Find(r, "wedges", "fxaa1-p3", "time_ms");
  EXPECT_EQ(l->verdict, Verdict::kWarning);
  EXPECT_FALSE(l->gated);
  EXPECT_NE(l->note.find("not gated (--fail-on quality)"), std::string::npos) << l->note;
  // --fail-on time: a quality regression is then a warning.
  CompareOptions t;
  t.fail_on = CompareOptions::FailOn::kTime;
  r = CompareReports(Rep({Row("wedges", "fxaa1-p3", 30.0, "h1")}), Rep({Row("wedges", "fxaa1-p3", 29.0, "h2")}), t);
  EXPECT_EQ(r.ExitCode(), 0);
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "psnr_db")->verdict, Verdict::kWarning);
  EXPECT_EQ(ParseFailOn("any"), CompareOptions::FailOn::kAny);
  EXPECT_THROW(ParseFailOn("all"), UserError);
  // Gating time with time off is a contradiction.
  CompareOptions bad = GateAny();
  bad.check_time = false;
  EXPECT_THROW(ValidateCompareOptions(bad), UserError);
}

TEST(Compare, WarnLevelBelowTheFailLevel) {
  const Report a = Rep({Row("wedges", "fxaa1-p3", 30.0, "h1")});
  // -0.0625 dB: beyond the 0.02 dB warn level, within the 0.1 dB fail level.
  CompareResult r = CompareReports(a, Rep({Row("wedges", "fxaa1-p3", 29.9375, "h2")}), NoTime());
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "psnr_db")->verdict, Verdict::kWarning);
  EXPECT_EQ(r.warnings, 1);
  EXPECT_EQ(r.ExitCode(), 0);
  // -0.015625 dB: within both.
  r = CompareReports(a, Rep({Row("wedges", "fxaa1-p3", 29.984375, "h2")}), NoTime());
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "psnr_db")->verdict, Verdict::kWithin);
  // Non-dB metrics warn at half their tolerance: mse 10% tolerance, +6% is a warning.
  CompareOptions o = NoTime();
  o.metrics = {"mse"};
  o.metric_change["mse"] = Threshold{0.10, true};
  Report m1 = a, m2 = a;
  m2.rows[0].output_hash = "h2";
  m2.rows[0].metrics[1].value = *m1.rows[0].metrics[1].value * 1.06;
  r = CompareReports(m1, m2, o);
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "mse")->verdict, Verdict::kWarning);
  m2.rows[0].metrics[1].value = *m1.rows[0].metrics[1].value * 1.04;
  EXPECT_EQ(Find(CompareReports(m1, m2, o), "wedges", "fxaa1-p3", "mse")->verdict, Verdict::kWithin);
  // The warn level may not exceed the fail level.
  o = NoTime();
  o.warn_drop_db = 0.2;
  EXPECT_THROW(ValidateCompareOptions(o), UserError);
}

TEST(Compare, MapComparesRenamedRows) {
  std::map<std::string, std::string> map;
  AddSpecMapping("fxaa311-p39=fxaa311-p39:subpix=0", &map);
  AddSpecMapping("a:x=1,y=2=b:z=3", &map);
  EXPECT_EQ(map.at("fxaa311-p39"), "fxaa311-p39:subpix=0");
  EXPECT_EQ(map.at("a:x=1,y=2"), "b:z=3");
  for (const char* bad : {"fxaa311-p39", "=b", "a=", "a:x=b"}) {
    std::map<std::string, std::string> m;
    EXPECT_THROW(AddSpecMapping(bad, &m), UserError) << bad;
  }
  EXPECT_THROW(AddSpecMapping("fxaa311-p39=c", &map), UserError);  // mapped twice

  const Report base = Rep({Row("wedges", "none", 20.0, "n"), Row("wedges", "fxaa311-p39", 30.0, "h1")});
  ResultRow renamed = Row("wedges", "fxaa311-p39:subpix=0", 29.5, "h2");
  renamed.params.emplace_back("subpix", "0");
  const Report cur = Rep({Row("wedges", "none", 20.0, "n"), renamed});
  // Without the map: one missing, one extra row.
  CompareResult r = CompareReports(base, cur, NoTime());
  EXPECT_EQ(r.ExitCode(), 2);
  ASSERT_EQ(r.missing_rows.size(), 1u);
  EXPECT_EQ(r.missing_rows[0], "wedges / fxaa311-p39");
  // With it: compared (-0.5 dB: a regression), the parameter change said in a note.
  CompareOptions o = NoTime();
  o.map = {{"fxaa311-p39", "fxaa311-p39:subpix=0"}};
  r = CompareReports(base, cur, o);
  EXPECT_EQ(r.ExitCode(), 1);
  const CompareLine* l = Find(r, "wedges", "fxaa311-p39:subpix=0", "psnr_db");
  ASSERT_NE(l, nullptr);
  EXPECT_EQ(l->base_spec, "fxaa311-p39");
  EXPECT_DOUBLE_EQ(*l->delta, -0.5);
  bool noted = false;
  for (const auto& n : r.notes)
    noted =
        noted ||
        n.find("mapped fxaa311-p39 (baseline) -> fxaa311-p39:subpix=0 (current): parameters subpix (absent) -> 0") !=
            std::string::npos;
  EXPECT_TRUE(noted);
  EXPECT_NE(FormatCompareText(r, base, cur, "a", "b", false).find("fxaa311-p39 -> fxaa311-p39:subpix=0"),
            std::string::npos);
  // A map naming a row that is not there cannot compare, and lists the specs there are.
  o.map = {{"fxaa311-p39", "fxaa311-p39:subpix=1"}};
  r = CompareReports(base, cur, o);
  EXPECT_EQ(r.ExitCode(), 2);
  ASSERT_FALSE(r.cannot_compare.empty());
  EXPECT_NE(r.cannot_compare[0].find("no row of spec 'fxaa311-p39:subpix=1' (its specs: fxaa311-p39:subpix=0, none)"),
            std::string::npos)
      << r.cannot_compare[0];
}

TEST(Compare, StrictFailsOnCaptureWarningsAndMachineReadableResults) {
  const Report a = Rep({Row("wedges", "fxaa1-p3", 30.0, "h1")});
  Report b = Rep({Row("wedges", "fxaa1-p3", 29.5, "h2")});
  b.scenes[0].warnings = {"mean interior bias 0.03"};
  CompareOptions o = NoTime();
  o.max_drop_db = 1.0;
  CompareResult r = CompareReports(a, b, o);
  EXPECT_EQ(r.ExitCode(), 0);
  ASSERT_EQ(r.capture_warnings.size(), 1u);
  EXPECT_EQ(r.capture_warnings[0], "wedges: mean interior bias 0.03");
  o.strict = true;
  r = CompareReports(a, b, o);
  EXPECT_EQ(r.ExitCode(), 1);
  const auto j = CompareToJson(r, "base.json", "cur.json");
  EXPECT_EQ(j["exit_code"], 1);
  EXPECT_EQ(j["verdict"], "regression");
  EXPECT_EQ(j["fail_on"], "quality");
  EXPECT_EQ(j["lines"][0]["quantity"], "psnr_db");
  EXPECT_DOUBLE_EQ(j["lines"][0]["delta"].get<double>(), -0.5);
  EXPECT_EQ(j["lines"][0]["verdict"], "warning");  // -0.5 dB: beyond 0.02 dB, within 1 dB
  const std::string x = CompareToJUnit(r, "base.json", "cur.json");
  EXPECT_NE(x.find("<testsuite name=\"aalab compare\" tests=\"3\" failures=\"1\" errors=\"0\""), std::string::npos)
      << x;
  EXPECT_NE(x.find("<testcase classname=\"wedges\" name=\"fxaa1-p3\">"), std::string::npos) << x;
  EXPECT_NE(x.find("<failure type=\"capture warning\" message=\"wedges: mean interior bias 0.03\"/>"),
            std::string::npos);
  // A gated regression is a <failure> of its row; could-not-compare items are <error>s.
  o.max_drop_db = 0.1;
  o.strict = false;
  r = CompareReports(a, Rep({Row("wedges", "fxaa1-p3", 29.5, "h2"), Row("circle", "none", 1.0, "z")}), o);
  const std::string y = CompareToJUnit(r, "a", "b");
  EXPECT_NE(
      y.find("<failure type=\"regression\" message=\"psnr_db 30.000 -&gt; 29.500 (-0.500), threshold -0.100 dB\"/>"),
      std::string::npos)
      << y;
  EXPECT_NE(y.find("<error type=\"could not compare\" message=\"row not in the baseline: circle / none\"/>"),
            std::string::npos)
      << y;
  EXPECT_EQ(CompareToJson(r, "a", "b")["exit_code"], 2);
}

TEST(Compare, MethodTimeExcludesTheSharedRender) {
  ResultRow shared = Row("wedges", "fxaa1-p3", 22.0, "h", {1.0, 2.0, 3.0});
  EXPECT_DOUBLE_EQ(MethodTime(shared).median_ms, 2.0);
  ResultRow own = shared;
  own.render_shared = false;  // e.g. SSAA: the render is the method's
  EXPECT_DOUBLE_EQ(MethodTime(own).median_ms, 7.0);
  // A slower shared 1x render does not make every post filter a regression.
  Report a = Rep({shared}), b = Rep({shared});
  b.rows[0].render = T({50.0, 50.0, 50.0});
  EXPECT_EQ(CompareReports(a, b, CompareOptions{}).ExitCode(), 0);
  a.rows[0] = own;
  b.rows[0] = own;
  b.rows[0].render = T({50.0, 50.0, 50.0});
  EXPECT_EQ(CompareReports(a, b, GateAny()).ExitCode(), 1);
  EXPECT_EQ(CompareReports(a, b, CompareOptions{}).ExitCode(), 0);  // time is not gated by default
}

TEST(Compare, TimeIsNotJudgedAcrossMachines) {
  Report a = Rep({Row("wedges", "fxaa1-p3", 22.0, "h", {1.0, 1.0, 1.0})});
  Report b = Rep({Row("wedges", "fxaa1-p3", 22.0, "h", {3.0, 3.0, 3.0})});
  b.context["cpu"] = "Other CPU";
  CompareResult r = CompareReports(a, b, CompareOptions{});
  EXPECT_EQ(r.ExitCode(), 0);
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "time_ms")->verdict, Verdict::kNotJudged);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes[0].find("time not judged"), std::string::npos);
  EXPECT_NE(r.notes[0].find("Other CPU"), std::string::npos);
  CompareOptions o = GateAny();
  o.time_across_machines = true;
  EXPECT_EQ(CompareReports(a, b, o).ExitCode(), 1);
  b.context["cpu"] = "Test CPU";
  b.settings.back().second = "8";  // threads
  EXPECT_EQ(CompareReports(a, b, CompareOptions{}).ExitCode(), 0);
  // --max-time-increase off: no time lines at all, and a note says so.
  r = CompareReports(a, b, NoTime());
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "time_ms"), nullptr);
  EXPECT_NE(r.notes[0].find("time not compared"), std::string::npos);
}

TEST(Compare, TextTableAndHtml) {
  const Report a = Rep({Row("wedges", "none", 21.0, "h1"), Row("wedges", "fxaa1-p3", 30.0, "h2")});
  const Report b = Rep({Row("wedges", "none", 21.0, "h1"), Row("wedges", "fxaa1-p3", 29.5, "h3")});
  const CompareResult r = CompareReports(a, b, NoTime());
  const std::string text = FormatCompareText(r, a, b, "base.json", "cur.json", false);
  for (const char* s : {"scene", "method", "metric", "baseline", "current", "delta", "threshold", "verdict", "fxaa1-p3",
                        "30.000", "29.500", "-0.500", "-0.100 dB", "REGRESSION", "exit 1 (regression)"}) {
    EXPECT_NE(text.find(s), std::string::npos) << s << "\n" << text;
  }
  EXPECT_EQ(text.find("wedges  none "), std::string::npos) << "unchanged rows are not listed\n" << text;
  auto images = CompareHtmlImages(r, a, b, "/base", "/cur");
  ASSERT_EQ(images.size(), 1u);  // only the changed row
  ASSERT_EQ(images[0].size(), 3u);
  EXPECT_EQ(images[0][0].source, "/base/images/wedges/fxaa1-p3.png");
  EXPECT_EQ(images[0][1].source, "/cur/images/wedges/fxaa1-p3.png");
  EXPECT_EQ(images[0][2].source, "/cur/images/wedges/reference.png");
  images[0][0].href = "cmp_files/row1-baseline-output.png";
  images[0][1].missing = "file not found: /cur/images/wedges/fxaa1-p3.png";
  images[0][2].href = "cmp_files/row1-reference.png";
  const std::string html = CompareHtml(r, images, "base.json", "cur.json");
  for (const char* s : {"<img src=\"cmp_files/row1-baseline-output.png\"", "not available: file not found",
                        "cmp_files/row1-reference.png", "wedges / fxaa1-p3", "REGRESSION"}) {
    EXPECT_NE(html.find(s), std::string::npos) << s;
  }
  EXPECT_EQ(html.find("http"), std::string::npos) << "offline page: no external references";
}

}  // namespace
}  // namespace aalab

namespace aalab {
namespace {

TEST(Compare, PerceptualMeasuresAsObjective) {
  // flip_mean and the perceptual temporal error are lower-is-better and have a default 5 %
  // tolerance, so `--metrics psnr_db,flip_mean` needs no --max-metric-change.
  EXPECT_EQ(MetricDirection("temporal_perceptual"), Better::kLower);
  EXPECT_EQ(MetricDirection("temporal_csf_rmse"), Better::kLower);
  CompareOptions o = NoTime();
  o.metrics = {"psnr_db", "flip_mean"};
  EXPECT_NO_THROW(ValidateCompareOptions(o));
  // A change that sharpens PSNR by 0.5 dB but raises FLIP by 10 % (0.040 → 0.044: more
  // than 5 %) is a regression by FLIP and an improvement by PSNR.
  ResultRow a = Row("wedges", "fxaa1-p3", 30.0, "h1"), b = Row("wedges", "fxaa1-p3", 30.5, "h2");
  a.metrics.push_back({"flip_mean", 0.040, ""});
  b.metrics.push_back({"flip_mean", 0.044, ""});
  const CompareResult r = CompareReports(Rep({a}), Rep({b}), o);
  EXPECT_EQ(r.ExitCode(), 1);
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "flip_mean")->verdict, Verdict::kRegression);
  EXPECT_EQ(Find(r, "wedges", "fxaa1-p3", "psnr_db")->verdict, Verdict::kImproved);
}

TEST(Compare, ViewingConditionMustAgree) {
  // FLIP depends on the pixels per degree: reports of two viewing conditions are not
  // comparable; a report without the setting (written before it existed) counts as 67.
  Report a = Rep({Row("wedges", "none", 21.0, "h1")}), b = a;
  b.settings.push_back({"ppd", "55.04364145434214"});
  const CompareResult r = CompareReports(a, b, NoTime());
  EXPECT_EQ(r.ExitCode(), 2);
  ASSERT_FALSE(r.cannot_compare.empty());
  EXPECT_NE(r.cannot_compare[0].find("setting 'ppd' differs: baseline 67, current 55.04"), std::string::npos)
      << r.cannot_compare[0];
  Report c = a;
  c.settings.push_back({"ppd", "67"});
  EXPECT_EQ(CompareReports(a, c, NoTime()).ExitCode(), 0);
}

}  // namespace
}  // namespace aalab
