// aalab_bench_msaa [WxH] [reps] [scene,...]: the MSAA figures of `make bench` alone
// (bench/bench_msaa.cpp), printed as a markdown table; default 480x270, 5 repetitions, every
// library scene.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "bench/bench_memory.h"
#include "bench/bench_msaa.h"
#include "core/params.h"
#include "scenes/library.h"

int main(int argc, char** argv) {
  std::fprintf(stderr, "%s\n", aalab::bench::ApplyBenchMemoryPolicy());
  int w = 480, h = 270, reps = 5;
  if (argc > 4 || (argc > 1 && std::sscanf(argv[1], "%dx%d", &w, &h) != 2) ||
      (argc > 2 && (reps = std::atoi(argv[2])) < 1) || w < 1 || h < 1) {
    std::fprintf(stderr, "usage: aalab_bench_msaa [WxH] [reps >= 1] [scene,...]\n");
    return 1;
  }
  try {
    const auto scenes = argc > 3 ? aalab::SplitCommaList(argv[3], "scene list") : aalab::LibrarySceneNames();
    std::printf("%s", aalab::RunMsaaBench(w, h, reps, scenes).markdown.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aalab_bench_msaa: %s\n", e.what());
    return 3;
  }
  return 0;
}
