/// The report's "Numerical stability" section: for every scene (hard-case scenes first),
/// how many metric values are finite and which are null, with the reasons and methods.
#pragma once
#include <string>

#include "reports/result.h"

namespace aalab {

/// Appends the section's HTML (static, no script needed) to `html`.
void AppendStabilitySection(std::string& html, const Report& report);

}  // namespace aalab
