// `aalab export` through the real binary on a tiny run: the exported numbers parsed back from
// the CSV and LaTeX equal report.json's, the figure's pixels equal the report's images at the
// crop rectangles, every file names report.json's SHA-256 (computed by sha256sum), bad input
// leaves nothing behind; and the LaTeX compiles where pdflatex exists (make test-latex).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "io/image_io.h"

namespace {
namespace fs = std::filesystem;
using aalab::clitest::Aalab;
using aalab::clitest::CmdResult;
using aalab::clitest::RunCommand;
using aalab::clitest::TempDir;
using Json = nlohmann::json;

std::string Slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

/// A tiny run: wedges (edges) and detail-texture (no edge pixels: edge PSNR is null there).
fs::path TinyRun(const fs::path& root, const std::string& methods = "none,fxaa-high,ssaa-2x2") {
  const fs::path run = root / "run";
  const CmdResult r =
      Aalab("run --size 96x54 --scenes wedges,detail-texture --methods " + methods + " --out " + run.string());
  EXPECT_EQ(r.code, 0) << r.output;
  return run;
}

std::optional<double> MetricIn(const Json& report, const std::string& scene, const std::string& spec,
                               const std::string& metric) {
  for (const auto& row : report["rows"]) {
    if (row["scene"] == scene && row["spec"] == spec) {
      const auto& v = row["metrics"][metric];
      if (v.is_null()) return std::nullopt;
      return v.get<double>();
    }
  }
  ADD_FAILURE() << "no row " << scene << " " << spec;
  return std::nullopt;
}

double MedianMs(const Json& report, const std::string& scene, const std::string& spec) {
  for (const auto& row : report["rows"]) {
    if (row["scene"] == scene && row["spec"] == spec) return row["timing"]["total"]["median_ms"].get<double>();
  }
  ADD_FAILURE() << "no row " << scene << " " << spec;
  return 0;
}

/// CSV lines (comments skipped), split on commas (no field here holds a comma).
std::vector<std::vector<std::string>> Csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream ss(text);
  std::string line;
  while (std::getline(ss, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    size_t start = 0;
    while (true) {
      const size_t c = line.find(',', start);
      f.push_back(line.substr(start, c == std::string::npos ? std::string::npos : c - start));
      if (c == std::string::npos) break;
      start = c + 1;
    }
    rows.push_back(f);
  }
  return rows;
}

/// A LaTeX body row "label & c1 & c2 \\" → label and cells (bold and $-$ undone, "--" empty).
std::map<std::string, std::vector<std::optional<double>>> LatexRows(const std::string& tex) {
  std::map<std::string, std::vector<std::optional<double>>> rows;
  const size_t begin = tex.find("\\midrule\n"), end = tex.find("\\bottomrule");
  std::stringstream ss(tex.substr(begin + 9, end - begin - 9));
  std::string line;
  while (std::getline(ss, line)) {
    if (line.rfind("\\", 0) == 0) continue;  // \midrule, \multicolumn group rows
    line = std::regex_replace(line, std::regex(R"(\\textbf\{([^}]*)\})"), "$1");
    line = std::regex_replace(line, std::regex(R"(\$-\$)"), "-");
    line = std::regex_replace(line, std::regex(R"(\$\^\\dagger\$)"), "");  // near the noise floor
    line = std::regex_replace(line, std::regex(R"(\s*\\\\\s*$)"), "");
    std::vector<std::string> f;
    size_t start = 0;
    while (true) {
      const size_t c = line.find(" & ", start);
      f.push_back(line.substr(start, c == std::string::npos ? std::string::npos : c - start));
      if (c == std::string::npos) break;
      start = c + 3;
    }
    std::vector<std::optional<double>> cells;
    for (size_t i = 1; i < f.size(); ++i) {
      if (f[i] == "--" || f[i].empty() || f[i] == "$\\bullet$") {
        cells.push_back(std::nullopt);
      } else {
        cells.push_back(std::stod(f[i]));
      }
    }
    rows[f[0]] = cells;
  }
  return rows;
}

std::string Sha256Of(const fs::path& file) {
  const CmdResult r = RunCommand("sha256sum '" + file.string() + "'");
  EXPECT_EQ(r.code, 0);
  return r.output.substr(0, 64);
}

TEST(ExportCli, NumbersFiguresAndProvenanceMatchTheReport) {
  const fs::path root = TempDir("export");
  const fs::path run = TinyRun(root);
  const fs::path out = root / "paper";
  const CmdResult r = Aalab("export " + run.string() + " --out " + out.string() + " --heatmap");
  ASSERT_EQ(r.code, 0) << r.output;
  const Json report = Json::parse(Slurp(run / "report.json"));
  const std::vector<std::string> specs = {"none", "fxaa-high", "ssaa-2x2"};
  const std::vector<std::string> scenes = {"wedges", "detail-texture"};

  // Metric table, CSV: the values of report.json exactly; the mean over the scenes where every
  // method has a value (wedges only: detail-texture has no edge pixels, so no column either,
  // only a note).
  const std::string csv_text = Slurp(out / "metric_table.csv");
  EXPECT_NE(csv_text.find("# No column for detail-texture: Edge PSNR is undefined there for every method"),
            std::string::npos)
      << csv_text;
  const auto csv = Csv(csv_text);
  ASSERT_EQ(csv[0], (std::vector<std::string>{"Method", "wedges", "Mean"}));
  for (size_t m = 0; m < specs.size(); ++m) {
    const auto& row = csv[1 + m];
    ASSERT_EQ(row[0], specs[m]);
    const auto wedges = MetricIn(report, "wedges", specs[m], "edge_psnr_db");
    ASSERT_TRUE(wedges);
    EXPECT_EQ(std::stod(row[1]), *wedges) << specs[m];
    EXPECT_FALSE(MetricIn(report, "detail-texture", specs[m], "edge_psnr_db"));
    EXPECT_EQ(std::stod(row[2]), *wedges) << specs[m];
  }
  // LaTeX: the same values to the printed 2 decimals.
  const auto tex = LatexRows(Slurp(out / "metric_table.tex"));
  for (const auto& spec : specs) {
    const auto& cells = tex.at(spec);
    ASSERT_EQ(cells.size(), 2u) << spec;
    EXPECT_NEAR(*cells[0], *MetricIn(report, "wedges", spec, "edge_psnr_db"), 0.005 + 1e-9) << spec;
    EXPECT_NEAR(*cells[1], *MetricIn(report, "wedges", spec, "edge_psnr_db"), 0.005 + 1e-9) << spec;
  }
  // Cost table: time = wedges' median, gain = value − none's value, both from report.json.
  const auto cost = Csv(Slurp(out / "cost_table.csv"));
  const double none_v = *MetricIn(report, "wedges", "none", "edge_psnr_db");
  const double none_t = MedianMs(report, "wedges", "none");
  int checked = 0;
  for (const auto& row : cost) {
    if (row[0] == "Method" || row[0] == "best") continue;
    const double v = *MetricIn(report, "wedges", row[0], "edge_psnr_db"), t = MedianMs(report, "wedges", row[0]);
    EXPECT_EQ(std::stod(row[1]), v);
    EXPECT_NEAR(std::stod(row[2]), v - none_v, 1e-12);
    EXPECT_EQ(std::stod(row[3]), t);
    EXPECT_NEAR(std::stod(row[4]), t - none_t, 1e-12);
    if (row[0] != "none" && t > none_t) {
      EXPECT_NEAR(std::stod(row[5]), (v - none_v) / (t - none_t), 1e-9);
    }
    ++checked;
  }
  EXPECT_EQ(checked, 3);

  // The crop figure: the default scene is wedges (the only one with crops), its first two
  // crop windows; the PNG's pixels at every image tile equal the report's images there.
  const std::string svg = Slurp(out / "figure_crops.svg");
  const aalab::Image8 png = aalab::ReadImage8((out / "figure_crops.png").string());
  const std::regex group(
      R"re(<g transform="translate\((\d+) (\d+)\) scale\((\d+)\)"[^>]*data-crop="(\d+) (\d+) (\d+) (\d+)" data-kind="(image|heatmap)" data-image="([^"]+)">)re");
  const auto& crops = report["scenes"][0]["crops"];
  int tiles = 0, heat = 0;
  for (auto g = std::sregex_iterator(svg.begin(), svg.end(), group); g != std::sregex_iterator(); ++g) {
    const int x = std::stoi((*g)[1].str()), y = std::stoi((*g)[2].str()), zoom = std::stoi((*g)[3].str());
    const std::vector<int> crop = {std::stoi((*g)[4].str()), std::stoi((*g)[5].str()), std::stoi((*g)[6].str()),
                                   std::stoi((*g)[7].str())};
    EXPECT_TRUE(crop == crops[0].get<std::vector<int>>() || crop == crops[1].get<std::vector<int>>());
    if ((*g)[8].str() == "heatmap") {
      ++heat;
      continue;
    }
    const aalab::Image8 src = aalab::ReadImage8((run / (*g)[9].str()).string());
    for (int j = 0; j < crop[3] * zoom; ++j) {
      for (int i = 0; i < crop[2] * zoom; ++i) {
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(png.At(x + i, y + j, c), src.At(crop[0] + i / zoom, crop[1] + j / zoom, c))
              << (*g)[9].str() << " at " << i << "," << j;
        }
      }
    }
    ++tiles;
  }
  EXPECT_EQ(tiles, 2 * 3);  // 2 crops × (reference, none, fxaa-high): ssaa-2x2 is not a figure default
  EXPECT_EQ(heat, 2 * 2);
  EXPECT_NE(r.output.find("figure: scene wedges"), std::string::npos) << r.output;

  // Provenance: report.json's SHA-256 (by sha256sum) and this build's commit in every file.
  const std::string sha = Sha256Of(run / "report.json");
  for (const char* f : {"metric_table.tex", "metric_table.md", "metric_table.csv", "cost_table.tex", "cost_table.md",
                        "cost_table.csv", "figure_crops.svg", "figure_crops.tex", "chart_quality_time.svg",
                        "references.bib", "figure_crops.png", "export.json"}) {
    const std::string text = Slurp(out / f);
    EXPECT_NE(text.find(sha), std::string::npos) << f;
    if (std::string(f) != "export.json") {
      EXPECT_NE(text.find("exported by aalab"), std::string::npos) << f;
    }
  }
  // Citations: the table's FXAA preset comes from the shader and the tutorial; no SMAA here.
  const std::string bib = Slurp(out / "references.bib");
  EXPECT_NE(bib.find("@misc{lottes2011fxaa311,"), std::string::npos);
  EXPECT_NE(bib.find("@misc{flick2021fxaa,"), std::string::npos);
  EXPECT_EQ(bib.find("jimenez2012smaa"), std::string::npos);
  // The chart plots every method (means over wedges).
  const std::string chart = Slurp(out / "chart_quality_time.svg");
  for (const auto& spec : specs) EXPECT_NE(chart.find("data-spec=\"" + spec + "\""), std::string::npos) << spec;

  // Again into the same folder: it holds export.json, so it is replaced.
  EXPECT_EQ(
      Aalab("export " + run.string() + " --out " + out.string() + " --scenes wedges --methods none,ssaa-2x2").code, 0);
  EXPECT_EQ(Csv(Slurp(out / "metric_table.csv"))[0], (std::vector<std::string>{"Method", "wedges"}));

  // Before/after: the same report twice under two labels.
  const CmdResult two =
      Aalab("export " + run.string() + " " + run.string() + " --labels before,after --out " + (root / "ab").string());
  ASSERT_EQ(two.code, 0) << two.output;
  EXPECT_EQ(Csv(Slurp(root / "ab" / "metric_table.csv"))[0][3], "after:wedges");
  fs::remove_all(root);
}

TEST(ExportCli, BadInputNamesTheProblemAndWritesNothing) {
  const fs::path root = TempDir("export-bad");
  const fs::path run = TinyRun(root, "none,fxaa-high");
  const fs::path out = root / "o";
  auto fails = [&](const std::string& args, const std::string& part) {
    const CmdResult r = Aalab("export " + args);
    EXPECT_EQ(r.code, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(part), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out)) << args;
    EXPECT_FALSE(fs::exists(out.string() + ".partial")) << args;
  };
  fails((root / "missing").string() + " --out " + out.string(), "neither a report folder");
  fails(run.string() + " --out " + out.string() + " --metric nope", "--metric 'nope' is not in report");
  fails(run.string() + " --out " + out.string() + " --scenes wedgez", "scene 'wedgez' is not in report");
  fails(run.string() + " --out " + out.string() + " --methods smaa-high", "method 'smaa-high' is not in report");
  fails(run.string() + " --out " + out.string() + " --crops 9", "--crops item '9'");
  fails(run.string() + " --out " + out.string() + " --crops 90:50:10:10", "must lie inside scene 'wedges'");
  fails(run.string() + " --out " + out.string() + " --zoom 40", "not in range 1 to 32");
  fails(run.string() + " " + run.string() + " --out " + out.string(), "two reports are labelled");
  fails(run.string() + " --out " + out.string() + " --figure-scene detail-texture", "no crop windows");
  {
    std::ofstream(root / "broken.json") << "{ not json";
    fails((root / "broken.json").string() + " --out " + out.string(), "is not valid JSON");
  }
  // A folder of other files is never replaced.
  fs::create_directories(out);
  std::ofstream(out / "thesis.tex") << "mine";
  const CmdResult r = Aalab("export " + run.string() + " --out " + out.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("cannot be replaced"), std::string::npos) << r.output;
  EXPECT_EQ(Slurp(out / "thesis.tex"), "mine");
  fs::remove_all(root);
}

/// The exported LaTeX (both tables, the figure snippet) and references.bib in a minimal
/// article through pdflatex + bibtex. Skipped without pdflatex: `make test-latex` installs
/// texlive-latex-base, texlive-latex-recommended and texlive-fonts-recommended and runs it.
TEST(ExportCli, LatexCompiles) {
  if (std::system("command -v pdflatex > /dev/null 2>&1 && command -v bibtex > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "no pdflatex/bibtex: run `make test-latex` (installs TeX Live from Debian)";
  }
  const fs::path root = TempDir("export-latex");
  const fs::path run = TinyRun(root, "none,fxaa-high,fxaa1-p3,smaa-high,ssaa-2x2,msaa-4x,aaa");
  const fs::path out = root / "paper";
  const CmdResult r = Aalab("export " + run.string() + " --out " + out.string() + " --heatmap");
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path doc = root / "doc";
  fs::create_directories(doc);
  for (const auto& e : fs::directory_iterator(out)) fs::copy_file(e.path(), doc / e.path().filename());
  std::ofstream(doc / "main.tex") << "\\documentclass{article}\n\\usepackage[T1]{fontenc}\n\\usepackage{booktabs}\n"
                                     "\\usepackage{graphicx}\n\\usepackage{url}\n\\begin{document}\n"
                                     "\\input{metric_table}\n\\input{cost_table}\n\\input{figure_crops}\n"
                                     "\\nocite{*}\n\\bibliographystyle{plain}\n\\bibliography{references}\n"
                                     "\\end{document}\n";
  const std::string tex = "cd '" + doc.string() + "' && pdflatex -interaction=nonstopmode -halt-on-error main.tex";
  CmdResult c = RunCommand(tex + " 2>&1");
  ASSERT_EQ(c.code, 0) << c.output;
  c = RunCommand("cd '" + doc.string() + "' && bibtex main 2>&1");
  ASSERT_EQ(c.code, 0) << c.output;
  c = RunCommand(tex + " 2>&1 && " + tex + " 2>&1");
  ASSERT_EQ(c.code, 0) << c.output;
  const std::string log = Slurp(doc / "main.log");
  EXPECT_EQ(log.find("Undefined control sequence"), std::string::npos);
  EXPECT_EQ(log.find("Citation"), std::string::npos) << "an unresolved citation";
  EXPECT_GT(fs::file_size(doc / "main.pdf"), 10000u);
  const std::string bbl = Slurp(doc / "main.bbl");
  for (const char* who : {"Lottes", "Jimenez", "Flick", "FrostKiwi", "aalab"}) {
    EXPECT_NE(bbl.find(who), std::string::npos) << who;
  }
  fs::remove_all(root);
}

}  // namespace
