#include "reports/html_stability.h"

#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "reports/html_page.h"

namespace aalab {

void AppendStabilitySection(std::string& h, const Report& r) {
  // Hard-case scenes (name "hard-...") first, then the others, each in report order.
  std::vector<const SceneResult*> order;
  for (const auto& s : r.scenes) {
    if (s.name.rfind("hard-", 0) == 0) order.push_back(&s);
  }
  for (const auto& s : r.scenes) {
    if (s.name.rfind("hard-", 0) != 0) order.push_back(&s);
  }
  size_t total_values = 0, total_null = 0, total_bad = 0;
  std::string rows;
  for (const SceneResult* s : order) {
    size_t n_rows = 0, finite = 0, nulls = 0, bad = 0;
    // reason → metric → methods
    std::map<std::string, std::map<std::string, std::set<std::string>>> null_by_reason;
    for (const auto& row : r.rows) {
      if (row.scene != s->name) continue;
      ++n_rows;
      for (const auto& m : row.metrics) {
        if (!m.value) {
          ++nulls;
          null_by_reason[m.null_reason.empty() ? "(no reason given)" : m.null_reason][m.name].insert(row.spec);
          if (m.null_reason.empty()) ++bad;
        } else if (std::isfinite(*m.value)) {
          ++finite;
        } else {
          ++bad;
        }
      }
    }
    total_values += finite + nulls;
    total_null += nulls;
    total_bad += bad;
    std::string detail;
    for (const auto& [reason, metrics] : null_by_reason) {
      for (const auto& [metric, methods] : metrics) {
        std::string list;
        size_t k = 0;
        for (const auto& m : methods) {
          if (k++ == 6) {
            list += ", … (" + std::to_string(methods.size()) + " methods)";
            break;
          }
          list += (list.empty() ? "" : ", ") + m;
        }
        detail += "<li><code>" + HtmlEscape(metric) + "</code> null — " + HtmlEscape(reason) + ": " + HtmlEscape(list) +
                  "</li>";
      }
    }
    // One status line per scene; the null values, their reasons and methods on demand.
    const bool hard = s->name.rfind("hard-", 0) == 0;
    const std::string line =
        std::string(bad ? "<span class=\"bad\">✗</span> " : "<span class=\"ok\">✓</span> ") + "<b>" +
        HtmlEscape(s->name) + "</b>" + (hard ? " <span class=\"tag\">hard</span>" : "") + ": " +
        std::to_string(n_rows) + " rows, " + std::to_string(finite) + " finite, " + std::to_string(nulls) + " null" +
        (null_by_reason.empty()
             ? ""
             : " (" + std::to_string(null_by_reason.size()) + (null_by_reason.size() == 1 ? " reason)" : " reasons)")) +
        ", " + (bad ? "<strong>" + std::to_string(bad) + " invalid</strong>" : std::string("0 invalid"));
    rows +=
        "<li" + std::string(hard ? " class=\"hard\"" : "") + " data-scene=\"" + HtmlEscape(s->name) + "\">" +
        (detail.empty() ? line
                        : "<details><summary>" + line + "</summary><ul class=\"nulls\">" + detail + "</ul></details>") +
        "</li>\n";
  }
  h += "<section id=\"stability\" class=\"prose\">\n<h2>Numerical stability</h2>\n<p>Every metric value of every "
       "row is either a finite number or <code>null</code> with a reason; NaN and Infinity never reach the "
       "report. Outputs are 8-bit frames, so every pixel is in [0, 1] by construction. Across this run: " +
       std::to_string(total_values) + " metric values, " + std::to_string(total_null) + " null with a reason, " +
       std::to_string(total_bad) +
       " invalid (non-finite, or null without a reason; must be 0). Scenes of the <code>hard</code> suite "
       "(<code>aalab run --suite hard</code>) come first; open a scene's line for its null values, their "
       "reasons and methods.</p>\n<ul class=\"stability\">\n" +
       rows + "</ul>\n</section>\n";
}

}  // namespace aalab
