// history: JSON-lines round trip, series rules, malformed lines, the trend page.
#include "reports/history.h"
#include "reports/history_page.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace aalab {
namespace {

Timing T(std::vector<double> s) {
  Timing t;
  t.samples_ms = std::move(s);
  t.Summarize();
  return t;
}

Report Rep(double psnr, const std::string& hash, const std::string& size = "48x27") {
  Report r;
  r.context = {{"git_commit", "c0ffee"}, {"cpu", "Test CPU"}, {"build_type", "Release"}};
  r.settings = {{"suite", "(custom)"}, {"scenes", "wedges"}, {"methods", "none, fxaa1-p3"},
                {"size", size},        {"ref_spp", "16"},    {"seed", "1"},
                {"threads", "2"}};
  for (const char* spec : {"none", "fxaa1-p3"}) {
    ResultRow row;
    row.scene = "wedges";
    row.method = spec;
    row.spec = spec;
    row.params = {{"edge_threshold", "0.125"}};
    row.render_shared = std::string(spec) != "none";
    row.render = T({1.0, 1.5, 1.25});
    row.post = T({0.5, 0.25, 0.75});
    row.resample = T({0, 0, 0});
    row.total = T({1.5, 1.75, 2.0});
    row.metrics = {{"psnr_db", psnr, ""}, {"mse", 0.01, ""}, {"edge_psnr_db", std::nullopt, "identical"}};
    row.output_hash = hash + spec;
    row.images = {{"output", "images/x.png"}};
    r.rows.push_back(row);
  }
  SceneResult s;
  s.name = "wedges";
  r.scenes.push_back(s);
  return r;
}

TEST(History, RoundTripsTwoEntries) {
  const HistoryEntry a = HistoryEntryFromReport(Rep(30.0, "a"), "default", "c0ffee", "2026-01-02T03:04:05Z", "a.json");
  const HistoryEntry b = HistoryEntryFromReport(Rep(29.0, "b"), "default", "beef", "2026-01-03", "b.json");
  CheckSeriesCompatible({a}, b);
  const std::string text = HistoryLine(a) + "\n" + HistoryLine(b) + "\n";
  EXPECT_EQ(text.find("images/x.png"), std::string::npos) << "no images in the history";
  const auto entries = ParseHistory(text, "db");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].line, 1);
  EXPECT_EQ(entries[1].line, 2);
  EXPECT_EQ(entries[1].commit, "beef");
  EXPECT_EQ(entries[1].date, "2026-01-03");
  EXPECT_EQ(entries[0].series, "default");
  EXPECT_EQ(entries[0].source, "a.json");
  EXPECT_EQ(SettingValue(entries[0].report, "size"), "48x27");
  ASSERT_EQ(entries[1].report.rows.size(), 2u);
  const ResultRow& r = entries[1].report.rows[1];
  EXPECT_EQ(r.spec, "fxaa1-p3");
  EXPECT_EQ(r.output_hash, "bfxaa1-p3");
  EXPECT_TRUE(r.render_shared);
  EXPECT_EQ(r.params, (std::vector<std::pair<std::string, std::string>>{{"edge_threshold", "0.125"}}));
  EXPECT_EQ(r.post.samples_ms, (std::vector<double>{0.5, 0.25, 0.75}));
  EXPECT_DOUBLE_EQ(r.post.median_ms, 0.5);
  ASSERT_EQ(r.metrics.size(), 3u);
  EXPECT_DOUBLE_EQ(*r.metrics[0].value, 29.0);
  EXPECT_FALSE(r.metrics[2].value);
  EXPECT_EQ(r.metrics[2].null_reason, "identical");
  // Written again, the same line.
  EXPECT_EQ(HistoryLine(entries[0]), HistoryLine(a));
}

TEST(History, MalformedLinesAreErrorsNamingTheLine) {
  const std::string good =
      HistoryLine(HistoryEntryFromReport(Rep(30.0, "a"), "default", "c0ffee", "2026-01-02", "a.json"));
  auto expect_error = [](const std::string& text, const std::string& part) {
    try {
      ParseHistory(text, "history database 'h.jsonl'");
      FAIL() << "accepted: " << text.substr(0, 80);
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expect_error(good + "\n{not json\n", "'h.jsonl' line 2: malformed JSON");
  expect_error(good + "\n\n" + good + "\n", "line 2: empty line");
  expect_error(good + "\n{\"history_version\": 1}\n", "line 2: not a history entry");
  expect_error("{\"history_version\": 9}\n", "line 1: history_version 9 is not supported");
  EXPECT_EQ(ParseHistory("", "x").size(), 0u);
  EXPECT_EQ(ParseHistory(good, "x").size(), 1u);  // no final newline is fine
}

TEST(History, SeriesMustAgreeOnSettings) {
  const HistoryEntry a = HistoryEntryFromReport(Rep(30.0, "a"), "default", "c0ffee", "2026-01-02", "a.json");
  const HistoryEntry small = HistoryEntryFromReport(Rep(30.0, "a", "16x9"), "default", "beef", "2026-01-03", "s.json");
  try {
    CheckSeriesCompatible({a}, small);
    FAIL() << "a report with another size joined the series";
  } catch (const UserError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("size: series 48x27, report 16x9"), std::string::npos) << m;
    EXPECT_NE(m.find("--series NAME"), std::string::npos) << m;
  }
  // Another series is fine.
  const HistoryEntry other = HistoryEntryFromReport(Rep(30.0, "a", "16x9"), "small", "beef", "2026-01-03", "s.json");
  CheckSeriesCompatible({a}, other);
  // The same commit and date twice is refused.
  EXPECT_THROW(CheckSeriesCompatible({a}, a), UserError);
  // Entry validation.
  EXPECT_THROW(HistoryEntryFromReport(Rep(30.0, "a"), "default", "unknown", "2026-01-02", "a.json"), UserError);
  EXPECT_THROW(HistoryEntryFromReport(Rep(30.0, "a"), "bad name", "c0ffee", "2026-01-02", "a.json"), UserError);
  EXPECT_THROW(HistoryEntryFromReport(Rep(30.0, "a"), "default", "c0ffee", "yesterday", "a.json"), UserError);
  EXPECT_THROW(HistoryEntryFromReport(Rep(30.0, "a"), "default", "c0ffee", "2026-01-02T03:04:05", "a.json"), UserError);
}

TEST(History, TrendPageMarksThresholdCrossings) {
  std::vector<HistoryEntry> es;
  es.push_back(HistoryEntryFromReport(Rep(30.0, "a"), "default", "c1", "2026-01-01", "1.json"));
  es.push_back(HistoryEntryFromReport(Rep(30.05, "b"), "default", "c2", "2026-01-02", "2.json"));  // within 0.1 dB
  es.push_back(HistoryEntryFromReport(Rep(29.0, "c"), "default", "c3", "2026-01-03", "3.json"));   // -1.05 dB
  es.push_back(HistoryEntryFromReport(Rep(31.0, "d", "16x9"), "small", "c3", "2026-01-03", "4.json"));
  const HistoryPage page = HistoryHtml(es, "", CompareOptions{});
  EXPECT_EQ(page.series, 2);
  EXPECT_EQ(page.entries, 4);
  // psnr_db of both rows dropped at c3; edge_psnr_db stays identical (infinite); timing unchanged.
  EXPECT_EQ(page.regressions, 2);
  EXPECT_EQ(page.improvements, 0);
  // Per series: 2 rows x (edge_psnr_db, psnr_db, time).
  EXPECT_EQ(page.charts, 12);
  for (const char* s : {"<svg", "series default", "series small", "wedges / fxaa1-p3", "#d00020",
                        "REGRESSION vs previous", "c3 2026-01-03", "&#8734;"}) {
    EXPECT_NE(page.html.find(s), std::string::npos) << s;
  }
  // fxaa1-p3's line and markers in its colour and marker, as on every page (html_method_style.h:
  // fxaa1's #e69f00; FNV-1a("fxaa1-p3") % 5 = 3 → the fourth non-circle shape, worked out by hand
  // in Python), a regression filled red.
  for (const char* s : {"stroke=\"#e69f00\" stroke-width=\"1.5\"", "data-marker=\"triangle-down\"",
                        "fill=\"#d00020\" stroke=\"#e69f00\""}) {
    EXPECT_NE(page.html.find(s), std::string::npos) << s;
  }
  const HistoryPage one = HistoryHtml(es, "small", CompareOptions{});
  EXPECT_EQ(one.series, 1);
  EXPECT_EQ(one.entries, 1);
  EXPECT_THROW(HistoryHtml(es, "nope", CompareOptions{}), UserError);
}

}  // namespace
}  // namespace aalab
