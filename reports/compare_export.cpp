// `aalab compare --json / --junit`: the comparison for machines (compare_export.h).
#include "reports/compare_export.h"

#include <cmath>
#include <map>
#include <sstream>

#include "reports/compare_text.h"
#include "reports/html_page.h"

namespace aalab {

namespace {

nlohmann::ordered_json Number(const std::optional<double>& v) {
  if (!v) return nullptr;
  if (std::isinf(*v)) return *v > 0 ? "inf" : "-inf";
  return *v;
}

const char* VerdictWord(int code) { return code == 0 ? "pass" : code == 1 ? "regression" : "could not compare"; }

std::string Xml(const std::string& s) { return HtmlEscape(s); }

std::string LineText(const CompareLine& l) {
  return l.quantity + " " + LineValueText(l, true) + " -> " + LineValueText(l, false) +
         (l.delta ? " (" + CompareDeltaText(l.quantity, *l.delta) + ")" : "") + ", threshold " + l.threshold +
         (l.note.empty() ? "" : ": " + l.note);
}

}  // namespace

nlohmann::ordered_json CompareToJson(const CompareResult& r, const std::string& baseline_name,
                                     const std::string& current_name) {
  using J = nlohmann::ordered_json;
  const int code = r.ExitCode();
  // The summary, in this key order (an ordered_json object from its pairs).
  J j = {{"compare_version", 1},
         {"exit_code", code},
         {"verdict", VerdictWord(code)},
         {"fail_on", FailOnName(r.fail_on)},
         {"strict", r.strict},
         {"baseline", baseline_name},
         {"current", current_name},
         {"metrics", r.metrics},
         {"regressions", r.regressions},
         {"warnings", r.warnings},
         {"improvements", r.improvements},
         {"cannot_compare", r.cannot_compare},
         {"missing_rows", r.missing_rows},
         {"extra_rows", r.extra_rows},
         {"notes", r.notes},
         {"capture_warnings", r.capture_warnings}};
  J rows = J::array();
  for (const auto& m : r.rows) {
    rows.push_back({{"scene", m.scene},
                    {"spec", m.spec},
                    {"baseline_spec", m.base_spec},
                    {"bit_identical", m.bit_identical},
                    {"regression", m.regression},
                    {"changed", m.changed}});
  }
  j["rows"] = rows;
  J lines = J::array();
  for (const auto& l : r.lines) {
    lines.push_back({{"scene", l.scene},
                     {"spec", l.spec},
                     {"baseline_spec", l.base_spec},
                     {"quantity", l.quantity},
                     {"baseline", Number(l.base)},
                     {"current", Number(l.current)},
                     {"baseline_null", l.base_null},
                     {"current_null", l.current_null},
                     {"delta", Number(l.delta)},
                     {"threshold", l.threshold},
                     {"verdict", VerdictName(l.verdict)},
                     {"gated", l.gated},
                     {"note", l.note}});
  }
  j["lines"] = lines;
  return j;
}

std::string CompareToJUnit(const CompareResult& r, const std::string& baseline_name, const std::string& current_name) {
  std::ostringstream cases;
  int tests = 0, failures = 0, errors = 0;
  // Comparability first: an error per reason.
  {
    std::vector<std::string> problems = r.cannot_compare;
    for (const auto& s : r.missing_rows) problems.push_back("row missing from the current report: " + s);
    for (const auto& s : r.extra_rows) problems.push_back("row not in the baseline: " + s);
    ++tests;
    cases << "  <testcase classname=\"aalab.compare\" name=\"comparability\">\n";
    for (const auto& p : problems) {
      ++errors;
      cases << "    <error type=\"could not compare\" message=\"" << Xml(p) << "\"/>\n";
    }
    cases << "  </testcase>\n";
  }
  for (const auto& m : r.rows) {
    ++tests;
    const std::string name = m.base_spec.empty() || m.base_spec == m.spec ? m.spec : m.base_spec + " -> " + m.spec;
    cases << "  <testcase classname=\"" << Xml(m.scene) << "\" name=\"" << Xml(name) << "\">\n";
    std::string out;
    bool failed = false;
    for (const auto& l : r.lines) {
      if (l.scene != m.scene || l.spec != m.spec || l.base_spec != m.base_spec) continue;
      if (l.verdict == Verdict::kRegression) {
        failed = true;
        cases << "    <failure type=\"regression\" message=\"" << Xml(LineText(l)) << "\"/>\n";
      } else if (l.verdict != Verdict::kUnchanged) {
        out += std::string(VerdictName(l.verdict)) + ": " + LineText(l) + "\n";
      }
    }
    failures += failed ? 1 : 0;
    if (!out.empty()) cases << "    <system-out>" << Xml(out) << "</system-out>\n";
    cases << "  </testcase>\n";
  }
  if (r.strict) {
    ++tests;
    cases << "  <testcase classname=\"aalab.compare\" name=\"capture warnings\">\n";
    if (!r.capture_warnings.empty()) ++failures;
    for (const auto& w : r.capture_warnings) {
      cases << "    <failure type=\"capture warning\" message=\"" << Xml(w) << "\"/>\n";
    }
    cases << "  </testcase>\n";
  }
  std::ostringstream doc;
  doc << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  doc << "<testsuite name=\"aalab compare\" tests=\"" << tests << "\" failures=\"" << failures << "\" errors=\""
      << errors << "\" skipped=\"0\">\n";
  doc << "  <properties>\n    <property name=\"baseline\" value=\"" << Xml(baseline_name) << "\"/>\n"
      << "    <property name=\"current\" value=\"" << Xml(current_name) << "\"/>\n"
      << "    <property name=\"fail_on\" value=\"" << FailOnName(r.fail_on) << "\"/>\n"
      << "    <property name=\"exit_code\" value=\"" << r.ExitCode() << "\"/>\n  </properties>\n";
  doc << cases.str() << "</testsuite>\n";
  return doc.str();
}

}  // namespace aalab
