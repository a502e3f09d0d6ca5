/// Registry rows of each method family, one function per family file. registry.cpp joins
/// them in listing order.
#pragma once
#include <vector>

#include "methods/method.h"

namespace aalab {

/// `none`, `ssaa-2x2`, `ssaa-4x4`, `ssaa-rgss`, `ssaa-jitter` (methods/supersample.cpp).
std::vector<MethodEntry> SupersampleMethods();

/// `fxaa1-p0` … `fxaa1-p5`: FXAA 1.0 whitepaper presets (methods/fxaa1.cpp).
std::vector<MethodEntry> Fxaa1Methods();

}  // namespace aalab
