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
        detail += "<li><code>" + HtmlEscape(metric) + "</code> null — " + HtmlEscape(reason) + ": " +
                  HtmlEscape(list) + "</li>";
      }
    }
    const bool hard = s->name.rfind("hard-", 0) == 0;
    rows += "<tr" + std::string(hard ? " class=\"hard\"" : "") + "><th scope=\"row\">" + HtmlEscape(s->name) +
            (hard ? " <span class=\"tag\">hard</span>" : "") + "</th><td class=\"num\">" + std::to_string(n_rows) +
            "</td><td class=\"num\">" + std::to_string(finite) + "</td><td class=\"num\">" + std::to_string(nulls) +
            "</td><td class=\"num\">" + (bad ? "<strong>" + std::to_string(bad) + "</strong>" : "0") +
            "</td><td>" + (detail.empty() ? "none" : "<ul class=\"nulls\">" + detail + "</ul>") + "</td></tr>\n";
  }
  h += "<section id=\"stability\" class=\"prose\">\n<h2>Numerical stability</h2>\n<p>Every metric value of every "
       "row is either a finite number or <code>null</code> with a reason; NaN and Infinity never reach the "
       "report. Outputs are 8-bit frames, so every pixel is in [0, 1] by construction. Across this run: " +
       std::to_string(total_values) + " metric values, " + std::to_string(total_null) + " null with a reason, " +
       std::to_string(total_bad) +
       " invalid (non-finite, or null without a reason; must be 0). Scenes of the <code>hard</code> suite "
       "(<code>aalab run --suite hard</code>) come first.</p>\n<table class=\"stability\"><thead><tr><th>scene</th>"
       "<th>rows</th><th>finite</th><th>null</th><th>invalid</th><th>null values (reason: methods)</th></tr>"
       "</thead><tbody>\n" +
       rows + "</tbody></table>\n</section>\n";
}

}  // namespace aalab
