// `aalab merge` (harness/run/merge.h): checks that shards fit together, then reassembles the
// single run's report from them.
#include "harness/run/merge.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/image_io.h"
#include "io/safe_path.h"
#include "harness/run/merge_internal.h"
#include "harness/run/out_folder.h"
#include "harness/run/shard.h"
#include "reports/html_report.h"
#include "reports/report_json.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

/// Context facts that name the program: shards built differently may compute different bits.
const char* const kProgramFacts[] = {"tool_version",         "git_commit",     "build_type",          "compiler",
                                     "float_flags",          "embree_version", "openimageio_version", "tbb_version",
                                     "nlohmann_json_version"};

std::string Get(const std::vector<std::pair<std::string, std::string>>& kv, const std::string& key) {
  for (const auto& [k, v] : kv) {
    if (k == key) return v;
  }
  return "(absent)";
}

std::string Fact(const std::map<std::string, std::string>& m, const std::string& key) {
  const auto it = m.find(key);
  return it == m.end() ? "(absent)" : it->second;
}

}  // namespace

std::vector<std::pair<size_t, size_t>> CheckShardSet(const std::vector<const Report*>& reports,
                                                     const std::vector<std::string>& dirs) {
  AALAB_CHECK(reports.size() == dirs.size(), "one folder per report");
  if (reports.empty()) throw UserError("merge: give the shard folders to merge");
  for (size_t i = 0; i < reports.size(); ++i) {
    if (!reports[i]->shard) {
      throw UserError("merge: '" + dirs[i] + "' holds a whole report, not a shard's (no \"shard\" block): " +
                      "merge takes the folders written by --shard K/N");
    }
  }
  const ShardInfo& first = *reports[0]->shard;
  const int n = first.count;
  if (first.total_units < 1) {
    throw UserError("merge: '" + dirs[0] + "' claims a run of " + std::to_string(first.total_units) + " " + first.unit +
                    "s: the report is damaged");
  }
  for (size_t i = 1; i < reports.size(); ++i) {
    const ShardInfo& s = *reports[i]->shard;
    if (s.count != n || s.unit != first.unit || s.total_units != first.total_units) {
      throw UserError("merge: '" + dirs[i] + "' is shard " + std::to_string(s.index) + "/" + std::to_string(s.count) +
                      " of " + std::to_string(s.total_units) + " " + s.unit + "s, but '" + dirs[0] + "' is shard " +
                      std::to_string(first.index) + "/" + std::to_string(n) + " of " +
                      std::to_string(first.total_units) + " " + first.unit + "s: they are not one split");
    }
  }
  // Each K exactly once.
  std::vector<int> owner(static_cast<size_t>(n), -1);
  for (size_t i = 0; i < reports.size(); ++i) {
    const int k = reports[i]->shard->index;
    if (k < 0 || k >= n)
      throw UserError("merge: '" + dirs[i] + "' claims shard " + std::to_string(k) + " of " + std::to_string(n));
    if (owner[static_cast<size_t>(k)] >= 0) {
      throw UserError("merge: shard " + std::to_string(k) + "/" + std::to_string(n) + " is given twice: '" +
                      dirs[static_cast<size_t>(owner[static_cast<size_t>(k)])] + "' and '" + dirs[i] + "'");
    }
    owner[static_cast<size_t>(k)] = static_cast<int>(i);
  }
  std::string missing;
  for (int k = 0; k < n; ++k) {
    if (owner[static_cast<size_t>(k)] < 0) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
  }
  if (!missing.empty()) {
    throw UserError("merge: shard(s) " + missing + " of " + std::to_string(n) + " missing (" +
                    std::to_string(reports.size()) + " folder(s) given): rerun them (e.g. sbatch --array=" + missing +
                    " ...) and merge all " + std::to_string(n));
  }
  // The same settings (threads aside) and the same program.
  for (size_t i = 1; i < reports.size(); ++i) {
    std::set<std::string> keys;
    for (const auto& kv : reports[0]->settings) keys.insert(kv.first);
    for (const auto& kv : reports[i]->settings) keys.insert(kv.first);
    for (const auto& key : keys) {
      if (key == "threads") continue;
      const std::string a = Get(reports[0]->settings, key), b = Get(reports[i]->settings, key);
      if (a != b) {
        throw UserError("merge: the shards were run with different settings: " + key + " is '" + a + "' in '" +
                        dirs[0] + "' and '" + b + "' in '" + dirs[i] + "'");
      }
    }
    for (const char* key : kProgramFacts) {
      const std::string a = Fact(reports[0]->context, key), b = Fact(reports[i]->context, key);
      if (a != b) {
        throw UserError("merge: the shards were run by different programs: " + std::string(key) + " is '" + a +
                        "' in '" + dirs[0] + "' and '" + b + "' in '" + dirs[i] + "' (run every shard with one build)");
      }
    }
  }
  // Each shard holds exactly its round-robin share; the global order interleaves them.
  const size_t total = static_cast<size_t>(first.total_units);
  std::vector<std::pair<size_t, size_t>> order(total);
  std::map<std::string, std::string> seen;  // unit → folder
  for (int k = 0; k < n; ++k) {
    const size_t i = static_cast<size_t>(owner[static_cast<size_t>(k)]);
    const ShardInfo& s = *reports[i]->shard;
    const std::vector<size_t> share = ShardShare(total, ShardSpec{k, n});
    if (s.units.size() != share.size()) {
      throw UserError("merge: '" + dirs[i] + "' (shard " + std::to_string(s.index) + "/" + std::to_string(n) +
                      ") holds " + std::to_string(s.units.size()) + " " + s.unit + "(s) where the split of " +
                      std::to_string(total) + " gives it " + std::to_string(share.size()) +
                      ": the folder is incomplete or from another run");
    }
    for (size_t j = 0; j < share.size(); ++j) {
      const auto [it, fresh] = seen.emplace(s.units[j], dirs[i]);
      if (!fresh) {
        throw UserError("merge: " + s.unit + " '" + s.units[j] + "' was done twice: in '" + it->second + "' and in '" +
                        dirs[i] + "'");
      }
      order[share[j]] = {i, j};
    }
  }
  return order;
}

Report MergeRunReports(const std::vector<Report>& reports, const std::vector<std::string>& dirs) {
  std::vector<const Report*> ptrs;
  for (const auto& r : reports) ptrs.push_back(&r);
  const auto order = CheckShardSet(ptrs, dirs);
  for (size_t i = 0; i < reports.size(); ++i) {
    const Report& r = reports[i];
    if (r.shard->unit != "scene") {
      throw UserError("merge: '" + dirs[i] + "' is a shard of " + r.shard->unit + "s, not of a run's scenes");
    }
    // Its scenes are its units, in order, and its rows belong to them, scene by scene.
    std::vector<std::string> names;
    for (const auto& sc : r.scenes) names.push_back(sc.name);
    if (names != r.shard->units) {
      throw UserError("merge: '" + dirs[i] +
                      "' lists scenes that differ from its shard's units: the report is damaged");
    }
    size_t scene = 0;
    for (const auto& row : r.rows) {
      while (scene < names.size() && names[scene] != row.scene) ++scene;
      if (scene == names.size()) {
        throw UserError("merge: '" + dirs[i] + "' has a row of scene '" + row.scene +
                        "' out of order or not in its share");
      }
    }
  }
  Report m;
  // Shard 0 (which holds unit 0) gives the context; the settings are everyone's (checked equal).
  const size_t zero = order.front().first;
  m.context = reports[zero].context;
  m.settings = reports[zero].settings;
  std::set<std::string> threads, hosts;
  for (const auto& r : reports) {
    threads.insert(Get(r.settings, "threads"));
    hosts.insert(Fact(r.context, "host"));
  }
  if (threads.size() > 1) {
    std::string t;
    for (const auto& v : threads) t += (t.empty() ? "" : ",") + v;
    for (auto& [k, v] : m.settings) {
      if (k == "threads") v = t;
    }
  }
  std::string host_list;
  for (const auto& h : hosts) host_list += (host_list.empty() ? "" : ",") + h;
  m.context["shards"] = std::to_string(reports[0].shard->count);
  m.context["shard_hosts"] = host_list;
  for (const auto& [i, j] : order) {
    const Report& r = reports[i];
    m.scenes.push_back(r.scenes[j]);
    for (const auto& row : r.rows) {
      if (row.scene == r.scenes[j].name) m.rows.push_back(row);
    }
  }
  // Each stage summed over the shards, in shard 0's order.
  for (const auto& r : reports) {
    for (const auto& t : r.time_breakdown) {
      auto it = std::find_if(m.time_breakdown.begin(), m.time_breakdown.end(),
                             [&](const StageTime& x) { return x.stage == t.stage; });
      if (it == m.time_breakdown.end()) {
        m.time_breakdown.push_back(t);
      } else {
        it->wall_ms += t.wall_ms;
        it->cpu_ms += t.cpu_ms;
      }
    }
  }
  return m;
}

namespace {

MergeResult MergeRunFolders(const std::vector<std::string>& dirs, const std::string& out_dir) {
  std::vector<Report> reports;
  for (const auto& d : dirs) reports.push_back(ReadReportFile((fs::path(d) / "report.json").string()));
  Report merged = MergeRunReports(reports, dirs);
  // Every linked image must be there before anything is written.
  std::vector<std::pair<fs::path, std::string>> copies;  // source, relative path
  std::set<std::string> planned;
  for (size_t i = 0; i < reports.size(); ++i) {
    const std::string origin = "report '" + (fs::path(dirs[i]) / "report.json").string() + "'";
    for (const auto& sc : reports[i].scenes) CheckOutputName(sc.name, "scene name in " + origin);
    for (const auto& rel : ReportImages(reports[i])) {
      // The report names both where the image is read and where its copy is written: both
      // must stay inside their folders (a damaged or received report cannot reach out).
      CheckOutputRelPath(rel, "image path in " + origin);
      const fs::path src = ResolveInside(dirs[i], rel, "image path in " + origin);
      if (!fs::is_regular_file(src)) {
        throw UserError("merge: '" + dirs[i] + "' lacks " + rel + ", which its report links (copied incompletely?)");
      }
      if (planned.insert(rel).second) copies.emplace_back(src, rel);
    }
  }
  OutFolder out(out_dir, "run", dirs);
  const fs::path tmp = out.Begin();
  fs::create_directories(tmp / "images");
  for (const auto& [src, rel] : copies) {
    fs::create_directories((tmp / rel).parent_path());
    CopyFileChecked(src.string(), (tmp / rel).string());
  }
  // The page of the merged report, with its time breakdown (each stage summed over the shards).
  WriteTextFile((tmp / "index.html").string(), RenderHtmlReport(merged));
  WriteTextFile((tmp / "report.json").string(), ReportToJson(merged).dump(2) + "\n");
  out.Commit();
  return MergeResult{"run", reports[0].shard->count, merged.scenes.size(), merged.rows.size(), out_dir};
}

}  // namespace

MergeResult MergeShards(const std::vector<std::string>& dirs, const std::string& out_dir) {
  if (dirs.empty()) throw UserError("merge: give the shard folders to merge");
  int runs = 0, sweeps = 0;
  for (const auto& d : dirs) {
    if (!fs::is_directory(d)) throw UserError("merge: '" + d + "' is not a folder");
    const bool run = fs::exists(fs::path(d) / "report.json"), sweep = fs::exists(fs::path(d) / "sweep.json");
    if (!run && !sweep)
      throw UserError("merge: '" + d + "' holds neither report.json nor sweep.json: not a shard's output");
    runs += run ? 1 : 0;
    sweeps += sweep ? 1 : 0;
  }
  if (runs == static_cast<int>(dirs.size())) return MergeRunFolders(dirs, out_dir);
  if (sweeps == static_cast<int>(dirs.size())) return MergeSweepFolders(dirs, out_dir);
  throw UserError("merge: the folders mix run shards (report.json) and sweep shards (sweep.json)");
}

}  // namespace aalab
