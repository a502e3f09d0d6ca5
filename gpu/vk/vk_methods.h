/// The methods aalab_vk runs as their original shaders dispatch them (docs/gpu.md "Original
/// shaders through Vulkan"): a table of report method specs, each a chain of passes over the
/// SPIR-V modules scripts/vk_shaders.sh writes, with the images, buffers, constants and
/// dispatch sizes the original's host code gives them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "gpu/vk/vk_runner.h"

namespace aalab::vk {

/// An 8-bit frame as RGBA rows (alpha 255).
struct Frame {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

/// One row of the method table.
struct MethodInfo {
  std::string spec;     ///< the report's method spec (`cmaa2-high`, `scale43-easu`, ...)
  std::string input;    ///< the export-frames role it reads: "1x", or "scale43-easu" (the render-size frame
                        ///< `aalab export-frames --render-methods scale43-easu` writes)
  std::string kernels;  ///< the passes in dispatch order, as the JSON names them
};

/// Every method the tool knows, in the order it runs them (`copy` first).
const std::vector<MethodInfo>& Methods();
/// The row for `spec`, or nullptr.
const MethodInfo* FindMethod(const std::string& spec);

/// Facts about a float output (FSR 2's RGBA16F output, before it becomes 8-bit).
struct OutputCheck {
  bool has = false;
  long nonfinite = 0;       ///< NaN or infinite rgb values
  double min = 0, max = 0;  ///< over the finite rgb values
  /// Mean |output − the sequence's last frame rendered at display size| over rgb (0..1 units),
  /// and the same for the render-size input of that frame scaled up by nearest neighbour.
  double mean_abs_error = 0, mean_abs_error_nearest = 0;
};

/// One method timed on one frame.
struct MethodResult {
  std::vector<std::string> pass_names;
  Timings timings;
  Frame output;  ///< the output frame after the last repetition
  OutputCheck check;
  std::vector<uint16_t> output_half;  ///< FSR 2: the output image's rgba16f texels as they are
  std::string note;                   ///< for the JSON: what the method ran on, where the input role does not say it
};

/// The SPIR-V modules (file names without .spv) `spec` needs.
std::vector<std::string> ModulesOf(const std::string& spec);

/// FsrEasuCon's four uint4 (float bits) for an in_w x in_h frame (viewport = texture) scaled to
/// out_w x out_h, term by term in float with ARcpF1(a) = 1/a, as ffx_fsr1.h writes it.
std::vector<uint32_t> EasuConstants(int in_w, int in_h, int out_w, int out_h);
/// FsrRcasCon's con.x: the bits of exp2(-sharpness_stops).
uint32_t RcasConstant(float sharpness_stops);

/// Runs `spec` (a Methods() row) with the modules in `spirv_dir` on `in` (the frame of its
/// input role), producing an out_w x out_h frame. Throws std::runtime_error naming a missing
/// module.
MethodResult RunMethod(Device& device, const std::string& spirv_dir, const std::string& spec, const Frame& in,
                       int out_w, int out_h, int warmup, int repeat);

}  // namespace aalab::vk
