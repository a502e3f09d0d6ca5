/// Internal to gpu/vk: the Vulkan instance and device behind aalab::vk::Device, shared by the
/// generic pass chain (vk_runner.cpp) and FSR 2's frame sequence (vk_fsr2.cpp).
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gpu/vk/vk_runner.h"

namespace aalab::vk {

/// Throws std::runtime_error naming `what` unless `r` is VK_SUCCESS.
inline void Check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(r) + ")");
}

struct Device::Impl {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice phys = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory{};
  DeviceFacts facts;

  uint32_t MemoryType(uint32_t bits, VkMemoryPropertyFlags want) const {
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
      if ((bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & want) == want) return i;
    }
    throw std::runtime_error("aalab_vk: no Vulkan memory type with the needed properties");
  }
  VkDeviceMemory Allocate(VkMemoryRequirements req, VkMemoryPropertyFlags want) const {
    VkMemoryAllocateInfo a{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    a.allocationSize = req.size;
    a.memoryTypeIndex = MemoryType(req.memoryTypeBits, want);
    VkDeviceMemory m = VK_NULL_HANDLE;
    Check(vkAllocateMemory(device, &a, nullptr, &m), "vkAllocateMemory");
    return m;
  }
  // Records `record` into a one-time command buffer, submits it and waits.
  template <class F>
  void Once(F record) const {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    Check(vkAllocateCommandBuffers(device, &ai, &cb), "vkAllocateCommandBuffers");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cb, &bi);
    record(cb);
    Check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
    Submit(cb);
    vkFreeCommandBuffers(device, pool, 1, &cb);
  }
  void Submit(VkCommandBuffer cb) const {
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    Check(vkCreateFence(device, &fi, nullptr, &fence), "vkCreateFence");
    Check(vkQueueSubmit(queue, 1, &si, fence), "vkQueueSubmit");
    const VkResult r = vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX);
    vkDestroyFence(device, fence, nullptr);
    Check(r, "vkWaitForFences");
  }
  // A host-visible, coherent buffer of `bytes` for uploads and read-backs; Release destroys it.
  std::pair<VkBuffer, VkDeviceMemory> Staging(uint64_t bytes) const {
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = bytes;
    bi.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkBuffer b = VK_NULL_HANDLE;
    Check(vkCreateBuffer(device, &bi, nullptr, &b), "vkCreateBuffer (staging)");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, b, &req);
    VkDeviceMemory m = Allocate(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    Check(vkBindBufferMemory(device, b, m, 0), "vkBindBufferMemory");
    return {b, m};
  }
  void Release(std::pair<VkBuffer, VkDeviceMemory> s) const {
    vkDestroyBuffer(device, s.first, nullptr);
    vkFreeMemory(device, s.second, nullptr);
  }
  // A compute descriptor-set layout with one descriptor of each (binding, type).
  VkDescriptorSetLayout ComputeSetLayout(const std::vector<std::pair<uint32_t, VkDescriptorType>>& bindings) const {
    std::vector<VkDescriptorSetLayoutBinding> lb;
    for (const auto& [binding, type] : bindings) {
      VkDescriptorSetLayoutBinding x{};
      x.binding = binding;
      x.descriptorType = type;
      x.descriptorCount = 1;
      x.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
      lb.push_back(x);
    }
    VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    li.bindingCount = static_cast<uint32_t>(lb.size());
    li.pBindings = lb.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    Check(vkCreateDescriptorSetLayout(device, &li, nullptr, &layout), "vkCreateDescriptorSetLayout");
    return layout;
  }
  // The shader module of `spirv` and its compute pipeline (entry "main") with `layout`; `name`
  // names the module in the error.
  void ComputePipeline(const std::vector<uint32_t>& spirv, VkPipelineLayout layout, const std::string& name,
                       VkShaderModule* module, VkPipeline* pipeline) const {
    VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    mi.codeSize = spirv.size() * 4;
    mi.pCode = spirv.data();
    Check(vkCreateShaderModule(device, &mi, nullptr, module), "vkCreateShaderModule");
    VkComputePipelineCreateInfo cpi{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    cpi.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    cpi.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cpi.stage.module = *module;
    cpi.stage.pName = "main";
    cpi.layout = layout;
    Check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &cpi, nullptr, pipeline),
          ("vkCreateComputePipelines (" + name + ")").c_str());
  }
  // A staging buffer (Staging) holding a copy of `bytes` bytes of `data`; Release destroys it.
  std::pair<VkBuffer, VkDeviceMemory> StagingFrom(const void* data, uint64_t bytes) const {
    auto st = Staging(bytes);
    void* p = nullptr;
    Check(vkMapMemory(device, st.second, 0, bytes, 0, &p), "vkMapMemory");
    std::memcpy(p, data, bytes);
    vkUnmapMemory(device, st.second);
    return st;
  }
  // The `bytes` bytes of a w x h image in VK_IMAGE_LAYOUT_GENERAL (mip 0, layer 0), read back to
  // the host after every earlier shader and transfer write (untimed).
  std::vector<uint8_t> ReadImage(VkImage image, uint32_t w, uint32_t h, uint64_t bytes) const {
    auto st = Staging(bytes);
    Once([&](VkCommandBuffer cb) {
      VkMemoryBarrier before{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
      before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
      before.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
      vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before, 0, nullptr, 0, nullptr);
      VkBufferImageCopy r{};
      r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      r.imageExtent = {w, h, 1};
      vkCmdCopyImageToBuffer(cb, image, VK_IMAGE_LAYOUT_GENERAL, st.first, 1, &r);
      VkMemoryBarrier after{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
      after.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      after.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &after, 0, nullptr, 0,
                           nullptr);
    });
    std::vector<uint8_t> out(bytes);
    void* p = nullptr;
    Check(vkMapMemory(device, st.second, 0, bytes, 0, &p), "vkMapMemory");
    std::memcpy(out.data(), p, bytes);
    vkUnmapMemory(device, st.second);
    Release(st);
    return out;
  }
};

}  // namespace aalab::vk
