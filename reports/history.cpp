// The history database (JSON lines). Format and rules in history.h; the trend page: history_page.cpp.
#include "reports/history.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/params.h"

namespace aalab {

namespace {

using Json = nlohmann::ordered_json;

Json Num(double v) {
  AALAB_CHECK(std::isfinite(v), "non-finite number headed for the history");
  return v;
}

Json Samples(const Timing& t) {
  Json a = Json::array();
  for (double v : t.samples_ms) a.push_back(Num(v));
  return a;
}

Timing SamplesFrom(const Json& j) {
  Timing t;
  for (const auto& v : j) t.samples_ms.push_back(v.get<double>());
  t.Summarize();
  return t;
}

HistoryEntry EntryFromJson(const Json& j, const std::string& where) {
  HistoryEntry e;
  try {
    if (!j.is_object()) throw UserError(where + ": not a JSON object");
    const int version = j.at("history_version").get<int>();
    if (version != kHistoryVersion) {
      throw UserError(where + ": history_version " + std::to_string(version) + " is not supported (this aalab reads " +
                      std::to_string(kHistoryVersion) + ")");
    }
    e.series = j.at("series").get<std::string>();
    e.commit = j.at("commit").get<std::string>();
    e.date = j.at("date").get<std::string>();
    e.source = j.at("source").get<std::string>();
    if (j.contains("accepted")) {
      const auto& a = j.at("accepted");
      e.accepted = HistoryEntry::Acceptance{a.at("by").get<std::string>(), a.at("at").get<std::string>(),
                                            a.at("why").get<std::string>(), a.at("baseline").get<std::string>()};
    }
    for (auto it = j.at("settings").begin(); it != j.at("settings").end(); ++it) {
      e.report.settings.emplace_back(it.key(), it.value().get<std::string>());
    }
    for (auto it = j.at("context").begin(); it != j.at("context").end(); ++it) {
      e.report.context[it.key()] = it.value().get<std::string>();
    }
    for (const auto& jr : j.at("rows")) {
      ResultRow row;
      row.scene = jr.at("scene").get<std::string>();
      row.method = jr.at("method").get<std::string>();
      row.spec = RespellSpecNumbers(jr.at("spec").get<std::string>());
      for (auto it = jr.at("params").begin(); it != jr.at("params").end(); ++it) {
        row.params.emplace_back(it.key(), RespellNumber(it.value().get<std::string>()));
      }
      const auto& reasons = jr.at("null_reasons");
      for (auto it = jr.at("metrics").begin(); it != jr.at("metrics").end(); ++it) {
        MetricResult m;
        m.name = it.key();
        if (!it.value().is_null()) m.value = it.value().get<double>();
        if (!m.value && reasons.contains(m.name)) m.null_reason = reasons.at(m.name).get<std::string>();
        row.metrics.push_back(m);
      }
      row.output_hash = jr.at("output_hash").get<std::string>();
      row.render_shared = jr.at("render_shared_with_none").get<bool>();
      const auto& t = jr.at("timing");
      row.render = SamplesFrom(t.at("render"));
      row.post = SamplesFrom(t.at("post"));
      row.resample = SamplesFrom(t.at("resample"));
      row.total = SamplesFrom(t.at("total"));
      e.report.rows.push_back(row);
    }
  } catch (const nlohmann::json::exception& ex) {
    throw UserError(where + ": not a history entry (" + std::string(ex.what()) + ")");
  }
  ValidateSeriesName(e.series);
  return e;
}

}  // namespace

const std::vector<std::string>& HistorySeriesKeys() {
  static const std::vector<std::string> keys = {"size",   "ref_spp", "seed", "scenes", "methods",
                                                "frames", "sampler", "ppd",  "fps"};
  return keys;
}

std::string HistorySettingText(const Report& r, const std::string& k) {
  const std::string v = SettingValue(r, k);
  // Conditions absent from older reports have their defaults (as compare reads them).
  if (v.empty() && k == "sampler") return "gl";
  if (v.empty() && k == "ppd") return "67";
  if (v.empty() && k == "fps") return "60";
  return v.empty() ? "(absent)" : v;
}

void ValidateSeriesName(const std::string& name) {
  bool ok = !name.empty() && name.size() <= 64;
  for (char c : name) {
    ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-');
  }
  if (!ok) throw UserError("series name '" + name + "' must be 1-64 characters from A-Z a-z 0-9 . _ -");
}

void ValidateHistoryDate(const std::string& d) {
  auto digits = [&d](size_t from, size_t n) {
    for (size_t i = from; i < from + n; ++i) {
      if (i >= d.size() || !std::isdigit(static_cast<unsigned char>(d[i]))) return false;
    }
    return true;
  };
  const bool day = d.size() >= 10 && digits(0, 4) && d[4] == '-' && digits(5, 2) && d[7] == '-' && digits(8, 2);
  const bool ok = day && (d.size() == 10 || (d.size() == 20 && d[10] == 'T' && digits(11, 2) && d[13] == ':' &&
                                             digits(14, 2) && d[16] == ':' && digits(17, 2) && d[19] == 'Z'));
  if (!ok) throw UserError("date '" + d + "' is not YYYY-MM-DD or YYYY-MM-DDTHH:MM:SSZ (UTC)");
}

HistoryEntry HistoryEntryFromReport(const Report& report, const std::string& series, const std::string& commit,
                                    const std::string& date, const std::string& source) {
  ValidateSeriesName(series);
  ValidateHistoryDate(date);
  if (commit.empty() || commit == "unknown") {
    throw UserError("report '" + source + "' has no git commit (git_commit '" + commit +
                    "': built outside git); give it with --commit");
  }
  if (report.rows.empty()) throw UserError("report '" + source + "' has no rows");
  HistoryEntry e;
  e.series = series;
  e.commit = commit;
  e.date = date;
  e.source = source;
  e.report.schema_version = report.schema_version;
  e.report.settings = report.settings;
  e.report.context = report.context;
  for (const auto& r : report.rows) {
    ResultRow row;
    row.scene = r.scene;
    row.method = r.method;
    row.spec = r.spec;
    row.params = r.params;
    row.metrics = r.metrics;
    row.output_hash = r.output_hash;
    row.render_shared = r.render_shared;
    row.render = r.render;
    row.post = r.post;
    row.resample = r.resample;
    row.total = r.total;
    e.report.rows.push_back(row);
  }
  return e;
}

std::string HistoryLine(const HistoryEntry& e) {
  Json j;
  j["history_version"] = kHistoryVersion;
  j["series"] = e.series;
  j["commit"] = e.commit;
  j["date"] = e.date;
  j["source"] = e.source;
  Json settings = Json::object();
  for (const auto& [k, v] : e.report.settings) settings[k] = v;
  j["settings"] = settings;
  Json ctx = Json::object();
  for (const auto& [k, v] : e.report.context) ctx[k] = v;
  j["context"] = ctx;
  Json rows = Json::array();
  for (const auto& r : e.report.rows) {
    Json jr;
    jr["scene"] = r.scene;
    jr["method"] = r.method;
    jr["spec"] = r.spec;
    Json params = Json::object();
    for (const auto& [k, v] : r.params) params[k] = v;
    jr["params"] = params;
    Json metrics = Json::object(), reasons = Json::object();
    for (const auto& m : r.metrics) {
      metrics[m.name] = m.value ? Num(*m.value) : Json(nullptr);
      if (!m.value) reasons[m.name] = m.null_reason;
    }
    jr["metrics"] = metrics;
    jr["null_reasons"] = reasons;
    jr["output_hash"] = r.output_hash;
    jr["render_shared_with_none"] = r.render_shared;
    jr["timing"] = {{"render", Samples(r.render)},
                    {"post", Samples(r.post)},
                    {"resample", Samples(r.resample)},
                    {"total", Samples(r.total)}};
    rows.push_back(jr);
  }
  j["rows"] = rows;
  if (e.accepted) {
    j["accepted"] = {
        {"by", e.accepted->by}, {"at", e.accepted->at}, {"why", e.accepted->why}, {"baseline", e.accepted->baseline}};
  }
  return j.dump();
}

std::vector<HistoryEntry> ParseHistory(const std::string& text, const std::string& origin) {
  std::vector<HistoryEntry> out;
  size_t pos = 0;
  int line_no = 0;
  while (pos < text.size()) {
    ++line_no;
    const size_t nl = text.find('\n', pos);
    const std::string line = text.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos);
    pos = nl == std::string::npos ? text.size() : nl + 1;
    const std::string where = origin + " line " + std::to_string(line_no);
    if (line.find_first_not_of(" \t\r") == std::string::npos) {
      throw UserError(where + ": empty line (every line must be one history entry)");
    }
    Json j;
    try {
      j = Json::parse(line);
    } catch (const nlohmann::json::parse_error& ex) {
      throw UserError(where + ": malformed JSON (" + std::string(ex.what()) + ")");
    }
    HistoryEntry e = EntryFromJson(j, where);
    e.line = line_no;
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<HistoryEntry> ReadHistoryFile(const std::string& path, bool missing_ok, std::string* raw) {
  if (raw) raw->clear();
  std::error_code ec;
  if (missing_ok && !std::filesystem::exists(path, ec)) return {};
  std::ifstream f(path, std::ios::binary);
  if (!f) throw UserError("history database '" + path + "' cannot be read");
  std::stringstream ss;
  ss << f.rdbuf();
  if (raw) *raw = ss.str();
  return ParseHistory(ss.str(), "history database '" + path + "'");
}

void CheckSeriesCompatible(const std::vector<HistoryEntry>& entries, const HistoryEntry& e) {
  // The same report twice (under another commit or date): its content without the entry's
  // own labels.
  auto content = [](const HistoryEntry& h) {
    HistoryEntry c = h;
    c.series = "s";
    c.commit = "c";
    c.date = "d";
    c.source.clear();
    c.accepted.reset();
    return HistoryLine(c);
  };
  const std::string mine = content(e);
  for (const auto& x : entries) {
    const bool same_label = x.series == e.series && x.commit == e.commit && x.date == e.date;  // said below
    if (!same_label && content(x) == mine) {
      throw UserError("the history already holds this report (line " + std::to_string(x.line) + ", series '" +
                      x.series + "', commit " + x.commit + ", from '" + x.source +
                      "'): the same rows, output hashes and timing samples; a report is added once");
    }
  }
  const HistoryEntry* last = nullptr;
  for (const auto& x : entries) {
    if (x.series != e.series) continue;
    last = &x;
    if (x.commit == e.commit && x.date == e.date) {
      throw UserError("series '" + e.series + "' already holds commit " + e.commit + " dated " + e.date + " (line " +
                      std::to_string(x.line) + ", from '" + x.source + "'); pass --date to add another run of it");
    }
  }
  if (!last) return;
  std::vector<std::string> diffs;
  for (const auto& k : HistorySeriesKeys()) {
    const std::string a = HistorySettingText(last->report, k), b = HistorySettingText(e.report, k);
    if (a != b) diffs.push_back(k + ": series " + a + ", report " + b);
  }
  if (!diffs.empty()) {
    std::string s;
    for (size_t i = 0; i < diffs.size(); ++i) s += (i ? "; " : "") + diffs[i];
    throw UserError("report '" + e.source + "' does not match series '" + e.series + "' (line " +
                    std::to_string(last->line) + "): " + s +
                    ". Entries of a series must agree on size, ref_spp, seed, scenes, methods, frames, the sampler and "
                    "the viewing condition (ppd, fps); start another series "
                    "with --series NAME");
  }
}

std::vector<std::string> HistorySeriesNames(const std::vector<HistoryEntry>& entries) {
  std::vector<std::string> names;
  for (const auto& e : entries) {
    if (std::find(names.begin(), names.end(), e.series) == names.end()) names.push_back(e.series);
  }
  return names;
}

}  // namespace aalab
