#include "reports/html_gpu.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <vector>

#include "core/format.h"
#include "reports/html_page.h"

namespace aalab::html {
namespace {

std::string Ms(double v) { return FormatDouble(v < 1 ? "%.3f" : "%.2f", v); }

// Sizes in first-seen order over the rows' gpu blocks.
std::vector<std::string> Sizes(const Report& r) {
  std::vector<std::string> out;
  for (const auto& row : r.rows) {
    if (!row.gpu) continue;
    for (const auto& s : row.gpu->sizes) {
      if (std::find(out.begin(), out.end(), s.size) == out.end()) out.push_back(s.size);
    }
  }
  return out;
}

const GpuTiming* FirstGpu(const Report& r) {
  for (const auto& row : r.rows) {
    if (row.gpu) return &*row.gpu;
  }
  return nullptr;
}

}  // namespace

bool AnyGpu(const Report& r) { return FirstGpu(r) != nullptr; }

std::string GpuHeader(const Report& r) {
  const GpuTiming* g = FirstGpu(r);
  if (!g) return "";
  std::string sizes;
  for (const auto& s : Sizes(r)) sizes += (sizes.empty() ? "" : " / ") + s;
  return "<th scope=\"col\" title=\"" +
         HtmlEscape("The post filter's CUDA twin on " + g->device + " (driver " + g->driver +
                    "): median ms per frame of this scene at " + sizes +
                    ", CUDA events over the timed launches; not comparable with the CPU time column. docs/gpu.md") +
         "\"><button type=\"button\">GPU ms <span class=\"unit\">" + HtmlEscape(sizes) + "</span></button></th>";
}

std::string GpuCell(const ResultRow& row) {
  if (!row.gpu || row.gpu->sizes.empty()) {
    return "<td class=\"num null\" title=\"no GPU timing: only post filters with a CUDA twin are timed on the "
           "GPU\">—</td>";
  }
  const GpuTiming& g = *row.gpu;
  std::string text, title = g.device + ", driver " + g.driver + ", CUDA " + g.cuda_runtime + ", measured " +
                            g.measured_utc + "; kernels: " + g.kernels;
  for (const auto& s : g.sizes) {
    text += (text.empty() ? "" : " / ") + Ms(s.median_ms);
    title += "\n" + s.size + ": median " + Ms(s.median_ms) + " ms [" + Ms(s.min_ms) + "–" + Ms(s.max_ms) + "], " +
             FormatDouble("%.2f", s.ratio_to_copy) + "× the copy floor (" + Ms(s.copy_ms) + " ms)";
    if (s.identical_share) {
      title += ", " + FormatDouble("%.3f", 100.0 * *s.identical_share) + "% of pixels identical to the CPU output";
    }
    if (s.max_diff) title += ", largest difference " + std::to_string(*s.max_diff) + " levels";
  }
  return "<td class=\"num\" data-v=\"" + FormatDouble("%.17g", g.sizes.front().median_ms) + "\" title=\"" +
         HtmlEscape(title) + "\">" + text + "</td>";
}

std::string GpuSummary(const Report& r) {
  const GpuTiming* g = FirstGpu(r);
  if (!g) return "";
  const std::vector<std::string> sizes = Sizes(r);
  struct Acc {
    std::map<std::string, std::pair<double, double>> sum;  // size → (ms, ratio) sums
    std::map<std::string, int> n;
    double worst_identical = 1.0;
    bool any_identical = false;
    std::string kernels;
  };
  std::vector<std::string> order;
  std::map<std::string, Acc> by_spec;
  for (const auto& row : r.rows) {
    if (!row.gpu) continue;
    if (!by_spec.count(row.spec)) order.push_back(row.spec);
    Acc& a = by_spec[row.spec];
    a.kernels = row.gpu->kernels;
    for (const auto& s : row.gpu->sizes) {
      a.sum[s.size].first += s.median_ms;
      a.sum[s.size].second += s.ratio_to_copy;
      ++a.n[s.size];
      if (s.identical_share) {
        a.any_identical = true;
        a.worst_identical = std::min(a.worst_identical, *s.identical_share);
      }
    }
  }
  std::string h =
      "<h3>GPU cost of the post filters</h3>\n<div class=\"table-wrap\"><table class=\"gpu sortable\">"
      "<caption>Each post filter's CUDA twin on <b>" +
      HtmlEscape(g->device) + "</b> (driver " + HtmlEscape(g->driver) + ", CUDA " + HtmlEscape(g->cuda_runtime) +
      ", measured " + HtmlEscape(g->measured_utc) +
      "): mean over scenes of the median ms per frame (CUDA events, clocks not locked) and of the ratio "
      "to a copy kernel of the same frame; identical = worst share of pixels equal to the CPU output. "
      "See docs/gpu.md.</caption>\n<thead><tr><th scope=\"col\" data-type=\"text\"><button "
      "type=\"button\">Method</button></th><th scope=\"col\" data-type=\"text\"><button "
      "type=\"button\">Kernels</button></th>";
  for (const auto& s : sizes) {
    h += "<th scope=\"col\"><button type=\"button\">ms " + HtmlEscape(s) +
         "</button></th><th scope=\"col\"><button "
         "type=\"button\">× copy " +
         HtmlEscape(s) + "</button></th>";
  }
  h += "<th scope=\"col\"><button type=\"button\">Identical</button></th></tr></thead>\n<tbody>\n";
  for (const auto& spec : order) {
    const Acc& a = by_spec[spec];
    h += "<tr data-spec=\"" + HtmlEscape(spec) + "\"><th scope=\"row\" data-v=\"" + HtmlEscape(spec) +
         "\"><span class=\"method\">" + HtmlEscape(spec) + "</span></th><td data-v=\"" + HtmlEscape(a.kernels) + "\">" +
         HtmlEscape(a.kernels) + "</td>";
    for (const auto& s : sizes) {
      auto it = a.n.find(s);
      if (it == a.n.end()) {
        h += "<td class=\"num null\">—</td><td class=\"num null\">—</td>";
        continue;
      }
      const double ms = a.sum.at(s).first / it->second, ratio = a.sum.at(s).second / it->second;
      h += "<td class=\"num\" data-v=\"" + FormatDouble("%.17g", ms) + "\">" + Ms(ms) +
           "</td><td class=\"num\" data-v=\"" + FormatDouble("%.17g", ratio) + "\">" + FormatDouble("%.2f", ratio) +
           "</td>";
    }
    h += a.any_identical ? "<td class=\"num\" data-v=\"" + FormatDouble("%.17g", a.worst_identical) + "\">" +
                               FormatDouble("%.3f", 100.0 * a.worst_identical) + "%</td>"
                         : std::string("<td class=\"num null\">—</td>");
    h += "</tr>\n";
  }
  return h + "</tbody></table></div>\n";
}

}  // namespace aalab::html
