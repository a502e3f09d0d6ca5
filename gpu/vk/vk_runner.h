/// A Vulkan compute runner for timing original shaders (docs/gpu.md "Original shaders through
/// Vulkan"): one device, images and buffers a method's passes share, one descriptor set per
/// pass, and a command buffer that repeats the whole pass chain with vkCmdWriteTimestamp
/// between the passes. Needs only the Vulkan headers and loader: no aalab library.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace aalab::vk {

/// What the tool reports about the device it ran on.
struct DeviceFacts {
  std::string name;    ///< VkPhysicalDeviceProperties::deviceName
  std::string driver;  ///< driverName + driverInfo (VkPhysicalDeviceDriverProperties), e.g. "NVIDIA 580.159.04"
  std::string api;     ///< the device's Vulkan version, e.g. "1.3.277"
  double timestamp_period_ns = 0;
  uint32_t timestamp_valid_bits = 0;
  bool robust_image_access = false;  ///< enabled (Vulkan 1.3's robustImageAccess) where offered
};

/// An image of a method (one mip level, one layer). UNORM/UINT formats are sampled and storage
/// images; an sRGB format is sampled only (no storage image can be sRGB).
struct ImageSpec {
  int width = 0, height = 0;
  int format = 0;  ///< a VkFormat value: R8G8B8A8_UNORM, R8G8B8A8_SRGB or R32_UINT
};

/// A storage buffer of a method; `indirect` also makes it a vkCmdDispatchIndirect argument.
struct BufferSpec {
  uint64_t bytes = 0;
  bool indirect = false;
};

/// One descriptor of a pass: binding `binding` of set 0 refers to image or buffer `resource`.
struct PassBinding {
  enum Kind { kSampledImage, kCombinedSampler, kStorageImage, kStorageBuffer } kind;
  uint32_t binding;
  int resource;  ///< index into the method's images (image kinds) or buffers (kStorageBuffer)
};

/// One dispatch of the chain: a SPIR-V module (entry "main"), its descriptors, push constants
/// (at most 16 words; empty = none) and either a direct grid or an indirect buffer.
struct PassSpec {
  std::string name;  ///< the entry point name as the original calls it (for the JSON)
  std::vector<uint32_t> spirv;
  std::vector<PassBinding> bindings;
  std::vector<uint32_t> push;
  uint32_t gx = 1, gy = 1, gz = 1;
  int indirect_buffer = -1;  ///< >= 0: vkCmdDispatchIndirect from that buffer at offset 0
};

/// The Vulkan instance and device (one per process).
class Device {
 public:
  /// Opens the first physical device whose name contains `name_filter` (any device when
  /// empty; a discrete GPU is preferred). Throws std::runtime_error saying what is missing.
  explicit Device(const std::string& name_filter);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
  const DeviceFacts& Facts() const;

  struct Impl;
  Impl* impl() const { return impl_.get(); }

 private:
  std::unique_ptr<Impl> impl_;
};

/// Per-run timestamps: ms[r][k] is pass k of repetition r; whole[r] the chain of repetition r.
struct Timings {
  std::vector<std::vector<double>> ms;
  std::vector<double> whole;
};

/// A method's resources and pipelines on a device.
class Chain {
 public:
  Chain(Device& device, std::vector<ImageSpec> images, std::vector<BufferSpec> buffers, std::vector<PassSpec> passes);
  ~Chain();
  Chain(const Chain&) = delete;
  Chain& operator=(const Chain&) = delete;

  /// Uploads tightly packed texel rows into image `i` (before Run).
  void FillImage(int i, const void* data, uint64_t bytes);
  /// Fills buffer `i` with the 32-bit value `word` (before Run).
  void FillBuffer(int i, uint32_t word);
  /// Runs the chain `warmup` times untimed, then `repeat` times with timestamps, in two
  /// command buffers (the repetitions back to back, a full compute barrier between passes).
  Timings Run(int warmup, int repeat);
  /// Image `i`'s texels as tightly packed rows (after Run).
  std::vector<uint8_t> ReadImage(int i);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aalab::vk
