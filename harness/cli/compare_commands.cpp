// `aalab compare` and `aalab history`: thin CLI over reports/compare.h and reports/history.h.
#include <sys/stat.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "harness/cli/commands.h"
#include "harness/core/error.h"
#include "harness/core/input_files.h"
#include "harness/io/safe_path.h"
#include "harness/run/out_folder.h"
#include "harness/core/exit_code.h"
#include "harness/core/params.h"
#include "harness/core/cleanup.h"
#include "harness/io/image_io.h"
#include "reports/compare.h"
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
  Time: the method's own time (post + resample, plus render unless it is the 1x frame
  shared with 'none'), median over the timed repeats. An increase is a regression only
  when it exceeds --max-time-increase AND the repeats' spread, max - min of samples_ms of
  either run. Time is judged only when both reports come from the same CPU model, thread
  count and build type (else a note says so; --time-across-machines judges it anyway).
Exit codes: 0 no regression; 1 regression; 2 could not compare (different settings or
  schema, missing/extra rows, changed parameters, missing metrics, unreadable input, bad
  option values); 3 internal error; >= 100 command-line syntax errors.)";

std::string FolderOf(const std::string& path) {
  const fs::path p = fs::path(path).parent_path();
  return p.empty() ? std::string(".") : p.string();
}

struct CompareArgs {
  std::string baseline, current, metrics, metric_change, time_increase = "10%", html;
  double max_drop_db = 0.1;
  bool all = false, time_across_machines = false;
};

CompareOptions BuildOptions(double max_drop_db, const std::string& metrics, const std::string& metric_change,
                            const std::string& time_increase, bool across) {
  CompareOptions o;
  o.max_drop_db = max_drop_db;
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
      throw UserError("--html '" + out + "' exists and was not written by aalab compare; refusing to replace it "
                      "(aalab never overwrites a file it did not write): give another file name");
    }
  }
  fs::create_directories(dir);
  const std::string files_name = page.stem().string() + "_files";
  const fs::path files = dir / files_name;
  const fs::path marker = files / ".aalab-compare";
  if (fs::exists(files) && !(fs::is_directory(files) && fs::exists(marker))) {
    throw UserError("--html: '" + files.string() + "' exists and was not written by aalab compare; refusing to replace it");
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
  WriteTextFile(page.string(), CompareHtml(res, images, a.baseline, a.current));
  std::printf("wrote %s (%zu changed rows; images copied to %s)\n", page.string().c_str(), images.size(),
              files.string().c_str());
  if (missing > 0) {
    std::fprintf(stderr, "aalab: note: %d image(s) not available for the HTML page (reports without their images "
                 "folder); the page says which\n", missing);
  }
}

int CompareCommand(const CompareArgs& a) {
  try {
    const CompareOptions o =
        BuildOptions(a.max_drop_db, a.metrics, a.metric_change, a.time_increase, a.time_across_machines);
    const Report base = ReadReportFile(a.baseline);
    const Report cur = ReadReportFile(a.current);
    const CompareResult res = CompareReports(base, cur, o);
    std::fputs(FormatCompareText(res, base, cur, a.baseline, a.current, a.all).c_str(), stdout);
    std::fflush(stdout);
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
  std::vector<HistoryEntry> entries;
  if (fs::exists(a.db)) {
    std::ifstream f(a.db, std::ios::binary);
    if (!f) throw UserError("history database '" + a.db + "' cannot be read");
    std::stringstream ss;
    ss << f.rdbuf();
    raw = ss.str();
    entries = ParseHistory(raw, "history database '" + a.db + "'");
  }
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
  std::printf("added commit %s (%s, %zu rows) to series '%s' in %s (line %d, entry %d of the series)\n", e.commit.c_str(),
              e.date.c_str(), e.report.rows.size(), e.series.c_str(), a.db.c_str(), line, in_series + 1);
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
  std::string db, out, series, time_increase = "10%";
  double max_drop_db = 0.1;
  bool time_across_machines = false;
};

int HistoryReport(const HistoryReportArgs& a) {
  const CompareOptions o = BuildOptions(a.max_drop_db, "", "", a.time_increase, a.time_across_machines);
  if (a.out.empty()) throw UserError("--out must name a folder");
  RequireRegularFile(a.db, "history database", "a .jsonl file written by aalab history add is expected");
  const std::vector<HistoryEntry> entries = ReadHistoryFile(a.db, false);
  const HistoryPage page = HistoryHtml(entries, a.series, o);
  // The folder rule of run (harness/run/out_folder.h): only an earlier history page's folder
  // is replaced, never a user's page or a run folder's index.html.
  OutFolder folder(a.out, "history", {a.db});
  WriteTextFile((folder.Begin() / "index.html").string(), page.html);
  folder.Commit();
  const fs::path index = fs::path(a.out) / "index.html";
  std::printf("wrote %s: %d series, %d entries, %d charts; threshold crossings between consecutive entries: "
              "%d regression(s), %d improvement(s), %d could-not-compare item(s)\n",
              index.string().c_str(), page.series, page.entries, page.charts, page.regressions, page.improvements,
              page.cannot_compare);
  return ToInt(ExitCode::kOk);
}

}  // namespace

void RegisterCompareCommands(CLI::App& app, Commands& commands) {
  // compare
  auto* cmp = app.add_subcommand(
      "compare", "compare CURRENT against BASELINE; exit 0 no regression, 1 regression, 2 could not compare");
  auto ca = std::make_shared<CompareArgs>();
  cmp->add_option("baseline", ca->baseline, "baseline report.json")->required();
  cmp->add_option("current", ca->current, "current report.json")->required();
  cmp->add_option("--max-drop-db", ca->max_drop_db, "largest allowed drop of a dB metric (PSNR) before it is a regression")
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
  rep->callback([&commands, hr] { commands.action = [hr] { return HistoryReport(*hr); }; });
}

}  // namespace aalab
