// aalab export's pure parts on a hand-made report: table numbers, means, best marks, the cost
// of accuracy and the Pareto front worked out by hand; the CSV and LaTeX parsed back; the crop
// figure's pixels against the source images; the bibliography against the registries.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>
#include <sstream>

#include "core/color.h"
#include "methods/registry.h"
#include "metrics/heatmap.h"
#include "metrics/metric.h"
#include "reports/export_bibliography.h"
#include "reports/export_crops.h"
#include "reports/export_tables.h"

namespace aalab {
namespace {

ResultRow Row(const std::string& scene, const std::string& spec, std::optional<double> edge, double flip, double ms) {
  ResultRow r;
  r.scene = scene;
  r.method = spec;
  r.spec = spec;
  r.metrics = {{"edge_psnr_db", edge, edge ? "" : "no edge pixels"}, {"flip_mean", flip, ""}};
  r.total.samples_ms = {ms};
  r.total.Summarize();
  r.images = {{"output", "images/" + scene + "/" + spec + ".png"}};
  return r;
}

/// Scenes a, b (values everywhere) and c (none has no edge PSNR there, so c is left out of
/// the means). Means over a and b: none 21 dB at 2 ms, fast 23 dB at 2 ms, slow 32 dB at 5 ms.
ExportSource Source() {
  ExportSource s;
  s.dir = "runs/x";
  s.label = "x";
  s.sha256 = std::string(64, '0');
  Report& r = s.report;
  r.settings = {{"size", "8x6"}, {"ref_spp", "16"}, {"repeat", "3"}, {"warmup", "1"}};
  r.context = {{"cpu", "test cpu"}, {"threads", "2"}};
  for (const char* name : {"a", "b", "c"}) {
    SceneResult sc;
    sc.name = name;
    sc.width = 8;
    sc.height = 6;
    sc.ref_spp = 16;
    sc.crops = {{1, 1, 3, 2}, {4, 2, 2, 2}};
    sc.images = {{"reference_png", std::string("images/") + name + "/reference.png"}};
    r.scenes.push_back(sc);
  }
  r.rows = {Row("a", "none", 20, 0.2, 1),           Row("a", "fast", 25, 0.1, 1.5), Row("a", "slow", 30, 0.05, 4),
            Row("b", "none", 22, 0.3, 3),           Row("b", "fast", 21, 0.2, 2.5), Row("b", "slow", 34, 0.04, 6),
            Row("c", "none", std::nullopt, 0.1, 1), Row("c", "fast", 10, 0.1, 1),   Row("c", "slow", 12, 0.1, 1)};
  return s;
}

ExportSelection Sel(const std::vector<ExportSource>& src, const std::string& metric = "") {
  ExportSelection asked;
  asked.metric = metric;
  return ResolveSelection(src, asked);
}

/// CSV rows by their first field (comment lines skipped).
std::map<std::string, std::vector<std::string>> ParseCsv(const std::string& csv) {
  std::map<std::string, std::vector<std::string>> rows;
  std::stringstream ss(csv);
  std::string line;
  while (std::getline(ss, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::stringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) f.push_back(cell);
    if (line.back() == ',') f.push_back("");
    rows[f[0]] = f;
  }
  return rows;
}

TEST(ExportTables, DefaultsAndChecks) {
  const std::vector<ExportSource> src{Source()};
  const ExportSelection sel = Sel(src);
  EXPECT_EQ(sel.metric, "edge_psnr_db");
  EXPECT_EQ(sel.scenes, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(sel.methods, (std::vector<std::string>{"none", "fast", "slow"}));
  ExportSelection bad;
  bad.metric = "nope";
  try {
    ResolveSelection(src, bad);
    FAIL() << "unknown metric accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("'nope'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("edge_psnr_db, flip_mean"), std::string::npos);
  }
  bad = {};
  bad.scenes = {"a", "zz"};
  EXPECT_THROW(ResolveSelection(src, bad), UserError);
  bad = {};
  bad.methods = {"fast", "fast"};
  EXPECT_THROW(ResolveSelection(src, bad), UserError);
}

TEST(ExportTables, MetricTableValuesMeansAndBest) {
  const std::vector<ExportSource> src{Source()};
  const ExportTable t = MetricTable(src, Sel(src));
  ASSERT_EQ(t.columns, (std::vector<std::string>{"a", "b", "c", "Mean"}));
  ASSERT_EQ(t.row_labels, (std::vector<std::string>{"none", "fast", "slow"}));
  EXPECT_EQ(*t.cells[1][1].value, 21.0);
  EXPECT_FALSE(t.cells[0][2].value);  // none on c: null
  // Means over a and b only (c is left out: none has no value there).
  EXPECT_DOUBLE_EQ(*t.cells[0][3].value, 21.0);
  EXPECT_DOUBLE_EQ(*t.cells[1][3].value, 23.0);
  EXPECT_DOUBLE_EQ(*t.cells[2][3].value, 32.0);
  for (size_t c = 0; c < 4; ++c) {
    EXPECT_TRUE(t.cells[2][c].best) << c;  // slow is best everywhere (higher is better)
    EXPECT_FALSE(t.cells[0][c].best) << c;
  }
  EXPECT_EQ(t.cells[1][0].text, "25.00");
  bool noted = false;
  for (const auto& n : t.notes) noted = noted || n.find("c: no edge pixels") != std::string::npos;
  EXPECT_TRUE(noted);
  EXPECT_NE(t.caption.find("16 stratified samples per pixel"), std::string::npos);
  EXPECT_NE(t.caption.find("Size 8x6"), std::string::npos);
  EXPECT_NE(t.caption.find("3 timed run(s) after 1 warm-up"), std::string::npos);

  // Lower is better for FLIP: the smallest value is marked; the viewing condition is stated.
  const ExportTable f = MetricTable(src, Sel(src, "flip_mean"));
  EXPECT_TRUE(f.cells[2][0].best);                                              // 0.05 on a
  EXPECT_TRUE(f.cells[2][1].best);                                              // 0.04 on b
  EXPECT_TRUE(f.cells[0][2].best && f.cells[1][2].best && f.cells[2][2].best);  // ties on c
  EXPECT_NE(f.caption.find("67 pixels per degree"), std::string::npos);
}

TEST(ExportTables, SceneWithoutAnyValueGetsANoteNotAColumn) {
  ExportSource src = Source();
  for (auto& r : src.report.rows) {
    if (r.scene == "c") r.metrics[0] = {"edge_psnr_db", std::nullopt, "empty mask"};
  }
  const ExportTable t = MetricTable({src}, Sel({src}));
  EXPECT_EQ(t.columns, (std::vector<std::string>{"a", "b", "Mean"}));
  ASSERT_FALSE(t.notes.empty());
  EXPECT_EQ(t.notes[0], "No column for c: Edge PSNR is undefined there for every method (empty mask).");
  EXPECT_DOUBLE_EQ(*t.cells[2][2].value, 32.0);  // the mean is unchanged: c was left out anyway
}

TEST(ExportTables, PsnrNearTheNoiseFloorIsMarked) {
  ExportSource src = Source();
  src.report.scenes[0].ref_floor_psnr_db = 32.0;  // scene a: slow's 30 dB is within 3 dB of it
  const ExportTable t = MetricTable({src}, Sel({src}));
  EXPECT_TRUE(t.cells[2][0].near_floor);
  EXPECT_FALSE(t.cells[1][0].near_floor);  // fast: 25 dB, 7 dB below
  EXPECT_FALSE(t.cells[2][1].near_floor);  // scene b has no floor
  EXPECT_FALSE(t.cells[2][3].near_floor);  // means are not marked
  const std::string tex = TableToLatex(t, "metric", {});
  EXPECT_NE(tex.find("slow & \\textbf{30.00}$^\\dagger$ & \\textbf{34.00} &"), std::string::npos) << tex;
  EXPECT_NE(tex.find("\\textdagger{}: within 3 dB of the reference's noise floor"), std::string::npos);
  EXPECT_NE(tex.find("a (noise floor 32.00 dB)"), std::string::npos);
  EXPECT_EQ(MetricTable({src}, Sel({src}, "flip_mean")).cells[2][0].near_floor, false);  // not a PSNR
}

TEST(ExportTables, CsvAndLatexParseBackToTheValues) {
  const std::vector<ExportSource> src{Source()};
  const ExportTable t = MetricTable(src, Sel(src));
  const auto csv = ParseCsv(TableToCsv(t, {"prov line"}));
  ASSERT_EQ(csv.at("Method"), (std::vector<std::string>{"Method", "a", "b", "c", "Mean"}));
  EXPECT_EQ(std::stod(csv.at("slow")[1]), 30.0);
  EXPECT_EQ(std::stod(csv.at("slow")[2]), 34.0);
  EXPECT_EQ(std::stod(csv.at("slow")[4]), 32.0);
  EXPECT_EQ(csv.at("none")[3], "");
  EXPECT_EQ(csv.at("best"), (std::vector<std::string>{"best", "slow", "slow", "slow", "slow"}));

  const std::string tex = TableToLatex(t, "metric", {"prov line"});
  EXPECT_EQ(tex.rfind("% prov line\n", 0), 0u);
  EXPECT_NE(tex.find("\\toprule"), std::string::npos);
  EXPECT_NE(tex.find("\\label{tab:aalab-metric}"), std::string::npos);
  const std::regex row(
      R"(slow & \\textbf\{([0-9.]+)\} & \\textbf\{([0-9.]+)\} & \\textbf\{([0-9.]+)\} & \\textbf\{([0-9.]+)\} \\\\)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(tex, m, row)) << tex;
  EXPECT_EQ(m[1].str(), "30.00");
  EXPECT_EQ(m[4].str(), "32.00");
  EXPECT_NE(tex.find("none & 20.00 & 22.00 & -- & 21.00 \\\\"), std::string::npos) << tex;
  EXPECT_EQ(LatexEscape("fxaa_1 50% a&b #x ~"), "fxaa\\_1 50\\% a\\&b \\#x \\textasciitilde{}");
}

TEST(ExportTables, CostOfAccuracyByHand) {
  const std::vector<ExportSource> src{Source()};
  const ExportTable t = CostTable(src, Sel(src));
  // Fastest first; none and fast tie at 2 ms (stable: report order), slow at 5 ms.
  ASSERT_EQ(t.row_labels, (std::vector<std::string>{"none", "fast", "slow"}));
  const auto& fast = t.cells[1];
  const auto& slow = t.cells[2];
  EXPECT_DOUBLE_EQ(*fast[0].value, 23.0);
  EXPECT_DOUBLE_EQ(*fast[1].value, 2.0);  // gain over none
  EXPECT_DOUBLE_EQ(*fast[2].value, 2.0);  // time
  EXPECT_DOUBLE_EQ(*fast[3].value, 0.0);  // added
  EXPECT_FALSE(fast[4].value);            // gain per ms undefined: added <= 0
  EXPECT_DOUBLE_EQ(*slow[1].value, 11.0);
  EXPECT_DOUBLE_EQ(*slow[3].value, 3.0);
  EXPECT_DOUBLE_EQ(*slow[4].value, 11.0 / 3.0);
  // Pareto front: fast (2 ms, 23 dB) beats none (2 ms, 21 dB); slow is better than both.
  EXPECT_EQ(*t.cells[0][5].value, 0.0);
  EXPECT_EQ(*fast[5].value, 1.0);
  EXPECT_EQ(*slow[5].value, 1.0);
  EXPECT_TRUE(t.cells[0][2].best && fast[2].best);  // tied fastest
  EXPECT_TRUE(slow[1].best);
  const std::string md = TableToMarkdown(t, {"p"});
  EXPECT_NE(md.find("| slow | **32.00** | **11.00** | 5.00 | 3.00 | **3.67** | yes |"), std::string::npos) << md;
}

TEST(ExportTables, SeveralReportsGroupColumnsAndRows) {
  ExportSource after = Source();
  after.label = "after";
  for (auto& r : after.report.rows) {
    if (r.spec == "fast") r.metrics[0].value = r.metrics[0].value ? *r.metrics[0].value + 1 : 0;
  }
  ExportSource before = Source();
  before.label = "before";
  const std::vector<ExportSource> src{before, after};
  const ExportTable t = MetricTable(src, Sel(src));
  ASSERT_EQ(t.columns.size(), 8u);
  EXPECT_EQ(t.column_groups[0], "before");
  EXPECT_EQ(t.column_groups[4], "after");
  EXPECT_EQ(*t.cells[1][4].value, 26.0);
  const std::string tex = TableToLatex(t, "metric", {});
  EXPECT_NE(tex.find("\\multicolumn{4}{c}{before} & \\multicolumn{4}{c}{after}"), std::string::npos);
  EXPECT_NE(tex.find("\\cmidrule(lr){2-5}\\cmidrule(lr){6-9}"), std::string::npos);
  const auto csv = ParseCsv(TableToCsv(t, {}));
  EXPECT_EQ(csv.at("Method")[5], "after:a");
  const ExportTable c = CostTable(src, Sel(src));
  EXPECT_EQ(c.row_groups.front(), "before");
  EXPECT_EQ(c.row_groups.back(), "after");
}

/// 8x6 images whose pixels encode where they are, so a wrong crop cannot pass.
Image8 Pattern(int seed) {
  Image8 img(8, 6, 4, 255);
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 8; ++x) {
      img.At(x, y, 0) = static_cast<uint8_t>(20 * x + seed);
      img.At(x, y, 1) = static_cast<uint8_t>(30 * y + seed);
      img.At(x, y, 2) = static_cast<uint8_t>(7 * seed);
    }
  }
  return img;
}

TEST(ExportCrops, PixelsAndHeatmapAtTheCropRectangles) {
  const std::vector<ExportSource> src{Source()};
  const ExportSelection sel = Sel(src);
  CropFigureOptions asked;
  asked.scene = "a";
  asked.methods = {"none", "fast"};
  asked.heatmap = true;
  const CropFigureOptions o = DefaultCropFigure(src, sel, asked);
  EXPECT_EQ(o.crops.size(), 2u);  // the scene's first two windows
  EXPECT_EQ(o.zoom, 32);          // tiles of about 128 px for the widest crop (3 px: 42x), at most 32x
  std::map<std::string, Image8> files;
  files["images/a/reference.png"] = Pattern(1);
  files["images/a/none.png"] = Pattern(2);
  Image8 fast = Pattern(1);
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 8; ++x) fast.At(x, y, 0) = static_cast<uint8_t>(fast.At(x, y, 0) + 51);
  }
  files["images/a/fast.png"] = fast;
  const CropFigure fig = ComposeCropFigure(src, o, [&](size_t, const std::string& p) { return files.at(p); });
  int images = 0, heatmaps = 0;
  for (const auto& t : fig.tiles) {
    if (t.path.empty()) continue;  // the scale bar
    const Image8& srcimg = files.at(t.path);
    for (int j = 0; j < t.crop[3] * t.zoom; ++j) {
      for (int i = 0; i < t.crop[2] * t.zoom; ++i) {
        const uint8_t* got = fig.pixels.Pixel(t.x + i, t.y + j);
        const int sx = t.crop[0] + i / t.zoom, sy = t.crop[1] + j / t.zoom;
        for (int c = 0; c < 3; ++c) {
          int want = srcimg.At(sx, sy, c);
          if (t.heatmap) {
            // |fast - reference| = 51 in one channel: mean over RGB 17/255 = 1/15; the colormap
            // entry is round(255 * (1/15) / 0.25) = 68. none differs from the reference by 1
            // in R and G and by 7 in B: 9/765 -> entry round(255 * 9/765 / 0.25) = 12.
            const int entry = t.path == "images/a/fast.png" ? 68 : 12;
            want = QuantizeUnorm8(ColormapEntry(Colormap::kViridis, entry)[c]);
          }
          ASSERT_EQ(got[c], want) << t.path << " heat " << t.heatmap << " at " << i << "," << j;
        }
      }
    }
    (t.heatmap ? heatmaps : images)++;
  }
  EXPECT_EQ(images, 2 * 3);    // 2 crops x (reference, none, fast)
  EXPECT_EQ(heatmaps, 2 * 2);  // 2 crops x (none, fast)

  // The SVG draws the same pixels: parse each image tile's paths back.
  const std::string svg = CropFigureToSvg(fig, {"prov"});
  EXPECT_NE(svg.find("<metadata>prov\n</metadata>"), std::string::npos);
  const std::regex group(
      R"re(<g transform="translate\((\d+) (\d+)\) scale\((\d+)\)"[^>]*data-crop="(\d+) (\d+) (\d+) (\d+)" data-kind="image" data-image="([^"]+)">\n((?:<path[^\n]*\n)*)</g>)re");
  const std::regex path(R"re(<path fill="#([0-9a-f]{6})" d="([^"]+)"/>)re");
  const std::regex seg(R"(M(\d+) (\d+)h(\d+)v1h-\d+z)");
  int parsed = 0;
  for (auto g = std::sregex_iterator(svg.begin(), svg.end(), group); g != std::sregex_iterator(); ++g) {
    const Image8& srcimg = files.at((*g)[8].str());
    const int cx = std::stoi((*g)[4].str()), cy = std::stoi((*g)[5].str()), w = std::stoi((*g)[6].str()),
              h = std::stoi((*g)[7].str());
    std::vector<int> seen(static_cast<size_t>(w * h), 0);
    const std::string body = (*g)[9].str();
    for (auto p = std::sregex_iterator(body.begin(), body.end(), path); p != std::sregex_iterator(); ++p) {
      const unsigned rgb = static_cast<unsigned>(std::stoul((*p)[1].str(), nullptr, 16));
      const std::string d = (*p)[2].str();
      for (auto s = std::sregex_iterator(d.begin(), d.end(), seg); s != std::sregex_iterator(); ++s) {
        const int x0 = std::stoi((*s)[1].str()), y = std::stoi((*s)[2].str()), n = std::stoi((*s)[3].str());
        for (int x = x0; x < x0 + n; ++x) {
          const uint8_t* want = srcimg.Pixel(cx + x, cy + y);
          EXPECT_EQ(rgb, (unsigned{want[0]} << 16) | (unsigned{want[1]} << 8) | want[2]);
          ++seen[static_cast<size_t>(y * w + x)];
        }
      }
    }
    for (int v : seen) EXPECT_EQ(v, 1);  // every pixel exactly once
    ++parsed;
  }
  EXPECT_EQ(parsed, 6);
}

TEST(ExportCrops, BadChoicesAreRefused) {
  const std::vector<ExportSource> src{Source()};
  const ExportSelection sel = Sel(src);
  CropFigureOptions asked;
  asked.scene = "a";
  asked.crops = {{6, 4, 3, 3}};  // past the 8x6 image
  EXPECT_THROW(DefaultCropFigure(src, sel, asked), UserError);
  asked.crops = {};
  asked.zoom = 33;
  EXPECT_THROW(DefaultCropFigure(src, sel, asked), UserError);
  asked.zoom = 0;
  asked.methods = {"nope"};
  EXPECT_THROW(DefaultCropFigure(src, sel, asked), UserError);
  asked.methods = {};
  asked.scene = "zz";
  EXPECT_THROW(DefaultCropFigure(src, sel, asked), UserError);
}

TEST(ExportBibliography, EveryRegistrySourceHasAnEntry) {
  for (const auto& e : MethodRegistry()) {
    for (const auto& key : SourceKeys(e.source)) EXPECT_NO_THROW(BibEntry(key)) << e.name << ": " << key;
  }
  for (const auto& e : MetricRegistry()) {
    for (const auto& key : SourceKeys(e.source)) EXPECT_NO_THROW(BibEntry(key)) << e.name << ": " << key;
  }
  // The sources the issue names: the whitepaper, the shader, SMAA, TAA, FLIP, SSIM.
  auto source_of = [](const std::string& name) {
    for (const auto& e : MethodRegistry()) {
      if (e.name == name) return e.source;
    }
    return std::string("?");
  };
  EXPECT_EQ(source_of("fxaa1-p3"), "lottes2009fxaa");
  EXPECT_EQ(source_of("fxaa311-p39"), "lottes2011fxaa311");
  EXPECT_EQ(source_of("fxaa-high"), "lottes2011fxaa311,flick2021fxaa");
  EXPECT_EQ(source_of("smaa-high"), "jimenez2012smaa");
  EXPECT_EQ(source_of("taa"), "karis2014taa,salvi2016taa");
  EXPECT_EQ(source_of("none"), "");
  const std::string bib = BibtexFile(
      {{"method fxaa-high", source_of("fxaa-high")}, {"method none", ""}, {"metric ssim", "wang2004ssim"}}, {"prov"});
  EXPECT_EQ(bib.rfind("% prov\n", 0), 0u);
  EXPECT_NE(bib.find("%   method none: no published source"), std::string::npos);
  EXPECT_NE(bib.find("@misc{lottes2011fxaa311,"), std::string::npos);
  EXPECT_NE(bib.find("@misc{flick2021fxaa,"), std::string::npos);
  EXPECT_NE(bib.find("@article{wang2004ssim,"), std::string::npos);
  EXPECT_EQ(bib.find("jimenez2012smaa,"), std::string::npos);  // only what the table uses
  EXPECT_NE(bib.find("@misc{aalab,"), std::string::npos);
}

TEST(ExportSource, Sha256KnownVector) {
  // FIPS 180-2, appendix B.1: SHA-256("abc").
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

}  // namespace
}  // namespace aalab
