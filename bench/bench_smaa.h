// SMAA's goal for aalab_bench (bench/bench_smaa.cpp). The four presets' production path is
// timed beside the FXAA figures and checked bit for bit against the reference implementation
// by bench/bench_post.cpp, which takes every post filter from the registry.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "core/image.h"
#include "methods/method.h"

namespace aalab::bench {

/// Adds the goal "each SMAA preset within 2× of fxaa311-p39 on the same 1080p frames, 1 and
/// 2 threads" through `goal`, reading the time ratio of figure a to figure b from `ratio(a, b)`
/// (keys "<filter>/<frame>/t<threads>", frames "real" and "dense").
void SmaaGoals(const std::function<double(const std::string&, const std::string&)>& ratio,
               const std::function<void(const std::string&, const std::string&, bool)>& goal);

}  // namespace aalab::bench
