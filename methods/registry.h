/// The method registry: an explicit table (no static self-registration) that also drives
/// `aalab list methods`.
#pragma once
#include <string>
#include <vector>

#include "methods/method.h"

namespace aalab {

/// Every method, in listing order.
const std::vector<MethodEntry>& MethodRegistry();

/// Parses "name[:key=value,...]" and resolves it against the registry. Unknown names list
/// the valid ones; unknown or out-of-range parameters list the allowed ones (UserError).
MethodPlan MakeMethod(const std::string& spec);

/// Names of every registered method.
std::vector<std::string> MethodNames();

}  // namespace aalab
