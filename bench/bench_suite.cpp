// The suite figures of `make bench`; see bench/bench_suite.h.
#include "bench/bench_suite.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <tuple>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/format.h"
#include "harness/run/runner.h"
#include "scenes/library.h"

namespace aalab::bench {

namespace {

// The output folder's size two ways: the files' bytes, and their disk usage rounded up to 4 KiB
// blocks (what `du` reports on this machine's ext4), both in MB of 10^6 bytes.
void MeasureFolder(const std::filesystem::path& dir, DefaultRun& d) {
  std::uintmax_t bytes = 0, blocks = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::uintmax_t n = e.file_size();
    bytes += n;
    blocks += (n + 4095) / 4096;
  }
  d.folder_mb = static_cast<double>(bytes) / 1e6;
  d.folder_disk_mb = static_cast<double>(blocks) * 4096.0 / 1e6;
}

// A scene is real when any of its materials was read from a glTF file (a real asset), not
// built from the scene file's own shapes.
void ClassifyDefaultScenes(DefaultRun& d) {
  const std::vector<std::string> names = SuiteScenes("default");
  d.scenes = static_cast<int>(names.size());
  for (const std::string& name : names) {
    const Scene scene = LoadScene(name);
    const bool gltf = std::any_of(scene.materials.begin(), scene.materials.end(),
                                  [](const Material& m) { return m.gltf.has_value(); });
    if (gltf) d.real.push_back(name);
  }
}

}  // namespace

namespace {

namespace fs = std::filesystem;

const std::string kSuiteMethods = "none,ssaa-2x2,fxaa1-p3,fxaa311-p12,fxaa311-p39,fxaa-high,scale43-fxaa-high";
const std::string kSuiteName = "quick";
const int kSuiteSpp = 16;

double ChildCpu(const rusage& u) {
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + (u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
}

// report.json's time_breakdown (stage, wall_ms, cpu_ms) in seconds; empty when unreadable.
std::vector<std::tuple<std::string, double, double>> ReadStages(const fs::path& report) {
  std::vector<std::tuple<std::string, double, double>> v;
  try {
    std::ifstream f(report);
    const Json j = Json::parse(f);
    for (const auto& s : j.at("time_breakdown"))
      v.emplace_back(s.at("stage").get<std::string>(), s.at("wall_ms").get<double>() / 1e3,
                     s.at("cpu_ms").get<double>() / 1e3);
  } catch (const std::exception&) {
    v.clear();
  }
  return v;
}

// A run's AALAB_LOOP_STATS file: (wall s in loops, busy thread-s), or false when unreadable.
bool ReadLoopStats(const fs::path& path, double* in_loops_s, double* busy_s) {
  try {
    std::ifstream f(path);
    const Json j = Json::parse(f);
    *in_loops_s = j.at("in_loops_s").get<double>();
    *busy_s = j.at("busy_s").get<double>();
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

Json StagesJson(const std::vector<std::tuple<std::string, double, double>>& stages) {
  Json j = Json::array();
  for (const auto& [name, wall, cpu] : stages) j.push_back({{"stage", name}, {"wall_s", wall}, {"cpu_s", cpu}});
  return j;
}

// The stage table: per configuration, each stage's wall and CPU seconds, then the process's
// time outside the stages (start, exit) and `aalab --version` alone.
void StageTable(const SuiteBench& sb, BenchOutput& out) {
  std::string head = "| stage (report.json time_breakdown, last repetition) |", rule = "|---|";
  for (const auto& s : sb.runs) {
    head.append(" ").append(s.size).append(", ").append(std::to_string(s.threads)).append(" thr.: wall s / CPU s |");
    rule += "---|";
  }
  out.Line("");
  out.Line(
      "Where a suite run's time goes (fixed per-process costs weigh most at small sizes; a stage whose wall "
      "time does not halve from 1 to 2 threads is serial):");
  out.Line("");
  out.Line(head);
  out.Line(rule);
  if (sb.runs.empty() || sb.runs[0].stages.empty()) return;
  for (size_t k = 0; k < sb.runs[0].stages.size(); ++k) {
    std::string line = "| ";
    line.append(std::get<0>(sb.runs[0].stages[k])).append(" |");
    for (const auto& s : sb.runs) {
      if (k >= s.stages.size()) {
        line += " |";
        continue;
      }
      line.append(" ").append(FormatDouble("%.2f", std::get<1>(s.stages[k]))).append(" / ");
      line.append(FormatDouble("%.2f", std::get<2>(s.stages[k]))).append(" |");
    }
    out.Line(line);
  }
  std::string outside = "| outside the stages (process start and exit: run's wall − stages' total) |";
  for (const auto& s : sb.runs) {
    const double total = s.stages.empty() ? 0.0 : std::get<1>(s.stages.back());
    const double cpu_total = s.stages.empty() ? 0.0 : std::get<2>(s.stages.back());
    outside.append(" ").append(FormatDouble("%.2f", s.secs.back() - total)).append(" / ");
    outside.append(FormatDouble("%.2f", s.cpu.back() - cpu_total)).append(" |");
  }
  out.Line(outside);
  if (sb.start_wall_s > 0) {
    out.Line("");
    out.Line("`aalab --version` alone (start and exit, loading its shared libraries; minimum of 3): " +
             FormatDouble("%.2f s", sb.start_wall_s) + " wall, " + FormatDouble("%.2f", sb.start_cpu_s) + " CPU s.");
  }
}

// A shell command run to its end: exit status, wall s and the CPU s of everything it ran
// (RUSAGE_CHILDREN reaches grandchildren once their parent has waited for them).
struct Timed {
  int rc;
  double wall, cpu;
};
Timed TimeCommand(const std::string& cmd) {
  rusage c0{}, c1{};
  getrusage(RUSAGE_CHILDREN, &c0);
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  getrusage(RUSAGE_CHILDREN, &c1);
  return {rc, sec, ChildCpu(c1) - ChildCpu(c0)};
}

// Where a run's loop statistics go: a file beside its output folder (which each run removes).
fs::path LoopStatsPath(const fs::path& out) { return out.string() + ".loops.json"; }

std::string SuiteCommand(const Settings& cfg, const SuiteRun& s, const fs::path& out) {
  return "AALAB_LOOP_STATS=" + LoopStatsPath(out).string() + " " + cfg.aalab_bin + " run --suite " + kSuiteName +
         " --methods " + kSuiteMethods + " --size " + s.size + " --ref-spp " + std::to_string(kSuiteSpp) +
         " --repeat 1 --threads " + std::to_string(s.threads) + " --quiet --out " + out.string() + " >/dev/null";
}

// The parallel loops of each configuration's runs (AALAB_LOOP_STATS), medians over its runs:
// a 2-thread run's shortfall from 2× split into serial time, idle time inside loops, and chunk
// work that took more thread time than the 1-thread run's. Sets sb's loop figures for the goal.
void LoopTable(SuiteBench& sb, BenchOutput& out) {
  const SuiteRun* one = nullptr;
  for (const auto& s : sb.runs)
    if (s.w == 960 && s.threads == 1 && !s.busy_s.empty()) one = &s;
  out.Line("");
  out.Line(
      "Where the runs' threads were (AALAB_LOOP_STATS, medians over runs; busy: thread-s inside loop chunks; idle: "
      "threads × in loops − busy; outside: the run's wall − in loops, serial work and process start):");
  out.Line("");
  out.Line(
      "| size | threads | wall s in loops | outside loops s | busy thread-s | idle in loops thread-s | busy / 1 "
      "thread's |");
  out.Line("|---|---|---|---|---|---|---|");
  for (const auto& s : sb.runs) {
    if (s.busy_s.empty() || s.busy_s.size() != s.secs.size()) continue;
    const Stats in{s.in_loops_s}, busy{s.busy_s};
    std::vector<double> outside, idle;
    for (size_t i = 0; i < s.secs.size(); ++i) {
      outside.push_back(s.secs[i] - s.in_loops_s[i]);
      idle.push_back(s.threads * s.in_loops_s[i] - s.busy_s[i]);
    }
    const double outside_s = Stats{outside}.Median(), idle_s = Stats{idle}.Median();
    const bool same_size = one && one->w == s.w && one->h == s.h;
    const double ratio = same_size ? busy.Median() / Stats{one->busy_s}.Median() : 0.0;
    if (same_size && s.threads == 2) sb.busy_ratio = ratio, sb.idle2_s = idle_s, sb.outside2_s = outside_s;
    out.Line("| " + s.size + " | " + std::to_string(s.threads) + " | " + FormatDouble("%.2f", in.Median()) + " | " +
             FormatDouble("%.2f", outside_s) + " | " + FormatDouble("%.2f", busy.Median()) + " | " +
             FormatDouble("%.2f", idle_s) + " | " + (same_size ? FormatDouble("%.3f", ratio) : std::string("")) + " |");
  }
}

// Two copies of the 1-thread run `s`, started together by one shell that waits for both (their
// CPU time reaches RUSAGE_CHILDREN through it): the throughput two independent processes get
// from this machine's two cores in the same minutes, the ceiling for a 2-thread run's scaling.
bool RunPair(const Settings& cfg, const SuiteRun& s, const fs::path& base, SuiteBench& sb) {
  const fs::path a = base.string() + "_pair_a", b = base.string() + "_pair_b";
  fs::remove_all(a);
  fs::remove_all(b);
  const std::string cmd = "( " + SuiteCommand(cfg, s, a) + " ) & pa=$!; ( " + SuiteCommand(cfg, s, b) +
                          " ) & pb=$!; wait $pa; ra=$?; wait $pb; rb=$?; [ $ra -eq 0 ] && [ $rb -eq 0 ]";
  std::fprintf(stderr, "  suite %s threads 1, two runs at once...\n", s.size.c_str());
  const Timed t = TimeCommand(cmd);
  fs::remove_all(a);
  fs::remove_all(b);
  fs::remove(LoopStatsPath(a));
  fs::remove(LoopStatsPath(b));
  if (t.rc != 0) {
    std::fprintf(stderr, "suite pair run failed (%d): %s\n", t.rc, cmd.c_str());
    return false;
  }
  sb.pair_secs.push_back(t.wall);
  sb.pair_cpu.push_back(t.cpu);
  return true;
}

}  // namespace

int SuiteReps(int width, int suite_reps) {
  const int reps = std::max(suite_reps, 1);
  if (width >= 1920) return 1;
  return width <= 480 ? 2 * reps : reps;
}

bool RunSuiteFigures(const Settings& cfg, SuiteBench& sb) {
  std::vector<SuiteRun>& suite = sb.runs;
  const auto config = [](const char* size, int w, int h, int threads) {
    SuiteRun r;  // the measurements start empty
    r.size = size, r.w = w, r.h = h, r.threads = threads;
    return r;
  };
  suite = {config("480x270", 480, 270, 2), config("960x540", 960, 540, 2), config("1920x1080", 1920, 1080, 2),
           config("960x540", 960, 540, 1)};
  if (cfg.quick) suite = {config("480x270", 480, 270, 2), config("960x540", 960, 540, 2)};
  const fs::path suite_out = fs::temp_directory_path() / ("aalab_bench_suite_" + std::to_string(getpid()));
  // Round-robin over the configurations (repetition r of each, then r + 1) so that the ratios
  // between them (2 threads over 1, per Mpix against 1080p's) compare runs made minutes apart,
  // not the start of the bench against its end. Repetitions by length: 1080p (~30 s) once;
  // 480x270 (~2 s, the run most exposed to the machine's moment-to-moment speed) twice as
  // often as the others, since its median holds the linearity goal's worst point.
  const auto reps_of = [&cfg](const SuiteRun& s) { return SuiteReps(s.w, cfg.suite_reps); };
  int rounds = 0;
  for (const auto& s : suite) rounds = std::max(rounds, reps_of(s));
  for (int r = 0; r < rounds; ++r) {
    for (auto& s : suite) {
      const int reps = reps_of(s);
      if (r >= reps) continue;
      fs::remove_all(suite_out);
      const std::string cmd = SuiteCommand(cfg, s, suite_out);
      std::fprintf(stderr, "  suite %s threads %d (%d/%d)...\n", s.size.c_str(), s.threads, r + 1, reps);
      const Timed t = TimeCommand(cmd);
      s.cpu.push_back(t.cpu);
      if (t.rc != 0) {
        std::fprintf(stderr, "suite run failed (%d): %s\n", t.rc, cmd.c_str());
        return false;
      }
      s.secs.push_back(t.wall);
      s.stages = ReadStages(suite_out / "report.json");
      double in_loops = 0, busy = 0;
      if (ReadLoopStats(LoopStatsPath(suite_out), &in_loops, &busy)) {
        s.in_loops_s.push_back(in_loops);
        s.busy_s.push_back(busy);
      }
      fs::remove(LoopStatsPath(suite_out));
      if (s.w == 960 && s.threads == 1 && !RunPair(cfg, s, suite_out, sb)) return false;
    }
  }
  fs::remove_all(suite_out);
  {  // the process's fixed cost: start (loading its shared libraries) and exit, nothing else
    double best_wall = 1e300, best_cpu = 1e300;
    for (int r = 0; r < 3; ++r) {
      const Timed t = TimeCommand(cfg.aalab_bin + " --version >/dev/null");
      if (t.rc != 0) break;
      best_wall = std::min(best_wall, t.wall);
      best_cpu = std::min(best_cpu, t.cpu);
    }
    if (best_wall < 1e300) sb.start_wall_s = best_wall, sb.start_cpu_s = best_cpu;
  }

  // The default run, as `make run` does it with the binary prebuilt (not in --quick): wall,
  // CPU and peak memory of that one process. The peak comes from /usr/bin/time (GNU time,
  // scripts/debian-packages-bench.txt), a small process that forks aalab: the rusage of a child
  // forked from this bench would not do, because Linux folds the forking process's resident
  // high-water mark into the child's ru_maxrss across execve (a 700 MB bench made a 268 MB run
  // read 703 MB).
  DefaultRun& default_run = sb.default_run;
  if (!cfg.quick) {
    fs::remove_all(suite_out);
    std::fprintf(stderr, "  default run (aalab run)...\n");
    const fs::path usage = fs::temp_directory_path() / ("aalab_bench_time_" + std::to_string(getpid()));
    const auto t0 = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid == 0) {
      const int null_fd = open("/dev/null", O_WRONLY);
      if (null_fd >= 0) dup2(null_fd, 1);
      execl("/usr/bin/time", "/usr/bin/time", "-f", "%U %S %M", "-o", usage.c_str(), cfg.aalab_bin.c_str(), "run",
            "--quiet", "--out", suite_out.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    double user = 0, sys = 0, max_kb = 0;
    bool parsed = false;
    if (pid > 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0) {
      default_run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (FILE* f = std::fopen(usage.c_str(), "r")) {
        parsed = std::fscanf(f, "%lf %lf %lf", &user, &sys, &max_kb) == 3;
        std::fclose(f);
      }
    }
    fs::remove(usage);
    if (!parsed) {
      std::fprintf(stderr, "the default run failed (status %d; /usr/bin/time present? Debian package 'time')\n",
                   status);
      return false;
    }
    default_run.ok = true;
    default_run.cpu_s = user + sys;
    default_run.max_rss_mb = max_kb / 1024.0;  // kB
    MeasureFolder(suite_out, default_run);
    ClassifyDefaultScenes(default_run);
    fs::remove_all(suite_out);
  }
  return true;
}

void SuiteTable(SuiteBench& sb, BenchOutput& out) {
  out.Line("");
  out.Line("## Suite — wall time of `aalab run --suite " + kSuiteName + " --ref-spp " + std::to_string(kSuiteSpp) +
           " --repeat 1` with 7 methods (" + kSuiteMethods + ")");
  out.Line("");
  out.Line(
      "| size | threads | runs | wall s median (min–max) | wall s per Mpix (/ 1080p's) | CPU s median | CPU s per Mpix "
      "(/ 1080p's) | cores used |");
  out.Line("|---|---|---|---|---|---|---|---|");
  double cpu_per_mpix_1080 = 0.0;
  for (const auto& s : sb.runs) {
    if (s.w == 1920 && s.threads == 2) {
      sb.per_mpix_1080 = Stats{s.secs}.Median() / (s.w * s.h / 1e6);
      cpu_per_mpix_1080 = Stats{s.cpu}.Median() / (s.w * s.h / 1e6);
    }
  }
  const double per_mpix_1080 = sb.per_mpix_1080;
  for (const auto& s : sb.runs) {
    const Stats st{s.secs}, sc{s.cpu};
    const double mp = s.w * s.h / 1e6;
    const double per = st.Median() / mp, cper = sc.Median() / mp;
    const double rel = per_mpix_1080 > 0 ? per / per_mpix_1080 : 0.0;
    const double crel = cpu_per_mpix_1080 > 0 ? cper / cpu_per_mpix_1080 : 0.0;
    if (s.threads == 2 && per_mpix_1080 > 0) {
      sb.linear_worst = std::max(sb.linear_worst, std::fabs(rel - 1.0));
      sb.linear_worst_cpu = std::max(sb.linear_worst_cpu, std::fabs(crel - 1.0));
    }
    if (s.w == 960 && s.threads == 1) sb.t1 = st.Median(), sb.t1_min = st.Min();
    if (s.w == 960 && s.threads == 2) sb.t2 = st.Median(), sb.t2_min = st.Min();
    const bool two = s.threads == 2 && per_mpix_1080 > 0;
    out.Line("| " + s.size + " | " + std::to_string(s.threads) + " | " + std::to_string(s.secs.size()) + " | " +
             Range(st, 1, "%.1f") + " | " + FormatDouble("%.1f", per) +
             (two ? " (" + FormatDouble("%.2f", rel) + ")" : "") + " | " + FormatDouble("%.1f", sc.Median()) + " | " +
             FormatDouble("%.1f", cper) + (two ? " (" + FormatDouble("%.2f", crel) + ")" : "") + " | " +
             FormatDouble("%.2f", sc.Median() / st.Median()) + " |");
    out.figures.push_back({{"group", "suite"},
                           {"size", s.size},
                           {"threads", s.threads},
                           {"unit", "s"},
                           {"value", StatsJson(s.secs, 1)},
                           {"cpu_s", StatsJson(s.cpu, 1)},
                           {"s_per_mpix", per},
                           {"cpu_s_per_mpix", cper},
                           {"suite", kSuiteName},
                           {"methods", kSuiteMethods},
                           {"ref_spp", kSuiteSpp},
                           {"stages_last_repetition", StagesJson(s.stages)},
                           {"in_loops_s", s.in_loops_s},
                           {"busy_thread_s", s.busy_s}});
  }
  if (!sb.pair_secs.empty()) {
    const Stats pw{sb.pair_secs}, pc{sb.pair_cpu};
    out.Line("| 960x540 | 1, two runs at once | " + std::to_string(sb.pair_secs.size()) + " | " + Range(pw, 1, "%.1f") +
             " (until both ended) | | " + FormatDouble("%.1f", pc.Median()) + " (both) | | " +
             FormatDouble("%.2f", pc.Median() / pw.Median()) + " |");
    out.figures.push_back({{"group", "suite-pair"},
                           {"size", "960x540"},
                           {"threads", 1},
                           {"processes", 2},
                           {"unit", "s"},
                           {"value", StatsJson(sb.pair_secs, 1)},
                           {"cpu_s", StatsJson(sb.pair_cpu, 1)},
                           {"suite", kSuiteName},
                           {"methods", kSuiteMethods},
                           {"ref_spp", kSuiteSpp}});
  }
  StageTable(sb, out);
  LoopTable(sb, out);
  const DefaultRun& d = sb.default_run;
  if (d.ok) {
    out.Line("");
    out.Line("## Default run — `aalab run` with its defaults (" + std::to_string(SuiteScenes("default").size()) +
             " scenes × " + std::to_string(DefaultMethods().size()) +
             " methods, 960x540, 64 spp, 2 timed repeats), prebuilt");
    out.Line("");
    out.Line("| wall s | CPU s | cores used | peak memory (max RSS) | folder (files / on disk) | real scenes |");
    out.Line("|---|---|---|---|---|---|");
    std::string real;
    for (const std::string& r : d.real) real += (real.empty() ? "" : ", ") + r;
    out.Line("| " + FormatDouble("%.1f", d.wall_s) + " | " + FormatDouble("%.1f", d.cpu_s) + " | " +
             FormatDouble("%.2f", d.cpu_s / d.wall_s) + " | " + FormatDouble("%.0f MB", d.max_rss_mb) + " | " +
             FormatDouble("%.1f", d.folder_mb) + " / " + FormatDouble("%.1f MB", d.folder_disk_mb) + " | " + real +
             " |");
    out.figures.push_back({{"group", "default-run"},
                           {"unit", "s"},
                           {"wall_s", d.wall_s},
                           {"cpu_s", d.cpu_s},
                           {"max_rss_mb", d.max_rss_mb},
                           {"folder_mb", d.folder_mb},
                           {"folder_disk_mb", d.folder_disk_mb},
                           {"real_scenes", d.real}});
  }
}

void SuiteGoals(const SuiteBench& sb, BenchOutput& out) {
  if (sb.per_mpix_1080 > 0) {
    out.Goal("suite time linear in pixel count within 15% (wall s per Mpix vs 1080p's, 2 threads)",
             FormatDouble("worst deviation %.0f%%", 100 * sb.linear_worst), sb.linear_worst <= 0.15);
    out.Goal("(same on CPU seconds, less exposed to other load)",
             FormatDouble("worst deviation %.0f%%", 100 * sb.linear_worst_cpu), sb.linear_worst_cpu <= 0.15);
  }
  if (sb.t1 > 0 && sb.t2 > 0) {
    // Beside it, the machine's own ceiling for the same work in the same rounds: two 1-thread
    // runs at once did twice the work in the pair's wall time, so 2 × (one alone) / (the pair).
    std::string ceiling;
    if (!sb.pair_secs.empty())
      ceiling = "; two 1-thread runs at once, same rounds: " +
                FormatDouble("%.2f×", 2.0 * sb.t1 / Stats{sb.pair_secs}.Median()) + " one run's throughput";
    const std::string fastest = "; fastest runs " + FormatDouble("%.2f×", sb.t1_min / sb.t2_min);
    // And where the 2-thread run's threads lost time (AALAB_LOOP_STATS, LoopTable).
    std::string loops;
    if (sb.busy_ratio > 0)
      loops = "; 2 threads: chunk work " + FormatDouble("%+.1f%%", 100 * (sb.busy_ratio - 1)) +
              " thread-s over 1 thread's, idle in loops " + FormatDouble("%.2f", sb.idle2_s) +
              " thread-s, outside loops " + FormatDouble("%.2f s", sb.outside2_s);
    out.Goal("quick suite at 960x540: 2 threads ≥ 1.85× one thread",
             FormatDouble("%.2f×", sb.t1 / sb.t2) + fastest + ceiling + loops, sb.t1 / sb.t2 >= 1.85);
  }
}

void DefaultRunGoal(const SuiteBench& sb, BenchOutput& out) {
  const DefaultRun& d = sb.default_run;
  if (!d.ok) return;
  std::string real;
  for (const std::string& r : d.real) real += (real.empty() ? "" : ", ") + r;
  out.Goal("default run (`aalab run`, prebuilt) ≤ 30 s wall with ≥ 3 real scenes, ≤ 300 MB peak memory, ≤ 40 MB folder",
           FormatDouble("%.1f s", d.wall_s) + " wall (" + FormatDouble("%.1f", d.cpu_s) + " CPU s), " +
               std::to_string(d.real.size()) + " of " + std::to_string(d.scenes) + " scenes real (" + real + "), " +
               FormatDouble("%.0f MB", d.max_rss_mb) + " peak, folder " + FormatDouble("%.1f MB", d.folder_mb) + " (" +
               FormatDouble("%.1f MB", d.folder_disk_mb) + " on disk)",
           d.wall_s <= 30.0 && d.real.size() >= 3 && d.max_rss_mb <= 300.0 && d.folder_disk_mb <= 40.0);
}

}  // namespace aalab::bench
