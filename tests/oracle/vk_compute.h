// A small Vulkan compute runner for test oracles: SPIR-V compute shaders on Mesa's lavapipe
// (Vulkan on the CPU), with storage/sampled images and storage buffers in one descriptor set.
//
// lavapipe settings, set in the environment before the loader starts: VK_DRIVER_FILES /
// VK_ICD_FILENAMES = lavapipe's ICD only; GALLIUM_OVERRIDE_CPU_CAPS=avx (at most 256-bit
// vectors, 8 lanes, on any machine with AVX; the CPU's FMA stays available, and lavapipe
// fuses some multiply-adds with it: docs/cmaa2.md. "sse4.1", which the GL oracles use to rule
// out FMA, makes lavapipe's LLVM 15 abort compiling CMAA2's f16 conversions); LP_NUM_THREADS=1 (workgroups run one
// after another, in dispatch order, so atomics happen in a fixed order). robustImageAccess is enabled where offered
// (image reads outside return 0).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace aalab::oracle {

/// Compiles HLSL text (entry point `entry`, compute) to SPIR-V with glslangValidator (Debian
/// glslang-tools): `-D -V -S comp --hlsl-iomap --shift-UAV-binding comp 10` plus `defines`
/// (NAME=VALUE). Registers t<n> get binding n, u<n> binding 10 + n. Throws with the compiler's
/// output on failure.
std::vector<uint32_t> CompileHlsl(const std::string& text, const std::string& entry,
                                  const std::vector<std::string>& defines);

/// Compiles a GLSL compute shader file (`path`; `#include`s resolved from its folder and
/// `include_dirs`) to SPIR-V with `glslangValidator -V -S comp` plus `defines` (NAME=VALUE).
/// Throws with the compiler's output on failure.
std::vector<uint32_t> CompileGlslFile(const std::string& path, const std::vector<std::string>& include_dirs,
                                      const std::vector<std::string>& defines);

/// Compiles GLSL compute text (no #includes) to SPIR-V as CompileGlslFile does, through a
/// temporary file. Throws with the compiler's output on failure.
std::vector<uint32_t> CompileGlslText(const std::string& text, const std::vector<std::string>& defines);

/// CompileGlslFile with more glslangValidator `options` (e.g. "--target-env vulkan1.1", which
/// subgroup operations need: SPIR-V 1.3). Throws with the compiler's output on failure.
std::vector<uint32_t> CompileGlslFileWith(const std::string& path, const std::vector<std::string>& defines,
                                          const std::string& options);

/// One binding of the descriptor sets (set `set`, binding `binding`).
struct VkBinding {
  enum Kind { kSampledImage, kStorageImage, kStorageBuffer, kUniformBuffer, kSampler } kind;
  uint32_t binding;
  // Images: size and format (VkFormat value); buffers: size in bytes.
  int width = 0, height = 0;
  int format = 0;
  uint64_t bytes = 0;
  bool indirect = false;  ///< a storage buffer also used as the DispatchIndirect argument
  uint32_t set = 0;       ///< the descriptor set (sets 0..max are all created; unused ones empty)
  bool linear = false;    ///< samplers: LINEAR (else NEAREST) filtering, always CLAMP_TO_EDGE, mip level 0
};

/// The key Fill and Read take for binding `binding` of set `set` (for set 0, the binding).
inline uint32_t VkKey(uint32_t set, uint32_t binding) { return set * 65536u + binding; }

/// One step of the command buffer: a pipeline and a direct or indirect dispatch.
struct VkStep {
  int pipeline;
  uint32_t gx = 1, gy = 1, gz = 1;
  int indirect_binding = -1;  ///< >= 0: vkCmdDispatchIndirect from that buffer binding, offset 0
};

class VkCompute {
 public:
  /// Starts lavapipe; "" on success, else what is missing.
  static std::string Start();
  /// The device name (VkPhysicalDeviceProperties::deviceName).
  static std::string DeviceName();
  /// lavapipe's vector width in 32-bit lanes (from the device name's "N bits"; 4 if absent):
  /// how many invocations run each statement together.
  static int Lanes();

  explicit VkCompute(std::vector<VkBinding> bindings);
  ~VkCompute();
  VkCompute(const VkCompute&) = delete;
  VkCompute& operator=(const VkCompute&) = delete;

  /// Adds a pipeline; returns its index for VkStep.
  int AddPipeline(const std::vector<uint32_t>& spirv, const std::string& entry);
  /// Initial contents (raw bytes, tightly packed rows for images); unset ones start as zero.
  /// `binding` is VkKey(set, binding).
  void Fill(uint32_t binding, const void* data, uint64_t bytes);
  /// Records every step (each followed by a full compute/indirect barrier), runs, waits.
  void Run(const std::vector<VkStep>& steps);
  /// The contents of a binding (VkKey(set, binding)) after Run (images as tightly packed rows).
  std::vector<uint8_t> Read(uint32_t binding);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aalab::oracle
