/// aalab_gpu's one output file (schema "aalab-gpu-timings", docs/gpu.md): the device, the
/// texture probe and rule, and every result row, as JSON written by hand (the stand-alone
/// tool needs only the C++ standard library).
#pragma once
#include <string>
#include <vector>

#include "gpu/measure.h"
#include "gpu/texture_probe.h"

namespace aalab {

/// What the tool records about the device and its driver (cudaGetDeviceProperties,
/// cudaDriverGetVersion/cudaRuntimeGetVersion, nvidia-smi before and after the measurements).
struct GpuDeviceFacts {
  std::string name;
  int major = 0, minor = 0, multiprocessors = 0;
  long long l2_bytes = 0, memory_bytes = 0;
  int driver = 0, runtime = 0;  ///< CUDA driver API and runtime versions (1000 · major + 10 · minor)
  std::string nvidia_driver, smi_before, smi_after;
};

/// A JSON number with 6 significant digits; "null" for NaN and infinities.
std::string JsonNumber(double v);

/// Writes the JSON file to `path` (through path.tmp, renamed when complete; UserError when
/// it cannot be written). `warmup` and `repeat`: the launches of each timing.
void WriteGpuTimingsJson(const std::string& path, const GpuDeviceFacts& device, const TextureProbe& probe,
                         const TextureRuleCheck& rule, int warmup, int repeat, const std::vector<Entry>& entries);

}  // namespace aalab
