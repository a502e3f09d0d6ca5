// `aalab export REPORT_DIR... --out DIR`: a report (or a merged one, or several for a
// before/after) to publication material — tables (LaTeX, Markdown, CSV), the crop figure (PNG,
// SVG, LaTeX snippet), the quality-vs-time chart (SVG) and references.bib — every number read
// from report.json, every file stamped with its provenance (docs/publishing.md).
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "build_info.h"
#include "harness/cli/commands.h"
#include "core/error.h"
#include "core/exit_code.h"
#include "io/image_io.h"
#include "io/safe_path.h"
#include "io/text_draw.h"
#include "harness/run/out_folder.h"
#include "methods/registry.h"
#include "metrics/heatmap.h"
#include "metrics/metric.h"
#include "reports/html_speed.h"
#include "reports/export_bibliography.h"
#include "reports/export_chart.h"
#include "reports/export_crops.h"
#include "reports/export_tables.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

struct ExportArgs {
  std::vector<std::string> reports;
  std::string out, labels, scenes, methods, metric;
  std::string figure_scene, figure_methods, crops;
  int zoom = 0;
  bool heatmap = false;
};

/// report.json's bytes and its folder, from a report folder or a report.json path.
std::pair<std::string, std::string> ReadReportBytes(const std::string& arg) {
  fs::path dir = arg, file = fs::path(arg) / "report.json";
  if (fs::is_regular_file(arg)) {
    file = arg;
    dir = fs::path(arg).parent_path();
    if (dir.empty()) dir = ".";
  }
  if (!fs::is_regular_file(file)) {
    throw UserError("'" + arg + "' is neither a report folder (with report.json) nor a report.json file");
  }
  std::ifstream f(file, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  if (!f.good() && !f.eof()) throw UserError("cannot read '" + file.string() + "'");
  return {ss.str(), dir.string()};
}

std::string FolderName(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  const std::string name = p.filename().string();
  return name.empty() || name == "." ? fs::absolute(p).lexically_normal().filename().string() : name;
}

/// Crop items: an index into the scene's crop windows ("0") or a rectangle "X:Y:W:H".
std::vector<std::array<int, 4>> ParseCrops(const std::string& text, const SceneResult& scene) {
  std::vector<std::array<int, 4>> out;
  for (const auto& item : SplitList(text)) {
    auto fail = [&] {
      throw UserError("--crops item '" + item + "' is neither an index of scene '" + scene.name + "''s " +
                      std::to_string(scene.crops.size()) + " crop windows (0.." +
                      std::to_string(static_cast<int>(scene.crops.size()) - 1) + ") nor a rectangle X:Y:W:H");
    };
    std::vector<int> nums;
    std::stringstream ss(item);
    std::string part;
    while (std::getline(ss, part, ':')) {
      if (part.empty() || part.size() > 6 || part.find_first_not_of("0123456789") != std::string::npos) fail();
      nums.push_back(std::stoi(part));
    }
    if (nums.size() == 1) {
      if (nums[0] >= static_cast<int>(scene.crops.size())) fail();
      out.push_back(scene.crops[nums[0]]);
    } else if (nums.size() == 4) {
      out.push_back({nums[0], nums[1], nums[2], nums[3]});
    } else {
      fail();
    }
  }
  return out;
}

/// The registry source of a report's method (by the registry name in its rows).
std::string MethodSource(const Report& r, const std::string& spec) {
  std::string name = spec;
  for (const auto& row : r.rows) {
    if (row.spec == spec) name = row.method;
  }
  for (const auto& e : MethodRegistry()) {
    if (e.name == name) return e.source;
  }
  return "";
}

std::string MetricSource(const std::string& metric) {
  const MetricEntry* e = FindMetricEntry(metric);
  return e ? e->source : "";
}

std::string CropList(const std::vector<std::array<int, 4>>& crops) {
  std::string s;
  for (const auto& c : crops) {
    s += (s.empty() ? "" : ", ") + std::string("[") + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " +
         std::to_string(c[2]) + ", " + std::to_string(c[3]) + "]";
  }
  return s;
}

std::string FigureLatex(const std::vector<ExportSource>& sources, const CropFigureOptions& o,
                        const std::vector<std::string>& provenance) {
  const SceneResult* scene = FindScene(sources.front().report, o.scene);
  std::string methods;
  for (const auto& m : o.methods) methods += (methods.empty() ? "" : ", ") + m;
  std::string caption = "Crops [x, y, w, h] = " + CropList(o.crops) + " of scene " + o.scene + " (" +
                        std::to_string(scene->width) + "x" + std::to_string(scene->height) + "), enlarged " +
                        std::to_string(o.zoom) + "x by pixel replication: the reference and the output of " + methods +
                        ".";
  if (sources.size() > 1)
    caption += " Each method is shown for every run in order (" + [&] {
      std::string s;
      for (const auto& src : sources) s += (s.empty() ? "" : ", ") + src.label;
      return s;
    }() + ").";
  if (o.heatmap) {
    char full[32];
    std::snprintf(full, sizeof full, "%g", static_cast<double>(kErrorHeatmapMax));
    caption += std::string(
                   " Under each crop: the absolute error against the reference (mean over RGB of the 8-bit "
                   "values), viridis from 0 to ") +
               full + " and above.";
  }
  // Each report's own conditions (viewing, sampler, reference): the first's, then any other
  // report's that differ, named by its label.
  const std::string first = ConditionsSentence(sources.front().report, false);
  caption += " " + (sources.size() > 1 ? sources.front().label + ": " : std::string()) + first;
  for (size_t i = 1; i < sources.size(); ++i) {
    const std::string own = ConditionsSentence(sources[i].report, false);
    caption += " " + sources[i].label + ": " + (own == first ? std::string("the same conditions.") : own);
  }
  std::string o_tex;
  for (const auto& line : provenance) o_tex += "% " + line + "\n";
  o_tex +=
      "% Needs \\usepackage{graphicx}.\n\\begin{figure*}[tbp]\n\\centering\n"
      "\\includegraphics[width=\\linewidth]{figure_crops.png}\n\\caption{" +
      LatexEscape(caption) + "}\n\\label{fig:aalab-crops}\n\\end{figure*}\n";
  return o_tex;
}

int RunExport(const ExportArgs& a) {
  if (a.out.empty()) throw UserError("--out is required");
  OutFolder folder(a.out, "export", a.reports);
  // Read and check every input before creating anything.
  std::vector<std::string> labels = a.labels.empty() ? std::vector<std::string>{} : SplitList(a.labels);
  if (!labels.empty() && labels.size() != a.reports.size()) {
    throw UserError("--labels gives " + std::to_string(labels.size()) + " labels for " +
                    std::to_string(a.reports.size()) + " reports");
  }
  std::vector<ExportSource> sources;
  for (size_t i = 0; i < a.reports.size(); ++i) {
    const auto [bytes, dir] = ReadReportBytes(a.reports[i]);
    const std::string label = labels.empty() ? FolderName(dir) : labels[i];
    for (const auto& s : sources) {
      if (s.label == label) throw UserError("two reports are labelled '" + label + "'; give --labels A,B");
    }
    sources.push_back(SourceFromBytes(bytes, (fs::path(dir) / "report.json").string(), dir, label));
  }
  ExportSelection asked;
  if (!a.scenes.empty()) asked.scenes = SplitList(a.scenes);
  if (!a.methods.empty()) asked.methods = SplitList(a.methods);
  asked.metric = a.metric;
  const ExportSelection sel = ResolveSelection(sources, asked);

  CropFigureOptions fig_asked;
  fig_asked.scene = a.figure_scene;
  if (!a.figure_methods.empty()) fig_asked.methods = SplitList(a.figure_methods);
  fig_asked.zoom = a.zoom;
  fig_asked.heatmap = a.heatmap;
  if (!a.crops.empty()) {
    const std::string scene_name =
        a.figure_scene.empty() ? DefaultCropFigure(sources, sel, fig_asked).scene : a.figure_scene;
    const SceneResult* scene = FindScene(sources.front().report, scene_name);
    if (!scene)
      throw UserError("--figure-scene: scene '" + scene_name + "' is not in report '" + sources.front().dir + "'");
    fig_asked.scene = scene_name;
    fig_asked.crops = ParseCrops(a.crops, *scene);
  }
  const CropFigureOptions fig_opts = DefaultCropFigure(sources, sel, fig_asked);
  CropFigure fig = ComposeCropFigure(sources, fig_opts, [&](size_t s, const std::string& rel) {
    // The report names the image; it must lie inside the report's folder (safe_path.h).
    return ReadImage8(
        ResolveInside(sources[s].dir, rel,
                      "image path in report '" + (fs::path(sources[s].dir) / "report.json").string() + "'")
            .string());
  });
  for (const auto& l : fig.labels) DrawText(fig.pixels, l.x, l.y, l.text, l.size);

  const std::vector<std::string> prov = ProvenanceLines(sources);
  const ExportTable metric_table = MetricTable(sources, sel);
  const ExportTable cost_table = CostTable(sources, sel);
  std::vector<std::pair<std::string, std::string>> uses;
  for (const auto& spec : sel.methods) uses.push_back({"method " + spec, MethodSource(sources.front().report, spec)});
  for (const auto& spec : fig_opts.methods) {
    if (std::find(sel.methods.begin(), sel.methods.end(), spec) == sel.methods.end()) {
      uses.push_back({"method " + spec, MethodSource(sources.front().report, spec)});
    }
  }
  uses.push_back({"metric " + sel.metric, MetricSource(sel.metric)});

  // Everything is computed; now write, through DIR.partial.
  const fs::path dir = folder.Begin();
  std::vector<std::pair<std::string, std::string>> files;  // name → contents (text files)
  files.push_back({"metric_table.tex", TableToLatex(metric_table, "metric", prov)});
  files.push_back({"metric_table.md", TableToMarkdown(metric_table, prov)});
  files.push_back({"metric_table.csv", TableToCsv(metric_table, prov)});
  files.push_back({"cost_table.tex", TableToLatex(cost_table, "cost", prov)});
  files.push_back({"cost_table.md", TableToMarkdown(cost_table, prov)});
  files.push_back({"cost_table.csv", TableToCsv(cost_table, prov)});
  files.push_back({"figure_crops.svg", CropFigureToSvg(fig, prov)});
  files.push_back({"figure_crops.tex", FigureLatex(sources, fig_opts, prov)});
  files.push_back({"chart_quality_time.svg", QualityTimeChartSvg(sources, sel, prov)});
  files.push_back({"references.bib", BibtexFile(uses, prov)});
  // Runs over the speed-sweep scenes (docs/motion.md): quality against speed per method.
  if (!SpeedSweepPoints(sources.front().report).empty()) {
    files.push_back({"speed_sweep.csv", SpeedSweepCsv(sources.front().report)});
  }
  nlohmann::ordered_json manifest;
  manifest["tool"] = "aalab export";
  manifest["tool_version"] = AALAB_VERSION;
  manifest["git_commit"] = AALAB_GIT_COMMIT;
  manifest["reports"] = nlohmann::ordered_json::array();
  for (const auto& s : sources) {
    manifest["reports"].push_back({{"label", s.label}, {"dir", s.dir}, {"report_json_sha256", s.sha256}});
  }
  manifest["scenes"] = sel.scenes;
  manifest["methods"] = sel.methods;
  manifest["metric"] = sel.metric;
  manifest["figure"] = {{"scene", fig_opts.scene},
                        {"methods", fig_opts.methods},
                        {"crops", fig_opts.crops},
                        {"zoom", fig_opts.zoom},
                        {"heatmap", fig_opts.heatmap}};
  manifest["files"] = nlohmann::ordered_json::object();
  for (const auto& [name, text] : files) {
    WriteTextFile((dir / name).string(), text);
    manifest["files"][name] = Sha256Hex(text);
  }
  ImageText meta = {{"Software", std::string("aalab ") + AALAB_VERSION + " (commit " + AALAB_GIT_COMMIT + ")"}};
  std::string comment;
  for (const auto& line : prov) comment += (comment.empty() ? "" : "\n") + line;
  meta.push_back({"Comment", comment});
  WriteImage8WithText((dir / "figure_crops.png").string(), fig.pixels, meta);
  manifest["files"]["figure_crops.png"] = "";  // PNG bytes depend on libpng; its pixels are the SVG's
  WriteTextFile((dir / "export.json").string(), manifest.dump(2) + "\n");
  folder.Commit();
  std::printf("exported %zu scene(s) x %zu method(s) of %s from %zu report(s) to %s\n", sel.scenes.size(),
              sel.methods.size(), sel.metric.c_str(), sources.size(), a.out.c_str());
  std::printf("figure: scene %s, crops %s, zoom %dx, methods", fig_opts.scene.c_str(), CropList(fig_opts.crops).c_str(),
              fig_opts.zoom);
  for (const auto& m : fig_opts.methods) std::printf(" %s", m.c_str());
  std::printf("\n");
  return ToInt(ExitCode::kOk);
}

}  // namespace

void RegisterExportCommand(CLI::App& app, Commands& commands) {
  auto* cmd = app.add_subcommand("export",
                                 "turn report folders (one, a merged one, or several for a before/after) into "
                                 "tables (LaTeX, Markdown, CSV), a crop figure (PNG, SVG), a quality-vs-time chart "
                                 "(SVG) and references.bib");
  auto a = std::make_shared<ExportArgs>();
  cmd->add_option("reports", a->reports, "report folders (or report.json files)")->required();
  cmd->add_option("--out", a->out, "output folder (created; replaced only if it holds a previous export.json)")
      ->required();
  cmd->add_option("--labels", a->labels, "names of the reports in tables and figures (default: folder names)");
  cmd->add_option("--scenes", a->scenes, "scenes of the tables and chart, in order (default: all of the first report)");
  cmd->add_option("--methods", a->methods, "method specs of the tables and chart, in order (default: all)");
  cmd->add_option("--metric", a->metric, "metric of the tables and chart (default: edge_psnr_db, else psnr_db)");
  cmd->add_option("--figure-scene", a->figure_scene,
                  "scene of the crop figure (default: where the metric spreads most over the figure's methods)");
  cmd->add_option("--figure-methods", a->figure_methods,
                  "methods of the crop figure (default: none, ssaa-4x4, msaa-4x, fxaa-high, smaa-high, aaa, taa "
                  "as far as the report has them)");
  cmd->add_option("--crops", a->crops,
                  "crop windows: indices into the scene's crops (0 = where none errs most) or X:Y:W:H rectangles "
                  "(default: 0,1)");
  cmd->add_option("--zoom", a->zoom, "pixel replication factor 1..32 (default: tiles of about 128 px)")
      ->check(CLI::Range(1, 32));
  cmd->add_flag("--heatmap", a->heatmap, "add a row of absolute-error heatmaps under each crop");
  cmd->callback([&commands, a] { commands.action = [a] { return RunExport(*a); }; });
}

}  // namespace aalab
