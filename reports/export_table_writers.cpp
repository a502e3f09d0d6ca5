// The writers of aalab export's tables (reports/export_tables.h): LaTeX (booktabs), Markdown
// and CSV over the one table model that export_tables.cpp fills.
#include <algorithm>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/export_tables.h"

namespace aalab {

std::string LatexEscape(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const std::string rest = text.substr(i);
    auto starts = [&](const char* s) { return rest.rfind(s, 0) == 0; };
    if (starts("—")) {
      out += "---";
      i += std::string("—").size() - 1;
    } else if (starts("–")) {
      out += "--";
      i += std::string("–").size() - 1;
    } else if (starts("×")) {
      out += "$\\times$";
      i += std::string("×").size() - 1;
    } else if (starts("≥")) {
      out += "$\\geq$";
      i += std::string("≥").size() - 1;
    } else if (starts("†")) {
      out += "\\textdagger{}";
      i += std::string("†").size() - 1;
    } else if (starts("·")) {
      out += "$\\cdot$";
      i += std::string("·").size() - 1;
    } else {
      switch (c) {
        case '\\': out += "\\textbackslash{}"; break;
        case '{': out += "\\{"; break;
        case '}': out += "\\}"; break;
        case '$': out += "\\$"; break;
        case '&': out += "\\&"; break;
        case '#': out += "\\#"; break;
        case '^': out += "\\^{}"; break;
        case '_': out += "\\_"; break;
        case '%': out += "\\%"; break;
        case '~': out += "\\textasciitilde{}"; break;
        case '<': out += "\\textless{}"; break;
        case '>': out += "\\textgreater{}"; break;
        case '|': out += "\\textbar{}"; break;
        default: out += c;
      }
    }
  }
  return out;
}

namespace {

std::string JoinWith(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

std::string LatexCell(const TableCell& c) {
  if (!c.value) return "--";
  if (c.text.empty()) return "";
  std::string s = c.text;
  if (s[0] == '-') s = "$-$" + s.substr(1);
  if (s == "yes") s = "$\\bullet$";
  if (c.best) s = "\\textbf{" + s + "}";
  return c.near_floor ? s + "$^\\dagger$" : s;
}

/// Consecutive equal groups: (label, first column, count).
struct Span {
  std::string label;
  size_t first, count;
};
std::vector<Span> Spans(const std::vector<std::string>& groups) {
  std::vector<Span> out;
  for (size_t i = 0; i < groups.size(); ++i) {
    if (!out.empty() && out.back().label == groups[i]) {
      ++out.back().count;
    } else {
      out.push_back({groups[i], i, 1});
    }
  }
  return out;
}

bool AnyNonEmpty(const std::vector<std::string>& v) {
  return std::any_of(v.begin(), v.end(), [](const std::string& s) { return !s.empty(); });
}

}  // namespace

std::string TableToLatex(const ExportTable& t, const std::string& id, const std::vector<std::string>& provenance) {
  std::string o;
  for (const auto& line : provenance) o += "% " + line + "\n";
  o += "% Needs \\usepackage{booktabs} and \\usepackage{graphicx} (the tabular is scaled to \\linewidth only when "
       "wider).\n";
  const bool wide = t.columns.size() > 6;
  const std::string env = wide ? "table*" : "table";
  o += "\\begin{" + env + "}[tbp]\n\\centering\n";
  o += "\\caption{" + LatexEscape(t.caption) + "}\n\\label{tab:aalab-" + id + "}\n";
  o += "\\setbox0=\\hbox{%\n";
  o += "\\begin{tabular}{l" + std::string(t.columns.size(), 'r') + "}\n\\toprule\n";
  if (AnyNonEmpty(t.column_groups)) {
    std::string rules;
    for (const auto& s : Spans(t.column_groups)) {
      o += " & \\multicolumn{" + std::to_string(s.count) + "}{c}{" + LatexEscape(s.label) + "}";
      rules += "\\cmidrule(lr){" + std::to_string(s.first + 2) + "-" + std::to_string(s.first + s.count + 1) + "}";
    }
    o += " \\\\\n" + rules + "\n";
  }
  o += LatexEscape(t.row_header);
  for (const auto& c : t.columns) o += " & " + LatexEscape(c);
  o += " \\\\\n\\midrule\n";
  std::string group;
  for (size_t r = 0; r < t.cells.size(); ++r) {
    if (!t.row_groups[r].empty() && t.row_groups[r] != group) {
      if (r > 0) o += "\\midrule\n";
      o += "\\multicolumn{" + std::to_string(t.columns.size() + 1) + "}{l}{\\emph{" + LatexEscape(t.row_groups[r]) +
           "}} \\\\\n";
      group = t.row_groups[r];
    }
    o += LatexEscape(t.row_labels[r]);
    for (const auto& c : t.cells[r]) o += " & " + LatexCell(c);
    o += " \\\\\n";
  }
  o += "\\bottomrule\n\\end{tabular}%\n}%\n";
  o += "\\ifdim\\wd0>\\linewidth\\resizebox{\\linewidth}{!}{\\box0}\\else\\box0\\fi\n";
  if (!t.notes.empty()) {
    o += "\\par\\smallskip\n{\\footnotesize\\raggedright\n";
    for (const auto& n : t.notes) o += LatexEscape(n) + "\n";
    o += "\\par}\n";
  }
  o += "\\end{" + env + "}\n";
  return o;
}

std::string TableToMarkdown(const ExportTable& t, const std::vector<std::string>& provenance) {
  auto esc = [](const std::string& s) {
    std::string out;
    for (char c : s) {
      if (c == '|' || c == '*' || c == '_' || c == '\\') out += '\\';
      out += c;
    }
    return out;
  };
  std::string o = "<!--\n";
  for (const auto& line : provenance) o += "  " + line + "\n";
  o += "-->\n\n**Table:** " + t.caption + "\n\n| " + esc(t.row_header);
  for (size_t c = 0; c < t.columns.size(); ++c) {
    o += " | " + esc(t.column_groups[c].empty() ? t.columns[c] : t.column_groups[c] + ": " + t.columns[c]);
  }
  o += " |\n|:--";
  for (size_t c = 0; c < t.columns.size(); ++c) o += "|--:";
  o += "|\n";
  std::string group;
  for (size_t r = 0; r < t.cells.size(); ++r) {
    if (!t.row_groups[r].empty() && t.row_groups[r] != group) {
      // A group row: the label, then empty cells (| *label* | | ... |).
      o += "| *" + esc(t.row_groups[r]) + "*";
      for (size_t c = 0; c < t.columns.size(); ++c) o += " |";
      o += " |\n";
      group = t.row_groups[r];
    }
    o += "| " + esc(t.row_labels[r]);
    for (const auto& c : t.cells[r]) {
      const std::string s = !c.value ? "—" : c.text;
      o += " | " + (c.best && !s.empty() ? "**" + s + "**" : s) + (c.near_floor ? "†" : "");
    }
    o += " |\n";
  }
  if (!t.notes.empty()) {
    o += "\n";
    for (const auto& n : t.notes) o += n + "\n";
  }
  return o;
}

std::string TableToCsv(const ExportTable& t, const std::vector<std::string>& provenance) {
  auto field = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  std::string o;
  for (const auto& line : provenance) o += "# " + line + "\n";
  o += "# " + t.caption + "\n";
  for (const auto& n : t.notes) o += "# " + n + "\n";
  const bool groups = AnyNonEmpty(t.row_groups);
  if (groups) o += "run,";
  o += field(t.row_header);
  for (size_t c = 0; c < t.columns.size(); ++c) {
    o += ',';
    o += field(t.column_groups[c].empty() ? t.columns[c] : t.column_groups[c] + ":" + t.columns[c]);
  }
  o += "\n";
  std::vector<std::string> group_order;
  for (size_t r = 0; r < t.cells.size(); ++r) {
    if (groups) o += field(t.row_groups[r]) + ",";
    o += field(t.row_labels[r]);
    for (const auto& c : t.cells[r]) {
      o += ',';
      if (c.value) o += nlohmann::json(*c.value).dump();
    }
    o += "\n";
    if (group_order.empty() || group_order.back() != t.row_groups[r]) group_order.push_back(t.row_groups[r]);
  }
  for (const auto& g : group_order) {
    if (groups) o += field(g) + ",";
    o += "best";
    for (size_t c = 0; c < t.columns.size(); ++c) {
      std::vector<std::string> names;
      for (size_t r = 0; r < t.cells.size(); ++r) {
        if (t.row_groups[r] == g && t.cells[r][c].best) names.push_back(t.row_labels[r]);
      }
      o += ',';
      o += field(JoinWith(names, ";"));
    }
    o += "\n";
  }
  return o;
}

}  // namespace aalab
