/// The method registry: an explicit table (no static self-registration) that also drives
/// `aalab list methods`.
#pragma once
#include <string>
#include <vector>

#include "methods/method.h"

namespace aalab {

/// What the listings say about one method family (one family file).
struct MethodFamily {
  std::string name;       ///< MethodEntry::family ("fxaa311")
  std::string title;      ///< "FXAA 3.11 Quality"
  std::string files;      ///< the family's source files, comma separated
  std::string page;       ///< its docs page ("" = none)
  std::string source;     ///< BibTeX keys of reports/export_bibliography.cpp, comma separated ("" = nothing to cite)
  bool gpu_twin = false;  ///< CUDA twins in methods/cuda/, run by the GPU tool (gpu/)
};

/// Every family, in listing order.
const std::vector<MethodFamily>& MethodFamilies();

/// Every method, in listing order.
const std::vector<MethodEntry>& MethodRegistry();

/// Parses "name[:key=value,...]" and resolves it against the registry. Unknown names list
/// the valid ones; unknown or out-of-range parameters list the allowed ones (UserError).
MethodPlan MakeMethod(const std::string& spec);

/// Names of every registered method.
std::vector<std::string> MethodNames();

/// The method table of README.md and docs/cli.md (`aalab list methods --markdown`): one row
/// per family with its methods (`aalab run`'s default list in bold), parameters, GPU twin,
/// files and docs page, then a line naming the default list. Generated from the registry; a
/// test checks that both documents hold exactly this text.
std::string MethodTableMarkdown();

}  // namespace aalab
