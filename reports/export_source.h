/// `aalab export`'s input: the reports it reads (one, a merged one, or several for a
/// before/after), what to take from them (scenes, methods, metric) and the provenance every
/// exported file carries (docs/publishing.md). Pure: reading and writing files is the CLI's.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "reports/result.h"

namespace aalab {

/// One report as export reads it.
struct ExportSource {
  Report report;
  std::string dir;     ///< the report folder as given on the command line
  std::string label;   ///< its name in tables and figures ("before", "after"; the folder name by default)
  std::string sha256;  ///< SHA-256 of report.json's bytes, 64 hex digits: the report's identity
};

/// What to export. Empty lists mean the defaults (ResolveSelection).
struct ExportSelection {
  std::vector<std::string> scenes;   ///< scene names, in table order
  std::vector<std::string> methods;  ///< canonical specs, in table order
  std::string metric;                ///< metric of the tables and the chart
};

/// SHA-256 of `bytes` as 64 lowercase hex digits (OpenSSL), so `sha256sum report.json` checks it.
std::string Sha256Hex(const std::string& bytes);

/// Parses report.json's bytes (`path` names it in errors) into a source labelled `label`.
ExportSource SourceFromBytes(const std::string& bytes, const std::string& path, const std::string& dir,
                             const std::string& label);

/// Fills the defaults and checks the choices against the first report; every other report
/// must hold the chosen scenes and methods too. Defaults: every scene and every method of the
/// first report in report order, metric `edge_psnr_db` (else `psnr_db`). UserError naming
/// the unknown scene/method/metric and listing the ones the report has.
ExportSelection ResolveSelection(const std::vector<ExportSource>& sources, const ExportSelection& asked);

/// The row of `spec` on `scene`, or null.
const ResultRow* FindRow(const Report& report, const std::string& scene, const std::string& spec);
/// The scene record of `name`, or null.
const SceneResult* FindScene(const Report& report, const std::string& name);
/// The value of `metric` in `row` (empty when null or absent).
std::optional<double> MetricOf(const ResultRow& row, const std::string& metric);
/// A setting of the run ("" when absent).
std::string SettingOf(const Report& report, const std::string& key);

/// The provenance lines every exported file carries, without comment markers: the exporting
/// tool's version and commit, and for each source its label, folder, report.json's SHA-256
/// and the tool version and commit that wrote it.
std::vector<std::string> ProvenanceLines(const std::vector<ExportSource>& sources);

/// What produced the numbers, for captions: reference ("64-spp stratified reference" or
/// "exact-coverage reference"), size, the viewing condition (FLIP and the temporal error: e.g.
/// 67 pixels per degree), the post filters' sampler and the timing conditions (repeats,
/// warm-up, CPU, threads).
/// `timing` false leaves the timing conditions out (a figure of images has no times).
std::string ConditionsSentence(const Report& report, bool timing = true);

}  // namespace aalab
