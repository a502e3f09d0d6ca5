// SMAA figures for aalab_bench; see bench/bench_smaa.h.
#include "bench/bench_smaa.h"

#include "bench/bench_post.h"

#include <algorithm>
#include <cstdio>

namespace aalab::bench {

void SmaaGoals(const std::function<double(const std::string&, const std::string&)>& ratio,
               const std::function<void(const std::string&, const std::string&, bool)>& goal) {
  for (int threads : {1, 2}) {
    double worst = 0.0;
    std::string worst_name, all;
    for (const char* frame : {"real", "dense"}) {
      const std::string suffix = std::string("/") + frame + "/t" + std::to_string(threads);
      for (const char* preset : {"low", "medium", "high", "ultra"}) {
        const double r = ratio(std::string("smaa-") + preset + suffix, "fxaa311-p39" + suffix);
        char buf[64];
        std::snprintf(buf, sizeof buf, "%s%s %s %.2f×", all.empty() ? "" : ", ", preset, frame, r);
        all += buf;
        if (r > worst) worst = r, worst_name = std::string(preset) + " on " + frame;
      }
    }
    char head[96];
    std::snprintf(head, sizeof head, "worst %s %.2f×; ", worst_name.c_str(), worst);
    goal(std::string("SMAA presets within 2× of fxaa311-p39's time, same 1080p frames (real = ") + kRealFrameScene +
             ", dense = " + kDenseFrameScene + "; " + std::to_string(threads) + " thread" + (threads > 1 ? "s" : "") +
             ")",
         head + all, worst <= 2.0);
  }
}

}  // namespace aalab::bench
