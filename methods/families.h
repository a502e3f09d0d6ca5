/// Registry rows of each method family, one function per family file. registry.cpp joins
/// them in listing order.
#pragma once
#include <vector>

#include "methods/method.h"

namespace aalab {

/// `none`, `ssaa-2x2`, `ssaa-4x4`, `ssaa-rgss`, `ssaa-jitter` (methods/supersample.cpp).
std::vector<MethodEntry> SupersampleMethods();

}  // namespace aalab
