// The method table of aalab_vk: each report method as the original's host code dispatches
// its shaders (docs/gpu.md "Original shaders through Vulkan").
//
// - CMAA2 (CMAA2.hlsl, GameTechDev/CMAA2): the sample's pass sequence, as the oracle
//   (tests/oracle/cmaa2_shader.cpp) runs it: EdgesColor2x2CS over ceil(ceil(W/2)/14) x
//   ceil(ceil(H/2)/14) groups, ComputeDispatchArgsCS (2,1,1), ProcessCandidatesCS (indirect),
//   ComputeDispatchArgsCS (1,2,1), DeferredColorApply2x2CS (indirect). The frame is an
//   R8G8B8A8_SRGB texture (the shader reads linear colour, the texture unit decodes), the
//   output an R8G8B8A8_UNORM storage image that starts as a copy of the frame (pixels the
//   shader does not write keep their bytes); the shader converts to sRGB itself
//   (CMAA2_UAV_STORE_CONVERT_TO_SRGB). The shader resets its counters and list heads for the
//   next frame itself, so the chain repeats as a game's frames do. The working buffers are
//   sized generously (candidates and blend locations: one per pixel; blend items: eight per
//   pixel); the shader clamps a count that would overflow, which would show as a fidelity
//   difference (not seen on the test's frames).
// - FSR 1 (ffx_fsr1.h): EASU from the render-size frame of scale43-easu (round(3W/4) x
//   round(3H/4), one centre sample: `aalab export-frames --render-methods scale43-easu`, role
//   `scale43-easu`) to the output size into an R8G8B8A8_UNORM image (the sample's
//   intermediate), RCAS (sharpness 0.2 stops, aalab's and the sample's default) from an
//   R8G8B8A8_UNORM texture to an R8G8B8A8_UNORM image; 64-thread groups over 16x16 tiles.
// - FSR 2 (ffx_fsr2_*_pass.glsl): fsr2-native, -quality, -balanced, -performance,
//   -ultra-performance, the default pipeline's six passes per frame over a warm sequence of
//   frames (gpu/vk/vk_fsr2_host.cpp says what the frames hold, vk_fsr2.cpp and which resources the passes get).
// - copy: gpu/vk/shaders/copy.comp, the floor.
#include "gpu/vk/vk_methods.h"

#include <vulkan/vulkan.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "gpu/vk/vk_fsr2.h"

namespace aalab::vk {

namespace {

std::vector<uint32_t> LoadSpirv(const std::string& dir, const std::string& name) {
  const std::string path = dir + "/" + name + ".spv";
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  if (!f) {
    throw std::runtime_error("SPIR-V module '" + path +
                             "' is missing (compile the modules with scripts/vk_shaders.sh " + dir + ")");
  }
  const std::streamsize n = f.tellg();
  if (n <= 0 || n % 4 != 0)
    throw std::runtime_error("'" + path + "' is not a SPIR-V module (size " + std::to_string(n) +
                             " is not a positive multiple of 4)");
  std::vector<uint32_t> words(static_cast<size_t>(n) / 4);
  f.seekg(0);
  f.read(reinterpret_cast<char*>(words.data()), n);
  if (words[0] != 0x07230203u) throw std::runtime_error("'" + path + "' is not a SPIR-V module (no magic number)");
  return words;
}

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

uint32_t Groups(int n, int per) { return static_cast<uint32_t>((n + per - 1) / per); }

const char* const kCmaa2Entries[] = {"EdgesColor2x2CS", "ComputeDispatchArgsCS", "ProcessCandidatesCS",
                                     "DeferredColorApply2x2CS"};

MethodResult RunCmaa2(Device& device, const std::string& dir, const std::string& preset, const Frame& in, int warmup,
                      int repeat) {
  const int w = in.width, h = in.height, ew = (w + 1) / 2, qh = (h + 1) / 2;
  const uint64_t px = static_cast<uint64_t>(w) * static_cast<uint64_t>(h);
  std::vector<std::vector<uint32_t>> mods;
  for (const char* e : kCmaa2Entries) mods.push_back(LoadSpirv(dir, "cmaa2-" + preset + "-" + e));
  enum { kIn, kOut, kEdges, kHeads };
  enum { kCandidates, kLocations, kItems, kControl, kIndirect };
  const std::vector<ImageSpec> images = {{w, h, VK_FORMAT_R8G8B8A8_SRGB},
                                         {w, h, VK_FORMAT_R8G8B8A8_UNORM},
                                         {ew, h, VK_FORMAT_R32_UINT},
                                         {ew, qh, VK_FORMAT_R32_UINT}};
  const std::vector<BufferSpec> buffers = {
      {px * 4, false}, {px * 4, false}, {px * 8 * 8, false}, {256, false}, {256, true}};
  // Registers as the shader declares them: t0 -> 0, u0..u7 -> 10..17.
  const std::vector<PassBinding> b = {
      {PassBinding::kSampledImage, 0, kIn},          {PassBinding::kStorageImage, 10, kOut},
      {PassBinding::kStorageImage, 11, kEdges},      {PassBinding::kStorageBuffer, 12, kCandidates},
      {PassBinding::kStorageBuffer, 13, kLocations}, {PassBinding::kStorageBuffer, 14, kItems},
      {PassBinding::kStorageImage, 15, kHeads},      {PassBinding::kStorageBuffer, 16, kControl},
      {PassBinding::kStorageBuffer, 17, kIndirect}};
  std::vector<PassSpec> passes(5);
  passes[0] = {kCmaa2Entries[0], mods[0], b, {}, Groups(ew, 14), Groups(qh, 14), 1, -1};
  passes[1] = {kCmaa2Entries[1], mods[1], b, {}, 2, 1, 1, -1};
  passes[2] = {kCmaa2Entries[2], mods[2], b, {}, 1, 1, 1, kIndirect};
  passes[3] = {kCmaa2Entries[1], mods[1], b, {}, 1, 2, 1, -1};
  passes[4] = {kCmaa2Entries[3], mods[3], b, {}, 1, 1, 1, kIndirect};
  Chain chain(device, images, buffers, passes);
  chain.FillImage(kIn, in.rgba.data(), in.rgba.size());
  chain.FillImage(kOut, in.rgba.data(), in.rgba.size());
  chain.FillImage(kHeads, std::vector<uint32_t>(static_cast<size_t>(ew) * static_cast<size_t>(qh), 0xFFFFFFFFu).data(),
                  static_cast<uint64_t>(ew) * static_cast<uint64_t>(qh) * 4);
  MethodResult r;
  for (const PassSpec& p : passes) r.pass_names.push_back(p.name);
  r.timings = chain.Run(warmup, repeat);
  r.output = {w, h, chain.ReadImage(kOut)};
  return r;
}

// EASU (in -> out size), RCAS (same size), or EASU then RCAS; or the copy.
MethodResult RunFsr1(Device& device, const std::string& dir, bool easu, bool rcas, const Frame& in, int out_w,
                     int out_h, int warmup, int repeat) {
  std::vector<ImageSpec> images = {{in.width, in.height, VK_FORMAT_R8G8B8A8_UNORM}};
  std::vector<PassSpec> passes;
  int src = 0;
  auto add = [&](const std::string& name, const std::string& module, std::vector<uint32_t> push, int tile) {
    images.push_back({out_w, out_h, VK_FORMAT_R8G8B8A8_UNORM});
    const int dst = static_cast<int>(images.size()) - 1;
    passes.push_back({name,
                      LoadSpirv(dir, module),
                      {{PassBinding::kCombinedSampler, 0, src}, {PassBinding::kStorageImage, 1, dst}},
                      std::move(push),
                      Groups(out_w, tile),
                      Groups(out_h, tile),
                      1,
                      -1});
    src = dst;
  };
  if (!easu && !rcas) {
    add("copy", "copy", {}, 16);
  } else {
    if (easu) add("FsrEasuF", "fsr1-easu", EasuConstants(in.width, in.height, out_w, out_h), 16);
    std::vector<uint32_t> con(16, 0u);
    con[0] = RcasConstant(0.2f);
    if (rcas) add("FsrRcasF", "fsr1-rcas", con, 16);
  }
  Chain chain(device, images, {}, passes);
  chain.FillImage(0, in.rgba.data(), in.rgba.size());
  MethodResult r;
  for (const PassSpec& p : passes) r.pass_names.push_back(p.name);
  r.timings = chain.Run(warmup, repeat);
  r.output = {out_w, out_h, chain.ReadImage(src)};
  return r;
}

}  // namespace

const std::vector<MethodInfo>& Methods() {
  static const std::vector<MethodInfo> m = [] {
    std::vector<MethodInfo> v = {{"copy", "1x", "copy"}};
    std::string chain;
    for (const char* e : {"EdgesColor2x2CS", "ComputeDispatchArgsCS", "ProcessCandidatesCS", "ComputeDispatchArgsCS",
                          "DeferredColorApply2x2CS"}) {
      chain += std::string(chain.empty() ? "" : " + ") + e;
    }
    for (const char* p : {"low", "medium", "high", "ultra"}) v.push_back({std::string("cmaa2-") + p, "1x", chain});
    v.push_back({"rcas", "1x", "FsrRcasF"});
    v.push_back({"scale43-easu", "scale43-easu", "FsrEasuF"});
    v.push_back({"scale43-easu-rcas", "scale43-easu", "FsrEasuF + FsrRcasF"});
    std::string fsr2;
    for (const std::string& p : Fsr2PassNames()) fsr2 += (fsr2.empty() ? "" : " + ") + p;
    for (const Fsr2Preset& p : Fsr2Presets()) v.push_back({p.spec, "1x", fsr2});
    return v;
  }();
  return m;
}

const MethodInfo* FindMethod(const std::string& spec) {
  for (const MethodInfo& m : Methods()) {
    if (m.spec == spec) return &m;
  }
  return nullptr;
}

std::vector<std::string> ModulesOf(const std::string& spec) {
  if (spec.rfind("cmaa2-", 0) == 0) {
    std::vector<std::string> v;
    for (const char* e : kCmaa2Entries) v.push_back(spec + "-" + e);
    return v;
  }
  if (FindFsr2Preset(spec)) return Fsr2Modules();
  if (spec == "copy") return {"copy"};
  if (spec == "rcas") return {"fsr1-rcas"};
  if (spec == "scale43-easu") return {"fsr1-easu"};
  return {"fsr1-easu", "fsr1-rcas"};
}

std::vector<uint32_t> EasuConstants(int in_w, int in_h, int out_w, int out_h) {
  const float iw = static_cast<float>(in_w), ih = static_cast<float>(in_h);
  const float rox = 1.0f / static_cast<float>(out_w), roy = 1.0f / static_cast<float>(out_h);
  const float rix = 1.0f / iw, riy = 1.0f / ih;
  return {Bits(iw * rox),
          Bits(ih * roy),
          Bits(0.5f * iw * rox - 0.5f),
          Bits(0.5f * ih * roy - 0.5f),
          Bits(rix),
          Bits(riy),
          Bits(1.0f * rix),
          Bits(-1.0f * riy),
          Bits(-1.0f * rix),
          Bits(2.0f * riy),
          Bits(1.0f * rix),
          Bits(2.0f * riy),
          Bits(0.0f * rix),
          Bits(4.0f * riy),
          0u,
          0u};
}

uint32_t RcasConstant(float sharpness_stops) { return Bits(std::exp2f(-sharpness_stops)); }

MethodResult RunMethod(Device& device, const std::string& spirv_dir, const std::string& spec, const Frame& in,
                       int out_w, int out_h, int warmup, int repeat) {
  if (spec.rfind("cmaa2-", 0) == 0) return RunCmaa2(device, spirv_dir, spec.substr(6), in, warmup, repeat);
  if (FindFsr2Preset(spec)) return RunFsr2(device, spirv_dir, spec, in, warmup, repeat);
  if (spec == "copy") return RunFsr1(device, spirv_dir, false, false, in, in.width, in.height, warmup, repeat);
  if (spec == "rcas") return RunFsr1(device, spirv_dir, false, true, in, in.width, in.height, warmup, repeat);
  if (spec == "scale43-easu") return RunFsr1(device, spirv_dir, true, false, in, out_w, out_h, warmup, repeat);
  if (spec == "scale43-easu-rcas") return RunFsr1(device, spirv_dir, true, true, in, out_w, out_h, warmup, repeat);
  throw std::runtime_error("unknown method '" + spec + "'");
}

}  // namespace aalab::vk
