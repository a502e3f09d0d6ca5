// TAA sequences on the GPU: see taa_gpu.h.
#include "gpu/taa_gpu.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>

#include "core/error.h"
#include "core/hash.h"
#include "core/params.h"
#include "methods/cuda/post_filters_cuda.h"
#include "methods/registry.h"
#include "methods/taa.h"

namespace aalab {
namespace {

float FromBits(uint32_t b) {
  float f;
  std::memcpy(&f, &b, sizeof f);
  return f;
}

// The 255 code thresholds of EncodeSrgb8 (code k starts at the smallest float in [0, 1]
// whose code is >= k), found by bisection over the float bit patterns, as methods/taa.cpp's
// encoder finds them: the kernel's binary search over them returns EncodeSrgb8's code.
std::vector<float> EncodeStarts() {
  std::vector<float> s(255);
  for (int k = 1; k < 256; ++k) {
    uint32_t lo = 0, hi = 0x3f800000u;
    while (lo < hi) {
      const uint32_t mid = lo + (hi - lo) / 2;
      if (EncodeSrgb8(FromBits(mid)) >= k) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
    s[static_cast<size_t>(k - 1)] = FromBits(lo);
  }
  return s;
}

cuda::TaaArgs TaaArgsFrom(const ParamValues& v) {  // the fields methods/taa.cpp reads
  cuda::TaaArgs a{};
  a.alpha = static_cast<float>(v.Number("alpha"));
  a.gamma = static_cast<float>(v.Number("gamma"));
  const std::string c = v.Choice("clip");
  a.clip = c == "variance" ? 0 : c == "minmax" ? 1 : 2;
  return a;
}

// A device buffer freed on scope exit.
struct DeviceBuffer {
  void* p = nullptr;
  explicit DeviceBuffer(size_t bytes) { cuda::Check(cudaMalloc(&p, bytes), "cudaMalloc"); }
  ~DeviceBuffer() { cudaFree(p); }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
};

Image8 Download(const cuda::GpuFrame& f) {
  Image8 img(f.Width(), f.Height(), 4);
  f.Download(img.Data().data());
  return img;
}

void Poison(cuda::GpuFrame& f) {
  std::vector<uint8_t> poison(static_cast<size_t>(f.Width()) * f.Height() * 4, 0xA5);
  f.Upload(poison.data());
}

}  // namespace

std::vector<std::string> DefaultGpuTaaSpecs() {  // the registry rows with memory and a CUDA twin
  std::vector<std::string> specs;
  for (const auto& e : MethodRegistry()) {
    if (e.has_gpu_twin && MakeMethod(e.name).NeedsHistory()) specs.push_back(e.name);
  }
  return specs;
}

TaaInput SyntheticTaaSequence(int width, int height, int frames) {
  TaaInput seq;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int t = 0; t < frames; ++t) {
    Image8 img(width, height, 4, 255);
    const double ox = 0.37 * t, oy = 0.13 * t;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const double u = (x + 0.5 - ox) / width, v = (y + 0.5 - oy) / height;
        double r = 0.2 + 0.3 * u, g = 0.25 + 0.2 * v, b = 0.4;
        if ((u - 0.4) * (u - 0.4) * width * width + (v - 0.5) * (v - 0.5) * height * height < 0.09 * height * height) {
          r = 0.95, g = 0.85, b = 0.1;
        }
        if (v > 0.1 + 0.23 * u && v < 0.16 + 0.23 * u) r = g = b = 0.05;
        const uint32_t n = MixBits32(static_cast<uint32_t>((t * 7919 + y) * 65537 + x));
        uint8_t* p = img.Pixel(x, y);
        const double c[3] = {r, g, b};
        for (int k = 0; k < 3; ++k) {
          const int q = static_cast<int>(std::lround(255.0 * c[k])) + static_cast<int>((n >> (8 * k)) % 9) - 4;
          p[k] = static_cast<uint8_t>(std::clamp(q, 0, 255));
        }
      }
    }
    seq.frames.push_back(std::move(img));
    std::vector<float> prev;
    if (t > 0) {
      prev.resize(2 * static_cast<size_t>(width) * height);
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          const size_t i = 2 * (static_cast<size_t>(y) * width + x);
          const bool none = x >= width / 2 && x < width / 2 + 9 && y >= height / 3 && y < height / 3 + 7;
          prev[i] = none ? nan : static_cast<float>(x) + 0.5f - 0.37f;
          prev[i + 1] = none ? nan : static_cast<float>(y) + 0.5f - 0.13f;
        }
      }
    }
    seq.previous.push_back(std::move(prev));
  }
  return seq;
}

Entry RunTaaSequence(const std::string& spec, const std::string& scene, const TaaInput& seq, const float* srgb_decode,
                     bool timing, int warmup, int repeat, cudaStream_t stream, std::vector<std::string>* failures) {
  AALAB_CHECK(!seq.frames.empty() && seq.previous.size() == seq.frames.size(), "RunTaaSequence: empty sequence");
  const MethodPlan plan = MakeMethod(spec);
  if (!plan.NeedsHistory() || !plan.has_gpu_twin) {
    throw UserError("'" + spec + "' is not a TAA spec (" + JoinNames(DefaultGpuTaaSpecs()) + ", with [:...])");
  }
  const cuda::TaaArgs args = TaaArgsFrom(plan.params);
  const int w = seq.frames[0].Width(), h = seq.frames[0].Height();
  const size_t n = static_cast<size_t>(w) * h;
  const std::string size = std::to_string(w) + "x" + std::to_string(h);
  Entry e = MakeEntry(scene, size, plan.spec, "taa-resolve");
  e.frames = static_cast<int>(seq.frames.size());
  e.has_fidelity = e.has_soft = true;
  e.fid.identical_share = 1.0;
  e.fid.within1_share = 1.0;
  e.soft.identical_share = 1.0;
  e.soft.within1_share = 1.0;

  static const std::vector<float> starts_host = EncodeStarts();
  DeviceBuffer starts(starts_host.size() * sizeof(float));
  cuda::Check(cudaMemcpy(starts.p, starts_host.data(), starts_host.size() * sizeof(float), cudaMemcpyHostToDevice),
              "upload");
  DeviceBuffer prev(2 * n * sizeof(float));
  const float* dstarts = static_cast<const float*>(starts.p);
  float* dprev = static_cast<float*>(prev.p);
  cuda::GpuFrame frame(w, h), out(w, h);
  // Two histories per chain (hardware, software filter), swapped after each frame.
  cuda::GpuHistory hw_a(w, h), hw_b(w, h), sw_a(w, h), sw_b(w, h);
  cuda::GpuHistory *hw_cur = &hw_a, *hw_next = &hw_b, *sw_cur = &sw_a, *sw_next = &sw_b;
  std::unique_ptr<TemporalState> cpu = plan.make_state();
  std::vector<double> with_history;
  auto fail = [&](const std::string& what) { failures->push_back(scene + " " + size + " " + plan.spec + " " + what); };

  for (size_t t = 0; t < seq.frames.size(); ++t) {
    const Image8& img = seq.frames[t];
    AALAB_CHECK(img.Width() == w && img.Height() == h, "RunTaaSequence: frame sizes differ");
    frame.Upload(img.Data().data());
    const bool has_prev = !seq.previous[t].empty();
    if (has_prev) {
      AALAB_CHECK(seq.previous[t].size() == 2 * n, "RunTaaSequence: previous positions size");
      cuda::Check(cudaMemcpy(dprev, seq.previous[t].data(), 2 * n * sizeof(float), cudaMemcpyHostToDevice), "upload");
    }
    const float* p = has_prev ? dprev : nullptr;
    const cuda::GpuHistory* hw_in = t > 0 ? hw_cur : nullptr;
    const cuda::GpuHistory* sw_in = t > 0 ? sw_cur : nullptr;
    auto hw_step = [&] { cuda::LaunchTaaResolve(frame, p, hw_in, *hw_next, out, args, srgb_decode, dstarts, stream); };
    Poison(out);
    hw_step();
    cuda::Check(cudaStreamSynchronize(stream), "taa");
    cuda::Check(cudaGetLastError(), "taa");
    const Image8 gpu = Download(out);
    Poison(out);
    hw_step();
    cuda::Check(cudaStreamSynchronize(stream), "taa");
    const Image8 gpu2 = Download(out);
    Poison(out);
    cuda::LaunchTaaResolve(frame, p, sw_in, *sw_next, out, args, srgb_decode, dstarts, stream, true);
    cuda::Check(cudaStreamSynchronize(stream), "taa");
    const Image8 soft = Download(out);
    TemporalInput tin;
    tin.frame = &img;
    tin.previous = has_prev ? &seq.previous[t] : nullptr;
    tin.frame_index = static_cast<int>(t);
    const Image8 cpu_out = cpu->Step(tin, nullptr);

    const std::string ft = "frame " + std::to_string(t);
    if (!AllOpaque(gpu) || !AllOpaque(soft)) e.all_written = false, fail(ft + ": output pixels left unwritten");
    if (gpu.Data() != gpu2.Data()) e.deterministic = false, fail(ft + ": two GPU runs differ");
    const Fidelity f = Compare(gpu, cpu_out);
    const Fidelity s = Compare(soft, cpu_out);
    if (f.identical_share < e.fid.identical_share) e.fid = f;
    e.soft.differing += s.differing;
    e.soft.max_diff = std::max(e.soft.max_diff, s.max_diff);
    e.soft.identical_share = std::min(e.soft.identical_share, s.identical_share);
    if (s.differing != 0) {
      fail(ft + ": the software-filter variant differs from the CPU on " + std::to_string(s.differing) +
           " pixels (max diff " + std::to_string(s.max_diff) + ")");
    }
    if (timing) {
      const Stats st = TimeLaunches(hw_step, warmup, repeat, stream);
      e.frame_ms.push_back(st.median);
      if (hw_in) with_history.push_back(st.median);
      if (!e.timed || st.min < e.t.min) e.t.min = st.min;
      if (!e.timed || st.max > e.t.max) e.t.max = st.max;
      e.timed = true;
    }
    std::swap(hw_cur, hw_next);
    std::swap(sw_cur, sw_next);
  }
  if (e.timed) e.t.median = Summarize(with_history.empty() ? e.frame_ms : with_history).median;
  return e;
}

}  // namespace aalab
