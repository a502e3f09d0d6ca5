// aalab export's input, selection and provenance (reports/export_source.h).
#include "reports/export_source.h"

#include <openssl/evp.h>

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "build_info.h"
#include "core/error.h"
#include "metrics/flip.h"
#include "reports/report_json.h"

namespace aalab {

std::string Sha256Hex(const std::string& bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  AALAB_CHECK(EVP_Digest(bytes.data(), bytes.size(), digest, &len, EVP_sha256(), nullptr) == 1 && len == 32,
              "SHA-256 failed");
  static const char* kHex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < len; ++i) {
    out += kHex[digest[i] >> 4];
    out += kHex[digest[i] & 15];
  }
  return out;
}

ExportSource SourceFromBytes(const std::string& bytes, const std::string& path, const std::string& dir,
                             const std::string& label) {
  nlohmann::ordered_json doc;
  try {
    doc = nlohmann::ordered_json::parse(bytes);
  } catch (const nlohmann::json::parse_error& e) {
    throw UserError("report '" + path + "' is not valid JSON: " + e.what());
  }
  ExportSource s;
  s.report = ReportFromJson(doc, "report '" + path + "'");
  if (s.report.shard) {
    throw UserError("report '" + path + "' is a shard's partial report (shard " +
                    std::to_string(s.report.shard->index) + "/" + std::to_string(s.report.shard->count) +
                    "); export the report `aalab merge` makes of all shards");
  }
  s.dir = dir;
  s.label = label;
  s.sha256 = Sha256Hex(bytes);
  return s;
}

const ResultRow* FindRow(const Report& report, const std::string& scene, const std::string& spec) {
  for (const auto& r : report.rows) {
    if (r.scene == scene && r.spec == spec) return &r;
  }
  return nullptr;
}

const SceneResult* FindScene(const Report& report, const std::string& name) {
  for (const auto& s : report.scenes) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

std::optional<double> MetricOf(const ResultRow& row, const std::string& metric) {
  for (const auto& m : row.metrics) {
    if (m.name == metric) return m.value;
  }
  return std::nullopt;
}

std::string SettingOf(const Report& report, const std::string& key) {
  for (const auto& [k, v] : report.settings) {
    if (k == key) return v;
  }
  return "";
}

namespace {

std::string Join(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
  return out;
}

std::vector<std::string> ReportSpecs(const Report& r) {
  std::vector<std::string> specs;
  for (const auto& row : r.rows) {
    if (std::find(specs.begin(), specs.end(), row.spec) == specs.end()) specs.push_back(row.spec);
  }
  return specs;
}

std::vector<std::string> ReportMetrics(const Report& r) {
  std::vector<std::string> names;
  for (const auto& row : r.rows) {
    for (const auto& m : row.metrics) {
      if (std::find(names.begin(), names.end(), m.name) == names.end()) names.push_back(m.name);
    }
  }
  return names;
}

std::string ContextOf(const Report& r, const std::string& key) {
  const auto it = r.context.find(key);
  return it == r.context.end() ? "unknown" : it->second;
}

}  // namespace

ExportSelection ResolveSelection(const std::vector<ExportSource>& sources, const ExportSelection& asked) {
  AALAB_CHECK(!sources.empty(), "export needs at least one report");
  const Report& first = sources.front().report;
  if (first.rows.empty()) throw UserError("report '" + sources.front().dir + "' has no rows: nothing to export");
  ExportSelection sel = asked;
  std::vector<std::string> scene_names;
  for (const auto& s : first.scenes) scene_names.push_back(s.name);
  const std::vector<std::string> specs = ReportSpecs(first);
  const std::vector<std::string> metrics = ReportMetrics(first);
  if (sel.scenes.empty()) sel.scenes = scene_names;
  if (sel.methods.empty()) sel.methods = specs;
  if (sel.metric.empty()) {
    for (const char* m : {"edge_psnr_db", "psnr_db"}) {
      if (std::find(metrics.begin(), metrics.end(), m) != metrics.end()) {
        sel.metric = m;
        break;
      }
    }
    if (sel.metric.empty()) sel.metric = metrics.empty() ? "" : metrics.front();
  }
  if (std::find(metrics.begin(), metrics.end(), sel.metric) == metrics.end()) {
    throw UserError("--metric '" + sel.metric + "' is not in report '" + sources.front().dir +
                    "' (it has: " + Join(metrics) + ")");
  }
  for (const auto& src : sources) {
    for (const auto& name : sel.scenes) {
      if (!FindScene(src.report, name)) {
        std::vector<std::string> have;
        for (const auto& s : src.report.scenes) have.push_back(s.name);
        throw UserError("--scenes: scene '" + name + "' is not in report '" + src.dir + "' (it has: " + Join(have) +
                        ")");
      }
    }
    for (const auto& spec : sel.methods) {
      const std::vector<std::string> have = ReportSpecs(src.report);
      if (std::find(have.begin(), have.end(), spec) == have.end()) {
        throw UserError("--methods: method '" + spec + "' is not in report '" + src.dir + "' (it has: " + Join(have) +
                        ")");
      }
    }
  }
  for (size_t i = 0; i < sel.scenes.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (sel.scenes[i] == sel.scenes[j]) throw UserError("--scenes names '" + sel.scenes[i] + "' twice");
    }
  }
  for (size_t i = 0; i < sel.methods.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (sel.methods[i] == sel.methods[j]) throw UserError("--methods names '" + sel.methods[i] + "' twice");
    }
  }
  return sel;
}

std::vector<std::string> ProvenanceLines(const std::vector<ExportSource>& sources) {
  std::vector<std::string> lines;
  lines.push_back(std::string("exported by aalab ") + AALAB_VERSION + " (commit " + AALAB_GIT_COMMIT +
                  ") with `aalab export`");
  for (const auto& s : sources) {
    lines.push_back("report '" + s.label + "': " + s.dir + "/report.json sha256 " + s.sha256 + ", written by aalab " +
                    ContextOf(s.report, "tool_version") + " (commit " + ContextOf(s.report, "git_commit") + ") on " +
                    ContextOf(s.report, "host"));
  }
  return lines;
}

std::string ConditionsSentence(const Report& r, bool timing) {
  std::string out;
  bool exact = !r.scenes.empty();
  for (const auto& s : r.scenes) exact = exact && s.ref_exact;
  bool image = !r.scenes.empty();
  for (const auto& s : r.scenes) image = image && s.kind == "image";
  const std::string spp = SettingOf(r, "ref_spp");
  if (exact) {
    out += "Reference: exact pixel coverage (closed form).";
  } else if (image) {
    out += "Reference: the user's own reference frames.";
  } else {
    out += "Reference: " + spp + " stratified samples per pixel.";
  }
  out += " Size " + SettingOf(r, "size") + ".";
  const std::string frames = SettingOf(r, "frames");
  if (!frames.empty() && frames != "1") out += " " + frames + " frames per scene; metrics pooled over frames.";
  // The report's own conditions (absent in older reports: the defaults they were run with).
  {
    char def_ppd[32];
    std::snprintf(def_ppd, sizeof def_ppd, "%g", kFlipDefaultPpd);
    std::string ppd = SettingOf(r, "ppd"), viewing = SettingOf(r, "viewing"), sampler = SettingOf(r, "sampler");
    if (ppd.empty()) ppd = def_ppd;
    if (viewing.empty()) viewing = "default";
    if (sampler.empty()) sampler = "gl";
    out += " Viewing condition (FLIP, temporal error): " + viewing + ", " + ppd + " pixels per degree.";
    out += " Post-filter sampler: " + sampler + ".";
  }
  if (!timing) return out;
  out += " Times: median over " + SettingOf(r, "repeat") + " timed run(s) after " + SettingOf(r, "warmup") +
         " warm-up, CPU, " + ContextOf(r, "cpu") + ", " + ContextOf(r, "threads") + " threads.";
  return out;
}

}  // namespace aalab
