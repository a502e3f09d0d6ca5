// `aalab export-sequences`: frame folders of a motion run for outside video metrics.
#include "harness/run/sequence_export.h"

#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/input_files.h"
#include "io/image_io.h"
#include "io/safe_path.h"
#include "harness/run/out_folder.h"
#include "reports/report_json.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

std::string FrameName(size_t t, const char* ext) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%05zu.%s", t, ext);
  return buf;
}

std::string Setting(const Report& r, const std::string& key, const std::string& fallback) {
  for (const auto& [k, v] : r.settings) {
    if (k == key) return v;
  }
  return fallback;
}

}  // namespace

SequenceExport ExportSequences(const std::string& run_dir, const std::string& out_dir) {
  const fs::path run = run_dir;
  if (const std::string what = WhatIsAt(run_dir); what != "is a folder") {
    throw UserError("'" + run_dir + "' " + (what.empty() ? "is a file" : what) +
                    ", not a run folder (give the folder that holds the motion run's report.json)");
  }
  const Report report = ReadReportFile((run / "report.json").string());
  bool any = false;
  for (const auto& s : report.scenes) any = any || s.frames > 1;
  if (!any) {
    throw UserError("'" + run_dir + "' is not a motion run (no scene has frames > 1): run aalab run --frames N first");
  }
  // Every input file must exist, inside the run folder, before anything is written; every
  // name that becomes a folder under --out must be a plain name (io/safe_path.h).
  const std::string origin = "report '" + (run / "report.json").string() + "'";
  auto need = [&run, &origin](const std::string& rel) {
    const fs::path p = ResolveInside(run, rel, "frame path in " + origin);
    if (!fs::is_regular_file(p)) throw UserError("frame file '" + p.string() + "' is missing");
  };
  for (const auto& s : report.scenes) {
    if (s.frames > 1) CheckOutputName(s.name, "scene name in " + origin);
    for (const auto& f : s.frame_images) need(f);
    for (const auto& f : s.frame_exr_images) need(f);
  }
  for (const auto& row : report.rows) {
    if (!row.frame_images.empty()) {
      CheckOutputName(SpecFileName(row.spec),
                      "method spec '" + row.spec + "' (row of scene '" + row.scene + "') in " + origin, {"reference"});
    }
    for (const auto& f : row.frame_images) need(f);
  }

  OutFolder out(out_dir, "sequences", {run.string()});
  const fs::path tmp = out.Begin();
  SequenceExport res;
  nlohmann::ordered_json doc;
  doc["source"] = fs::absolute(run).string();
  doc["viewing"] = {{"spec", Setting(report, "viewing", "default")},
                    {"ppd", Setting(report, "ppd", "67")},
                    {"fps", Setting(report, "fps", "60")},
                    {"display_px", Setting(report, "display_px", "3840x2160")},
                    {"display_diagonal_in", Setting(report, "display_diagonal_in", "31.62")},
                    {"viewing_distance_m", Setting(report, "viewing_distance_m", "0.7")},
                    {"peak_cd_m2", Setting(report, "peak_cd_m2", "200")},
                    {"ambient_lux", Setting(report, "ambient_lux", "250")}};
  doc["pattern"] = "%05d";
  nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
  for (const auto& s : report.scenes) {
    if (s.frames < 2) continue;
    ++res.scenes;
    const fs::path sdir = tmp / s.name;
    nlohmann::ordered_json js = {{"scene", s.name}, {"frames", s.frames}};
    fs::create_directories(sdir / "reference");
    for (size_t t = 0; t < s.frame_images.size(); ++t) {
      WriteImage8((sdir / "reference" / FrameName(t, "png")).string(), ReadImage8((run / s.frame_images[t]).string()));
      ++res.frames;
    }
    for (size_t t = 0; t < s.frame_exr_images.size(); ++t) {
      WriteImageF((sdir / "reference" / FrameName(t, "exr")).string(),
                  ReadImage((run / s.frame_exr_images[t]).string()).pixels);
      ++res.frames;
    }
    ++res.sequences;
    js["reference"] = {
        {"folder", s.name + "/reference"},
        {"png", "%05d.png"},
        {"exr", s.frame_exr_images.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json("%05d.exr")}};
    nlohmann::ordered_json methods = nlohmann::ordered_json::array();
    for (const auto& row : report.rows) {
      if (row.scene != s.name || row.frame_images.empty()) continue;
      const std::string folder = SpecFileName(row.spec);
      fs::create_directories(sdir / folder);
      for (size_t t = 0; t < row.frame_images.size(); ++t) {
        WriteImage8((sdir / folder / FrameName(t, "png")).string(), ReadImage8((run / row.frame_images[t]).string()));
        ++res.frames;
      }
      ++res.sequences;
      methods.push_back({{"spec", row.spec}, {"folder", s.name + "/" + folder}, {"png", "%05d.png"}});
    }
    js["methods"] = methods;
    scenes.push_back(js);
  }
  doc["scenes"] = scenes;
  WriteTextFile((tmp / "sequences.json").string(), doc.dump(2) + "\n");
  out.Commit();
  return res;
}

}  // namespace aalab
