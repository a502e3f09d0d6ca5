// `aalab same-results` (harness/run/same_results.h).
#include "harness/run/same_results.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/error.h"
#include "reports/report_json.h"

namespace aalab {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

Json ReadJson(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw UserError("same-results: '" + path.string() + "' is not a regular file");
  std::ifstream f(path);
  if (!f) throw UserError("same-results: '" + path.string() + "' cannot be read: " + std::strerror(errno));
  std::stringstream ss;
  ss << f.rdbuf();
  try {
    return Json::parse(ss.str());
  } catch (const Json::parse_error& e) {
    throw UserError("same-results: '" + path.string() + "' is not valid JSON: " + e.what());
  }
}

void Erase(Json& j, const char* key) {
  if (j.is_object()) j.erase(key);
}

bool SameBytes(const fs::path& a, const fs::path& b) {
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  if (!fa || !fb) return false;
  const std::string da((std::istreambuf_iterator<char>(fa)), std::istreambuf_iterator<char>());
  const std::string db((std::istreambuf_iterator<char>(fb)), std::istreambuf_iterator<char>());
  return da == db;
}

}  // namespace

Json WithoutTimings(Json doc) {
  Erase(doc, "context");
  Erase(doc, "time_breakdown");
  Erase(doc, "shard");
  if (doc.contains("settings")) Erase(doc["settings"], "threads");
  if (doc.contains("scenes")) {
    for (auto& s : doc["scenes"]) {
      Erase(s, "bvh_build_ms");
      if (s.contains("content")) Erase(s["content"], "load_ms");
      if (s.contains("reference")) Erase(s["reference"], "time_ms");
      if (s.contains("sequence")) {
        Erase(s["sequence"], "scene_and_bvh_ms");
        Erase(s["sequence"], "reference_ms");
      }
    }
  }
  if (doc.contains("rows")) {
    for (auto& r : doc["rows"]) {
      Erase(r, "timing");
      Erase(r, "gpu");
    }
  }
  if (doc.contains("points")) {  // a sweep
    for (auto& p : doc["points"]) {
      Erase(p, "mean_time_ms");
      Erase(p, "pareto");
    }
    Erase(doc, "pareto_front");
  }
  return doc;
}

SameResults CompareResultFolders(const std::string& a, const std::string& b, size_t max_listed) {
  auto report_of = [](const std::string& dir) {
    const fs::path d(dir);
    if (fs::is_regular_file(d / "report.json")) return d / "report.json";
    if (fs::is_regular_file(d / "sweep.json")) return d / "sweep.json";
    throw UserError("same-results: '" + dir + "' holds neither report.json nor sweep.json");
  };
  const fs::path ra = report_of(a), rb = report_of(b);
  if (ra.filename() != rb.filename()) {
    throw UserError("same-results: '" + a + "' holds a " + ra.filename().string() + " and '" + b + "' a " +
                    rb.filename().string() + ": a run and a sweep cannot be compared");
  }
  const Json da = ReadJson(ra), db = ReadJson(rb);
  // Both must be aalab reports of the schema this build reads (a sweep.json holds a report's
  // scenes and rows without a schema version of its own): checked before any comparison.
  for (const auto& [doc, path] : {std::pair<const Json&, const fs::path&>{da, ra}, {db, rb}}) {
    if (!doc.is_object())
      throw UserError("same-results: '" + path.string() + "' is not an aalab report (not a JSON object)");
    Json check = doc;
    if (path.filename() == "sweep.json") {
      const Json version = check.value("sweep_version", Json());
      if (!version.is_number_integer() || version.get<int>() != 1) {
        throw UserError("same-results: '" + path.string() + "' is not an aalab sweep file of a supported version " +
                        "(sweep_version " + (version.is_null() ? std::string("missing") : version.dump()) +
                        "; this aalab reads 1)");
      }
      check["schema_version"] = kSchemaVersion;
    }
    ReportFromJson(check, "same-results: '" + path.string() + "'");
  }
  SameResults out;
  auto differ = [&](const std::string& line) {
    out.same = false;
    if (out.differences.size() < max_listed) out.differences.push_back(line);
  };
  const Json na = WithoutTimings(da), nb = WithoutTimings(db);
  if (na != nb) {
    // RFC 6902 patch from A to B: each operation names a JSON path that differs.
    for (const auto& op : Json::diff(na, nb)) {
      std::string line = ra.filename().string() + " " + op.at("path").get<std::string>() + ": ";
      const std::string kind = op.at("op").get<std::string>();
      if (kind == "remove") {
        line += "only in A";
      } else {
        const std::string value = op.at("value").dump();
        line +=
            (kind == "add" ? "only in B: " : "B has ") + (value.size() > 120 ? value.substr(0, 117) + "..." : value);
      }
      differ(line);
    }
  }
  // The images A links (a sweep.json holds the report's scenes and rows too, without a
  // schema version of its own).
  Json report_a = da;
  report_a["schema_version"] = kSchemaVersion;
  for (const auto& rel : ReportImages(ReportFromJson(report_a, "same-results: '" + ra.string() + "'"))) {
    const fs::path fa = fs::path(a) / rel, fb = fs::path(b) / rel;
    if (!fs::is_regular_file(fa)) {
      differ(rel + ": missing in A");
    } else if (!fs::is_regular_file(fb)) {
      differ(rel + ": missing in B");
    } else if (!SameBytes(fa, fb)) {
      differ(rel + ": the bytes differ");
    }
  }
  return out;
}

}  // namespace aalab
