#include "tests/oracle/vk_compute.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>

namespace aalab::oracle {

namespace {

void Check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(r) + ")");
}

struct Context {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice phys = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory{};
  std::string name, error;
  // Kept for the process (lavapipe compiles a pipeline when it is created: seconds for a
  // large shader): set layouts by binding signature, pipelines by signature and module.
  std::map<std::string, std::pair<std::vector<VkDescriptorSetLayout>, VkPipelineLayout>> layouts;
  std::map<std::string, std::pair<VkShaderModule, VkPipeline>> pipelines;
};

std::string LavapipeIcd() {
  for (const char* dir : {"/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d", "/usr/local/share/vulkan/icd.d"}) {
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
      if (e.path().filename().string().rfind("lvp_icd", 0) == 0) return e.path().string();
    }
  }
  return "";
}

Context Init() {
  Context c;
  const std::string icd = LavapipeIcd();
  if (icd.empty()) {
    c.error = "no lavapipe ICD (lvp_icd*.json) found: install mesa-vulkan-drivers (scripts/debian-packages.txt)";
    return c;
  }
  setenv("VK_DRIVER_FILES", icd.c_str(), 1);
  setenv("VK_ICD_FILENAMES", icd.c_str(), 1);
  setenv("GALLIUM_OVERRIDE_CPU_CAPS", "avx", 1);
  setenv("LP_NUM_THREADS", "1", 1);
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "aalab-oracle";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  if (vkCreateInstance(&ici, nullptr, &c.instance) != VK_SUCCESS) {
    c.error = "vkCreateInstance failed (Vulkan loader libvulkan1 / lavapipe mesa-vulkan-drivers missing?)";
    return c;
  }
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(c.instance, &n, nullptr);
  std::vector<VkPhysicalDevice> devs(n);
  vkEnumeratePhysicalDevices(c.instance, &n, devs.data());
  for (VkPhysicalDevice d : devs) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    if (std::string(p.deviceName).find("llvmpipe") != std::string::npos) {
      c.phys = d;
      c.name = p.deviceName;
    }
  }
  if (!c.phys) {
    c.error = "no lavapipe (llvmpipe) Vulkan device: install mesa-vulkan-drivers";
    return c;
  }
  uint32_t nq = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(c.phys, &nq, nullptr);
  std::vector<VkQueueFamilyProperties> qf(nq);
  vkGetPhysicalDeviceQueueFamilyProperties(c.phys, &nq, qf.data());
  for (uint32_t i = 0; i < nq; ++i) {
    if (qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
      c.family = i;
      break;
    }
  }
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f2.pNext = &f13;
  vkGetPhysicalDeviceFeatures2(c.phys, &f2);
  VkPhysicalDeviceVulkan13Features want13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  want13.robustImageAccess = f13.robustImageAccess;
  const float prio = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = c.family;
  qci.queueCount = 1;
  qci.pQueuePriorities = &prio;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = f13.robustImageAccess ? &want13 : nullptr;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  if (vkCreateDevice(c.phys, &dci, nullptr, &c.device) != VK_SUCCESS) {
    c.error = "vkCreateDevice on lavapipe failed";
    return c;
  }
  vkGetDeviceQueue(c.device, c.family, 0, &c.queue);
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = c.family;
  Check(vkCreateCommandPool(c.device, &pci, nullptr, &c.pool), "vkCreateCommandPool");
  vkGetPhysicalDeviceMemoryProperties(c.phys, &c.memory);
  return c;
}

Context& Ctx() {
  static Context c = Init();
  return c;
}

uint32_t MemoryType(uint32_t bits, VkMemoryPropertyFlags want) {
  const auto& m = Ctx().memory;
  for (uint32_t i = 0; i < m.memoryTypeCount; ++i) {
    if ((bits & (1u << i)) && (m.memoryTypes[i].propertyFlags & want) == want) return i;
  }
  throw std::runtime_error("no suitable Vulkan memory type");
}

uint32_t TexelBytes(int format) {
  switch (format) {
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_UNORM: return 8;
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_B10G11R11_UFLOAT_PACK32:
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB: return 4;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16_SNORM:
    case VK_FORMAT_R8G8_UNORM: return 2;
    case VK_FORMAT_R8_UNORM: return 1;
    default: throw std::runtime_error("vk_compute: unsupported image format " + std::to_string(format));
  }
}

struct HostBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* ptr = nullptr;
  uint64_t bytes = 0;
};

HostBuffer MakeHostBuffer(uint64_t bytes, VkBufferUsageFlags usage) {
  VkDevice dev = Ctx().device;
  HostBuffer b;
  b.bytes = bytes;
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = bytes;
  bci.usage = usage;
  Check(vkCreateBuffer(dev, &bci, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(dev, b.buffer, &req);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex =
      MemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  Check(vkAllocateMemory(dev, &mai, nullptr, &b.memory), "vkAllocateMemory");
  Check(vkBindBufferMemory(dev, b.buffer, b.memory, 0), "vkBindBufferMemory");
  Check(vkMapMemory(dev, b.memory, 0, bytes, 0, &b.ptr), "vkMapMemory");
  std::memset(b.ptr, 0, bytes);
  return b;
}

void FreeHostBuffer(HostBuffer& b) {
  if (!b.buffer) return;
  vkUnmapMemory(Ctx().device, b.memory);
  vkDestroyBuffer(Ctx().device, b.buffer, nullptr);
  vkFreeMemory(Ctx().device, b.memory, nullptr);
  b = HostBuffer{};
}

// The name of the module's first OpEntryPoint.
std::string EntryName(const std::vector<uint32_t>& words) {
  for (size_t i = 5; i < words.size();) {
    const uint32_t op = words[i] & 0xffffu, len = words[i] >> 16;
    if (len == 0) break;
    if (op == 15 && i + 3 < words.size()) return reinterpret_cast<const char*>(&words[i + 3]);
    i += len;
  }
  throw std::runtime_error("SPIR-V module without an entry point");
}

}  // namespace

namespace {

/// A folder made by mkdtemp from `pattern`, removed with everything in it at scope exit.
struct TempDir {
  std::string path;
  explicit TempDir(std::string pattern) {
    if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path = pattern;
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

/// Runs `glslangValidator ARGS -o DIR/shader.spv INPUT` and returns the SPIR-V words; throws
/// with glslang's log (naming `what`) when it fails or writes no whole words.
std::vector<uint32_t> RunGlslang(const std::string& args, const std::string& input, const std::string& dir,
                                 const std::string& what) {
  const std::string spv = dir + "/shader.spv", log = dir + "/log.txt";
  const std::string cmd = "glslangValidator " + args + " -o '" + spv + "' '" + input + "' > '" + log + "' 2>&1";
  const int rc = std::system(cmd.c_str());
  std::ifstream in(spv, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (rc != 0 || bytes.empty() || bytes.size() % 4 != 0) {
    std::stringstream out;
    out << std::ifstream(log).rdbuf();
    throw std::runtime_error("glslangValidator (" + what + ") failed (rc " + std::to_string(rc) + "): " + out.str());
  }
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), bytes.size());
  return words;
}

}  // namespace

std::vector<uint32_t> CompileHlsl(const std::string& text, const std::string& entry,
                                  const std::vector<std::string>& defines) {
  TempDir tmp("/tmp/aalab-hlsl-XXXXXX");
  const std::string src = tmp.path + "/shader.hlsl";
  std::ofstream(src) << text;
  std::string args = "-D -V -S comp --hlsl-iomap --shift-UAV-binding comp 10 -e " + entry;
  for (const auto& d : defines) args += " -D" + d;
  return RunGlslang(args, src, tmp.path, entry);
}

std::vector<uint32_t> CompileGlslFile(const std::string& path, const std::vector<std::string>& include_dirs,
                                      const std::vector<std::string>& defines) {
  TempDir tmp("/tmp/aalab-glsl-XXXXXX");
  std::string args = "-V -S comp";
  for (const auto& i : include_dirs) args += " '-I" + i + "'";
  for (const auto& d : defines) args += " -D" + d;
  return RunGlslang(args, path, tmp.path, path);
}

std::vector<uint32_t> CompileGlslText(const std::string& text, const std::vector<std::string>& defines) {
  TempDir tmp("/tmp/aalab-glsl-XXXXXX");
  const std::string src = tmp.path + "/shader.comp";
  std::ofstream(src) << text;
  std::string args = "-V -S comp";
  for (const auto& d : defines) args += " -D" + d;
  return RunGlslang(args, src, tmp.path, "GLSL text");
}

std::vector<uint32_t> CompileGlslFileWith(const std::string& path, const std::vector<std::string>& defines,
                                          const std::string& options) {
  TempDir tmp("/tmp/aalab-glsl-XXXXXX");
  std::string args = "-V -S comp " + options;
  for (const auto& d : defines) args += " -D" + d;
  return RunGlslang(args, path, tmp.path, path);
}

std::string VkCompute::Start() { return Ctx().error; }
std::string VkCompute::DeviceName() { return Ctx().name; }
int VkCompute::Lanes() {
  const std::string& n = Ctx().name;
  const size_t p = n.find(" bits");
  if (p == std::string::npos) return 4;
  size_t b = p;
  while (b > 0 && std::isdigit(static_cast<unsigned char>(n[b - 1]))) --b;
  return b < p ? std::stoi(n.substr(b, p - b)) / 32 : 4;
}

struct VkCompute::Impl {
  struct Res {
    VkBinding b;
    HostBuffer host;  // the buffer itself (buffers) or the staging buffer (images)
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkDeviceMemory image_memory = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    bool filled = false;
  };
  std::map<uint32_t, Res> res;
  std::vector<VkDescriptorSetLayout> set_layouts;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets;
  std::vector<VkPipeline> pipelines;
  std::string signature;
};

VkCompute::VkCompute(std::vector<VkBinding> bindings) : impl_(std::make_unique<Impl>()) {
  if (!Ctx().error.empty()) throw std::runtime_error(Ctx().error);
  VkDevice dev = Ctx().device;
  uint32_t set_count = 1;
  for (const VkBinding& b : bindings) set_count = std::max(set_count, b.set + 1);
  std::vector<std::vector<VkDescriptorSetLayoutBinding>> lb(set_count);
  std::vector<VkDescriptorPoolSize> sizes;
  auto type_of = [](VkBinding::Kind k) {
    switch (k) {
      case VkBinding::kSampledImage: return VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
      case VkBinding::kStorageImage: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
      case VkBinding::kUniformBuffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
      case VkBinding::kSampler: return VK_DESCRIPTOR_TYPE_SAMPLER;
      default: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    }
  };
  for (const VkBinding& b : bindings) {
    Impl::Res r;
    r.b = b;
    if (b.kind == VkBinding::kStorageBuffer || b.kind == VkBinding::kUniformBuffer) {
      r.host = MakeHostBuffer(b.bytes, (b.kind == VkBinding::kUniformBuffer ? VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT
                                                                            : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) |
                                           (b.indirect ? VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT : 0));
    } else if (b.kind == VkBinding::kSampler) {
      VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
      sci.magFilter = sci.minFilter = b.linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
      sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
      sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
      sci.maxLod = 0.0f;
      Check(vkCreateSampler(dev, &sci, nullptr, &r.sampler), "vkCreateSampler");
    } else {
      VkImageCreateInfo ic{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
      ic.imageType = VK_IMAGE_TYPE_2D;
      ic.format = static_cast<VkFormat>(b.format);
      ic.extent = {static_cast<uint32_t>(b.width), static_cast<uint32_t>(b.height), 1};
      ic.mipLevels = 1;
      ic.arrayLayers = 1;
      ic.samples = VK_SAMPLE_COUNT_1_BIT;
      ic.tiling = VK_IMAGE_TILING_OPTIMAL;
      ic.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                 (b.kind == VkBinding::kSampledImage ? VK_IMAGE_USAGE_SAMPLED_BIT : VK_IMAGE_USAGE_STORAGE_BIT);
      Check(vkCreateImage(dev, &ic, nullptr, &r.image), "vkCreateImage");
      VkMemoryRequirements req;
      vkGetImageMemoryRequirements(dev, r.image, &req);
      VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
      mai.allocationSize = req.size;
      mai.memoryTypeIndex = MemoryType(req.memoryTypeBits, 0);
      Check(vkAllocateMemory(dev, &mai, nullptr, &r.image_memory), "vkAllocateMemory");
      Check(vkBindImageMemory(dev, r.image, r.image_memory, 0), "vkBindImageMemory");
      VkImageViewCreateInfo vc{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
      vc.image = r.image;
      vc.viewType = VK_IMAGE_VIEW_TYPE_2D;
      vc.format = ic.format;
      vc.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      Check(vkCreateImageView(dev, &vc, nullptr, &r.view), "vkCreateImageView");
      r.host = MakeHostBuffer(static_cast<uint64_t>(b.width) * static_cast<uint64_t>(b.height) * TexelBytes(b.format),
                              VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    }
    lb[b.set].push_back({b.binding, type_of(b.kind), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    sizes.push_back({type_of(b.kind), 1});
    impl_->res[VkKey(b.set, b.binding)] = r;
  }
  for (uint32_t s = 0; s < set_count; ++s) {
    impl_->signature += "|";
    for (const auto& l : lb[s])
      impl_->signature += std::to_string(l.binding) + ":" + std::to_string(l.descriptorType) + ";";
  }
  auto& cached = Ctx().layouts[impl_->signature];
  if (!cached.second) {
    for (uint32_t s = 0; s < set_count; ++s) {
      VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
      lci.bindingCount = static_cast<uint32_t>(lb[s].size());
      lci.pBindings = lb[s].data();
      VkDescriptorSetLayout l;
      Check(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &l), "vkCreateDescriptorSetLayout");
      cached.first.push_back(l);
    }
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    plci.setLayoutCount = set_count;
    plci.pSetLayouts = cached.first.data();
    Check(vkCreatePipelineLayout(dev, &plci, nullptr, &cached.second), "vkCreatePipelineLayout");
  }
  impl_->set_layouts = cached.first;
  impl_->layout = cached.second;
  VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpci.maxSets = set_count;
  dpci.poolSizeCount = static_cast<uint32_t>(sizes.size());
  dpci.pPoolSizes = sizes.data();
  Check(vkCreateDescriptorPool(dev, &dpci, nullptr, &impl_->pool), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo dsai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  dsai.descriptorPool = impl_->pool;
  dsai.descriptorSetCount = set_count;
  dsai.pSetLayouts = impl_->set_layouts.data();
  impl_->sets.resize(set_count);
  Check(vkAllocateDescriptorSets(dev, &dsai, impl_->sets.data()), "vkAllocateDescriptorSets");
  std::vector<VkDescriptorImageInfo> ii(bindings.size());
  std::vector<VkDescriptorBufferInfo> bi(bindings.size());
  std::vector<VkWriteDescriptorSet> writes;
  for (size_t i = 0; i < bindings.size(); ++i) {
    const Impl::Res& r = impl_->res[VkKey(bindings[i].set, bindings[i].binding)];
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = impl_->sets[bindings[i].set];
    w.dstBinding = bindings[i].binding;
    w.descriptorCount = 1;
    w.descriptorType = type_of(bindings[i].kind);
    if (bindings[i].kind == VkBinding::kStorageBuffer || bindings[i].kind == VkBinding::kUniformBuffer) {
      bi[i] = {r.host.buffer, 0, VK_WHOLE_SIZE};
      w.pBufferInfo = &bi[i];
    } else if (bindings[i].kind == VkBinding::kSampler) {
      ii[i] = {r.sampler, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED};
      w.pImageInfo = &ii[i];
    } else {
      ii[i] = {VK_NULL_HANDLE, r.view, VK_IMAGE_LAYOUT_GENERAL};
      w.pImageInfo = &ii[i];
    }
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(dev, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

VkCompute::~VkCompute() {
  VkDevice dev = Ctx().device;
  vkDeviceWaitIdle(dev);
  vkDestroyDescriptorPool(dev, impl_->pool, nullptr);
  for (auto& [k, r] : impl_->res) {
    FreeHostBuffer(r.host);
    if (r.view) vkDestroyImageView(dev, r.view, nullptr);
    if (r.image) vkDestroyImage(dev, r.image, nullptr);
    if (r.image_memory) vkFreeMemory(dev, r.image_memory, nullptr);
    if (r.sampler) vkDestroySampler(dev, r.sampler, nullptr);
  }
}

int VkCompute::AddPipeline(const std::vector<uint32_t>& spirv, const std::string& entry) {
  (void)entry;
  VkDevice dev = Ctx().device;
  const std::string key = impl_->signature + "#" +
                          std::to_string(std::hash<std::string>{}(
                              std::string(reinterpret_cast<const char*>(spirv.data()), spirv.size() * 4)));
  auto& cached = Ctx().pipelines[key];
  if (!cached.second) {
    VkShaderModuleCreateInfo smci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    smci.codeSize = spirv.size() * 4;
    smci.pCode = spirv.data();
    Check(vkCreateShaderModule(dev, &smci, nullptr, &cached.first), "vkCreateShaderModule");
    const std::string name = EntryName(spirv);
    VkComputePipelineCreateInfo cpci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    cpci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    cpci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cpci.stage.module = cached.first;
    cpci.stage.pName = name.c_str();
    cpci.layout = impl_->layout;
    Check(vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &cpci, nullptr, &cached.second), "vkCreateComputePipelines");
  }
  impl_->pipelines.push_back(cached.second);
  return static_cast<int>(impl_->pipelines.size()) - 1;
}

void VkCompute::Fill(uint32_t binding, const void* data, uint64_t bytes) {
  Impl::Res& r = impl_->res.at(binding);
  if (bytes > r.host.bytes) throw std::runtime_error("vk_compute: Fill larger than binding " + std::to_string(binding));
  std::memcpy(r.host.ptr, data, bytes);
  r.filled = true;
}

void VkCompute::Run(const std::vector<VkStep>& steps) {
  VkDevice dev = Ctx().device;
  VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cai.commandPool = Ctx().pool;
  cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cai.commandBufferCount = 1;
  VkCommandBuffer cb;
  Check(vkAllocateCommandBuffers(dev, &cai, &cb), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cb, &begin);
  auto transition = [&](VkImage img, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                        VkAccessFlags dst_access, VkPipelineStageFlags src, VkPipelineStageFlags dst) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = img;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cb, src, dst, 0, 0, nullptr, 0, nullptr, 1, &b);
  };
  for (auto& [k, r] : impl_->res) {
    if (!r.image) continue;
    transition(r.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
               VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    const VkBufferImageCopy region{0,         0,
                                   0,         {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                   {0, 0, 0}, {static_cast<uint32_t>(r.b.width), static_cast<uint32_t>(r.b.height), 1}};
    vkCmdCopyBufferToImage(cb, r.host.buffer, r.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transition(r.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL, VK_ACCESS_TRANSFER_WRITE_BIT,
               VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  }
  VkMemoryBarrier host_to_shader{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  host_to_shader.srcAccessMask = VK_ACCESS_HOST_WRITE_BIT;
  host_to_shader.dstAccessMask =
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_HOST_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, 0, 1,
                       &host_to_shader, 0, nullptr, 0, nullptr);
  vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, impl_->layout, 0,
                          static_cast<uint32_t>(impl_->sets.size()), impl_->sets.data(), 0, nullptr);
  const VkPipelineStageFlags stages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT;
  for (const VkStep& s : steps) {
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, impl_->pipelines.at(static_cast<size_t>(s.pipeline)));
    if (s.indirect_binding >= 0) {
      vkCmdDispatchIndirect(cb, impl_->res.at(static_cast<uint32_t>(s.indirect_binding)).host.buffer, 0);
    } else {
      vkCmdDispatch(cb, s.gx, s.gy, s.gz);
    }
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
    mb.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
    vkCmdPipelineBarrier(cb, stages, stages, 0, 1, &mb, 0, nullptr, 0, nullptr);
  }
  for (auto& [k, r] : impl_->res) {
    if (!r.image) continue;
    transition(r.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_SHADER_WRITE_BIT,
               VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    const VkBufferImageCopy region{0,         0,
                                   0,         {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                   {0, 0, 0}, {static_cast<uint32_t>(r.b.width), static_cast<uint32_t>(r.b.height), 1}};
    vkCmdCopyImageToBuffer(cb, r.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r.host.buffer, 1, &region);
  }
  VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr, 0, nullptr);
  Check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  Check(vkCreateFence(dev, &fci, nullptr, &fence), "vkCreateFence");
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cb;
  Check(vkQueueSubmit(Ctx().queue, 1, &si, fence), "vkQueueSubmit");
  Check(vkWaitForFences(dev, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  vkDestroyFence(dev, fence, nullptr);
  vkFreeCommandBuffers(dev, Ctx().pool, 1, &cb);
}

std::vector<uint8_t> VkCompute::Read(uint32_t binding) {
  const Impl::Res& r = impl_->res.at(binding);
  const auto* p = static_cast<const uint8_t*>(r.host.ptr);
  return std::vector<uint8_t>(p, p + r.host.bytes);
}

}  // namespace aalab::oracle
