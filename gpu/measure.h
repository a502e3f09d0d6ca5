/// What the GPU tool measures and compares (gpu/aalab_gpu.cpp, gpu/taa_gpu.cpp): timing of
/// launches with CUDA events, GPU output against CPU output, and one result row.
#pragma once
#include <cuda_runtime_api.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace aalab {

/// Median, min and max of timed launches, ms.
struct Stats {
  double median = 0, min = 0, max = 0;
};

/// A GPU output against the CPU output of the same input.
struct Fidelity {
  double identical_share = 0;
  double within1_share = 0;  ///< pixels whose rgb differs by at most one 8-bit level
  int max_diff = 0;
  long long differing = 0;
  double mean_abs_diff = 0;  ///< over all pixels and rgb channels, in 8-bit levels
};

/// One result row of the tool's JSON (one scene × size × method).
struct Entry {
  std::string scene, size, spec, kernels;
  bool timed = false;
  Stats t, pass;  ///< pass: FXAA pass alone for pre-pass methods (pass.median 0 otherwise)
  std::vector<std::pair<std::string, Stats>> passes;  ///< each kernel alone (SMAA)
  std::vector<double> frame_ms;                       ///< per-frame medians of a sequence (TAA), frame 0 first
  int frames = 0;                                     ///< frames of a sequence (TAA; 0 for a still method)
  double ratio = 0, ratio_linear = 0;                 ///< over the texture-path copy / the linear copy
  bool has_fidelity = false;
  Fidelity fid;  ///< a sequence: its worst frame
  bool has_soft = false;
  Fidelity soft;  ///< the software-filter variant (CPU bilinear arithmetic) against the CPU
  bool has_hw_mode = false;
  Fidelity hw_mode;  ///< the texture path against the CPU with --sampler gpu-texture
  bool deterministic = true, all_written = true;
};

Entry MakeEntry(const std::string& scene, const std::string& size, const std::string& spec, const std::string& kernels);

/// Median (mean of the middle two for an even count), min and max of `v` (not empty).
Stats Summarize(std::vector<double> v);

/// `warmup` untimed calls of `launch`, then `repeat` calls each between two CUDA events on
/// `stream`: their elapsed times summarised.
Stats TimeLaunches(const std::function<void()>& launch, int warmup, int repeat, cudaStream_t stream);

/// Share of identical pixels (rgb), largest difference, ... of `gpu` against `cpu` (same size).
Fidelity Compare(const Image8& gpu, const Image8& cpu);

/// True when every alpha byte is 255 (outputs are poisoned with 0xA5 before a check run).
bool AllOpaque(const Image8& img);

}  // namespace aalab
