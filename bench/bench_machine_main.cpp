// aalab_bench_machine [ROUNDS]: the machine's own 2-thread scaling, with no aalab code in it.
// Each round times one thread running a fixed dependent floating-point loop (no memory
// traffic, nothing shared), then two threads each running the same loop at once, and prints
// the round's scaling = 2 × (1-thread wall) / (2-thread wall); 2.00 is two whole cores. On a
// machine whose vCPUs run at a varying share of a physical core, the spread of these rounds is
// the noise floor under `make bench`'s "2 threads ≥ 1.8× one thread" goals: a filter or scene
// cannot be judged against 1.8× more finely than this loop scales in the same minutes.
// Default: 8 rounds (about 2 s each on this project's 2.5 GHz Xeon).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

namespace {

double Spin() {  // ~0.4 G dependent multiply-adds; the result is returned so nothing is elided
  double x = 1.0;
  for (long i = 0; i < 400000000L; ++i) x = x * 1.0000001 + 1e-9;
  return x;
}

double Seconds(const std::chrono::steady_clock::time_point& t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 8;
  if (rounds < 1) {
    std::fprintf(stderr, "usage: aalab_bench_machine [ROUNDS ≥ 1]\n");
    return 1;
  }
  std::vector<double> scaling;
  volatile double sink = 0.0;
  for (int r = 0; r < rounds; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    sink = sink + Spin();
    const double one = Seconds(t0);
    double a = 0.0, b = 0.0;
    t0 = std::chrono::steady_clock::now();
    std::thread ta([&a] { a = Spin(); }), tb([&b] { b = Spin(); });
    ta.join();
    tb.join();
    const double two = Seconds(t0);
    sink = sink + a + b;
    scaling.push_back(2.0 * one / two);
    std::printf("round %d: 1 thread %.3f s, 2 threads (twice the work) %.3f s, scaling %.2f×\n", r + 1, one, two,
                scaling.back());
  }
  std::sort(scaling.begin(), scaling.end());
  const size_t n = scaling.size();
  const double median = n % 2 ? scaling[n / 2] : 0.5 * (scaling[n / 2 - 1] + scaling[n / 2]);
  std::printf("scaling over %d rounds: median %.2f×, min %.2f×, max %.2f×\n", rounds, median, scaling.front(),
              scaling.back());
  return 0;
}
