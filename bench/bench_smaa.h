// SMAA figures for aalab_bench (bench/bench_smaa.cpp): the four presets' production path
// beside the FXAA figures, checked bit for bit against the reference implementation, and
// the speed goal. bench_post.cpp (the post filters timed) and bench_main.cpp (the goals) use these.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "harness/core/image.h"
#include "methods/method.h"

namespace aalab::bench {

/// One post filter to time: its production path and its reference implementation.
struct PostCase {
  std::string name;
  std::function<Image8(const Image8&, PostStats*)> fast, ref;
};

/// smaa-low, smaa-medium, smaa-high, smaa-ultra with the reference presets.
std::vector<PostCase> SmaaPostCases();

/// Adds the goal "each SMAA preset within 2× of fxaa311-p39 on the same 1080p frames, 1 and
/// 2 threads" through `goal`, reading median seconds of figure `key` from `median`
/// ("<filter>/<frame>/t<threads>", frames "real" and "dense").
void SmaaGoals(const std::function<double(const std::string&)>& median,
               const std::function<void(const std::string&, const std::string&, bool)>& goal);

}  // namespace aalab::bench
