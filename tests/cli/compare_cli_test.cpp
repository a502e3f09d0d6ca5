// End-to-end tests of `aalab compare`, `aalab history` and `aalab sweep` on real (tiny) runs:
// exit codes, messages, and what is written.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_util.h"

namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using aalab::clitest::Aalab;
using aalab::clitest::CmdResult;

fs::path TempDir(const std::string& name) { return aalab::clitest::TempDir("cmp-" + name); }

Json ReadJson(const fs::path& p) {
  std::ifstream f(p);
  return Json::parse(f);
}

void WriteJson(const fs::path& p, const Json& j) { std::ofstream(p) << j.dump(2); }

/// A tiny real run; returns the report path.
fs::path RunTiny(const fs::path& out, const std::string& methods, const std::string& extra = "") {
  const CmdResult r = Aalab("run --scenes wedges,circle --methods " + methods +
                            " --size 48x27 --ref-spp 16 --repeat 3 --quiet --out " + out.string() + " " + extra);
  EXPECT_EQ(r.code, 0) << r.output;
  return out / "report.json";
}

bool Has(const CmdResult& r, const std::string& s) { return r.output.find(s) != std::string::npos; }

/// `aalab sweep ARGS --quiet --out TMP/NAME/sweep`: the folder TMP/NAME, what the sweep printed
/// and its sweep.json (null when it failed; a non-zero exit fails the test).
struct SweepRun {
  fs::path dir, out;
  CmdResult r;
  Json j;
};
SweepRun Sweep(const std::string& name, const std::string& args) {
  SweepRun s;
  s.dir = TempDir(name);
  s.out = s.dir / "sweep";
  s.r = Aalab("sweep " + args + " --quiet --out " + s.out.string());
  EXPECT_EQ(s.r.code, 0) << s.r.output;
  if (s.r.code == 0) s.j = ReadJson(s.out / "sweep.json");
  return s;
}

TEST(CompareCli, FlagsAnInjectedQualityDropAndWritesHtml) {
  const fs::path dir = TempDir("drop");
  const fs::path base = RunTiny(dir / "base", "none,fxaa1-p3");
  // The "current" build's fxaa1-p3 is worse: produced with edge_threshold=1 (FXAA skips every
  // pixel), relabelled as plain fxaa1-p3 with its usual parameters.
  const fs::path cur = RunTiny(dir / "cur", "none,fxaa1-p3:edge_threshold=1");
  Json j = ReadJson(cur);
  for (auto& row : j["rows"]) {
    if (row["spec"] == "fxaa1-p3:edge_threshold=1") {
      row["spec"] = "fxaa1-p3";
      row["params"]["edge_threshold"] = "0.125";
    }
  }
  WriteJson(cur, j);
  const fs::path html = dir / "cmp" / "compare.html";
  const CmdResult r =
      Aalab("compare " + base.string() + " " + cur.string() + " --max-time-increase off --html " + html.string());
  EXPECT_EQ(r.code, 1) << r.output;
  for (const char* s : {"wedges  fxaa1-p3  psnr_db", "circle  fxaa1-p3  psnr_db", "REGRESSION", "-0.100 dB",
                        "exit 1 (regression)", "(2 bit-identical outputs)"}) {
    EXPECT_TRUE(Has(r, s)) << s << "\n" << r.output;
  }
  EXPECT_FALSE(Has(r, "wedges  none ")) << "unchanged rows are not listed\n" << r.output;
  // The page and its copied images (offline: relative paths into compare_files/).
  ASSERT_TRUE(fs::exists(html));
  std::stringstream page;
  page << std::ifstream(html).rdbuf();
  EXPECT_NE(page.str().find("src=\"compare_files/row1-baseline-output.png\""), std::string::npos);
  EXPECT_NE(page.str().find("src=\"compare_files/row1-reference.png\""), std::string::npos);
  for (const char* f :
       {"row1-baseline-output.png", "row1-current-output.png", "row1-reference.png", "row2-current-output.png"}) {
    EXPECT_TRUE(fs::exists(dir / "cmp" / "compare_files" / f)) << f;
  }
  EXPECT_FALSE(fs::exists(dir / "cmp" / "compare_files.partial"));
  // A folder that is not ours is never replaced.
  fs::create_directories(dir / "mine_files");
  const CmdResult refused =
      Aalab("compare " + base.string() + " " + cur.string() + " --html " + (dir / "mine.html").string());
  EXPECT_EQ(refused.code, 2) << refused.output;
  EXPECT_TRUE(Has(refused, "not written by aalab compare")) << refused.output;

  // A report compared with itself: bit-identical, exit 0 (time included: equal samples).
  const CmdResult same = Aalab("compare " + base.string() + " " + base.string());
  EXPECT_EQ(same.code, 0) << same.output;
  EXPECT_TRUE(Has(same, "(4 bit-identical outputs)")) << same.output;
  // A second run of the same build: bit-identical outputs pass (time left out: it is noisy).
  const fs::path again = RunTiny(dir / "again", "none,fxaa1-p3");
  const CmdResult rerun = Aalab("compare " + base.string() + " " + again.string() + " --max-time-increase off");
  EXPECT_EQ(rerun.code, 0) << rerun.output;
  EXPECT_TRUE(Has(rerun, "no changed values")) << rerun.output;
  EXPECT_TRUE(Has(rerun, "time not compared")) << rerun.output;
}

TEST(CompareCli, MissingRowsAndMismatchedSettingsExit2) {
  const fs::path dir = TempDir("mismatch");
  const fs::path base = RunTiny(dir / "base", "none,fxaa1-p3");
  const fs::path fewer = RunTiny(dir / "fewer", "none");
  CmdResult r = Aalab("compare " + base.string() + " " + fewer.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_TRUE(Has(r, "missing from the current report (2 rows):")) << r.output;
  EXPECT_TRUE(Has(r, "  wedges / fxaa1-p3")) << r.output;
  EXPECT_TRUE(Has(r, "  circle / fxaa1-p3")) << r.output;
  r = Aalab("compare " + fewer.string() + " " + base.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_TRUE(Has(r, "extra in the current report, not in the baseline (2 rows):")) << r.output;

  // Size, seed, ref_spp, schema.
  const Json j = ReadJson(base);
  struct Case {
    const char* key;
    const char* value;
    const char* message;
  };
  for (const Case& c : {Case{"size", "96x54", "setting 'size' differs: baseline 48x27, current 96x54"},
                        Case{"seed", "2", "setting 'seed' differs: baseline 1, current 2"},
                        Case{"ref_spp", "64", "setting 'ref_spp' differs"}}) {
    Json k = j;
    k["settings"][c.key] = c.value;
    WriteJson(dir / "edited.json", k);
    r = Aalab("compare " + base.string() + " " + (dir / "edited.json").string());
    EXPECT_EQ(r.code, 2) << c.key << "\n" << r.output;
    EXPECT_TRUE(Has(r, c.message)) << r.output;
  }
  Json k = j;
  k["schema_version"] = 2;
  WriteJson(dir / "v2.json", k);
  r = Aalab("compare " + base.string() + " " + (dir / "v2.json").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_TRUE(Has(r, "schema_version 2 is not supported")) << r.output;
  // A real run at another size.
  const fs::path small = dir / "small";
  ASSERT_EQ(
      Aalab("run --scenes wedges,circle --methods none,fxaa1-p3 --size 16x9 --ref-spp 16 --repeat 1 --quiet --out " +
            small.string())
          .code,
      0);
  r = Aalab("compare " + base.string() + " " + (small / "report.json").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_TRUE(Has(r, "setting 'size' differs")) << r.output;

  // Unreadable input and bad options are "could not compare" too, never "regression".
  r = Aalab("compare " + base.string() + " " + (dir / "nope.json").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_TRUE(Has(r, "nope.json")) << r.output;
  r = Aalab("compare " + base.string() + " " + base.string() + " --metrics ssim");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_TRUE(Has(r, "--max-metric-change")) << r.output;
  r = Aalab("compare " + base.string() + " " + base.string() + " --metrics psnr");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_TRUE(Has(r, "unknown metric 'psnr'")) << r.output;
  EXPECT_TRUE(Has(r, "edge_psnr_db")) << r.output;
  r = Aalab("compare " + base.string() + " " + base.string() + " --max-time-increase 10");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_TRUE(Has(r, "needs a unit")) << r.output;
  // Non-dB metric with a tolerance works.
  r = Aalab("compare " + base.string() + " " + base.string() + " --metrics psnr_db,mse --max-metric-change mse=2%");
  EXPECT_EQ(r.code, 0) << r.output;
  // The rules are in --help.
  r = Aalab("compare --help");
  EXPECT_EQ(r.code, 0);
  for (const char* s : {"max - min of samples_ms", "Exit codes: 0 no regression; 1 regression (gated)",
                        "2 could not compare", "--fail-on quality (default)"}) {
    EXPECT_TRUE(Has(r, s)) << s << "\n" << r.output;
  }
}

TEST(HistoryCli, AddsReportsRejectsMismatchedSeriesAndWritesTrends) {
  const fs::path dir = TempDir("history");
  const fs::path a = RunTiny(dir / "a", "none,fxaa1-p3");
  const fs::path b = RunTiny(dir / "b", "none,fxaa1-p3");
  const fs::path db = dir / "history.jsonl";
  CmdResult r = Aalab("history add " + a.string() + " --db " + db.string() + " --commit 1111111 --date 2026-01-01");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(Has(r, "added commit 1111111")) << r.output;
  r = Aalab("history add " + b.string() + " --db " + db.string() + " --commit 2222222 --date 2026-01-02");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(Has(r, "vs previous entry (commit 1111111)")) << r.output;
  // The same commit and date again: refused.
  r = Aalab("history add " + b.string() + " --db " + db.string() + " --commit 2222222 --date 2026-01-02");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(Has(r, "already holds commit 2222222")) << r.output;
  // Two lines, one per report, with per-row metrics and times, no images.
  {
    std::ifstream f(db);
    std::string line;
    int n = 0;
    while (std::getline(f, line)) {
      const Json e = Json::parse(line);
      EXPECT_EQ(e["rows"].size(), 4u);
      EXPECT_TRUE(e["rows"][0]["metrics"].contains("psnr_db"));
      EXPECT_EQ(e["rows"][0]["timing"]["post"].size(), 3u);
      EXPECT_FALSE(e["rows"][0].contains("images"));
      ++n;
    }
    EXPECT_EQ(n, 2);
  }
  // Another size does not join the series ...
  const fs::path small = dir / "small";
  ASSERT_EQ(
      Aalab("run --scenes wedges,circle --methods none,fxaa1-p3 --size 16x9 --ref-spp 16 --repeat 1 --quiet --out " +
            small.string())
          .code,
      0);
  r = Aalab("history add " + (small / "report.json").string() + " --db " + db.string() + " --commit 3333333");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(Has(r, "does not match series 'default'")) << r.output;
  EXPECT_TRUE(Has(r, "size: series 48x27, report 16x9")) << r.output;
  EXPECT_TRUE(Has(r, "--series NAME")) << r.output;
  // ... but starts another one with --series (date from the file's modification time).
  r = Aalab("history add " + (small / "report.json").string() + " --db " + db.string() +
            " --commit 3333333 --series small");
  EXPECT_EQ(r.code, 0) << r.output;
  // The trend page.
  r = Aalab("history report --db " + db.string() + " --out " + (dir / "trend").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(Has(r, "2 series, 3 entries")) << r.output;
  std::stringstream page;
  page << std::ifstream(dir / "trend" / "index.html").rdbuf();
  for (const char* s : {"<svg", "series default", "series small", "circle / fxaa1-p3", "method time", "2222222"}) {
    EXPECT_NE(page.str().find(s), std::string::npos) << s;
  }
  // A malformed line is an error naming its number; nothing is appended.
  std::ofstream(db, std::ios::app) << "{oops\n";
  const auto size_before = fs::file_size(db);
  r = Aalab("history add " + a.string() + " --db " + db.string() + " --commit 4444444");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(Has(r, "line 4: malformed JSON")) << r.output;
  EXPECT_EQ(fs::file_size(db), size_before);
  r = Aalab("history report --db " + db.string() + " --out " + (dir / "trend").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(Has(r, "line 4")) << r.output;
}

TEST(SweepCli, PerceptualObjectiveAtAViewingCondition) {
  // flip_mean as the objective (lower is better): the best point is the one with the lowest
  // mean FLIP, computed at the viewing condition the sweep records.
  const SweepRun s = Sweep("sweep-flip",
                           "--scenes wedges,circle --method fxaa311-p39 --grid subpix=0,0.5,1 "
                           "--objective flip_mean,edge_psnr_db --viewing tv-1080p-2m --size 48x27 "
                           "--ref-spp 4 --repeat 1");
  ASSERT_EQ(s.r.code, 0);
  const CmdResult& r = s.r;
  const Json& j = s.j;
  const fs::path& dir = s.dir;
  EXPECT_EQ(j["settings"]["viewing"], "tv-1080p-2m");
  EXPECT_EQ(j["settings"]["ppd"], "55.04364145434214");  // shortest text that reads back exactly
  size_t best = 0;
  for (size_t p = 0; p < j["points"].size(); ++p) {
    if (j["points"][p]["objectives"]["flip_mean"]["mean"].get<double>() <
        j["points"][best]["objectives"]["flip_mean"]["mean"].get<double>())
      best = p;
  }
  EXPECT_EQ(j["best"]["flip_mean"]["point"], best);
  EXPECT_EQ(j["suggested_preset"], j["points"][best]["spec"]);  // the first objective drives it
  EXPECT_TRUE(Has(r, "best flip_mean (mean over 2 scenes)")) << r.output;
  fs::remove_all(dir);
}

TEST(SweepCli, RendersEachReferenceOnceAndWritesTheFront) {
  const SweepRun s = Sweep("sweep",
                           "--scenes wedges,circle --method fxaa1-p3 --grid edge_threshold=0.125,1 "
                           "--grid subpix_cap=0,0.75 --objective psnr_db,mse --size 48x27 --ref-spp 4 --repeat 1");
  ASSERT_EQ(s.r.code, 0);
  const CmdResult& r = s.r;
  const fs::path &dir = s.dir, &out = s.out;
  for (const char* s : {"4 points on 2 scenes; 2 reference renders", "best psnr_db (mean over 2 scenes)", "best mse",
                        "pareto front", "suggested preset: fxaa1-p3:edge_threshold="}) {
    EXPECT_TRUE(Has(r, s)) << s << "\n" << r.output;
  }
  const Json& j = s.j;
  EXPECT_EQ(j["reference_renders"], 2);  // one per scene, not per grid point
  EXPECT_EQ(j["points"].size(), 4u);
  ASSERT_EQ(j["rows"].size(), 8u);
  int per_scene[2] = {0, 0};
  for (const auto& row : j["rows"]) ++per_scene[row["scene"] == "wedges" ? 0 : 1];
  EXPECT_EQ(per_scene[0], 4);
  EXPECT_EQ(per_scene[1], 4);
  EXPECT_EQ(j["rows"][3]["spec"], "fxaa1-p3:edge_threshold=1,subpix_cap=0.75");
  EXPECT_EQ(j["rows"][3]["point"], 3);
  EXPECT_EQ(j["axes"][0]["name"], "edge_threshold");
  // The Pareto front: non-empty, flagged points, and no point on it dominated by another.
  const auto& front = j["pareto_front"];
  ASSERT_FALSE(front.empty());
  for (const auto& i : front) {
    const auto& p = j["points"][i.get<size_t>()];
    EXPECT_TRUE(p["pareto"].get<bool>());
    for (const auto& q : j["points"]) {
      const double pq = p["objectives"]["psnr_db"]["mean"], qq = q["objectives"]["psnr_db"]["mean"];
      const double pt = p["mean_time_ms"], qt = q["mean_time_ms"];
      // One repeat: the spreads are unknown, so only a better point no slower dominates
      // (equally good points all stay; harness/run/sweep.h).
      EXPECT_FALSE(qt <= pt && qq > pq) << p["spec"] << " dominated by " << q["spec"];
    }
  }
  // edge_threshold=1 turns FXAA off: the best psnr_db point has edge_threshold 0.125.
  EXPECT_EQ(j["points"][j["best"]["psnr_db"]["point"].get<size_t>()]["overrides"]["edge_threshold"], "0.125");
  EXPECT_EQ(j["suggested_preset"], j["best"]["psnr_db"]["spec"]);
  std::stringstream page;
  page << std::ifstream(out / "index.html").rdbuf();
  for (const char* s : {"<svg", "Pareto front", "edge_threshold", "subpix_cap", "Suggested preset"}) {
    EXPECT_NE(page.str().find(s), std::string::npos) << s;
  }
  EXPECT_FALSE(fs::exists(dir / "sweep.partial"));
}

TEST(SweepCli, GridErrorsNameTheProblem) {
  const fs::path dir = TempDir("sweep-bad");
  const std::string common =
      " --scenes wedges --size 16x9 --ref-spp 4 --repeat 1 --quiet --objective psnr_db --out " + (dir / "s").string();
  struct Case {
    std::string args;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {"--method fxaa1-p3 --grid edge_threshld=0.1,0.2", {"unknown parameter 'edge_threshld'", "edge_threshold"}},
      {"--method fxaa1-p3 --grid edge_threshold=0.1,2", {"out of range"}},
      {"--method fxaa1-p3 --grid edge_threshold=0.1 --grid edge_threshold=0.2", {"'edge_threshold' is given twice"}},
      {"--method fxaa1-p3:edge_threshold=0.1 --grid edge_threshold=0.2", {"set both in --method"}},
      {"--method fxaa1-p3 --grid edge_threshold=0.1,0.1", {"lists value '0.1' twice"}},
      {"--method fxaa1-p3 --grid edge_threshold=0.5,0.50", {"are the same value"}},
      {"--method fxaa1-p3 --grid edge_threshold", {"is not NAME=V1,V2"}},
      {"--method fxaa9 --grid edge_threshold=0.1", {"unknown method 'fxaa9'"}},
      {"--method fxaa1-p3 --grid "
       "search_steps=1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23,24,25,26,27,28,"
       "29,30,31,32 --grid subpix_cap=0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1 --grid edge_threshold=0.1,0.2,0.3",
       {"has 1056 points; the limit is 1024"}},
  };
  for (const auto& c : cases) {
    const CmdResult r = Aalab("sweep " + c.args + common);
    EXPECT_EQ(r.code, 1) << c.args << "\n" << r.output;
    EXPECT_TRUE(Has(r, "aalab: error:")) << r.output;
    for (const auto& p : c.parts) EXPECT_TRUE(Has(r, p)) << c.args << "\nmissing: " << p << "\n" << r.output;
  }
  const CmdResult r = Aalab("sweep --method fxaa1-p3 --grid edge_threshold=0.1 --objective nope" +
                            common.substr(0, common.find(" --objective")) + " --out " + (dir / "s").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(Has(r, "unknown metric 'nope'")) << r.output;
  EXPECT_FALSE(fs::exists(dir / "s"));  // nothing written by a refused sweep
}

}  // namespace

namespace {

TEST(BaselineCli, AcceptReplacesThroughTheOutputRuleAndRecordsWhoWhenWhy) {
  const fs::path dir = TempDir("accept");
  RunTiny(dir / "run1", "none,fxaa1-p3");
  RunTiny(dir / "run2", "none,fxaa1-p3");
  const fs::path db = dir / "h.jsonl";
  const std::string base = (dir / "baseline").string();
  CmdResult r = Aalab("baseline accept " + (dir / "run1").string() + " --to " + base +
                      " --why 'first baseline' --by tester --db " + db.string() + " --commit 1234567");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::is_regular_file(fs::path(base) / "report.json"));
  EXPECT_TRUE(fs::is_regular_file(fs::path(base) / "index.html"));
  std::stringstream note;
  note << std::ifstream(fs::path(base) / "BASELINE.txt").rdbuf();
  EXPECT_NE(note.str().find(" by tester from "), std::string::npos) << note.str();
  EXPECT_NE(note.str().find("why: first baseline"), std::string::npos) << note.str();
  {
    std::ifstream f(db);
    std::string line;
    ASSERT_TRUE(std::getline(f, line));
    const Json e = Json::parse(line);
    EXPECT_EQ(e["commit"], "1234567");
    EXPECT_EQ(e["accepted"]["by"], "tester");
    EXPECT_EQ(e["accepted"]["why"], "first baseline");
  }
  // The same report again is refused by history add (a report is added once) ...
  r = Aalab("history add " + (dir / "run1" / "report.json").string() + " --db " + db.string() + " --commit 7654321");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(Has(r, "already holds this report (line 1")) << r.output;
  // ... while run2, added first and accepted later, has its entry marked, not duplicated.
  r = Aalab("history add " + (dir / "run2" / "report.json").string() + " --db " + db.string() + " --commit 2222222");
  ASSERT_EQ(r.code, 0) << r.output;
  r = Aalab("baseline accept " + (dir / "run2").string() + " --to " + base + " --why 'sharper' --by tester --db " +
            db.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(Has(r, "line 2 (commit 2222222) marked as accepted")) << r.output;
  {
    std::ifstream f(db);
    std::string line;
    int n = 0;
    while (std::getline(f, line)) ++n;
    EXPECT_EQ(n, 2);
  }
  // The trend page shows the acceptance and the threshold band.
  r = Aalab("history report --db " + db.string() + " --out " + (dir / "trend").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::stringstream page;
  page << std::ifstream(dir / "trend" / "index.html").rdbuf();
  for (const char* s : {"accepted as baseline", "sharper", "threshold band", "2222222"}) {
    EXPECT_NE(page.str().find(s), std::string::npos) << s;
  }
  // A folder aalab did not write is never replaced.
  fs::create_directories(dir / "mine");
  std::ofstream(dir / "mine" / "notes.txt") << "keep";
  r = Aalab("baseline accept " + (dir / "run1").string() + " --to " + (dir / "mine").string() + " --why x");
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "mine" / "notes.txt"));
  EXPECT_FALSE(fs::exists(dir / "mine" / "report.json"));
  // Not a run folder; no reason given.
  r = Aalab("baseline accept " + dir.string() + " --to " + (dir / "b2").string() + " --why x");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(Has(r, "is not a run folder")) << r.output;
  r = Aalab("baseline accept " + (dir / "run1").string() + " --to " + (dir / "b2").string());
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / "b2"));
}

TEST(SweepCli, ObjectivesDisagreeLoudlyAndTheSuggestionIsComparedWithTheDefault) {
  const SweepRun s = Sweep("sweep-verdict",
                           "--scenes wedges,circle --method fxaa311-p39 --grid subpix=0,0.75,1 "
                           "--size 64x36 --ref-spp 16 --repeat 3");
  ASSERT_EQ(s.r.code, 0);
  const CmdResult& r = s.r;
  const Json& j = s.j;
  const fs::path& out = s.out;
  // FLIP first by default (edge PSNR rewards blur), edge PSNR second.
  EXPECT_EQ(j["objectives"], Json::parse(R"(["flip_mean","edge_psnr_db"])"));
  auto subpix = [&j](const Json& point) { return j["points"][point.get<size_t>()]["overrides"]["subpix"]; };
  // Measured at this size: FLIP picks the sharpest, edge PSNR the blurriest.
  EXPECT_EQ(subpix(j["best"]["flip_mean"]["point"]), "0");
  EXPECT_EQ(subpix(j["best"]["edge_psnr_db"]["point"]), "1");
  ASSERT_EQ(j["disagreements"].size(), 1u);
  EXPECT_TRUE(Has(r, "NOTE: edge_psnr_db picks subpix=1")) << r.output;
  EXPECT_TRUE(Has(r, "the objectives disagree")) << r.output;
  // The suggestion is the FLIP pick, on the front.
  EXPECT_EQ(j["suggested_point"], j["best"]["flip_mean"]["point"]);
  EXPECT_TRUE(j["points"][j["suggested_point"].get<size_t>()]["pareto"].get<bool>());
  // The default (subpix=0.75) is point 1; per scene, the change is the rows' own values.
  ASSERT_EQ(j["default_point"], 1);
  ASSERT_EQ(j["scene_changes"].size(), 2u);
  for (const auto& c : j["scene_changes"]) {
    for (const auto& row : j["rows"]) {
      if (row["scene"] != c["scene"]) continue;
      const char* side = row["point"] == 1 ? "default" : row["point"] == j["suggested_point"] ? "suggested" : nullptr;
      if (!side) continue;
      EXPECT_EQ(c["objectives"]["flip_mean"][side], row["metrics"]["flip_mean"]) << c.dump();
    }
  }
  EXPECT_TRUE(Has(r, "against the default (subpix=0.75), per scene:")) << r.output;
  EXPECT_TRUE(Has(r, "  wedges: flip_mean ")) << r.output;
  // Crops of the reference, the default, the suggestion/picks and the extremes, on the page.
  // (4 crop windows per scene at this size; points 0, 1, 2 and the reference.)
  for (const char* scene : {"s0-wedges", "s1-circle"}) {
    for (const char* f : {"reference-w0.png", "p0-w0.png", "p1-w3.png", "p2-w0.png"}) {
      EXPECT_TRUE(fs::is_regular_file(out / "crops" / scene / f)) << scene << "/" << f;
    }
  }
  EXPECT_FALSE(j.contains("crops"));
  EXPECT_TRUE(Has(r, "crops: 32 images in crops/")) << r.output;
  std::stringstream page;
  page << std::ifstream(out / "index.html").rdbuf();
  for (const char* s : {"<h2>Crops</h2>", "src=\"crops/s0-wedges/p1-w0.png\"", "the objectives disagree",
                        "suggested, best flip_mean, extreme subpix=0", "best edge_psnr_db, extreme subpix=1",
                        "Suggestion against the default", "class=\"scene-change\""}) {
    EXPECT_NE(page.str().find(s), std::string::npos) << s;
  }
}

}  // namespace
