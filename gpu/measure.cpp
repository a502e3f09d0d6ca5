// Timing and comparison helpers of the GPU tool (measure.h).
#include "gpu/measure.h"

#include <algorithm>
#include <cstdlib>

#include "core/error.h"
#include "methods/cuda/post_filters_cuda.h"

namespace aalab {

Entry MakeEntry(const std::string& scene, const std::string& size, const std::string& spec,
                const std::string& kernels) {
  Entry e;
  e.scene = scene;
  e.size = size;
  e.spec = spec;
  e.kernels = kernels;
  return e;
}

Stats Summarize(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  Stats s;
  s.min = v.front();
  s.max = v.back();
  const size_t n = v.size();
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return s;
}

Stats TimeLaunches(const std::function<void()>& launch, int warmup, int repeat, cudaStream_t stream) {
  for (int i = 0; i < warmup; ++i) launch();
  std::vector<cudaEvent_t> ev(2 * static_cast<size_t>(repeat));
  for (auto& e : ev) cuda::Check(cudaEventCreate(&e), "cudaEventCreate");
  for (int i = 0; i < repeat; ++i) {
    cuda::Check(cudaEventRecord(ev[2 * i], stream), "cudaEventRecord");
    launch();
    cuda::Check(cudaEventRecord(ev[2 * i + 1], stream), "cudaEventRecord");
  }
  cuda::Check(cudaStreamSynchronize(stream), "timed launches");
  cuda::Check(cudaGetLastError(), "timed launches");
  std::vector<double> ms;
  for (int i = 0; i < repeat; ++i) {
    float t = 0;
    cuda::Check(cudaEventElapsedTime(&t, ev[2 * i], ev[2 * i + 1]), "cudaEventElapsedTime");
    ms.push_back(t);
  }
  for (auto& e : ev) cudaEventDestroy(e);
  return Summarize(ms);
}

Fidelity Compare(const Image8& gpu, const Image8& cpu) {
  AALAB_CHECK(gpu.Width() == cpu.Width() && gpu.Height() == cpu.Height(), "Compare: sizes differ");
  Fidelity f;
  long long same = 0, within1 = 0;
  double sum = 0;
  const size_t n = static_cast<size_t>(gpu.Width()) * gpu.Height();
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* a = gpu.Data().data() + 4 * i;
    const uint8_t* b = cpu.Data().data() + 4 * i;
    int d = 0;
    for (int c = 0; c < 3; ++c) {
      const int dc = std::abs(static_cast<int>(a[c]) - static_cast<int>(b[c]));
      d = std::max(d, dc);
      sum += dc;
    }
    if (d == 0) ++same;
    if (d <= 1) ++within1;
    f.max_diff = std::max(f.max_diff, d);
  }
  f.differing = static_cast<long long>(n) - same;
  f.identical_share = static_cast<double>(same) / static_cast<double>(n);
  f.within1_share = static_cast<double>(within1) / static_cast<double>(n);
  f.mean_abs_diff = sum / (3.0 * static_cast<double>(n));
  return f;
}

bool AllOpaque(const Image8& img) {
  for (size_t i = 3; i < img.Data().size(); i += 4) {
    if (img.Data()[i] != 255) return false;
  }
  return true;
}

}  // namespace aalab
