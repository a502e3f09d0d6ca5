/// Machine-readable results of `aalab compare` (reports/compare.h): `--json FILE` and
/// `--junit FILE` (JUnit XML for CI systems: GitLab, Jenkins, GitHub test reporters).
///
/// JSON (compare_version 1): {"compare_version":1, "exit_code", "verdict" ("pass",
/// "regression", "could not compare"), "fail_on", "baseline", "current", "metrics",
/// "regressions", "warnings", "improvements", "cannot_compare", "missing_rows", "extra_rows",
/// "notes", "capture_warnings", "strict", "rows":[{"scene","spec","baseline_spec",
/// "bit_identical","regression","changed"}], "lines":[{"scene","spec","baseline_spec",
/// "quantity","baseline","current","baseline_null","current_null","delta","threshold",
/// "verdict","gated","note"}]}. Infinite values are written as the strings "inf" / "-inf".
///
/// JUnit: one <testsuite name="aalab compare">; one <testcase classname=SCENE name=SPEC> per
/// matched row with a <failure> per gated regression line and the warnings in <system-out>;
/// one <testcase name="comparability"> with an <error> per could-not-compare reason, missing
/// or extra row; with --strict, a <testcase name="capture warnings"> failing on each.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "reports/compare.h"

namespace aalab {

/// The comparison as JSON (schema above).
nlohmann::ordered_json CompareToJson(const CompareResult& result, const std::string& baseline_name,
                                     const std::string& current_name);

/// The comparison as a JUnit XML document.
std::string CompareToJUnit(const CompareResult& result, const std::string& baseline_name,
                           const std::string& current_name);

}  // namespace aalab
