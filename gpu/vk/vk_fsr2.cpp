// FSR 2's whole frame through its original GLSL passes (gpu/vk/vk_fsr2.h; docs/gpu.md
// "Original shaders through Vulkan"). What ffx_fsr2.cpp's ffxFsr2ContextDispatch does with
// sharpening on (the default pipeline): compute_luminance_pyramid (SpdSetup's groups),
// reconstruct_previous_depth, depth_clip, lock (render size / 8), accumulate with
// APPLY_SHARPENING (display size / 8), rcas (display size / 16), one full compute barrier
// after each pass (the API's backends put a barrier between every pair of dependent passes).
//
// Resources, in the formats ffxFsr2ContextCreate gives them (max render size = render size):
// prepared colour rgba16f, previous nearest depth r32ui, dilated motion rg16f ×2, dilated depth
// r32f, lock status rg16f ×2 (display), lock luma r16f, new locks r8 (display), internal
// upscaled rgba16f ×2 (display), luma history rgba8 ×2 (display), SPD atomic r32ui 1×1,
// dilated reactive masks rg8, the Lanczos table r16 snorm 128×1, the default reactivity r8
// 1×1 (0: bound as reactive and composition mask, no app masks), the maximum-bias table r16
// snorm 16×16 (declared by accumulate, not read: left zero), the auto exposure rg32f 1×1
// (the input exposure: FFX_FSR2_ENABLE_AUTO_EXPOSURE). The pairs ping-pong by the frame's
// parity as the API swaps them. Two departures, both without effect on the work done:
// - FSR2_ExposureMips is one r16f chain of max render/2 with mips; here its two written
//   levels are two one-level r16f images of those levels' sizes (the shading-change level 4,
//   which accumulate samples with textureLod at level 4, clamped to the image's level 0, and
//   level 5). The pyramid writes no other level through a view.
// - The GLSL declares dilated depth r16f and prepared colour rgba16 (unorm) for its stores,
//   the API creates r32f and rgba16f: the images have the API's formats (as the oracle
//   binds the prepared colour; tests/oracle/fsr2_shader.cpp).
// The app's inputs are the FSR 2 sample's render targets: colour rgba16f, depth r32f (not
// inverted: 0 near), motion rg16f at render size; the output rgba16f at display size.
//
// The sequence and the constants: gpu/vk/vk_fsr2_host.cpp.
#include "gpu/vk/vk_fsr2.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>
#include <thread>

#include "gpu/vk/vk_device_impl.h"

namespace aalab::vk {

namespace {

constexpr int kSlots = 8;  // distinct input frames of the sequence (even: the parity follows)

std::vector<uint32_t> LoadModule(const std::string& dir, const std::string& name) {
  const std::string path = dir + "/" + name + ".spv";
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  if (!f)
    throw std::runtime_error("SPIR-V module '" + path + "' is missing (compile with scripts/vk_shaders.sh " + dir +
                             ")");
  const std::streamsize n = f.tellg();
  if (n <= 0 || n % 4 != 0) throw std::runtime_error("'" + path + "' is not a SPIR-V module");
  std::vector<uint32_t> w(static_cast<size_t>(n) / 4);
  f.seekg(0);
  f.read(reinterpret_cast<char*>(w.data()), n);
  if (w[0] != 0x07230203u) throw std::runtime_error("'" + path + "' is not a SPIR-V module (no magic number)");
  return w;
}

uint32_t TexelBytes(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R8_UNORM: return 1;
    case VK_FORMAT_R8G8_UNORM:
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16_SNORM: return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT: return 8;
    default: throw std::runtime_error("vk_fsr2: unexpected format " + std::to_string(f));
  }
}

// The resources of one run (indices into Run::images).
enum Res {
  kExposure,  // auto exposure rg32f 1x1
  kAtomic,
  kLumaShading,
  kMip5,
  kPrevDepth,
  kDilMv1,
  kDilMv2,
  kDilDepth,
  kLockLuma,
  kNewLocks,
  kLock1,
  kLock2,
  kUp1,
  kUp2,
  kLumaHist1,
  kLumaHist2,
  kReactive,
  kPrepared,
  kLanczos,
  kDefaultMask,
  kMaxBias,
  kOutput,
  kInputs  // then kSlots x (colour, depth, motion)
};

struct Binding {
  uint32_t binding;
  VkDescriptorType type;
  int image = -1;  // image resource, or -1 for a uniform buffer (cbFSR2 / the pass's own)
};

class Run {
 public:
  Run(Device::Impl* d, const std::string& dir, int rw, int rh, int dw, int dh)
      : d_(d), rw_(rw), rh_(rh), dw_(dw), dh_(dh) {
    modules_ = Fsr2Modules();
    for (const std::string& m : modules_) spirv_.push_back(LoadModule(dir, m));
  }
  ~Run() { Destroy(); }
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  MethodResult Go(const Frame& display, int warmup, int repeat);

 private:
  struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    int w = 0, h = 0;
    VkFormat format = VK_FORMAT_UNDEFINED;
  };
  struct Pass {
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkPipelineLayout playout = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorSet sets[kSlots] = {};
    uint32_t gx = 1, gy = 1;
    uint32_t own_cb_offset = 0;  // offset of the pass's own constant buffer (cbSPD / cbRCAS) in cb_
  };

  void AddImage(int w, int h, VkFormat f, bool storage);
  void CreateResources();
  void Upload(int image, const void* data, uint64_t bytes);
  void UploadBuffer(VkBuffer b, const void* data, uint64_t bytes);
  std::vector<Binding> Bindings(int pass, int slot) const;
  void CreatePasses();
  void Record(VkCommandBuffer cb, int frame, bool timed, uint32_t query_base) const;
  std::vector<uint8_t> Read(int image);
  void Destroy();

  Device::Impl* d_;
  int rw_, rh_, dw_, dh_;
  std::vector<std::string> modules_;
  std::vector<std::vector<uint32_t>> spirv_;
  std::vector<Image> images_;
  VkBuffer cb_ = VK_NULL_HANDLE;  // cbFSR2 slots (kSlots + 1: the reset frame last), cbSPD, cbRCAS
  VkDeviceMemory cb_memory_ = VK_NULL_HANDLE;
  uint32_t cb_stride_ = 256;
  VkSampler samplers_[2] = {};
  VkDescriptorSetLayout set0_layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set0_ = VK_NULL_HANDLE;
  std::vector<Pass> passes_;
  VkQueryPool queries_ = VK_NULL_HANDLE;
};

void Run::AddImage(int w, int h, VkFormat f, bool storage) {
  Image im;
  im.w = std::max(w, 1);
  im.h = std::max(h, 1);
  im.format = f;
  VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ii.imageType = VK_IMAGE_TYPE_2D;
  ii.format = f;
  ii.extent = {static_cast<uint32_t>(im.w), static_cast<uint32_t>(im.h), 1};
  ii.mipLevels = 1;
  ii.arrayLayers = 1;
  ii.samples = VK_SAMPLE_COUNT_1_BIT;
  ii.tiling = VK_IMAGE_TILING_OPTIMAL;
  ii.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
             (storage ? VK_IMAGE_USAGE_STORAGE_BIT : 0);
  Check(vkCreateImage(d_->device, &ii, nullptr, &im.image), "vkCreateImage (FSR 2)");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(d_->device, im.image, &req);
  im.memory = d_->Allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  Check(vkBindImageMemory(d_->device, im.image, im.memory, 0), "vkBindImageMemory");
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = im.image;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = f;
  vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  Check(vkCreateImageView(d_->device, &vi, nullptr, &im.view), "vkCreateImageView");
  images_.push_back(im);
}

void Run::CreateResources() {
  const int hw = rw_ / 2, hh = rh_ / 2;  // FSR2_ExposureMips: max render size / 2, level m is >> m
  AddImage(1, 1, VK_FORMAT_R32G32_SFLOAT, true);
  AddImage(1, 1, VK_FORMAT_R32_UINT, true);
  AddImage(hw >> 4, hh >> 4, VK_FORMAT_R16_SFLOAT, true);
  AddImage(hw >> 5, hh >> 5, VK_FORMAT_R16_SFLOAT, true);
  AddImage(rw_, rh_, VK_FORMAT_R32_UINT, true);
  AddImage(rw_, rh_, VK_FORMAT_R16G16_SFLOAT, true);
  AddImage(rw_, rh_, VK_FORMAT_R16G16_SFLOAT, true);
  AddImage(rw_, rh_, VK_FORMAT_R32_SFLOAT, true);
  AddImage(rw_, rh_, VK_FORMAT_R16_SFLOAT, true);
  AddImage(dw_, dh_, VK_FORMAT_R8_UNORM, true);
  AddImage(dw_, dh_, VK_FORMAT_R16G16_SFLOAT, true);
  AddImage(dw_, dh_, VK_FORMAT_R16G16_SFLOAT, true);
  AddImage(dw_, dh_, VK_FORMAT_R16G16B16A16_SFLOAT, true);
  AddImage(dw_, dh_, VK_FORMAT_R16G16B16A16_SFLOAT, true);
  AddImage(dw_, dh_, VK_FORMAT_R8G8B8A8_UNORM, true);
  AddImage(dw_, dh_, VK_FORMAT_R8G8B8A8_UNORM, true);
  AddImage(rw_, rh_, VK_FORMAT_R8G8_UNORM, true);
  AddImage(rw_, rh_, VK_FORMAT_R16G16B16A16_SFLOAT, true);
  AddImage(128, 1, VK_FORMAT_R16_SNORM, false);
  AddImage(1, 1, VK_FORMAT_R8_UNORM, false);
  AddImage(16, 16, VK_FORMAT_R16_SNORM, false);
  AddImage(dw_, dh_, VK_FORMAT_R16G16B16A16_SFLOAT, true);
  for (int k = 0; k < kSlots; ++k) {
    AddImage(rw_, rh_, VK_FORMAT_R16G16B16A16_SFLOAT, false);
    AddImage(rw_, rh_, VK_FORMAT_R32_SFLOAT, false);
    AddImage(rw_, rh_, VK_FORMAT_R16G16_SFLOAT, false);
  }
  // Every image in GENERAL layout, cleared to 0 (what ffxFsr2ContextDispatch's first frame
  // clears, and a fresh context's zeroed resources); the auto exposure to (-1, 1e8) as the
  // reset frame's clear.
  d_->Once([&](VkCommandBuffer cb) {
    for (size_t i = 0; i < images_.size(); ++i) {
      VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
      b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      b.image = images_[i].image;
      b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                           nullptr, 1, &b);
      VkClearColorValue v{};
      if (i == kExposure) {
        v.float32[0] = -1.0f;
        v.float32[1] = 1e8f;
      }
      const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(cb, images_[i].image, VK_IMAGE_LAYOUT_GENERAL, &v, 1, &range);
    }
  });
  const std::array<int16_t, 128> lut = Fsr2LanczosCodes();
  Upload(kLanczos, lut.data(), sizeof(lut));

  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(d_->phys, &props);
  cb_stride_ = static_cast<uint32_t>(std::max<VkDeviceSize>(256, props.limits.minUniformBufferOffsetAlignment));
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = static_cast<VkDeviceSize>(cb_stride_) * (kSlots + 3);
  bi.usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  Check(vkCreateBuffer(d_->device, &bi, nullptr, &cb_), "vkCreateBuffer (constants)");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(d_->device, cb_, &req);
  cb_memory_ = d_->Allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  Check(vkBindBufferMemory(d_->device, cb_, cb_memory_, 0), "vkBindBufferMemory");

  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.maxLod = 1000.0f;
  si.magFilter = si.minFilter = VK_FILTER_NEAREST;
  Check(vkCreateSampler(d_->device, &si, nullptr, &samplers_[0]), "vkCreateSampler");
  si.magFilter = si.minFilter = VK_FILTER_LINEAR;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  Check(vkCreateSampler(d_->device, &si, nullptr, &samplers_[1]), "vkCreateSampler");
}

void Run::UploadBuffer(VkBuffer b, const void* data, uint64_t bytes) {
  auto st = d_->StagingFrom(data, bytes);
  d_->Once([&](VkCommandBuffer cb) {
    const VkBufferCopy r{0, 0, bytes};
    vkCmdCopyBuffer(cb, st.first, b, 1, &r);
  });
  d_->Release(st);
}

void Run::Upload(int i, const void* data, uint64_t bytes) {
  const Image& im = images_.at(static_cast<size_t>(i));
  if (bytes != static_cast<uint64_t>(im.w) * static_cast<uint64_t>(im.h) * TexelBytes(im.format))
    throw std::runtime_error("vk_fsr2: upload size mismatch");
  auto st = d_->StagingFrom(data, bytes);
  d_->Once([&](VkCommandBuffer cb) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &mb, 0, nullptr, 0,
                         nullptr);
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    r.imageExtent = {static_cast<uint32_t>(im.w), static_cast<uint32_t>(im.h), 1};
    vkCmdCopyBufferToImage(cb, st.first, im.image, VK_IMAGE_LAYOUT_GENERAL, 1, &r);
  });
  d_->Release(st);
}

// The set-1 descriptors of pass `pass` on a frame showing input slot `slot` (its parity picks
// the ping-pong side as ffxFsr2ContextDispatch does), at the FSR2_BIND_* numbers of each
// *_pass.glsl; the tables the oracle binds (tests/oracle/fsr2_shader.cpp).
std::vector<Binding> Run::Bindings(int pass, int slot) const {
  const bool odd = slot % 2 == 1;
  const int color = kInputs + 3 * slot, depth = color + 1, motion = color + 2;
  const int lock_srv = odd ? kLock2 : kLock1, lock_uav = odd ? kLock1 : kLock2;
  const int up_srv = odd ? kUp2 : kUp1, up_uav = odd ? kUp1 : kUp2;
  const int mv = odd ? kDilMv2 : kDilMv1, prev_mv = odd ? kDilMv1 : kDilMv2;
  const int hist_srv = odd ? kLumaHist2 : kLumaHist1, hist_uav = odd ? kLumaHist1 : kLumaHist2;
  const VkDescriptorType T = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, I = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                         CB = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, OWN = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  switch (pass) {
    case 0:  // compute_luminance_pyramid
      return {{0, T, color}, {1, I, kAtomic}, {2, I, kLumaShading}, {3, I, kMip5}, {4, I, kExposure},
              {5, CB},       {6, OWN}};
    case 1:  // reconstruct_previous_depth
      return {{0, T, motion}, {1, T, depth},     {2, T, color},      {3, T, kExposure}, {5, I, kPrevDepth},
              {6, I, mv},     {7, I, kDilDepth}, {11, I, kLockLuma}, {12, CB}};
    case 2:  // depth_clip
      return {{0, T, kPrevDepth},   {1, T, mv},        {2, T, kDilDepth},  {3, T, kDefaultMask},
              {4, T, kDefaultMask}, {5, T, kPrepared}, {6, T, prev_mv},    {7, T, motion},
              {8, T, color},        {9, T, depth},     {10, T, kExposure}, {12, I, kReactive},
              {13, I, kPrepared},   {14, CB}};
    case 3:  // lock
      return {{0, T, kLockLuma}, {1, I, kNewLocks}, {2, I, kPrevDepth}, {3, CB}};
    case 4:  // accumulate (APPLY_SHARPENING: leaves the output to RCAS)
      return {{0, T, kExposure}, {1, T, kReactive}, {2, T, mv},        {3, T, up_srv},        {4, T, lock_srv},
              {6, T, kPrepared}, {8, T, kLanczos},  {9, T, kMaxBias},  {10, T, kLumaShading}, {11, T, kExposure},
              {12, T, hist_srv}, {13, I, up_uav},   {14, I, lock_uav}, {15, I, kOutput},      {16, I, kNewLocks},
              {17, I, hist_uav}, {18, CB}};
    default:  // rcas: its input is this frame's upscaled colour (the accumulate's UAV)
      return {{0, T, kExposure}, {1, T, up_uav}, {2, I, kOutput}, {3, CB}, {4, OWN}};
  }
}

void Run::CreatePasses() {
  const VkDevice dev = d_->device;
  VkDescriptorSetLayoutBinding s0[2] = {};
  for (uint32_t i = 0; i < 2; ++i) {
    s0[i].binding = i;
    s0[i].descriptorType = VK_DESCRIPTOR_TYPE_SAMPLER;
    s0[i].descriptorCount = 1;
    s0[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = 2;
  li.pBindings = s0;
  Check(vkCreateDescriptorSetLayout(dev, &li, nullptr, &set0_layout_), "vkCreateDescriptorSetLayout");
  const uint32_t sets = 6 * kSlots + 1;
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_SAMPLER, 2},
                                        {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 16 * sets},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 16 * sets},
                                        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, sets},
                                        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, sets}};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.maxSets = sets;
  dpi.poolSizeCount = 5;
  dpi.pPoolSizes = sizes;
  Check(vkCreateDescriptorPool(dev, &dpi, nullptr, &pool_), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &set0_layout_;
  Check(vkAllocateDescriptorSets(dev, &ai, &set0_), "vkAllocateDescriptorSets");
  VkDescriptorImageInfo smp[2] = {{samplers_[0], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED},
                                  {samplers_[1], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED}};
  VkWriteDescriptorSet w0[2] = {};
  for (uint32_t i = 0; i < 2; ++i) {
    w0[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w0[i].dstSet = set0_;
    w0[i].dstBinding = i;
    w0[i].descriptorCount = 1;
    w0[i].descriptorType = VK_DESCRIPTOR_TYPE_SAMPLER;
    w0[i].pImageInfo = &smp[i];
  }
  vkUpdateDescriptorSets(dev, 2, w0, 0, nullptr);

  const Fsr2Spd spd = Fsr2SpdSetup(rw_, rh_);
  const uint32_t dsx = static_cast<uint32_t>((rw_ + 7) / 8), dsy = static_cast<uint32_t>((rh_ + 7) / 8);
  const uint32_t ddx = static_cast<uint32_t>((dw_ + 7) / 8), ddy = static_cast<uint32_t>((dh_ + 7) / 8);
  const uint32_t grid[6][2] = {{spd.groups_x, spd.groups_y},
                               {dsx, dsy},
                               {dsx, dsy},
                               {dsx, dsy},
                               {ddx, ddy},
                               {static_cast<uint32_t>((dw_ + 15) / 16), static_cast<uint32_t>((dh_ + 15) / 16)}};
  passes_.resize(6);
  for (int p = 0; p < 6; ++p) {
    Pass& q = passes_[static_cast<size_t>(p)];
    q.gx = grid[p][0];
    q.gy = grid[p][1];
    q.own_cb_offset = cb_stride_ * static_cast<uint32_t>(p == 0 ? kSlots + 1 : kSlots + 2);
    std::vector<std::pair<uint32_t, VkDescriptorType>> lb;
    for (const Binding& b : Bindings(p, 0)) lb.emplace_back(b.binding, b.type);
    q.layout = d_->ComputeSetLayout(lb);
    const VkDescriptorSetLayout both[2] = {set0_layout_, q.layout};
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 2;
    pli.pSetLayouts = both;
    Check(vkCreatePipelineLayout(dev, &pli, nullptr, &q.playout), "vkCreatePipelineLayout");
    d_->ComputePipeline(spirv_[static_cast<size_t>(p)], q.playout, modules_[static_cast<size_t>(p)], &q.module,
                        &q.pipeline);
    for (int slot = 0; slot < kSlots; ++slot) {
      VkDescriptorSetAllocateInfo a1{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
      a1.descriptorPool = pool_;
      a1.descriptorSetCount = 1;
      a1.pSetLayouts = &q.layout;
      Check(vkAllocateDescriptorSets(dev, &a1, &q.sets[slot]), "vkAllocateDescriptorSets");
      const std::vector<Binding> bs = Bindings(p, slot);
      std::vector<VkDescriptorImageInfo> ii(bs.size());
      std::vector<VkDescriptorBufferInfo> bi(bs.size());
      std::vector<VkWriteDescriptorSet> w;
      for (size_t k = 0; k < bs.size(); ++k) {
        VkWriteDescriptorSet x{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        x.dstSet = q.sets[slot];
        x.dstBinding = bs[k].binding;
        x.descriptorCount = 1;
        x.descriptorType = bs[k].type;
        if (bs[k].type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC) {
          bi[k] = {cb_, 0, sizeof(Fsr2Cb)};
          x.pBufferInfo = &bi[k];
        } else if (bs[k].type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER) {
          bi[k] = {cb_, q.own_cb_offset, 32};
          x.pBufferInfo = &bi[k];
        } else {
          ii[k] = {VK_NULL_HANDLE, images_.at(static_cast<size_t>(bs[k].image)).view, VK_IMAGE_LAYOUT_GENERAL};
          x.pImageInfo = &ii[k];
        }
        w.push_back(x);
      }
      vkUpdateDescriptorSets(dev, static_cast<uint32_t>(w.size()), w.data(), 0, nullptr);
    }
  }
}

void FullBarrier(VkCommandBuffer cb) {
  VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  mb.dstAccessMask =
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_UNIFORM_READ_BIT;
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &mb, 0, nullptr, 0,
                       nullptr);
}

// Frame `frame` of the run: input slot frame mod 8, cbFSR2 slot the same (the reset frame's
// constants for frame 0), the six passes with a barrier after each.
void Run::Record(VkCommandBuffer cb, int frame, bool timed, uint32_t query_base) const {
  const int slot = frame % kSlots;
  const uint32_t offset = cb_stride_ * static_cast<uint32_t>(frame == 0 ? kSlots : slot);
  if (timed) vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, query_base);
  for (size_t p = 0; p < passes_.size(); ++p) {
    const Pass& q = passes_[p];
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, q.pipeline);
    const VkDescriptorSet sets[2] = {set0_, q.sets[slot]};
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, q.playout, 0, 2, sets, 1, &offset);
    vkCmdDispatch(cb, q.gx, q.gy, 1);
    FullBarrier(cb);
    if (timed) vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, query_base + 1 + p);
  }
}

std::vector<uint8_t> Run::Read(int i) {
  const Image& im = images_.at(static_cast<size_t>(i));
  const uint64_t bytes = static_cast<uint64_t>(im.w) * static_cast<uint64_t>(im.h) * TexelBytes(im.format);
  return d_->ReadImage(im.image, static_cast<uint32_t>(im.w), static_cast<uint32_t>(im.h), bytes);
}

void Run::Destroy() {
  const VkDevice dev = d_->device;
  vkDeviceWaitIdle(dev);
  if (queries_) vkDestroyQueryPool(dev, queries_, nullptr);
  for (Pass& q : passes_) {
    vkDestroyPipeline(dev, q.pipeline, nullptr);
    vkDestroyShaderModule(dev, q.module, nullptr);
    vkDestroyPipelineLayout(dev, q.playout, nullptr);
    vkDestroyDescriptorSetLayout(dev, q.layout, nullptr);
  }
  if (pool_) vkDestroyDescriptorPool(dev, pool_, nullptr);
  if (set0_layout_) vkDestroyDescriptorSetLayout(dev, set0_layout_, nullptr);
  for (VkSampler s : samplers_) {
    if (s) vkDestroySampler(dev, s, nullptr);
  }
  if (cb_) vkDestroyBuffer(dev, cb_, nullptr);
  if (cb_memory_) vkFreeMemory(dev, cb_memory_, nullptr);
  for (Image& im : images_) {
    vkDestroyImageView(dev, im.view, nullptr);
    vkDestroyImage(dev, im.image, nullptr);
    vkFreeMemory(dev, im.memory, nullptr);
  }
}

MethodResult Run::Go(const Frame& display, int warmup, int repeat) {
  const auto start = std::chrono::steady_clock::now();
  CreateResources();
  const int phases = Fsr2PhaseCount(rw_, dw_);
  // Inputs and cbFSR2 of each slot; the reset frame's constants after them.
  std::vector<uint8_t> cbs(static_cast<size_t>(cb_stride_) * (kSlots + 3), 0);
  // The 8 input frames are made on 8 threads (each independent: the same bytes at any count).
  std::vector<Fsr2InputFrame> inputs(kSlots);
  {
    std::vector<std::thread> threads;
    for (int k = 0; k < kSlots; ++k) {
      threads.emplace_back([&, k] {
        float j[2];
        Fsr2SequenceJitter(k, phases, j);
        inputs[static_cast<size_t>(k)] = Fsr2MakeInput(display, k, rw_, rh_, j);
      });
    }
    for (std::thread& t : threads) t.join();
  }
  for (int k = 0; k < kSlots; ++k) {
    float j[2];
    Fsr2SequenceJitter(k, phases, j);
    Fsr2InputFrame& in = inputs[static_cast<size_t>(k)];
    Upload(kInputs + 3 * k, in.color.data(), in.color.size() * 2);
    Upload(kInputs + 3 * k + 1, in.depth.data(), in.depth.size() * 4);
    Upload(kInputs + 3 * k + 2, in.motion.data(), in.motion.size() * 2);
    const Fsr2Cb c = Fsr2FrameConstants(rw_, rh_, dw_, dh_, j, k == 0 ? kSlots : k);
    std::memcpy(&cbs[static_cast<size_t>(cb_stride_) * static_cast<size_t>(k)], &c, sizeof c);
    in = Fsr2InputFrame();  // release the host copy
    if (k == 0) {
      const Fsr2Cb r = Fsr2FrameConstants(rw_, rh_, dw_, dh_, j, 0);
      std::memcpy(&cbs[static_cast<size_t>(cb_stride_) * kSlots], &r, sizeof r);
    }
  }
  const Fsr2Spd spd = Fsr2SpdSetup(rw_, rh_);
  std::memcpy(&cbs[static_cast<size_t>(cb_stride_) * (kSlots + 1)], &spd, 24);
  const uint32_t rcas[4] = {Fsr2RcasConstant(0.8f), 0, 0, 0};
  std::memcpy(&cbs[static_cast<size_t>(cb_stride_) * (kSlots + 2)], rcas, sizeof rcas);
  UploadBuffer(cb_, cbs.data(), cbs.size());
  CreatePasses();
  std::fprintf(stderr, "  (fsr2 %dx%d -> %dx%d: sequence made, uploaded and pipelines built in %.2f s)\n", rw_, rh_,
               dw_, dh_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());

  const uint32_t per = static_cast<uint32_t>(passes_.size()) + 1;
  VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = per * static_cast<uint32_t>(repeat);
  Check(vkCreateQueryPool(d_->device, &qi, nullptr, &queries_), "vkCreateQueryPool");
  if (warmup > 0) {
    d_->Once([&](VkCommandBuffer cb) {
      for (int f = 0; f < warmup; ++f) Record(cb, f, false, 0);
    });
  }
  d_->Once([&](VkCommandBuffer cb) {
    vkCmdResetQueryPool(cb, queries_, 0, qi.queryCount);
    for (int r = 0; r < repeat; ++r) Record(cb, warmup + r, true, per * static_cast<uint32_t>(r));
  });
  std::vector<uint64_t> ts(qi.queryCount);
  Check(vkGetQueryPoolResults(d_->device, queries_, 0, qi.queryCount, ts.size() * 8, ts.data(), 8,
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  const uint32_t bits = d_->facts.timestamp_valid_bits;
  const uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  const double ms_per_tick = d_->facts.timestamp_period_ns * 1e-6;
  auto delta = [&](uint64_t a, uint64_t b) { return static_cast<double>((b - a) & mask) * ms_per_tick; };
  MethodResult res;
  res.pass_names = Fsr2PassNames();
  for (int r = 0; r < repeat; ++r) {
    const uint64_t* q = ts.data() + per * static_cast<uint32_t>(r);
    std::vector<double> ms;
    for (uint32_t k = 0; k + 1 < per; ++k) ms.push_back(delta(q[k], q[k + 1]));
    res.timings.ms.push_back(ms);
    res.timings.whole.push_back(delta(q[0], q[per - 1]));
  }

  // The last frame's output against the same frame rendered at display size (no jitter).
  const std::vector<uint8_t> raw = Read(kOutput);
  res.output_half.resize(raw.size() / 2);
  std::memcpy(res.output_half.data(), raw.data(), raw.size());
  const int last = (warmup + repeat - 1) % kSlots;
  float lj[2];
  Fsr2SequenceJitter(last, phases, lj);
  const Fsr2InputFrame low = Fsr2MakeInput(display, last, rw_, rh_, lj);
  res.output = {dw_, dh_, std::vector<uint8_t>(static_cast<size_t>(dw_) * static_cast<size_t>(dh_) * 4, 255)};
  OutputCheck& c = res.check;
  c.has = true;
  c.min = INFINITY;
  c.max = -INFINITY;
  double err = 0, err_nearest = 0;
  for (int y = 0; y < dh_; ++y) {
    for (int x = 0; x < dw_; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(dw_) + static_cast<size_t>(x);
      float ref[3];
      Fsr2SceneColor(display, last, static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, ref);
      const int lx = std::min(rw_ - 1, x * rw_ / dw_), ly = std::min(rh_ - 1, y * rh_ / dh_);
      const size_t li = static_cast<size_t>(ly) * static_cast<size_t>(rw_) + static_cast<size_t>(lx);
      for (size_t k = 0; k < 3; ++k) {
        uint16_t h;
        std::memcpy(&h, &raw[(i * 4 + k) * 2], 2);
        const float v = Fsr2HalfToFloat(h);
        if (!std::isfinite(v)) {
          ++c.nonfinite;
          continue;
        }
        c.min = std::min(c.min, static_cast<double>(v));
        c.max = std::max(c.max, static_cast<double>(v));
        err += std::fabs(static_cast<double>(v) - ref[k]);
        err_nearest += std::fabs(static_cast<double>(Fsr2HalfToFloat(low.color[li * 4 + k])) - ref[k]);
        res.output.rgba[i * 4 + k] = static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
      }
    }
  }
  const double n = 3.0 * static_cast<double>(dw_) * static_cast<double>(dh_);
  c.mean_abs_error = err / n;
  c.mean_abs_error_nearest = err_nearest / n;
  res.note =
      "render " + std::to_string(rw_) + "x" + std::to_string(rh_) + " (synthetic sequence from the scene's frame)";
  return res;
}

}  // namespace

MethodResult RunFsr2(Device& device, const std::string& spirv_dir, const std::string& spec, const Frame& display,
                     int warmup, int repeat) {
  const Fsr2Preset* p = FindFsr2Preset(spec);
  if (!p) throw std::runtime_error("unknown FSR 2 method '" + spec + "'");
  const int rw = Fsr2RenderSide(display.width, p->ratio), rh = Fsr2RenderSide(display.height, p->ratio);
  if (rw < 1 || rh < 1)
    throw std::runtime_error(spec + ": the render size of a " + std::to_string(display.width) + "x" +
                             std::to_string(display.height) + " frame is empty");
  Run run(device.impl(), spirv_dir, rw, rh, display.width, display.height);
  return run.Go(display, warmup, repeat);
}

}  // namespace aalab::vk
