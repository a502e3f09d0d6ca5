// aalab_bench_taa: the TAA cost figure of `make bench` alone (bench/bench_taa.cpp).
//   aalab_bench_taa [REPS] [THREADS]   defaults 9 and 2
#include <cstdio>
#include <string>

#include "bench/bench_memory.h"
#include "bench/bench_taa.h"

int main(int argc, char** argv) {
  std::fprintf(stderr, "%s\n", aalab::bench::ApplyBenchMemoryPolicy());
  const int reps = argc > 1 ? std::stoi(argv[1]) : 9;
  const int threads = argc > 2 ? std::stoi(argv[2]) : 2;
  const aalab::TaaBench b = aalab::RunTaaBench(reps, threads);
  for (const auto& l : b.lines) std::printf("%s\n", l.c_str());
  return 0;
}
