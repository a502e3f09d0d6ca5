// `aalab compare` and `aalab history`: thin CLI over reports/compare.h and reports/history.h.
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "harness/cli/commands.h"
#include "core/error.h"
#include "core/input_files.h"
#include "io/safe_path.h"
#include "harness/run/out_folder.h"
#include "core/exit_code.h"
#include "core/params.h"
#include "core/cleanup.h"
#include "io/image_io.h"
#include "harness/run/out_folder.h"
#include "reports/compare.h"
#include "reports/compare_export.h"
#include "reports/compare_page.h"
#include "reports/compare_text.h"
#include "reports/history.h"
#include "reports/history_page.h"
#include "reports/report_json.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

constexpr const char* kCompareRules = R"(Rules:
  Comparable: schema_version and the settings size, ref_spp and seed must agree.
  Rows match by scene and canonical method spec; their resolved parameters must agree.
  Missing or extra rows are listed by name and make the comparison incomplete (exit 2).
  Quality: a dB metric (name ending in _db) regresses when it drops by more than
  --max-drop-db; another metric when it gets worse by more than its --max-metric-change
  (absolute, or N% of the baseline value). A null PSNR with reason 'identical' is
  +infinity (better than any number); a value that became null for another reason is a
  regression. Rows whose output_hash is unchanged are unchanged for quality at once.
  Warn level: a dB metric that drops by more than --warn-drop-db but not more than
  --max-drop-db is a warning (other metrics: half their tolerance); warnings never fail.
  Time: the method's own time (post + resample, plus render unless it is the 1x frame
  shared with 'none'), median over the timed repeats. An increase is a regression only
  when it exceeds --max-time-increase, --time-floor AND the sum of both runs' repeat
  spreads (max - min of samples_ms), and the runs' ranges do not overlap (the current
  run's fastest repeat is slower than the baseline's slowest). Time is judged only when
  both reports come from the same CPU model, thread count and build type (else a note
  says so; --time-across-machines judges it anyway).
  Gating: --fail-on quality (default) fails on quality only: time is shown and a time
  regression is a warning. --fail-on time / any gate time / both.
  Renamed rows: --map OLD=NEW compares the baseline's OLD rows with the current NEW rows
  (e.g. --map fxaa311-p39=fxaa311-p39:subpix=0); their parameters may differ.
Exit codes: 0 no regression; 1 regression (gated), or a capture warning with --strict;
  2 could not compare (different settings or schema, missing/extra rows, changed
  parameters, missing metrics, unreadable input, bad options or usage); 3 internal error.)";

std::string FolderOf(const std::string& path) {
  const fs::path p = fs::path(path).parent_path();
  return p.empty() ? std::string(".") : p.string();
}

struct CompareArgs {
  std::string baseline, current, metrics, metric_change, time_increase = "10%", html, json, junit;
  std::string fail_on = "quality", time_floor = "0.5ms";
  std::vector<std::string> maps;
  double max_drop_db = 0.1, warn_drop_db = 0.02;
  bool all = false, time_across_machines = false, strict = false;
};

CompareOptions BuildOptions(double max_drop_db, const std::string& metrics, const std::string& metric_change,
                            const std::string& time_increase, bool across, const std::vector<std::string>& maps = {},
                            double warn_drop_db = -1, const std::string& fail_on = "quality",
                            const std::string& time_floor = "0.5ms", bool strict = false) {
  CompareOptions o;
  o.max_drop_db = max_drop_db;
  o.warn_drop_db = warn_drop_db < 0 ? std::min(o.warn_drop_db, max_drop_db) : warn_drop_db;
  o.fail_on = ParseFailOn(fail_on);
  o.strict = strict;
  for (const auto& m : maps) AddSpecMapping(m, &o.map);
  {
    const Threshold floor = ParseTimeThreshold(time_floor, "--time-floor");
    if (floor.relative) throw UserError("--time-floor '" + time_floor + "' must be a duration in ms (e.g. 0.5ms)");
    o.time_floor_ms = floor.value;
  }
  if (!metrics.empty()) o.metrics = SplitCommaList(metrics, "--metrics");
  if (!metric_change.empty()) o.metric_change = ParseMetricChangeOption(metric_change);
  if (time_increase == "off") {
    o.check_time = false;
  } else {
    o.time_increase = ParseTimeThreshold(time_increase, "--max-time-increase");
  }
  o.time_across_machines = across;
  ValidateCompareOptions(o);
  return o;
}

/// Copies the changed rows' images next to the page (OUT_files/) and writes OUT.
void WriteCompareHtml(const std::string& out, const CompareResult& res, const Report& base, const Report& cur,
                      const CompareArgs& a) {
  const fs::path page(out);
  if (page.filename().empty() || (page.extension() != ".html" && page.extension() != ".htm")) {
    throw UserError("--html '" + out + "' must name a .html file");
  }
  const fs::path dir = page.parent_path().empty() ? fs::path(".") : page.parent_path();
  // The same file rule as run's folders: an existing page is replaced only when aalab compare
  // wrote it (it carries the page's heading); a user's file, a run folder's index.html or any
  // other page is refused before anything is written.
  CheckOutFile(out, {a.baseline, a.current});
  if (fs::exists(fs::symlink_status(page))) {
    std::ifstream f(page, std::ios::binary);
    std::string head(4096, '\0');
    f.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<size_t>(f.gcount()));
    if (!fs::is_regular_file(page) || head.find("<h1>aalab compare</h1>") == std::string::npos) {
      throw UserError("--html '" + out +
                      "' exists and was not written by aalab compare; refusing to replace it "
                      "(aalab never overwrites a file it did not write): give another file name");
    }
  }
  fs::create_directories(dir);
  const std::string files_name = page.stem().string() + "_files";
  const fs::path files = dir / files_name;
  const fs::path marker = files / ".aalab-compare";
  if (fs::exists(files) && !(fs::is_directory(files) && fs::exists(marker))) {
    throw UserError("--html: '" + files.string() +
                    "' exists and was not written by aalab compare; refusing to replace it");
  }
  std::vector<std::vector<HtmlImage>> images =
      CompareHtmlImages(res, base, cur, FolderOf(a.baseline), FolderOf(a.current));
  // The reports name their images: each must lie inside its report's folder (safe_path.h).
  for (const auto& row : images) {
    for (const auto& im : row) {
      if (im.source.empty()) continue;
      const bool from_base = im.label.rfind("baseline", 0) == 0;
      const fs::path folder = FolderOf(from_base ? a.baseline : a.current);
      ResolveInside(folder, fs::path(im.source).lexically_relative(folder).string(),
                    "image path (" + im.label + ") in report '" + (from_base ? a.baseline : a.current) + "'");
    }
  }
  const fs::path staging = files.string() + ".partial";
  // Only a leftover of an earlier compare (it holds the marker) is removed.
  if (fs::exists(fs::symlink_status(staging)) && !fs::exists(staging / ".aalab-compare")) {
    throw UserError("--html: '" + staging.string() + "' exists and was not written by aalab compare; move it away");
  }
  fs::remove_all(staging);
  fs::create_directories(staging);
  TrackUnfinished(staging.string());  // an interruption removes it
  // A failed copy removes the staging folder (the page's old images stay as they were).
  struct RemoveUnlessDone {
    fs::path path;
    bool done = false;
    ~RemoveUnlessDone() {
      std::error_code ec;
      if (!done) fs::remove_all(path, ec);
      UntrackUnfinished(path.string());
    }
  } guard{staging};
  WriteTextFile((staging / ".aalab-compare").string(), "images of " + page.filename().string() + "\n");
  int missing = 0;
  for (size_t k = 0; k < images.size(); ++k) {
    for (auto& im : images[k]) {
      if (im.source.empty()) {
        ++missing;
        continue;
      }
      std::error_code ec;
      if (!fs::is_regular_file(im.source, ec)) {
        im.missing = "file not found: " + im.source;
        ++missing;
        continue;
      }
      std::string role = im.label;
      for (char& c : role) c = c == ' ' ? '-' : c;
      const std::string name = "row" + std::to_string(k + 1) + "-" + role + fs::path(im.source).extension().string();
      CopyFileChecked(im.source, (staging / name).string());
      im.href = files_name + "/" + name;
    }
  }
  {
    auto lock = LockUnfinished();
    fs::remove_all(files);
    fs::rename(staging, files);
    guard.done = true;
  }
  WriteTextFile(page.string(), CompareHtml(res, images, a.baseline, a.current, &cur));
  std::printf("wrote %s (%zu changed rows; images copied to %s)\n", page.string().c_str(), images.size(),
              files.string().c_str());
  if (missing > 0) {
    std::fprintf(stderr,
                 "aalab: note: %d image(s) not available for the HTML page (reports without their images "
                 "folder); the page says which\n",
                 missing);
  }
}

int CompareCommand(const CompareArgs& a) {
  try {
    const CompareOptions o =
        BuildOptions(a.max_drop_db, a.metrics, a.metric_change, a.time_increase, a.time_across_machines, a.maps,
                     a.warn_drop_db, a.fail_on, a.time_floor, a.strict);
    // The result files may not overwrite an input, nor each other.
    std::vector<std::string> inputs = {a.baseline, a.current};
    for (const std::string* out : {&a.json, &a.junit, &a.html}) {
      if (out->empty()) continue;
      inputs.push_back(CheckOutFile(*out, inputs));
    }
    const Report base = ReadReportFile(a.baseline);
    const Report cur = ReadReportFile(a.current);
    const CompareResult res = CompareReports(base, cur, o);
    std::fputs(FormatCompareText(res, base, cur, a.baseline, a.current, a.all).c_str(), stdout);
    std::fflush(stdout);
    if (!a.json.empty()) {
      WriteTextFile(a.json, CompareToJson(res, a.baseline, a.current).dump(2) + "\n");
      std::printf("wrote %s\n", a.json.c_str());
    }
    if (!a.junit.empty()) {
      WriteTextFile(a.junit, CompareToJUnit(res, a.baseline, a.current));
      std::printf("wrote %s\n", a.junit.c_str());
    }
    if (!a.html.empty()) WriteCompareHtml(a.html, res, base, cur, a);
    return res.ExitCode();
  } catch (const UserError& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "aalab: error: %s\n", e.what());
    std::fprintf(stderr, "aalab: could not compare (exit 2)\n");
    return ToInt(ExitCode::kCouldNotCompare);
  } catch (const InternalError&) {
    throw;  // a bug: exit 3 from main
  } catch (const std::exception& e) {
    // Anything else (file system, parsing) also means "could not compare", never "regression".
    std::fflush(stdout);
    std::fprintf(stderr, "aalab: error: %s\n", e.what());
    std::fprintf(stderr, "aalab: could not compare (exit 2)\n");
    return ToInt(ExitCode::kCouldNotCompare);
  }
}

std::string UtcDate(std::time_t t) {
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

struct HistoryAddArgs {
  std::string report, db, series = "default", commit, date;
};

int HistoryAdd(const HistoryAddArgs& a) {
  ValidateSeriesName(a.series);
  if (a.db.empty()) throw UserError("--db must name a .jsonl file");
  if (fs::exists(fs::symlink_status(a.db))) RequireRegularFile(a.db, "history database", "a .jsonl file is expected");
  // Validate the whole database first: a malformed line is an error naming its number.
  std::string raw;
  const std::vector<HistoryEntry> entries = ReadHistoryFile(a.db, true, &raw);
  const Report report = ReadReportFile(a.report);
  std::string commit = a.commit;
  if (commit.empty()) {
    auto it = report.context.find("git_commit");
    commit = it == report.context.end() ? "" : it->second;
  }
  std::string date = a.date;
  if (date.empty()) {
    auto it = report.context.find("date");
    if (it != report.context.end()) {
      date = it->second;
      try {
        ValidateHistoryDate(date);
      } catch (const UserError& e) {
        throw UserError("report '" + a.report + "' context.date: " + e.what() + "; give the date with --date");
      }
    } else {
      struct stat st {};
      if (stat(a.report.c_str(), &st) != 0) throw UserError("report '" + a.report + "' cannot be read");
      date = UtcDate(st.st_mtime);
    }
  }
  HistoryEntry e = HistoryEntryFromReport(report, a.series, commit, date, a.report);
  CheckSeriesCompatible(entries, e);
  int line = 1;
  for (const auto& x : entries) line = std::max(line, x.line + 1);
  std::string text = raw;
  if (!text.empty() && text.back() != '\n') text += '\n';
  text += HistoryLine(e) + "\n";
  WriteTextFile(a.db, text);  // temporary file + rename: the database is never half-written
  int in_series = 0;
  const HistoryEntry* prev = nullptr;
  for (const auto& x : entries) {
    if (x.series == e.series) {
      ++in_series;
      prev = &x;
    }
  }
  std::printf("added commit %s (%s, %zu rows) to series '%s' in %s (line %d, entry %d of the series)\n",
              e.commit.c_str(), e.date.c_str(), e.report.rows.size(), e.series.c_str(), a.db.c_str(), line,
              in_series + 1);
  if (prev) {
    CompareOptions o;
    const CompareResult c = CompareReports(prev->report, e.report, o);
    std::printf("vs previous entry (commit %s): %d regression(s), %d improvement(s)%s (see aalab history report)\n",
                prev->commit.c_str(), c.regressions, c.improvements,
                c.ExitCode() == 2 ? ", some rows could not be compared" : "");
  }
  return ToInt(ExitCode::kOk);
}

struct HistoryReportArgs {
  std::vector<std::string> maps;
  std::string db, out, series, time_increase = "10%";
  double max_drop_db = 0.1;
  bool time_across_machines = false;
};

int HistoryReport(const HistoryReportArgs& a) {
  const CompareOptions o = BuildOptions(a.max_drop_db, "", "", a.time_increase, a.time_across_machines, a.maps);
  if (a.out.empty()) throw UserError("--out must name a folder");
  RequireRegularFile(a.db, "history database", "a .jsonl file written by aalab history add is expected");
  const std::vector<HistoryEntry> entries = ReadHistoryFile(a.db, false);
  const HistoryPage page = HistoryHtml(entries, a.series, o, a.out);
  // The folder rule of run (harness/run/out_folder.h): only an earlier history page's folder
  // is replaced, never a user's page or a run folder's index.html.
  OutFolder folder(a.out, "history", {a.db});
  WriteTextFile((folder.Begin() / "index.html").string(), page.html);
  folder.Commit();
  const fs::path index = fs::path(a.out) / "index.html";
  std::printf(
      "wrote %s: %d series, %d entries, %d charts; threshold crossings between consecutive entries: "
      "%d regression(s), %d improvement(s), %d could-not-compare item(s)\n",
      index.string().c_str(), page.series, page.entries, page.charts, page.regressions, page.improvements,
      page.cannot_compare);
  return ToInt(ExitCode::kOk);
}

struct BaselineAcceptArgs {
  std::string run_dir, to, why, by, db, series = "default", commit;
};

/// The user accepting a baseline: --by, else $USER / $LOGNAME, else "unknown".
std::string WhoAccepts(const std::string& by) {
  if (!by.empty()) return by;
  for (const char* var : {"GITHUB_ACTOR", "USER", "LOGNAME"}) {
    const char* v = std::getenv(var);
    if (v && *v) return v;
  }
  return "unknown";
}

int BaselineAccept(const BaselineAcceptArgs& a) {
  if (a.why.empty()) throw UserError("--why must say why the numbers moved (it is recorded with the baseline)");
  const fs::path src = fs::path(a.run_dir);
  const fs::path report_path = src / "report.json";
  if (!fs::is_directory(src) || !fs::is_regular_file(report_path)) {
    throw UserError("'" + a.run_dir +
                    "' is not a run folder (no report.json in it): give the folder of an aalab run "
                    "(its --out)");
  }
  const Report report = ReadReportFile(report_path.string());  // a malformed report is refused before any change
  if (!a.db.empty()) ValidateSeriesName(a.series);
  // The history database is checked (readable, well-formed) before the baseline changes.
  std::string raw;
  const std::vector<HistoryEntry> entries =
      a.db.empty() ? std::vector<HistoryEntry>{} : ReadHistoryFile(a.db, true, &raw);
  const std::string now = UtcDate(std::time(nullptr));
  std::optional<HistoryEntry> entry;
  if (!a.db.empty()) {
    std::string commit = a.commit;
    if (commit.empty()) {
      auto it = report.context.find("git_commit");
      commit = it == report.context.end() ? "" : it->second;
    }
    auto it = report.context.find("date");
    std::string date = it == report.context.end() ? now : it->second;
    try {
      ValidateHistoryDate(date);
    } catch (const UserError&) {
      date = now;
    }
    entry = HistoryEntryFromReport(report, a.series, commit, date, report_path.string());
  }
  // The baseline folder: the output rule (replaced only when it is an earlier aalab output
  // holding nothing else; written through DIR.partial).
  OutFolder out(a.to, "run", {src.string()});
  const fs::path tmp = out.Begin();
  int files = 0;
  for (auto it = fs::recursive_directory_iterator(src); it != fs::recursive_directory_iterator(); ++it) {
    const fs::path rel = fs::relative(it->path(), src);
    const std::string name = rel.filename().string();
    if (name == kOutputMarker || name == ".aalab-lock") continue;
    if (it->is_directory()) {
      fs::create_directories(tmp / rel);
    } else if (it->is_regular_file()) {
      fs::create_directories((tmp / rel).parent_path());
      CopyFileChecked(it->path().string(), (tmp / rel).string());
      ++files;
    }
  }
  WriteTextFile((tmp / "BASELINE.txt").string(), "accepted " + now + " by " + WhoAccepts(a.by) + " from " +
                                                     fs::absolute(src).string() + "\nwhy: " + a.why + "\n");
  out.Commit();
  std::printf("baseline %s replaced by %s (%d files, %zu rows); accepted by %s at %s: %s\n", out.Dir().string().c_str(),
              a.run_dir.c_str(), files, report.rows.size(), WhoAccepts(a.by).c_str(), now.c_str(), a.why.c_str());
  if (entry) {
    entry->accepted = HistoryEntry::Acceptance{WhoAccepts(a.by), now, a.why, out.Dir().string()};
    // The report already in the history (added by `history add`): that entry is marked.
    for (const auto& x : entries) {
      HistoryEntry mine = *entry, theirs = x;
      for (HistoryEntry* h : {&mine, &theirs}) {
        h->series = "s";
        h->commit = "c";
        h->date = "d";
        h->source.clear();
        h->accepted.reset();
      }
      if (HistoryLine(mine) != HistoryLine(theirs)) continue;
      HistoryEntry marked = x;
      marked.accepted = entry->accepted;
      std::stringstream in(raw);
      std::string line, text;
      for (int n = 1; std::getline(in, line); ++n) text += (n == x.line ? HistoryLine(marked) : line) + "\n";
      WriteTextFile(a.db, text);
      std::printf("recorded in %s: line %d (commit %s) marked as accepted\n", a.db.c_str(), x.line, x.commit.c_str());
      return ToInt(ExitCode::kOk);
    }
    CheckSeriesCompatible(entries, *entry);
    std::string text = raw;
    if (!text.empty() && text.back() != '\n') text += '\n';
    text += HistoryLine(*entry) + "\n";
    WriteTextFile(a.db, text);
    std::printf("recorded in %s: commit %s added to series '%s' as the accepted baseline\n", a.db.c_str(),
                entry->commit.c_str(), entry->series.c_str());
  }
  return ToInt(ExitCode::kOk);
}

}  // namespace

void RegisterCompareCommands(CLI::App& app, Commands& commands) {
  // baseline accept
  auto* bl = app.add_subcommand("baseline", "manage the baseline that aalab compare gates against");
  bl->require_subcommand(1);
  auto* acc = bl->add_subcommand(
      "accept",
      "replace the baseline folder with a run's folder (the output rule applies) and record who, when and why");
  auto ba = std::make_shared<BaselineAcceptArgs>();
  acc->add_option("run", ba->run_dir, "the run folder to accept (holds report.json)")->required();
  acc->add_option("--to", ba->to,
                  "the baseline folder (e.g. ci/baseline): replaced only when it is an earlier aalab "
                  "output holding nothing else")
      ->required();
  acc->add_option("--why", ba->why, "why the numbers moved (recorded in BASELINE.txt and the history)")->required();
  acc->add_option("--by", ba->by, "who accepts (default: $GITHUB_ACTOR, $USER or $LOGNAME)");
  acc->add_option("--db", ba->db, "history database (.jsonl) to record the acceptance in (optional)");
  acc->add_option("--series", ba->series, "history series (with --db)")->capture_default_str();
  acc->add_option("--commit", ba->commit, "git commit (with --db; default: the report's context.git_commit)");
  acc->callback([&commands, ba] { commands.action = [ba] { return BaselineAccept(*ba); }; });

  // compare
  auto* cmp = app.add_subcommand(
      "compare", "compare CURRENT against BASELINE; exit 0 no regression, 1 regression, 2 could not compare");
  auto ca = std::make_shared<CompareArgs>();
  cmp->add_option("baseline", ca->baseline, "baseline report.json")->required();
  cmp->add_option("current", ca->current, "current report.json")->required();
  cmp->add_option("--max-drop-db", ca->max_drop_db,
                  "largest allowed drop of a dB metric (PSNR) before it is a regression")
      ->capture_default_str();
  cmp->add_option("--metrics", ca->metrics,
                  "comma-separated metrics to compare (default: edge_psnr_db,psnr_db when both reports have "
                  "edge_psnr_db, else psnr_db)");
  cmp->add_option("--max-metric-change", ca->metric_change,
                  "tolerance for non-dB metrics: 0.005 (absolute), 2% (of the baseline value), or per metric "
                  "ssim=0.002,flip_mean=5%");
  cmp->add_option("--max-time-increase", ca->time_increase,
                  "allowed increase of the method time's median: N% of the baseline or Nms; 'off' to skip time")
      ->capture_default_str();
  cmp->add_flag("--time-across-machines", ca->time_across_machines,
                "judge time even when CPU model, thread count or build type differ");
  cmp->add_option("--html", ca->html,
                  "also write an HTML page with the changed rows' images (copied into OUT's folder as <name>_files/)");
  cmp->add_flag("--all", ca->all, "list every compared value, not only the changed ones");
  cmp->add_option("--fail-on", ca->fail_on,
                  "what makes exit 1: quality (default; time is shown, a time regression is a warning), time, or any")
      ->capture_default_str();
  cmp->add_option("--warn-drop-db", ca->warn_drop_db,
                  "a dB metric's drop beyond this but within --max-drop-db is a warning (exit 0); non-dB metrics warn "
                  "at half their tolerance")
      ->capture_default_str();
  cmp->add_option("--time-floor", ca->time_floor,
                  "absolute floor: a time change of at most this many ms never counts (e.g. 0.5ms)")
      ->capture_default_str();
  cmp->add_option("--map", ca->maps,
                  "OLD=NEW: compare the baseline's rows of method spec OLD with the current rows of spec NEW (a "
                  "renamed row or a deliberately changed preset; repeatable)");
  cmp->add_option("--json", ca->json, "also write the result as JSON (every compared value, verdicts, exit code)");
  cmp->add_option("--junit", ca->junit, "also write the result as JUnit XML (one test case per scene x method)");
  cmp->add_flag("--strict", ca->strict, "also fail (exit 1) when the current report's scenes carry capture warnings");
  cmp->footer(kCompareRules);
  cmp->callback([&commands, ca] { commands.action = [ca] { return CompareCommand(*ca); }; });

  // history
  auto* hist = app.add_subcommand("history", "track reports over commits in a JSON-lines database");
  hist->require_subcommand(1);
  auto* add = hist->add_subcommand("add", "append a report (per-row metrics and times, no images) to a series");
  auto ha = std::make_shared<HistoryAddArgs>();
  add->add_option("report", ha->report, "report.json to add")->required();
  add->add_option("--db", ha->db, "the database (.jsonl; created when missing)")->required();
  add->add_option("--series", ha->series,
                  "series name; a report whose size, ref_spp, seed, scenes or methods differ from the series' "
                  "must go to another series")
      ->capture_default_str();
  add->add_option("--commit", ha->commit,
                  "git commit (default: the report's context.git_commit, the commit at the build's configure time)");
  add->add_option("--date", ha->date,
                  "YYYY-MM-DD or YYYY-MM-DDTHH:MM:SSZ (default: the report's context.date, else the report file's "
                  "modification time, UTC)");
  add->callback([&commands, ha] { commands.action = [ha] { return HistoryAdd(*ha); }; });

  auto* rep = hist->add_subcommand("report", "write DIR/index.html with trend charts per scene x method");
  auto hr = std::make_shared<HistoryReportArgs>();
  rep->add_option("--db", hr->db, "the database (.jsonl)")->required();
  rep->add_option("--out", hr->out, "output folder (index.html is replaced atomically)")->required();
  rep->add_option("--series", hr->series, "only this series (default: all)");
  rep->add_option("--max-drop-db", hr->max_drop_db, "as in aalab compare")->capture_default_str();
  rep->add_option("--max-time-increase", hr->time_increase, "as in aalab compare ('off' to leave time out)")
      ->capture_default_str();
  rep->add_flag("--time-across-machines", hr->time_across_machines, "as in aalab compare");
  rep->add_option("--map", hr->maps,
                  "OLD=NEW: as in aalab compare; consecutive entries' rows of spec OLD and NEW are one trend line");
  rep->callback([&commands, hr] { commands.action = [hr] { return HistoryReport(*hr); }; });
}

}  // namespace aalab
