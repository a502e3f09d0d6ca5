// sweep.json (SweepToJson) and the sweep half of `aalab merge` (harness/run/merge.h): a sweep's
// shards each hold every scene and a round-robin share of the grid points; the merge puts the
// rows back in the single sweep's order (scene-major, points in grid order) and summarises.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/image_io.h"
#include "harness/run/merge_internal.h"
#include "harness/run/out_folder.h"
#include "harness/run/pipeline.h"
#include "harness/run/runner.h"
#include "harness/run/sweep.h"
#include "reports/report_json.h"
#include "reports/sweep_page.h"

namespace aalab {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

Json SweepToJson(const SweepResult& res) {
  const Report& report = res.report;
  const Json rep = ReportToJson(report);
  Json j;
  j["sweep_version"] = 1;
  j["context"] = rep["context"];
  j["settings"] = rep["settings"];
  j["method"] = res.method;
  j["base_spec"] = res.base_spec;
  Json axes = Json::array();
  for (const auto& a : res.axes) axes.push_back({{"name", a.name}, {"values", a.values}});
  j["axes"] = axes;
  j["objectives"] = res.objectives;
  j["reference_renders"] = res.reference_renders;
  j["specs"] = res.specs;
  if (res.report.shard) {
    // A shard: its share and its rows; the summary is the merge's.
    j["shard"] = rep["shard"];
    j["objective_note"] = res.objective_note;
    j["scenes"] = rep["scenes"];
    Json rows = rep["rows"];
    for (size_t i = 0; i < rows.size(); ++i) rows[i]["point"] = res.row_point[i];
    j["rows"] = rows;
    return j;
  }
  auto mean_json = [](const ObjectiveMean& m) {
    Json x;
    x["mean"] = m.mean && std::isfinite(*m.mean) ? Json(*m.mean) : Json(nullptr);
    if (!m.mean || !std::isfinite(*m.mean)) {
      x["null_reason"] = m.mean ? "infinite: " + m.null_reason : m.null_reason;
    }
    return x;
  };
  Json points = Json::array();
  for (size_t p = 0; p < res.points.size(); ++p) {
    const auto& pt = res.points[p];
    Json x;
    x["index"] = p;
    Json ov = Json::object();
    for (const auto& [k, v] : pt.overrides) ov[k] = v;
    x["overrides"] = ov;
    x["spec"] = pt.spec;
    Json obj = Json::object();
    for (const auto& o : res.objectives) obj[o] = mean_json(pt.objectives.at(o));
    x["objectives"] = obj;
    x["mean_time_ms"] = pt.mean_time_ms;
    x["time_spread_ms"] = pt.time_spread_ms;
    x["pareto"] = pt.pareto;
    points.push_back(x);
  }
  j["points"] = points;
  j["pareto_front"] = res.pareto_front;
  Json best = Json::object();
  for (const auto& [o, p] : res.best) {
    Json b = mean_json(res.points[p].objectives.at(o));
    b["point"] = p;
    b["spec"] = res.points[p].spec;
    b["ties"] = res.best_ties.at(o);
    best[o] = b;
  }
  j["best"] = best;
  j["suggested_preset"] = res.suggested_preset.empty() ? Json(nullptr) : Json(res.suggested_preset);
  j["suggested_point"] = res.suggested ? Json(*res.suggested) : Json(nullptr);
  j["suggestion_rule"] = res.suggestion_rule;
  j["default_point"] = res.default_point ? Json(*res.default_point) : Json(nullptr);
  if (!res.default_note.empty()) j["default_note"] = res.default_note;
  j["disagreements"] = res.disagreements;
  Json changes = Json::array();
  for (const auto& c : res.scene_changes) {
    Json vals = Json::object();
    auto num = [](const std::optional<double>& v) {
      return v && std::isfinite(*v) ? Json(*v) : v ? Json("inf") : Json(nullptr);
    };
    for (const auto& v : c.values)
      vals[v.objective] = {{"default", num(v.at_default)}, {"suggested", num(v.suggested)}};
    changes.push_back({{"scene", c.scene},
                       {"objectives", vals},
                       {"default_ms", c.default_ms},
                       {"suggested_ms", c.suggested_ms},
                       {"default_spread_ms", c.default_spread_ms},
                       {"suggested_spread_ms", c.suggested_spread_ms}});
  }
  j["scene_changes"] = changes;
  // The crops (crops/, shown on the page) are not listed here: a merged sweep has none, and
  // its sweep.json must equal the single sweep's (aalab same-results).
  j["scenes"] = rep["scenes"];
  Json rows = rep["rows"];
  for (size_t i = 0; i < rows.size(); ++i) rows[i]["point"] = res.row_point[i];
  j["rows"] = rows;

  return j;
}

int RenderSweepReferences(const SweepSettings& s, int* cached) {
  if (s.scenes.empty()) throw UserError("give the scenes to sweep with --scenes a,b (see aalab list scenes)");
  RunSettings rs;
  rs.scenes = s.scenes;
  rs.width = s.width;
  rs.height = s.height;
  rs.ref_spp = s.ref_spp;
  rs.reference = s.reference;
  rs.seed = s.seed;
  rs.threads = s.threads;
  rs.quiet = s.quiet;
  rs.shard = s.shard;
  rs.ref_cache = s.ref_cache;
  return RenderReferencesOnly(rs, cached);
}

namespace {

/// A sweep shard's sweep.json, read back: the report part (context, settings, scenes, rows,
/// shard block) plus what the summary needs.
struct SweepShard {
  Report report;
  std::vector<size_t> row_point;
  Json doc;
};

SweepShard ReadSweepShard(const std::string& dir) {
  const fs::path path = fs::path(dir) / "sweep.json";
  std::ifstream f(path);
  if (!f) throw UserError("merge: '" + path.string() + "' cannot be read");
  std::stringstream ss;
  ss << f.rdbuf();
  SweepShard s;
  try {
    s.doc = Json::parse(ss.str());
  } catch (const Json::parse_error& e) {
    throw UserError("merge: '" + path.string() + "' is not valid JSON: " + e.what());
  }
  const Json& d = s.doc;
  if (!d.contains("shard")) {
    throw UserError("merge: '" + dir + "' holds a whole sweep, not a shard's (no \"shard\" block): merge takes the " +
                    "folders written by sweep --shard K/N");
  }
  Json rep = {{"schema_version", kSchemaVersion}};
  try {
    for (const char* key : {"context", "settings", "shard", "scenes", "rows"}) rep[key] = d.at(key);
    for (const auto& row : d.at("rows")) s.row_point.push_back(row.at("point").get<size_t>());
    for (const char* key : {"method", "base_spec", "axes", "objectives", "specs", "reference_renders"}) {
      if (!d.contains(key)) throw UserError("merge: '" + path.string() + "' lacks \"" + key + "\"");
    }
  } catch (const Json::exception& e) {
    throw UserError("merge: '" + path.string() + "' is not a sweep shard's sweep.json (" + e.what() + ")");
  }
  s.report = ReportFromJson(rep, "sweep shard '" + path.string() + "'");
  return s;
}

}  // namespace

MergeResult MergeSweepFolders(const std::vector<std::string>& dirs, const std::string& out_dir) {
  std::vector<SweepShard> shards;
  for (const auto& d : dirs) shards.push_back(ReadSweepShard(d));
  std::vector<const Report*> reports;
  for (const auto& s : shards) reports.push_back(&s.report);
  const auto order = CheckShardSet(reports, dirs);
  const Json& d0 = shards[0].doc;
  // Shard 0 holds point 0, so it ran every scene: its scene records are the merged ones.
  const size_t zero = order.front().first;
  for (size_t i = 0; i < shards.size(); ++i) {
    const Json& d = shards[i].doc;
    if (shards[i].report.shard->unit != "grid point") {
      throw UserError("merge: '" + dirs[i] + "' is a shard of " + shards[i].report.shard->unit +
                      "s, not of grid points");
    }
    for (const char* key : {"method", "base_spec", "axes", "objectives", "specs"}) {
      if (d.at(key) != d0.at(key)) {
        throw UserError("merge: the sweep shards differ in \"" + std::string(key) + "\": '" + dirs[0] + "' and '" +
                        dirs[i] + "'");
      }
    }
    // Every shard ran every scene; its rows are scene-major over its points.
    std::vector<std::string> names, names0;
    for (const auto& sc : shards[i].report.scenes) names.push_back(sc.name);
    for (const auto& sc : shards[zero].report.scenes) names0.push_back(sc.name);
    const size_t mine = shards[i].report.shard->units.size();
    if (mine > 0 && names != names0) {  // a shard without points renders no scene
      throw UserError("merge: '" + dirs[i] + "' and '" + dirs[0] + "' hold different scenes");
    }
    if (shards[i].report.rows.size() != names.size() * mine) {
      throw UserError("merge: '" + dirs[i] + "' holds " + std::to_string(shards[i].report.rows.size()) +
                      " rows where its " + std::to_string(mine) + " point(s) on " + std::to_string(names.size()) +
                      " scene(s) make " + std::to_string(names.size() * mine) + ": the sweep is incomplete");
    }
  }
  SweepResult res;
  res.method = d0.at("method").get<std::string>();
  res.base_spec = d0.at("base_spec").get<std::string>();
  for (const auto& a : d0.at("axes"))
    res.axes.push_back({a.at("name").get<std::string>(), a.at("values").get<std::vector<std::string>>()});
  res.objectives = d0.at("objectives").get<std::vector<std::string>>();
  res.specs = d0.at("specs").get<std::vector<std::string>>();
  res.objective_note = d0.value("objective_note", std::string());
  res.reference_renders = shards[zero].doc.at("reference_renders").get<int>();
  if (res.specs.size() != order.size()) {
    throw UserError("merge: the shards' grid has " + std::to_string(res.specs.size()) +
                    " points but the split counts " + std::to_string(order.size()));
  }
  Report& m = res.report;
  m.context = shards[zero].report.context;
  m.context["shards"] = std::to_string(shards[0].report.shard->count);
  m.settings = shards[zero].report.settings;
  m.scenes = shards[zero].report.scenes;
  for (size_t sc = 0; sc < m.scenes.size(); ++sc) {
    for (size_t p = 0; p < order.size(); ++p) {
      const auto [i, j] = order[p];
      const size_t mine = shards[i].report.shard->units.size();
      const ResultRow& row = shards[i].report.rows[sc * mine + j];
      if (shards[i].row_point[sc * mine + j] != p || row.spec != res.specs[p]) {
        throw UserError("merge: '" + dirs[i] + "' has its rows out of order (expected point " + std::to_string(p) +
                        ", " + res.specs[p] + ")");
      }
      m.rows.push_back(row);
      res.row_point.push_back(p);
    }
  }
  SummarizeSweep(&res, ResolveMethods(res.specs));
  OutFolder out(out_dir, "sweep", dirs);
  res.out_dir = out_dir;
  const fs::path tmp = out.Begin();
  WriteTextFile((tmp / "sweep.json").string(), SweepToJson(res).dump(2) + "\n");
  WriteTextFile((tmp / "index.html").string(), SweepHtml(res));
  out.Commit();
  return MergeResult{"sweep", shards[0].report.shard->count, m.scenes.size(), m.rows.size(), out_dir};
}

}  // namespace aalab
