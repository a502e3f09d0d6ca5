// The Vulkan side of aalab_vk (gpu/vk/vk_runner.h). Device-local images (optimal tiling) and
// buffers, uploads and read-backs through one host-visible staging buffer, a descriptor set
// and a compute pipeline per pass, a timestamp query pool for the timed repetitions.
#include "gpu/vk/vk_runner.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "gpu/vk/vk_device_impl.h"

namespace aalab::vk {

namespace {

uint32_t TexelBytes(int format) {
  switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R32_UINT: return 4;
    default: throw std::runtime_error("aalab_vk: unsupported image format " + std::to_string(format));
  }
}

std::string VersionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

}  // namespace

Device::Device(const std::string& name_filter) : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "aalab_vk";
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  if (vkCreateInstance(&ci, nullptr, &d.instance) != VK_SUCCESS) {
    throw std::runtime_error(
        "vkCreateInstance failed: no Vulkan driver found (set VK_DRIVER_FILES to the driver's ICD json; "
        "docs/gpu.md \"Original shaders through Vulkan\")");
  }
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(d.instance, &n, nullptr);
  std::vector<VkPhysicalDevice> devs(n);
  vkEnumeratePhysicalDevices(d.instance, &n, devs.data());
  std::string seen;
  for (int pass = 0; pass < 2 && d.phys == VK_NULL_HANDLE; ++pass) {
    for (VkPhysicalDevice p : devs) {
      VkPhysicalDeviceProperties props;
      vkGetPhysicalDeviceProperties(p, &props);
      if (pass == 0) seen += std::string(seen.empty() ? "" : ", ") + props.deviceName;
      const bool named = name_filter.empty() || std::string(props.deviceName).find(name_filter) != std::string::npos;
      const bool discrete = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
      if (named && (discrete || pass == 1 || !name_filter.empty())) {
        d.phys = p;
        break;
      }
    }
  }
  if (d.phys == VK_NULL_HANDLE) {
    throw std::runtime_error("no Vulkan device" + (name_filter.empty() ? "" : " named '*" + name_filter + "*'") +
                             " (devices: " + (seen.empty() ? "none" : seen) + ")");
  }
  VkPhysicalDeviceDriverProperties drv{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  p2.pNext = &drv;
  vkGetPhysicalDeviceProperties2(d.phys, &p2);
  d.facts.name = p2.properties.deviceName;
  d.facts.driver = std::string(drv.driverName) + " " + drv.driverInfo;
  d.facts.api = VersionString(p2.properties.apiVersion);
  d.facts.timestamp_period_ns = p2.properties.limits.timestampPeriod;
  vkGetPhysicalDeviceMemoryProperties(d.phys, &d.memory);

  uint32_t nq = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(d.phys, &nq, nullptr);
  std::vector<VkQueueFamilyProperties> qs(nq);
  vkGetPhysicalDeviceQueueFamilyProperties(d.phys, &nq, qs.data());
  bool found = false;
  for (uint32_t i = 0; i < nq && !found; ++i) {
    if ((qs[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && qs[i].timestampValidBits > 0) {
      d.family = i;
      d.facts.timestamp_valid_bits = qs[i].timestampValidBits;
      found = true;
    }
  }
  if (!found) throw std::runtime_error("Vulkan device '" + d.facts.name + "' has no compute queue with timestamps");
  const float prio = 1.0f;
  VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qi.queueFamilyIndex = d.family;
  qi.queueCount = 1;
  qi.pQueuePriorities = &prio;
  // Features the modules use: texel loads with offsets (ImageGatherExtended: CMAA2's edges
  // and candidates passes), and where the device offers it robust image access (reads outside an image return
  // 0, as D3D12 defines them for CMAA2's sample and as the oracles run lavapipe).
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  const bool v13 = p2.properties.apiVersion >= VK_API_VERSION_1_3;
  if (v13) f2.pNext = &f13;
  vkGetPhysicalDeviceFeatures2(d.phys, &f2);
  VkPhysicalDeviceVulkan13Features want13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  want13.robustImageAccess = v13 ? f13.robustImageAccess : VK_FALSE;
  d.facts.robust_image_access = want13.robustImageAccess == VK_TRUE;
  VkPhysicalDeviceFeatures want{};
  want.shaderImageGatherExtended = f2.features.shaderImageGatherExtended;
  // FSR 2's passes declare r16f, rg16f, r8, rg8, rgba16 storage images (extended formats), and
  // its RCAS stores to the app's output declared without a format and loads formatted
  // (GL_EXT_shader_image_load_formatted): enabled where offered.
  want.shaderStorageImageExtendedFormats = f2.features.shaderStorageImageExtendedFormats;
  want.shaderStorageImageWriteWithoutFormat = f2.features.shaderStorageImageWriteWithoutFormat;
  want.shaderStorageImageReadWithoutFormat = f2.features.shaderStorageImageReadWithoutFormat;
  if (!want.shaderImageGatherExtended) {
    throw std::runtime_error("Vulkan device '" + d.facts.name +
                             "' lacks shaderImageGatherExtended (CMAA2's texel loads with offsets need it)");
  }
  VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  di.pNext = want13.robustImageAccess ? &want13 : nullptr;
  di.pEnabledFeatures = &want;
  di.queueCreateInfoCount = 1;
  di.pQueueCreateInfos = &qi;
  Check(vkCreateDevice(d.phys, &di, nullptr, &d.device), "vkCreateDevice");
  vkGetDeviceQueue(d.device, d.family, 0, &d.queue);
  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pi.queueFamilyIndex = d.family;
  pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  Check(vkCreateCommandPool(d.device, &pi, nullptr, &d.pool), "vkCreateCommandPool");
}

Device::~Device() {
  if (impl_->device) {
    vkDeviceWaitIdle(impl_->device);
    vkDestroyCommandPool(impl_->device, impl_->pool, nullptr);
    vkDestroyDevice(impl_->device, nullptr);
  }
  if (impl_->instance) vkDestroyInstance(impl_->instance, nullptr);
}

const DeviceFacts& Device::Facts() const { return impl_->facts; }

struct Chain::Impl {
  const Device::Impl* d = nullptr;
  struct Image {
    ImageSpec spec;
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
  };
  struct Buffer {
    BufferSpec spec;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
  };
  std::vector<Image> images;
  std::vector<Buffer> buffers;
  std::vector<PassSpec> passes;
  VkSampler sampler = VK_NULL_HANDLE;
  VkDescriptorPool dpool = VK_NULL_HANDLE;
  struct Pipe {
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkPipelineLayout playout = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
  };
  std::vector<Pipe> pipes;
  VkQueryPool queries = VK_NULL_HANDLE;

  std::pair<VkBuffer, VkDeviceMemory> Staging(uint64_t bytes) const { return d->Staging(bytes); }
  void Release(std::pair<VkBuffer, VkDeviceMemory> s) const { d->Release(s); }
  static void FullBarrier(VkCommandBuffer cb) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT |
                       VK_ACCESS_TRANSFER_READ_BIT;
    vkCmdPipelineBarrier(
        cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
        1, &mb, 0, nullptr, 0, nullptr);
  }
  void RecordChain(VkCommandBuffer cb, uint32_t query_base, bool timed) const {
    if (timed) vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries, query_base);
    for (size_t k = 0; k < passes.size(); ++k) {
      const PassSpec& p = passes[k];
      const Pipe& q = pipes[k];
      vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, q.pipeline);
      vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, q.playout, 0, 1, &q.set, 0, nullptr);
      if (!p.push.empty()) {
        vkCmdPushConstants(cb, q.playout, VK_SHADER_STAGE_COMPUTE_BIT, 0, static_cast<uint32_t>(p.push.size() * 4),
                           p.push.data());
      }
      if (p.indirect_buffer >= 0) {
        vkCmdDispatchIndirect(cb, buffers[static_cast<size_t>(p.indirect_buffer)].buffer, 0);
      } else {
        vkCmdDispatch(cb, p.gx, p.gy, p.gz);
      }
      FullBarrier(cb);
      if (timed) {
        vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries,
                            query_base + static_cast<uint32_t>(k) + 1);
      }
    }
  }
};

Chain::Chain(Device& device, std::vector<ImageSpec> images, std::vector<BufferSpec> buffers,
             std::vector<PassSpec> passes)
    : impl_(std::make_unique<Impl>()) {
  Impl& c = *impl_;
  c.d = device.impl();
  const VkDevice dev = c.d->device;
  c.passes = std::move(passes);
  for (const ImageSpec& s : images) {
    Impl::Image im;
    im.spec = s;
    VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = static_cast<VkFormat>(s.format);
    ii.extent = {static_cast<uint32_t>(s.width), static_cast<uint32_t>(s.height), 1};
    ii.mipLevels = 1;
    ii.arrayLayers = 1;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (s.format != VK_FORMAT_R8G8B8A8_SRGB) ii.usage |= VK_IMAGE_USAGE_STORAGE_BIT;
    ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    Check(vkCreateImage(dev, &ii, nullptr, &im.image), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(dev, im.image, &req);
    im.memory = c.d->Allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    Check(vkBindImageMemory(dev, im.image, im.memory, 0), "vkBindImageMemory");
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = im.image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = ii.format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    Check(vkCreateImageView(dev, &vi, nullptr, &im.view), "vkCreateImageView");
    c.images.push_back(im);
  }
  // Every image lives in GENERAL layout (sampled and storage access alike), zeroed.
  c.d->Once([&](VkCommandBuffer cb) {
    for (const auto& im : c.images) {
      VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      b.srcAccessMask = 0;
      b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
      b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      b.image = im.image;
      b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                           nullptr, 1, &b);
      const VkClearColorValue zero{};
      const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(cb, im.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    }
    Impl::FullBarrier(cb);
  });
  for (const BufferSpec& s : buffers) {
    Impl::Buffer b;
    b.spec = s;
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = std::max<uint64_t>(s.bytes, 16);
    bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    if (s.indirect) bi.usage |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    Check(vkCreateBuffer(dev, &bi, nullptr, &b.buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev, b.buffer, &req);
    b.memory = c.d->Allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    Check(vkBindBufferMemory(dev, b.buffer, b.memory, 0), "vkBindBufferMemory");
    c.buffers.push_back(b);
    FillBuffer(static_cast<int>(c.buffers.size()) - 1, 0u);
  }
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_LINEAR;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.maxLod = 0.0f;
  Check(vkCreateSampler(dev, &si, nullptr, &c.sampler), "vkCreateSampler");

  const uint32_t np = static_cast<uint32_t>(c.passes.size());
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 16 * np},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16 * np},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 16 * np},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 16 * np}};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.maxSets = np;
  dpi.poolSizeCount = 4;
  dpi.pPoolSizes = sizes;
  Check(vkCreateDescriptorPool(dev, &dpi, nullptr, &c.dpool), "vkCreateDescriptorPool");
  auto type_of = [](PassBinding::Kind k) {
    switch (k) {
      case PassBinding::kSampledImage: return VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
      case PassBinding::kCombinedSampler: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      case PassBinding::kStorageImage: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
      default: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    }
  };
  for (const PassSpec& p : c.passes) {
    Impl::Pipe q;
    std::vector<std::pair<uint32_t, VkDescriptorType>> lb;
    for (const PassBinding& b : p.bindings) lb.emplace_back(b.binding, type_of(b.kind));
    q.layout = c.d->ComputeSetLayout(lb);
    VkPushConstantRange pr{VK_SHADER_STAGE_COMPUTE_BIT, 0, static_cast<uint32_t>(p.push.size() * 4)};
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &q.layout;
    pli.pushConstantRangeCount = p.push.empty() ? 0 : 1;
    pli.pPushConstantRanges = &pr;
    Check(vkCreatePipelineLayout(dev, &pli, nullptr, &q.playout), "vkCreatePipelineLayout");
    c.d->ComputePipeline(p.spirv, q.playout, p.name, &q.module, &q.pipeline);
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = c.dpool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &q.layout;
    Check(vkAllocateDescriptorSets(dev, &ai, &q.set), "vkAllocateDescriptorSets");
    std::vector<VkDescriptorImageInfo> ii(p.bindings.size());
    std::vector<VkDescriptorBufferInfo> bi(p.bindings.size());
    std::vector<VkWriteDescriptorSet> w;
    for (size_t k = 0; k < p.bindings.size(); ++k) {
      const PassBinding& b = p.bindings[k];
      VkWriteDescriptorSet x{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      x.dstSet = q.set;
      x.dstBinding = b.binding;
      x.descriptorCount = 1;
      x.descriptorType = type_of(b.kind);
      if (b.kind == PassBinding::kStorageBuffer) {
        bi[k] = {c.buffers.at(static_cast<size_t>(b.resource)).buffer, 0, VK_WHOLE_SIZE};
        x.pBufferInfo = &bi[k];
      } else {
        ii[k] = {b.kind == PassBinding::kCombinedSampler ? c.sampler : VK_NULL_HANDLE,
                 c.images.at(static_cast<size_t>(b.resource)).view, VK_IMAGE_LAYOUT_GENERAL};
        x.pImageInfo = &ii[k];
      }
      w.push_back(x);
    }
    vkUpdateDescriptorSets(dev, static_cast<uint32_t>(w.size()), w.data(), 0, nullptr);
    c.pipes.push_back(q);
  }
}

Chain::~Chain() {
  Impl& c = *impl_;
  const VkDevice dev = c.d->device;
  vkDeviceWaitIdle(dev);
  if (c.queries) vkDestroyQueryPool(dev, c.queries, nullptr);
  for (auto& q : c.pipes) {
    vkDestroyPipeline(dev, q.pipeline, nullptr);
    vkDestroyShaderModule(dev, q.module, nullptr);
    vkDestroyPipelineLayout(dev, q.playout, nullptr);
    vkDestroyDescriptorSetLayout(dev, q.layout, nullptr);
  }
  if (c.dpool) vkDestroyDescriptorPool(dev, c.dpool, nullptr);
  if (c.sampler) vkDestroySampler(dev, c.sampler, nullptr);
  for (auto& im : c.images) {
    vkDestroyImageView(dev, im.view, nullptr);
    vkDestroyImage(dev, im.image, nullptr);
    vkFreeMemory(dev, im.memory, nullptr);
  }
  for (auto& b : c.buffers) {
    vkDestroyBuffer(dev, b.buffer, nullptr);
    vkFreeMemory(dev, b.memory, nullptr);
  }
}

void Chain::FillImage(int i, const void* data, uint64_t bytes) {
  Impl& c = *impl_;
  const Impl::Image& im = c.images.at(static_cast<size_t>(i));
  const uint64_t need =
      static_cast<uint64_t>(im.spec.width) * static_cast<uint64_t>(im.spec.height) * TexelBytes(im.spec.format);
  if (bytes != need)
    throw std::runtime_error("aalab_vk: FillImage got " + std::to_string(bytes) + " bytes, needs " +
                             std::to_string(need));
  auto st = c.d->StagingFrom(data, bytes);
  c.d->Once([&](VkCommandBuffer cb) {
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    r.imageExtent = {static_cast<uint32_t>(im.spec.width), static_cast<uint32_t>(im.spec.height), 1};
    vkCmdCopyBufferToImage(cb, st.first, im.image, VK_IMAGE_LAYOUT_GENERAL, 1, &r);
    Impl::FullBarrier(cb);
  });
  c.Release(st);
}

void Chain::FillBuffer(int i, uint32_t word) {
  Impl& c = *impl_;
  const Impl::Buffer& b = c.buffers.at(static_cast<size_t>(i));
  c.d->Once([&](VkCommandBuffer cb) {
    vkCmdFillBuffer(cb, b.buffer, 0, VK_WHOLE_SIZE, word);
    Impl::FullBarrier(cb);
  });
}

Timings Chain::Run(int warmup, int repeat) {
  Impl& c = *impl_;
  const VkDevice dev = c.d->device;
  const uint32_t per = static_cast<uint32_t>(c.passes.size()) + 1;
  if (c.queries) vkDestroyQueryPool(dev, c.queries, nullptr);
  VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = per * static_cast<uint32_t>(std::max(repeat, 1));
  Check(vkCreateQueryPool(dev, &qi, nullptr, &c.queries), "vkCreateQueryPool");
  if (warmup > 0) {
    c.d->Once([&](VkCommandBuffer cb) {
      for (int r = 0; r < warmup; ++r) c.RecordChain(cb, 0, false);
    });
  }
  c.d->Once([&](VkCommandBuffer cb) {
    vkCmdResetQueryPool(cb, c.queries, 0, qi.queryCount);
    for (int r = 0; r < repeat; ++r) c.RecordChain(cb, per * static_cast<uint32_t>(r), true);
  });
  std::vector<uint64_t> ts(qi.queryCount);
  Check(vkGetQueryPoolResults(dev, c.queries, 0, qi.queryCount, ts.size() * 8, ts.data(), 8,
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  const uint32_t bits = c.d->facts.timestamp_valid_bits;
  const uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  const double ms_per_tick = c.d->facts.timestamp_period_ns * 1e-6;
  auto delta = [&](uint64_t a, uint64_t b) { return static_cast<double>((b - a) & mask) * ms_per_tick; };
  Timings t;
  for (int r = 0; r < repeat; ++r) {
    const uint64_t* q = ts.data() + per * static_cast<uint32_t>(r);
    std::vector<double> ms;
    for (uint32_t k = 0; k + 1 < per; ++k) ms.push_back(delta(q[k], q[k + 1]));
    t.ms.push_back(ms);
    t.whole.push_back(delta(q[0], q[per - 1]));
  }
  return t;
}

std::vector<uint8_t> Chain::ReadImage(int i) {
  Impl& c = *impl_;
  const Impl::Image& im = c.images.at(static_cast<size_t>(i));
  const uint64_t bytes =
      static_cast<uint64_t>(im.spec.width) * static_cast<uint64_t>(im.spec.height) * TexelBytes(im.spec.format);
  return c.d->ReadImage(im.image, static_cast<uint32_t>(im.spec.width), static_cast<uint32_t>(im.spec.height), bytes);
}

}  // namespace aalab::vk
