// The HTML report page built from a Report made in code: rows, escaping, embedded JSON, links,
// noise-floor marks, null reasons.
#include "reports/html_report.h"
#include "reports/html_stability.h"

#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/html_assets.h"
#include "reports/html_method_style.h"
#include "reports/html_page.h"
#include "reports/report_json.h"

namespace aalab {
namespace {

const std::string kEvilMethod = "x</script><img src=x onerror=alert(1)>";
const std::string kEvilScene = "evil<b>\"&'scene";

ResultRow Row(const std::string& scene, const std::string& spec, double psnr, double edge_psnr, double ms) {
  ResultRow row;
  row.scene = scene;
  row.method = spec;
  row.spec = spec;
  row.render_width = 16;
  row.render_height = 9;
  row.render.samples_ms = {ms, ms * 1.1, ms * 0.9};
  row.render.Summarize();
  row.post.samples_ms = {0, 0, 0};
  row.post.Summarize();
  row.resample = row.post;
  row.total = row.render;
  row.primary_rays_per_px = 4;
  row.metrics = {{"psnr_db", psnr, ""}, {"edge_psnr_db", edge_psnr, ""}, {"flip_mean", 0.05, ""}};
  row.output_hash = spec + scene;
  row.images = {{"output", "images/" + scene + "/" + spec + ".png"}};
  return row;
}

Report Sample() {
  Report r;
  r.context = {{"tool", "aalab"},   {"tool_version", "0.1.0"}, {"git_commit", "abc123"},
               {"cpu", "Test CPU"}, {"threads", "2"},          {"hardware_threads", "4"}};
  r.settings = {{"suite", "quick"}, {"size", "16x9"}, {"ref_spp", "16"}, {"repeat", "3"}, {"warmup", "1"}};
  for (const std::string& name : {std::string("wedges"), kEvilScene}) {
    SceneResult s;
    s.name = name;
    s.description = "a <scene> & more";
    s.source = "/home/someone/scenes/" + name + ".json";  // absolute: may be shown as text, never linked
    s.width = 16;
    s.height = 9;
    s.ref_spp = 16;
    s.ref_halves_psnr_db = 33.98;
    s.ref_floor_psnr_db = 40.0;
    s.images = {{"reference_png", "images/" + name + "/reference.png"},
                {"edge_mask", "images/" + name + "/edge_mask.png"}};
    s.crops = {{0, 0, 8, 8}};
    r.scenes.push_back(s);
    r.rows.push_back(Row(name, "none", 30.0, 25.0, 2.0));
    r.rows.push_back(Row(name, "ssaa-2x2", 38.5, 41.0, 8.0));  // within 3 dB of the 40 dB floor (and above it)
    ResultRow evil = Row(name, kEvilMethod, 0, 0, 3.0);
    evil.metrics[0] = {"psnr_db", std::nullopt, "identical <x>"};
    evil.metrics[1] = {"edge_psnr_db", 36.99, ""};  // 3.01 dB below the floor: not marked
    r.rows.push_back(evil);
  }
  return r;
}

/// The `<tr>` of one scene × method in the metrics tables.
std::string RowHtml(const std::string& page, const std::string& scene, const std::string& spec) {
  const std::string key =
      "<tr class=\"row\" data-scene=\"" + HtmlEscape(scene) + "\" data-spec=\"" + HtmlEscape(spec) + "\">";
  const size_t a = page.find(key);
  if (a == std::string::npos) return "";
  EXPECT_EQ(page.find(key, a + 1), std::string::npos) << "row twice: " << key;
  return page.substr(a, page.find("</tr>", a) - a);
}

std::string CellHtml(const std::string& row, const std::string& metric) {
  const size_t a = row.find("<td class=\"num");
  const size_t m = row.find("data-metric=\"" + metric + "\"", a);
  if (m == std::string::npos) return "";
  const size_t start = row.rfind("<td", m);
  return row.substr(start, row.find("</td>", m) - start);
}

std::string ScriptJson(const std::string& page, const std::string& id) {
  const std::string open = "<script type=\"application/json\" id=\"" + id + "\">";
  const size_t a = page.find(open);
  if (a == std::string::npos) return "";
  const size_t b = page.find("</script>", a);
  return page.substr(a + open.size(), b - a - open.size());
}

TEST(HtmlReport, HasEverySceneMethodRow) {
  const Report r = Sample();
  const std::string page = RenderHtmlReport(r);
  size_t rows = 0;
  for (size_t p = page.find("<tr class=\"row\""); p != std::string::npos; p = page.find("<tr class=\"row\"", p + 1))
    ++rows;
  EXPECT_EQ(rows, r.rows.size());
  for (const auto& row : r.rows)
    EXPECT_FALSE(RowHtml(page, row.scene, row.spec).empty()) << row.scene << " × " << row.spec;
  for (const auto& s : r.scenes) {
    EXPECT_NE(page.find("data-view=\"scene-" + HtmlEscape(s.name) + "\""), std::string::npos) << s.name;
  }
}

TEST(HtmlReport, EscapesNames) {
  const std::string page = RenderHtmlReport(Sample());
  EXPECT_EQ(page.find("</script><img"), std::string::npos);
  EXPECT_EQ(page.find("<img src=x"), std::string::npos);
  EXPECT_EQ(page.find("evil<b>"), std::string::npos);
  EXPECT_NE(page.find("x&lt;/script&gt;&lt;img src=x onerror=alert(1)&gt;"), std::string::npos);
  EXPECT_NE(page.find("evil&lt;b&gt;&quot;&amp;&#39;scene"), std::string::npos);
  EXPECT_NE(page.find("a &lt;scene&gt; &amp; more"), std::string::npos);
  // Exactly the page's own script elements close: the two data blocks and the script.
  size_t closes = 0;
  for (size_t p = page.find("</script>"); p != std::string::npos; p = page.find("</script>", p + 1)) ++closes;
  EXPECT_EQ(closes, 3u);
}

TEST(HtmlReport, EmbedsTheReportAsValidJson) {
  const Report r = Sample();
  const std::string page = RenderHtmlReport(r);
  const std::string data = ScriptJson(page, "aalab-data");
  ASSERT_FALSE(data.empty());
  EXPECT_EQ(data.find('<'), std::string::npos);
  const auto parsed = nlohmann::ordered_json::parse(data);  // throws on invalid JSON
  EXPECT_EQ(parsed.dump(), ReportToJson(r).dump());
  const auto meta = nlohmann::json::parse(ScriptJson(page, "aalab-meta"));
  EXPECT_EQ(meta["default_axis"], "edge_psnr_db");  // preferred when present
  EXPECT_EQ(meta["axis"], nlohmann::json::array({"edge_psnr_db", "psnr_db", "flip_mean"}));
  EXPECT_EQ(meta["metrics"]["flip_mean"]["better"], -1);
  EXPECT_EQ(meta["metrics"]["psnr_db"]["better"], 1);
}

TEST(HtmlReport, DefaultAxisFallsBackToPsnr) {
  Report r = Sample();
  for (auto& row : r.rows) row.metrics.erase(row.metrics.begin() + 1);  // no edge_psnr_db
  const auto meta = nlohmann::json::parse(ScriptJson(RenderHtmlReport(r), "aalab-meta"));
  EXPECT_EQ(meta["default_axis"], "psnr_db");
}

TEST(HtmlReport, NoAbsolutePathsOrNetworkUrls) {
  const std::string page = RenderHtmlReport(Sample());
  const std::regex attr(R"((?:href|src)\s*=\s*["']([^"']*)["'])");
  int links = 0;
  for (auto it = std::sregex_iterator(page.begin(), page.end(), attr); it != std::sregex_iterator(); ++it) {
    const std::string v = (*it)[1];
    ++links;
    EXPECT_FALSE(v.empty());
    EXPECT_NE(v[0], '/') << v;
    EXPECT_FALSE(std::regex_search(v, std::regex("^[A-Za-z][A-Za-z0-9+.-]*:"))) << v;  // http:, file:, data:, ...
  }
  EXPECT_GT(links, 3);
  EXPECT_NE(page.find("href=\"report.json\""), std::string::npos);
  // The only URL in the page is the SVG namespace name (an identifier, never fetched).
  std::string rest = page;
  for (size_t p; (p = rest.find("http://www.w3.org/2000/svg")) != std::string::npos;) rest.erase(p, 26);
  // CSS `url(#id)` names an SVG filter inside the page (the heatmap colouring), never a file.
  for (size_t p; (p = rest.find("url(#")) != std::string::npos;) rest.erase(p, 5);
  for (const char* bad : {"http://", "https://", "//cdn", "@import", "url(", "fetch(", "XMLHttpRequest", "file://"}) {
    EXPECT_EQ(rest.find(bad), std::string::npos) << bad;
  }
  EXPECT_EQ(page.find("href=\"/home/someone"), std::string::npos);
}

TEST(HtmlReport, MarksScoresNearTheNoiseFloor) {
  const std::string page = RenderHtmlReport(Sample());
  const std::string near = CellHtml(RowHtml(page, "wedges", "ssaa-2x2"), "psnr_db");
  EXPECT_NE(near.find("near-floor"), std::string::npos) << near;
  EXPECT_NE(near.find("⚠"), std::string::npos);
  EXPECT_NE(near.find("noise floor (40.00 dB at 16 spp)"), std::string::npos) << near;
  const std::string above = CellHtml(RowHtml(page, "wedges", "ssaa-2x2"), "edge_psnr_db");  // 41 > floor: marked
  EXPECT_NE(above.find("near-floor"), std::string::npos) << above;
  const std::string far = CellHtml(RowHtml(page, "wedges", "none"), "psnr_db");
  EXPECT_NE(far.find(">30.00"), std::string::npos) << far;
  EXPECT_EQ(far.find("near-floor"), std::string::npos);
  const std::string just_below = CellHtml(RowHtml(page, "wedges", kEvilMethod), "edge_psnr_db");  // 36.99 < 37
  EXPECT_EQ(just_below.find("near-floor"), std::string::npos) << just_below;
  EXPECT_EQ(CellHtml(RowHtml(page, "wedges", "none"), "flip_mean").find("near-floor"), std::string::npos);
  EXPECT_NE(page.find("noise floor 40.00 dB"), std::string::npos);  // in the table caption
}

TEST(HtmlReport, NullShowsDashWithReason) {
  const std::string page = RenderHtmlReport(Sample());
  const std::string cell = CellHtml(RowHtml(page, "wedges", kEvilMethod), "psnr_db");
  EXPECT_NE(cell.find("title=\"null: identical &lt;x&gt;\""), std::string::npos) << cell;
  EXPECT_NE(cell.find(">—"), std::string::npos) << cell;
}

TEST(HtmlReport, ShowsTimingAndCostColumnsAndContext) {
  const std::string page = RenderHtmlReport(Sample());
  const std::string row = RowHtml(page, "wedges", "ssaa-2x2");
  EXPECT_NE(row.find("8.00 <span class=\"range\">[7.20–8.80]</span>"), std::string::npos) << row;
  EXPECT_NE(row.find("4 + 0"), std::string::npos) << row;  // rays/px primary + shadow
  for (const char* s : {"Timing methodology", "Test CPU", "abc123", "CPU time is not GPU cost", "Run context"}) {
    EXPECT_NE(page.find(s), std::string::npos) << s;
  }
}

TEST(HtmlReport, SaysTheVerdictPerScene) {
  const std::string page = RenderHtmlReport(Sample());
  // wedges: edge PSNR 25 (none), 41 (ssaa-2x2, 8 ms), 36.99; FLIP 0.05 on every row (a tie).
  EXPECT_NE(page.find("<p class=\"verdict\" data-scene=\"wedges\"><b>Verdict:</b> edge PSNR → ssaa-2x2 41.00 dB "
                      "(+16.00 dB over none, 8.00 ms, +6.00 ms over none); FLIP → none (tied with ssaa-2x2, " +
                      HtmlEscape(kEvilMethod) + ") 0.0500 (no method beats none); both axes agree</p>"),
            std::string::npos);
  // The suite view lists the same line per scene.
  EXPECT_NE(page.find("<li><b>wedges</b>: edge PSNR → ssaa-2x2 41.00 dB"), std::string::npos);
  EXPECT_NE(page.find("<li><b>" + HtmlEscape(kEvilScene) + "</b>: edge PSNR → ssaa-2x2"), std::string::npos);
}

TEST(HtmlReport, HidesMetricsNullOnEveryRowOfAScene) {
  Report r = Sample();
  for (auto& row : r.rows) row.metrics.push_back({"temporal_flicker", std::nullopt, "a still run"});
  for (auto& row : r.rows) {
    if (row.scene == kEvilScene && row.spec == "none") row.metrics.back().value = 0.25;
  }
  const std::string page = RenderHtmlReport(r);
  const std::string head = "<th scope=\"col\" data-metric=\"temporal_flicker\"";
  const size_t wedges = page.find("<table class=\"metrics sortable\" id=\"table-0\"");
  const size_t evil = page.find("<table class=\"metrics sortable\" id=\"table-1\"");
  ASSERT_NE(wedges, std::string::npos);
  ASSERT_NE(evil, std::string::npos);
  // Only in the second scene's table, where one row has a value.
  EXPECT_GT(page.find(head), evil);
  EXPECT_EQ(page.find(head, page.find(head) + 1), std::string::npos);
  const std::string caption = page.substr(wedges, page.find("</caption>", wedges) - wedges);
  EXPECT_NE(caption.find("Not shown, null on every row: temporal_flicker (a still run)."), std::string::npos)
      << caption;
  EXPECT_TRUE(CellHtml(RowHtml(page, "wedges", "none"), "temporal_flicker").empty());
  EXPECT_FALSE(CellHtml(RowHtml(page, kEvilScene, "ssaa-2x2"), "temporal_flicker").empty());
}

TEST(HtmlReport, IsPure) { EXPECT_EQ(RenderHtmlReport(Sample()), RenderHtmlReport(Sample())); }

TEST(HtmlReport, Helpers) {
  EXPECT_EQ(HtmlEscape("<a href=\"x\">'&'</a>"), "&lt;a href=&quot;x&quot;&gt;&#39;&amp;&#39;&lt;/a&gt;");
  EXPECT_EQ(JsonForScriptTag(R"({"a":"</script><!--&"})"), R"({"a":"\u003c/script\u003e\u003c!--\u0026"})");
  EXPECT_EQ(nlohmann::json::parse(JsonForScriptTag("[\"\xE2\x80\xA8</\"]")), nlohmann::json::array({"\xE2\x80\xA8</"}));
  EXPECT_EQ(UrlEncodePath("images/a b/fxaa#1?.png"), "images/a%20b/fxaa%231%3F.png");
  EXPECT_EQ(UrlEncodePath("images/c:d%.png"), "images/c%3Ad%25.png");
  EXPECT_EQ(html::DescribeMetric("flip_max").better, -1);
  EXPECT_EQ(html::DescribeMetric("new_psnr_db").better, 1);
  EXPECT_EQ(html::DescribeMetric("mystery").better, 0);  // unknown direction: not offered as a chart axis
  EXPECT_TRUE(html::IsPsnrMetric("interior_psnr_db"));
  EXPECT_FALSE(html::IsPsnrMetric("mse"));
}

TEST(HtmlStability, CountsFiniteAndNullValuesWithReasons) {
  Report r;
  SceneResult hard;
  hard.name = "hard-dark";
  SceneResult easy;
  easy.name = "wedges";
  r.scenes = {easy, hard};
  ResultRow a;
  a.scene = "hard-dark";
  a.spec = "fxaa311-p39";
  a.metrics = {{"psnr_db", std::nullopt, "identical"}, {"ssim", 1.0, ""}};
  ResultRow b;
  b.scene = "wedges";
  b.spec = "none";
  b.metrics = {{"psnr_db", 30.0, ""}, {"ssim", 0.9, ""}};
  r.rows = {a, b};
  std::string h;
  AppendStabilitySection(h, r);
  EXPECT_NE(h.find("4 metric values, 1 null with a reason, 0 invalid"), std::string::npos) << h;
  // The hard scene is listed first, with its null value, reason and method.
  EXPECT_LT(h.find("hard-dark"), h.find("wedges"));
  EXPECT_NE(h.find("<code>psnr_db</code> null — identical: fxaa311-p39"), std::string::npos);
  // One status line per scene; the scene with a null value has its details in a <details>, the
  // other has none.
  EXPECT_NE(h.find("<details><summary><span class=\"ok\">✓</span> <b>hard-dark</b> <span class=\"tag\">hard</span>: "
                   "1 rows, 1 finite, 1 null (1 reason), 0 invalid</summary>"),
            std::string::npos)
      << h;
  EXPECT_NE(h.find("<li data-scene=\"wedges\"><span class=\"ok\">✓</span> <b>wedges</b>: 1 rows, 2 finite, 0 null, "
                   "0 invalid</li>"),
            std::string::npos)
      << h;
  EXPECT_EQ(h.find("<table"), std::string::npos);
  // A null without a reason counts as invalid.
  r.rows[1].metrics[1] = {"ssim", std::nullopt, ""};
  h.clear();
  AppendStabilitySection(h, r);
  EXPECT_NE(h.find("1 invalid"), std::string::npos);
  EXPECT_NE(
      h.find("<span class=\"bad\">✗</span> <b>wedges</b>: 1 rows, 1 finite, 1 null (1 reason), <strong>1 invalid"),
      std::string::npos)
      << h;
}

}  // namespace
}  // namespace aalab

// One colour and marker per method on every page: the family's colour from the fixed table, the
// marker from FNV-1a of the whole spec modulo the five non-circle shapes (values worked out by
// hand in Python: ssaa-2x2 → 1 + h % 5 = diamond, fxaa311-p39 → triangle, its :subpix=0 variant
// → triangle-down, smaa-high → square); a family's bare name is a circle.
TEST(MethodStyle, OneColourPerFamilyAndAStableMarkerPerSpec) {
  using aalab::html::MethodFamily;
  using aalab::html::StyleOfMethod;
  EXPECT_EQ(MethodFamily("ssaa-2x2"), "ssaa");
  EXPECT_EQ(MethodFamily("fxaa311-p39:subpix=0"), "fxaa311");
  EXPECT_EQ(MethodFamily("taau"), "taau");
  EXPECT_EQ(MethodFamily("9x"), "9x");  // no leading letters: the whole spec
  EXPECT_EQ(StyleOfMethod("none").colour, "#7f7f7f");
  EXPECT_EQ(StyleOfMethod("none").marker, "circle");
  EXPECT_EQ(StyleOfMethod("ssaa-2x2").colour, "#0072b2");
  EXPECT_EQ(StyleOfMethod("ssaa-2x2").marker, "diamond");
  EXPECT_EQ(StyleOfMethod("fxaa311-p39").marker, "triangle");
  EXPECT_EQ(StyleOfMethod("fxaa311-p39:subpix=0").marker, "triangle-down");
  EXPECT_EQ(StyleOfMethod("fxaa311-p39:subpix=0").colour, StyleOfMethod("fxaa311-p39").colour);
  EXPECT_EQ(StyleOfMethod("smaa-high").marker, "square");
  EXPECT_NE(StyleOfMethod("fxaa1-p3").colour, StyleOfMethod("fxaa311-p39").colour);
  // A family outside the table still gets a colour, the same every time.
  EXPECT_EQ(StyleOfMethod("newaa-x").colour, StyleOfMethod("newaa-y").colour);
  EXPECT_EQ(StyleOfMethod("newaa-x").colour.size(), 7u);
  const std::string m = aalab::html::MarkerSvg("ssaa-2x2", 10, 20, 4);
  EXPECT_NE(m.find("translate(10.0 20.0) scale(4.00)"), std::string::npos) << m;
  EXPECT_NE(m.find("fill=\"#0072b2\" stroke=\"#0072b2\""), std::string::npos) << m;
  EXPECT_NE(aalab::html::MarkerSvg("ssaa-2x2", 0, 0, 4, "#d00020").find("fill=\"#d00020\" stroke=\"#0072b2\""),
            std::string::npos);
}
