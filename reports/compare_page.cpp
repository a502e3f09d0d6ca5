#include "reports/compare_page.h"

#include <filesystem>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "reports/compare_text.h"
#include "reports/html_assets.h"
#include "reports/html_page.h"

namespace aalab {

std::vector<size_t> ChangedRowOrder(const CompareResult& r) {
  std::vector<size_t> order;
  for (size_t i = 0; i < r.rows.size(); ++i) {
    if (r.rows[i].regression) order.push_back(i);
  }
  for (size_t i = 0; i < r.rows.size(); ++i) {
    if (!r.rows[i].regression && r.rows[i].changed) order.push_back(i);
  }
  return order;
}

std::vector<std::vector<HtmlImage>> CompareHtmlImages(const CompareResult& r, const Report& base, const Report& cur,
                                                      const std::string& base_dir, const std::string& cur_dir) {
  namespace fs = std::filesystem;
  std::vector<std::vector<HtmlImage>> out;
  auto image = [](const std::string& label, const std::map<std::string, std::string>& images, const std::string& key,
                  const std::string& dir, const std::string& which) {
    HtmlImage im;
    im.label = label;
    auto it = images.find(key);
    if (it == images.end()) {
      im.missing = "the " + which + " names no '" + key + "' image";
    } else {
      im.source = (fs::path(dir) / it->second).string();
    }
    return im;
  };
  for (size_t i : ChangedRowOrder(r)) {
    const RowMatch& m = r.rows[i];
    const ResultRow& brow = base.rows[static_cast<size_t>(m.base_index)];
    const ResultRow& crow = cur.rows[static_cast<size_t>(m.current_index)];
    std::vector<HtmlImage> ims;
    ims.push_back(image("baseline output", brow.images, "output", base_dir, "baseline row"));
    ims.push_back(image("current output", crow.images, "output", cur_dir, "current row"));
    const SceneResult* scene = nullptr;
    for (const auto& s : cur.scenes) {
      if (s.name == m.scene) scene = &s;
    }
    if (scene) {
      ims.push_back(image("reference", scene->images, "reference_png", cur_dir, "current report's scene"));
    } else {
      HtmlImage im;
      im.label = "reference";
      im.missing = "the current report has no scene entry '" + m.scene + "'";
      ims.push_back(im);
    }
    out.push_back(ims);
  }
  return out;
}

namespace {

/// The A/B view of changed row `k` (abview.js): its baseline and current outputs, the
/// reference and the outputs of the other changed rows of the same scene; A = baseline, B =
/// current. Empty when the scene is unknown or fewer than two images are available.
std::string AbViewHost(const CompareResult& r, const std::vector<size_t>& order,
                       const std::vector<std::vector<HtmlImage>>& images, size_t k, const Report& cur) {
  const std::string& scene = r.rows[order[k]].scene;
  const SceneResult* sc = nullptr;
  for (const auto& s : cur.scenes) {
    if (s.name == scene) sc = &s;
  }
  if (!sc || sc->width <= 0 || sc->height <= 0) return "";
  nlohmann::json choices = nlohmann::json::array();
  auto add = [&choices](const std::string& key, const std::string& label, const HtmlImage& im) {
    if (!im.href.empty()) choices.push_back({{"key", key}, {"label", label}, {"path", im.href}});
  };
  // This row first, then the other changed rows of the scene.
  std::vector<size_t> rows{k};
  for (size_t j = 0; j < order.size(); ++j) {
    if (j != k && r.rows[order[j]].scene == scene) rows.push_back(j);
  }
  for (size_t j : rows) {
    const RowMatch& m = r.rows[order[j]];
    const std::string base_label = m.base_spec.empty() || m.base_spec == m.spec ? m.spec : m.base_spec;
    add("b" + std::to_string(j), base_label + " (baseline)", images[j][0]);
    add("c" + std::to_string(j), m.spec + " (current)", images[j][1]);
  }
  if (images[k].size() > 2) add("ref", "reference", images[k][2]);
  if (choices.size() < 2) return "";
  nlohmann::json crops = nlohmann::json::array();
  for (const auto& c : sc->crops) crops.push_back({c[0], c[1], c[2], c[3]});
  const nlohmann::json d = {{"width", sc->width}, {"height", sc->height},   {"crops", crops},
                            {"choices", choices}, {"a", choices[0]["key"]}, {"b", choices[1]["key"]}};
  return "<h3>Any two side by side</h3>\n<div class=\"abview abview-host\" data-ab=\"" + HtmlEscape(d.dump()) +
         "\"></div>\n";
}

}  // namespace

std::string CompareHtml(const CompareResult& r, const std::vector<std::vector<HtmlImage>>& images,
                        const std::string& base_name, const std::string& cur_name, const Report* current) {
  std::ostringstream h;
  const int code = r.ExitCode();
  h << HtmlPageStart("aalab compare");
  h << "<h1>aalab compare</h1>\n<p>baseline <code>" << HtmlEscape(base_name) << "</code>, current <code>"
    << HtmlEscape(cur_name) << "</code></p>\n";
  h << "<p class=\"" << (code == 0 ? "improved" : "regression") << "\">exit " << code << ": "
    << (code == 0   ? "no regression"
        : code == 1 ? "regression"
                    : "could not compare")
    << " &mdash; " << r.rows.size() << " rows compared, " << r.regressions << " regression(s), " << r.improvements
    << " improvement(s)</p>\n";
  auto list = [&h](const std::string& title, const std::vector<std::string>& items) {
    if (items.empty()) return;
    h << "<h2>" << HtmlEscape(title) << " (" << items.size() << ")</h2>\n<ul>\n";
    for (const auto& s : items) h << "<li>" << HtmlEscape(s) << "</li>\n";
    h << "</ul>\n";
  };
  list("Could not compare", r.cannot_compare);
  list("Missing from the current report", r.missing_rows);
  list("Extra in the current report", r.extra_rows);
  list("Notes", r.notes);
  auto verdict_class = [](Verdict v) {
    switch (v) {
      case Verdict::kRegression: return "regression";
      case Verdict::kImproved: return "improved";
      case Verdict::kWithin: return "within";
      case Verdict::kNotJudged: return "not-judged";
      default: return "unchanged";
    }
  };
  const std::vector<size_t> order = ChangedRowOrder(r);
  AALAB_CHECK(order.size() == images.size(), "one image list per changed row");
  if (order.empty()) h << "<p>No changed rows.</p>\n";
  for (size_t k = 0; k < order.size(); ++k) {
    const RowMatch& m = r.rows[order[k]];
    h << "<section><h2 class=\"" << (m.regression ? "regression" : "") << "\">" << HtmlEscape(m.scene) << " / "
      << HtmlEscape(m.spec) << (m.bit_identical ? " (bit-identical output)" : "") << "</h2>\n";
    h << "<table><tr><th class=\"l\">metric</th><th>baseline</th><th>current</th><th>delta</th><th>threshold</th>"
         "<th class=\"l\">verdict</th></tr>\n";
    for (const auto& l : r.lines) {
      if (l.scene != m.scene || l.spec != m.spec) continue;
      h << "<tr><td class=\"l\">" << HtmlEscape(l.quantity) << "</td><td>" << HtmlEscape(LineValueText(l, true))
        << "</td><td>" << HtmlEscape(LineValueText(l, false)) << "</td><td>"
        << (l.delta ? HtmlEscape(CompareDeltaText(l.quantity, *l.delta)) : "-") << "</td><td>"
        << HtmlEscape(l.threshold) << "</td><td class=\"l " << verdict_class(l.verdict) << "\">"
        << VerdictName(l.verdict) << (l.note.empty() ? "" : ": " + HtmlEscape(l.note)) << "</td></tr>\n";
    }
    h << "</table>\n<div class=\"imgs\">\n";
    for (const auto& im : images[k]) {
      h << "<figure>";
      if (!im.href.empty()) {
        h << "<img src=\"" << HtmlEscape(im.href) << "\" alt=\"" << HtmlEscape(im.label) << "\" width=\"320\">";
      } else {
        h << "<div class=\"missing\">not available: " << HtmlEscape(im.missing) << "</div>";
      }
      h << "<figcaption>" << HtmlEscape(im.label) << "</figcaption></figure>\n";
    }
    h << "</div>\n";
    if (current) h << AbViewHost(r, order, images, k, *current);
    h << "</section>\n";
  }
  if (current) h << html::AbViewAssets();
  h << HtmlPageEnd();
  return h.str();
}

}  // namespace aalab
