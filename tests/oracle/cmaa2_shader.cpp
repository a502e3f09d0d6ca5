#include "tests/oracle/cmaa2_shader.h"

#include <vulkan/vulkan.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>

#include "tests/oracle/third_party_sources.h"
#include "tests/oracle/vk_compute.h"

namespace aalab::oracle {

namespace {

constexpr const char* kSource = "cmaa2/CMAA2.hlsl";

std::string WorkingCopy() {
  std::istringstream in(ReadThirdParty(kSource));
  std::string out, line;
  while (std::getline(in, line)) {
    const size_t p = line.find_first_not_of(" \t");
    if (p != std::string::npos && line.compare(p, 6, "#error") == 0) continue;
    out += line + "\n";
  }
  return out;
}

// The four passes' SPIR-V for one set of defines (compiled once per process).
const std::vector<std::vector<uint32_t>>& Modules(int preset, bool sharp, bool color) {
  static std::map<int, std::vector<std::vector<uint32_t>>> cache;
  const int key = preset * 4 + (sharp ? 2 : 0) + (color ? 1 : 0);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  const std::string text = WorkingCopy();
  const std::vector<std::string> defines = {"CMAA2_UAV_STORE_TYPED=1",
                                            "CMAA2_UAV_STORE_TYPED_UNORM_FLOAT=0",
                                            "CMAA2_UAV_STORE_CONVERT_TO_SRGB=0",
                                            "CMAA2_STATIC_QUALITY_PRESET=" + std::to_string(preset),
                                            "CMAA2_EXTRA_SHARPNESS=" + std::string(sharp ? "1" : "0"),
                                            "CMAA2_EDGE_DETECTION_LUMA_PATH=" + std::string(color ? "0" : "1")};
  std::vector<std::vector<uint32_t>> m;
  for (const char* e : {"EdgesColor2x2CS", "ComputeDispatchArgsCS", "ProcessCandidatesCS", "DeferredColorApply2x2CS"}) {
    m.push_back(CompileHlsl(text, e, defines));
  }
  return cache[key] = m;
}

}  // namespace

std::string Cmaa2ShaderAvailable() {
  if (!ThirdPartyHas(kSource)) return "the CMAA2 source " + ThirdPartyDir() + "/" + kSource + " is missing";
  if (std::system("glslangValidator --version > /dev/null 2>&1") != 0) {
    return "glslangValidator not found: install glslang-tools (scripts/debian-packages.txt)";
  }
  return VkCompute::Start();
}

std::vector<float> RunCmaa2Shader(const std::vector<float>& rgb, int w, int h, int preset, bool extra_sharpness,
                                  bool color_edges) {
  const auto& mods = Modules(preset, extra_sharpness, color_edges);
  const int ew = (w + 1) / 2, qh = (h + 1) / 2;
  const uint64_t px = static_cast<uint64_t>(w) * static_cast<uint64_t>(h);
  // Bindings as the shader's registers: t0 = 0, u0..u7 = 10..17. Lists sized so they never
  // overflow (the shader clamps its counts to them).
  VkCompute vk({{VkBinding::kSampledImage, 0, w, h, VK_FORMAT_R32G32B32A32_SFLOAT},
                {VkBinding::kStorageImage, 10, w, h, VK_FORMAT_R32G32B32A32_SFLOAT},
                {VkBinding::kStorageImage, 11, ew, h, VK_FORMAT_R32_UINT},
                {VkBinding::kStorageBuffer, 12, 0, 0, 0, px * 4},
                {VkBinding::kStorageBuffer, 13, 0, 0, 0, px * 4},
                {VkBinding::kStorageBuffer, 14, 0, 0, 0, px * 8 * 64},
                {VkBinding::kStorageImage, 15, ew, qh, VK_FORMAT_R32_UINT},
                {VkBinding::kStorageBuffer, 16, 0, 0, 0, 256},
                {VkBinding::kStorageBuffer, 17, 0, 0, 0, 256, true}});
  std::vector<float> rgba(px * 4);
  for (uint64_t i = 0; i < px; ++i) {
    for (int c = 0; c < 3; ++c) rgba[i * 4 + static_cast<uint64_t>(c)] = rgb[i * 3 + static_cast<uint64_t>(c)];
    rgba[i * 4 + 3] = 1.0f;
  }
  vk.Fill(0, rgba.data(), rgba.size() * 4);
  vk.Fill(10, rgba.data(), rgba.size() * 4);
  const std::vector<uint32_t> heads(static_cast<size_t>(ew) * static_cast<size_t>(qh), 0xFFFFFFFFu);
  vk.Fill(15, heads.data(), heads.size() * 4);
  int p[4];
  for (int i = 0; i < 4; ++i) p[i] = vk.AddPipeline(mods[static_cast<size_t>(i)], "");
  const uint32_t gx = static_cast<uint32_t>((ew + 13) / 14), gy = static_cast<uint32_t>((qh + 13) / 14);
  vk.Run({{p[0], gx, gy, 1}, {p[1], 2, 1, 1}, {p[2], 1, 1, 1, 17}, {p[1], 1, 2, 1}, {p[3], 1, 1, 1, 17}});
  const std::vector<uint8_t> out = vk.Read(10);
  std::vector<float> result(px * 4);
  std::memcpy(result.data(), out.data(), result.size() * 4);
  return result;
}

}  // namespace aalab::oracle
