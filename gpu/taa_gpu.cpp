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
#include "methods/taa_production.h"

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

// The production TAA's settings for its CUDA twin; UserError for what the twin does not do.
cuda::TaaProdArgs TaaProdArgsFrom(const ParamValues& v, const std::string& spec) {
  const TaaProdParams p = TaaProdParamsFrom(v);
  if (p.reconstruct != TaaReconstruct::kBox || p.sharpen > 0.0f) {
    throw UserError("'" + spec +
                    "': the CUDA twin of taa-prod runs filter=box and sharpen=0 only (filter=gauss needs "
                    "expf, not bit-identical to the CPU's; sharpen is a second pass)");
  }
  cuda::TaaProdArgs a{};
  a.dilate = p.dilate ? 1 : 0;
  a.history = p.history == TaaHistoryFilter::kBilinear ? 0 : (p.history == TaaHistoryFilter::kCatmullRom ? 1 : 2);
  a.disocclusion = p.disocclusion ? 1 : 0;
  a.disocclusion_depth = p.disocclusion_depth;
  a.disocclusion_px = p.disocclusion_px;
  a.clip = p.clip == TaaRectify::kVariance ? 0 : (p.clip == TaaRectify::kMinMax ? 1 : 2);
  a.gamma = p.gamma;
  a.adaptive = p.feedback == TaaFeedback::kAdaptive ? 1 : 0;
  a.alpha = p.alpha;
  a.alpha_min = p.alpha_min;
  a.alpha_max = p.alpha_max;
  a.motion_px = p.motion_px;
  a.luma_weight = p.luma_weight ? 1 : 0;
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

void CheckGpuTaaSpec(const std::string& spec) {
  const MethodPlan plan = MakeMethod(spec);
  if (!plan.NeedsHistory() || !plan.has_gpu_twin) {
    throw UserError("'" + spec + "' is not a TAA spec (" + JoinNames(DefaultGpuTaaSpecs()) + ", with [:...])");
  }
  if (plan.name == "taa-prod") TaaProdArgsFrom(plan.params, plan.spec);
}

TaaInput SyntheticTaaSequence(int width, int height, int frames, bool with_depth) {
  TaaInput seq;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // The disc (centre (0.4, 0.5) of the frame at t = 0, radius 0.3·height) moves faster.
  auto in_disc = [&](double x, double y, int t) {
    const double cx = 0.4 * width + 1.6 * t, cy = 0.5 * height + 0.13 * t;
    return (x - cx) * (x - cx) + (y - cy) * (y - cy) < 0.09 * height * height;
  };
  for (int t = 0; t < frames; ++t) {
    Image8 img(width, height, 4, 255);
    std::vector<float> depth;
    if (with_depth) depth.resize(static_cast<size_t>(width) * height);
    const double ox = 0.37 * t, oy = 0.13 * t;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const double u = (x + 0.5 - ox) / width, v = (y + 0.5 - oy) / height;
        double r = 0.2 + 0.3 * u, g = 0.25 + 0.2 * v, b = 0.4;
        float d = 10.0f + 0.001f * static_cast<float>(x);
        if (y < height / 8) d = inf;
        if (in_disc(x + 0.5, y + 0.5, t)) r = 0.95, g = 0.85, b = 0.1, d = 3.0f;
        if (v > 0.1 + 0.23 * u && v < 0.16 + 0.23 * u) r = g = b = 0.05, d = 5.0f;
        const int occ_x = width / 4 + 3 * t;
        if (x >= occ_x && x < occ_x + width / 8 + 1 && y >= height / 2 && y < height / 2 + height / 6 + 1) d = 1.5f;
        const uint32_t n = MixBits32(static_cast<uint32_t>((t * 7919 + y) * 65537 + x));
        uint8_t* p = img.Pixel(x, y);
        const double c[3] = {r, g, b};
        for (int k = 0; k < 3; ++k) {
          const int q = static_cast<int>(std::lround(255.0 * c[k])) + static_cast<int>((n >> (8 * k)) % 9) - 4;
          p[k] = static_cast<uint8_t>(std::clamp(q, 0, 255));
        }
        if (with_depth) depth[static_cast<size_t>(y) * width + x] = d;
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
          const float mx = in_disc(x + 0.5, y + 0.5, t) ? 1.6f : 0.37f;
          prev[i] = none ? nan : static_cast<float>(x) + 0.5f - mx;
          prev[i + 1] = none ? nan : static_cast<float>(y) + 0.5f - 0.13f;
        }
      }
    }
    seq.previous.push_back(std::move(prev));
    if (with_depth) {
      seq.depth.push_back(std::move(depth));
      seq.jitter.push_back(FrameJitterAt(JitterSpec{16}, t));
    }
  }
  return seq;
}

Entry RunTaaSequence(const std::string& spec, const std::string& scene, const TaaInput& seq, const float* srgb_decode,
                     bool timing, int warmup, int repeat, cudaStream_t stream, std::vector<std::string>* failures) {
  AALAB_CHECK(!seq.frames.empty() && seq.previous.size() == seq.frames.size(), "RunTaaSequence: empty sequence");
  AALAB_CHECK(seq.depth.empty() || seq.depth.size() == seq.frames.size(), "RunTaaSequence: depth per frame");
  AALAB_CHECK(seq.jitter.empty() || seq.jitter.size() == seq.frames.size(), "RunTaaSequence: jitter per frame");
  CheckGpuTaaSpec(spec);
  const MethodPlan plan = MakeMethod(spec);
  const bool prod = plan.name == "taa-prod";
  const cuda::TaaArgs args = prod ? cuda::TaaArgs{} : TaaArgsFrom(plan.params);
  cuda::TaaProdArgs pargs = prod ? TaaProdArgsFrom(plan.params, plan.spec) : cuda::TaaProdArgs{};
  const bool half = prod && plan.params.Choice("precision") == "rgba16f";
  const int w = seq.frames[0].Width(), h = seq.frames[0].Height();
  const size_t n = static_cast<size_t>(w) * h;
  const std::string size = std::to_string(w) + "x" + std::to_string(h);
  Entry e = MakeEntry(scene, size, plan.spec, prod ? "taa-prod-resolve" : "taa-resolve");
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
  // This frame's and the last frame's previous positions and depths (taa-prod reads both).
  DeviceBuffer prev_a(2 * n * sizeof(float)), prev_b(2 * n * sizeof(float)), depth_a(n * sizeof(float)),
      depth_b(n * sizeof(float));
  float *dprev = static_cast<float*>(prev_a.p), *dprev_old = static_cast<float*>(prev_b.p);
  float *ddepth = static_cast<float*>(depth_a.p), *ddepth_old = static_cast<float*>(depth_b.p);
  bool old_has_prev = false, old_has_depth = false;
  const float* dstarts = static_cast<const float*>(starts.p);
  cuda::GpuFrame frame(w, h), out(w, h);
  // Two histories per chain (hardware, software filter), swapped after each frame.
  cuda::GpuHistory hw_a(w, h, half), hw_b(w, h, half), sw_a(w, h, half), sw_b(w, h, half);
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
    const bool has_depth = !seq.depth.empty();
    if (has_depth) {
      AALAB_CHECK(seq.depth[t].size() == n, "RunTaaSequence: depth size");
      cuda::Check(cudaMemcpy(ddepth, seq.depth[t].data(), n * sizeof(float), cudaMemcpyHostToDevice), "upload");
    }
    const FrameJitter jit = seq.jitter.empty() ? FrameJitter{} : seq.jitter[t];
    pargs.jitter_x = jit.x;
    pargs.jitter_y = jit.y;
    const float* p = has_prev ? dprev : nullptr;
    cuda::TaaProdFrame pin;
    pin.previous = p;
    pin.depth = has_depth ? ddepth : nullptr;
    pin.prev_depth = t > 0 && old_has_depth ? ddepth_old : nullptr;
    pin.prev_previous = t > 0 && old_has_prev ? dprev_old : nullptr;
    const cuda::GpuHistory* hw_in = t > 0 ? hw_cur : nullptr;
    const cuda::GpuHistory* sw_in = t > 0 ? sw_cur : nullptr;
    auto step = [&](const cuda::GpuHistory* in, cuda::GpuHistory& next, bool soft) {
      if (prod) {
        cuda::LaunchTaaProdResolve(frame, pin, in, next, out, pargs, srgb_decode, dstarts, stream, soft);
      } else {
        cuda::LaunchTaaResolve(frame, p, in, next, out, args, srgb_decode, dstarts, stream, soft);
      }
    };
    auto hw_step = [&] { step(hw_in, *hw_next, false); };
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
    step(sw_in, *sw_next, true);
    cuda::Check(cudaStreamSynchronize(stream), "taa");
    const Image8 soft = Download(out);
    TemporalInput tin;
    tin.frame = &img;
    tin.previous = has_prev ? &seq.previous[t] : nullptr;
    tin.depth = has_depth ? &seq.depth[t] : nullptr;
    tin.jitter = jit;
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
    std::swap(dprev, dprev_old);
    std::swap(ddepth, ddepth_old);
    old_has_prev = has_prev;
    old_has_depth = has_depth;
  }
  if (e.timed) e.t.median = Summarize(with_history.empty() ? e.frame_ms : with_history).median;
  return e;
}

}  // namespace aalab
