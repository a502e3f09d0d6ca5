#include "tests/oracle/fsr2_shader.h"

#include <vulkan/vulkan.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "tests/oracle/third_party_sources.h"
#include "tests/oracle/vk_compute.h"

namespace aalab::oracle {

namespace {

constexpr const char* kDir = "fidelityfx-fsr2/shaders";

std::vector<std::string> Defines(const Fsr2Options& o) {
  auto b = [](bool v) { return std::string(v ? "1" : "0"); };
  return {"FFX_GPU=1",
          "FFX_GLSL=1",
          "FFX_HALF=0",
          "FFX_FSR2_OPTION_HDR_COLOR_INPUT=" + b(o.hdr_color_input),
          "FFX_FSR2_OPTION_LOW_RESOLUTION_MOTION_VECTORS=" + b(o.low_res_motion_vectors),
          "FFX_FSR2_OPTION_JITTERED_MOTION_VECTORS=" + b(o.jittered_motion_vectors),
          "FFX_FSR2_OPTION_INVERTED_DEPTH=" + b(o.inverted_depth),
          "FFX_FSR2_OPTION_APPLY_SHARPENING=" + b(o.apply_sharpening),
          "FFX_FSR2_OPTION_REPROJECT_USE_LANCZOS_TYPE=" + std::string(o.reproject_lanczos_lut ? "1" : "0"),
          "FFX_FSR2_OPTION_UPSAMPLE_USE_LANCZOS_TYPE=2"};
}

}  // namespace

std::vector<uint32_t> PreciseSpirv(const std::vector<uint32_t>& words) {
  // Result ids of float arithmetic: OpFNegate, OpFAdd, OpFSub, OpFMul, OpFDiv, OpFRem, OpFMod,
  // OpVectorTimesScalar, OpMatrixTimesScalar, OpVectorTimesMatrix, OpMatrixTimesVector,
  // OpMatrixTimesMatrix, OpDot.
  static const uint32_t kFloatOps[] = {127, 129, 131, 133, 136, 140, 141, 142, 143, 144, 145, 146, 148};
  std::vector<uint32_t> ids;
  size_t insert_at = 0;
  bool in_functions = false;
  for (size_t i = 5; i < words.size();) {
    const uint32_t op = words[i] & 0xffffu, wc = words[i] >> 16;
    if (wc == 0 || i + wc > words.size()) throw std::runtime_error("PreciseSpirv: malformed SPIR-V");
    if (op == 54) in_functions = true;  // OpFunction
    const bool annotation =
        op == 71 || op == 72 || op == 73 || op == 74 || op == 75 || op == 332 || op == 5632 || op == 5633;
    if (!in_functions && annotation) insert_at = i + wc;
    for (uint32_t f : kFloatOps) {
      if (op == f && wc >= 3) ids.push_back(words[i + 2]);
    }
    i += wc;
  }
  if (insert_at == 0) throw std::runtime_error("PreciseSpirv: no annotation section");
  std::vector<uint32_t> out(words.begin(), words.begin() + static_cast<std::ptrdiff_t>(insert_at));
  for (uint32_t id : ids) {
    out.push_back((3u << 16) | 71u);  // OpDecorate id NoContraction (42)
    out.push_back(id);
    out.push_back(42u);
  }
  out.insert(out.end(), words.begin() + static_cast<std::ptrdiff_t>(insert_at), words.end());
  return out;
}

namespace {

// One pass's SPIR-V for one set of options (compiled once per process), every float operation
// decorated NoContraction (PreciseSpirv).
const std::vector<uint32_t>& Module(const std::string& pass, const Fsr2Options& o, bool precise = true) {
  static std::map<std::string, std::vector<uint32_t>> cache;
  std::string key = pass + (precise ? " precise" : "");
  for (const auto& d : Defines(o)) key += " " + d;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  std::vector<uint32_t> spirv = CompileGlslFile(ThirdPartyDir() + "/" + kDir + "/" + pass, {}, Defines(o));
  return cache[key] = precise ? PreciseSpirv(spirv) : spirv;
}

VkBinding Tex(uint32_t binding, int w, int h, VkFormat f) {
  VkBinding b{VkBinding::kSampledImage, binding, w, h, f};
  b.set = 1;
  return b;
}
VkBinding Img(uint32_t binding, int w, int h, VkFormat f) {
  VkBinding b{VkBinding::kStorageImage, binding, w, h, f};
  b.set = 1;
  return b;
}
VkBinding Cb(uint32_t binding) {
  VkBinding b{VkBinding::kUniformBuffer, binding};
  b.bytes = 128;
  b.set = 1;
  return b;
}
std::vector<VkBinding> WithSamplers(std::vector<VkBinding> v) {
  VkBinding point{VkBinding::kSampler, 0}, linear{VkBinding::kSampler, 1};
  linear.linear = true;
  v.push_back(point);
  v.push_back(linear);
  return v;
}

// A plane's texels padded to `channels` floats each (the texture's format).
std::vector<float> Padded(const Fsr2Plane& p, int channels) {
  std::vector<float> out(static_cast<size_t>(p.w) * static_cast<size_t>(p.h) * static_cast<size_t>(channels), 0.0f);
  for (size_t i = 0; i < static_cast<size_t>(p.w) * static_cast<size_t>(p.h); ++i) {
    for (int c = 0; c < std::min(p.c, channels); ++c)
      out[i * static_cast<size_t>(channels) + static_cast<size_t>(c)] =
          p.v[i * static_cast<size_t>(p.c) + static_cast<size_t>(c)];
  }
  return out;
}

// An r16f / rg16f / rgba16f image read back as a plane of `channels` floats.
Fsr2Plane FromHalves(const std::vector<uint8_t>& bytes, int w, int h, int channels) {
  Fsr2Plane p(w, h, channels);
  for (size_t i = 0; i < p.v.size(); ++i) {
    uint16_t hv;
    std::memcpy(&hv, bytes.data() + i * 2, 2);
    p.v[i] = Fsr2HalfToFloat(hv);
  }
  return p;
}

// A plane as 16-bit float texels (all its channels; its values are halves, so exact).
std::vector<uint16_t> ToHalves(const Fsr2Plane& p) {
  std::vector<uint16_t> out(p.v.size());
  for (size_t i = 0; i < p.v.size(); ++i) out[i] = Fsr2HalfBits(p.v[i]);
  return out;
}

// A plane as UNORM8 codes (values k/255).
std::vector<uint8_t> ToUnorm8(const Fsr2Plane& p) {
  std::vector<uint8_t> out(p.v.size());
  for (size_t i = 0; i < p.v.size(); ++i) out[i] = static_cast<uint8_t>(std::lround(p.v[i] * 255.0f));
  return out;
}

void Upload(VkCompute& vk, uint32_t binding, const std::vector<float>& v) {
  vk.Fill(VkKey(1, binding), v.data(), v.size() * 4);
}

}  // namespace

std::string Fsr2ShaderAvailable() {
  if (!ThirdPartyHas(std::string(kDir) + "/ffx_fsr2_reconstruct_previous_depth_pass.glsl")) {
    return "the FSR2 sources " + ThirdPartyDir() + "/" + kDir + " are missing";
  }
  if (std::system("glslangValidator --version > /dev/null 2>&1") != 0) {
    return "glslangValidator not found: install glslang-tools (scripts/debian-packages.txt)";
  }
  return VkCompute::Start();
}

void RunFsr2ReconstructShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& color,
                              const Fsr2Plane& depth, const Fsr2Plane& motion, float exposure,
                              Fsr2ReconstructOut* out) {
  const int rw = k.render_size[0], rh = k.render_size[1];
  if (out->prev_depth.size() != static_cast<size_t>(rw) * static_cast<size_t>(rh)) {
    throw std::invalid_argument("RunFsr2ReconstructShader: prev_depth must be render-size long");
  }
  // FSR2_BIND_* of ffx_fsr2_reconstruct_previous_depth_pass.glsl.
  VkCompute vk(
      WithSamplers({Tex(0, motion.w, motion.h, VK_FORMAT_R32G32_SFLOAT), Tex(1, depth.w, depth.h, VK_FORMAT_R32_SFLOAT),
                    Tex(2, color.w, color.h, VK_FORMAT_R32G32B32A32_SFLOAT), Tex(3, 1, 1, VK_FORMAT_R32G32_SFLOAT),
                    Img(5, rw, rh, VK_FORMAT_R32_UINT), Img(6, rw, rh, VK_FORMAT_R16G16_SFLOAT),
                    Img(7, rw, rh, VK_FORMAT_R16_SFLOAT), Img(11, rw, rh, VK_FORMAT_R16_SFLOAT), Cb(12)}));
  Upload(vk, 0, Padded(motion, 2));
  Upload(vk, 1, Padded(depth, 1));
  Upload(vk, 2, Padded(color, 4));
  Upload(vk, 3, {exposure, 0.0f});
  vk.Fill(VkKey(1, 5), out->prev_depth.data(), out->prev_depth.size() * 4);
  vk.Fill(VkKey(1, 12), &k, sizeof(k));
  const int p = vk.AddPipeline(Module("ffx_fsr2_reconstruct_previous_depth_pass.glsl", o), "main");
  vk.Run({{p, static_cast<uint32_t>((rw + 7) / 8), static_cast<uint32_t>((rh + 7) / 8), 1}});
  const std::vector<uint8_t> prev = vk.Read(VkKey(1, 5));
  std::memcpy(out->prev_depth.data(), prev.data(), out->prev_depth.size() * 4);
  out->dilated_motion = FromHalves(vk.Read(VkKey(1, 6)), rw, rh, 2);
  out->dilated_depth = FromHalves(vk.Read(VkKey(1, 7)), rw, rh, 1);
  out->lock_luma = FromHalves(vk.Read(VkKey(1, 11)), rw, rh, 1);
}

void RunFsr2LockShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& lock_luma, Fsr2Plane* new_locks,
                       std::vector<uint32_t>* prev_depth) {
  const int rw = k.render_size[0], rh = k.render_size[1], dw = new_locks->w, dh = new_locks->h;
  // FSR2_BIND_* of ffx_fsr2_lock_pass.glsl.
  VkCompute vk(WithSamplers({Tex(0, rw, rh, VK_FORMAT_R16_SFLOAT), Img(1, dw, dh, VK_FORMAT_R8_UNORM),
                             Img(2, rw, rh, VK_FORMAT_R32_UINT), Cb(3)}));
  const std::vector<uint16_t> luma = ToHalves(lock_luma);
  vk.Fill(VkKey(1, 0), luma.data(), luma.size() * 2);
  std::vector<uint8_t> locks(new_locks->v.size());
  for (size_t i = 0; i < locks.size(); ++i) locks[i] = static_cast<uint8_t>(std::lround(new_locks->v[i] * 255.0f));
  vk.Fill(VkKey(1, 1), locks.data(), locks.size());
  vk.Fill(VkKey(1, 2), prev_depth->data(), prev_depth->size() * 4);
  vk.Fill(VkKey(1, 3), &k, sizeof(k));
  const int p = vk.AddPipeline(Module("ffx_fsr2_lock_pass.glsl", o), "main");
  vk.Run({{p, static_cast<uint32_t>((rw + 7) / 8), static_cast<uint32_t>((rh + 7) / 8), 1}});
  locks = vk.Read(VkKey(1, 1));
  for (size_t i = 0; i < locks.size(); ++i) new_locks->v[i] = static_cast<float>(locks[i]) / 255.0f;
  const std::vector<uint8_t> prev = vk.Read(VkKey(1, 2));
  std::memcpy(prev_depth->data(), prev.data(), prev_depth->size() * 4);
}

void RunFsr2DepthClipShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2DepthClipIn& in,
                            Fsr2DepthClipOut* out) {
  const int rw = k.render_size[0], rh = k.render_size[1];
  const Fsr2Plane zero(1, 1, 1);
  const Fsr2Plane& reactive = in.reactive.v.empty() ? zero : in.reactive;
  const Fsr2Plane& comp = in.composition.v.empty() ? zero : in.composition;
  // FSR2_BIND_* of ffx_fsr2_depth_clip_pass.glsl.
  VkCompute vk(
      WithSamplers({Tex(0, rw, rh, VK_FORMAT_R32_UINT), Tex(1, rw, rh, VK_FORMAT_R16G16_SFLOAT),
                    Tex(2, rw, rh, VK_FORMAT_R16_SFLOAT), Tex(3, reactive.w, reactive.h, VK_FORMAT_R8_UNORM),
                    Tex(4, comp.w, comp.h, VK_FORMAT_R8_UNORM), Tex(5, rw, rh, VK_FORMAT_R16G16B16A16_SFLOAT),
                    Tex(6, in.previous_dilated_motion->w, in.previous_dilated_motion->h, VK_FORMAT_R16G16_SFLOAT),
                    Tex(7, in.motion->w, in.motion->h, VK_FORMAT_R32G32_SFLOAT),
                    Tex(8, in.color->w, in.color->h, VK_FORMAT_R32G32B32A32_SFLOAT),
                    Tex(9, in.depth->w, in.depth->h, VK_FORMAT_R32_SFLOAT), Tex(10, 1, 1, VK_FORMAT_R32G32_SFLOAT),
                    Img(12, rw, rh, VK_FORMAT_R8G8_UNORM), Img(13, rw, rh, VK_FORMAT_R16G16B16A16_SFLOAT), Cb(14)}));
  vk.Fill(VkKey(1, 0), in.prev_depth->data(), in.prev_depth->size() * 4);
  const auto mv = ToHalves(*in.dilated_motion), dd = ToHalves(*in.dilated_depth),
             pmv = ToHalves(*in.previous_dilated_motion);
  vk.Fill(VkKey(1, 1), mv.data(), mv.size() * 2);
  vk.Fill(VkKey(1, 2), dd.data(), dd.size() * 2);
  const auto r8 = ToUnorm8(reactive), c8 = ToUnorm8(comp);
  vk.Fill(VkKey(1, 3), r8.data(), r8.size());
  vk.Fill(VkKey(1, 4), c8.data(), c8.size());
  vk.Fill(VkKey(1, 6), pmv.data(), pmv.size() * 2);
  Upload(vk, 7, Padded(*in.motion, 2));
  Upload(vk, 8, Padded(*in.color, 4));
  Upload(vk, 9, Padded(*in.depth, 1));
  Upload(vk, 10, {in.exposure, 0.0f});
  vk.Fill(VkKey(1, 14), &k, sizeof(k));
  const int p = vk.AddPipeline(Module("ffx_fsr2_depth_clip_pass.glsl", o), "main");
  vk.Run({{p, static_cast<uint32_t>((rw + 7) / 8), static_cast<uint32_t>((rh + 7) / 8), 1}});
  out->prepared_color = FromHalves(vk.Read(VkKey(1, 13)), rw, rh, 4);
  const std::vector<uint8_t> masks = vk.Read(VkKey(1, 12));
  out->reactive_masks = Fsr2Plane(rw, rh, 2);
  for (size_t i = 0; i < out->reactive_masks.v.size(); ++i)
    out->reactive_masks.v[i] = static_cast<float>(masks[i]) / 255.0f;
}

void RunFsr2AccumulateShader(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2AccumulateIn& in,
                             const std::vector<int16_t>& lanczos_lut, Fsr2AccumulateOut* out) {
  const int dw = k.display_size[0], dh = k.display_size[1];
  const Fsr2Plane& masks = *in.dilated_reactive_masks;
  const Fsr2Plane& prepared = *in.prepared_color;
  const Fsr2Plane& mip = *in.luma_mip;
  const Fsr2Plane& mv = o.low_res_motion_vectors ? *in.dilated_motion : *in.motion;
  // FSR2_BIND_* of ffx_fsr2_accumulate_pass.glsl; the maximum-bias table (9) is declared, not read.
  VkCompute vk(WithSamplers(
      {Tex(0, 1, 1, VK_FORMAT_R32G32_SFLOAT), Tex(1, masks.w, masks.h, VK_FORMAT_R8G8_UNORM),
       Tex(2, mv.w, mv.h, o.low_res_motion_vectors ? VK_FORMAT_R16G16_SFLOAT : VK_FORMAT_R32G32_SFLOAT),
       Tex(3, dw, dh, VK_FORMAT_R16G16B16A16_SFLOAT), Tex(4, dw, dh, VK_FORMAT_R16G16_SFLOAT),
       Tex(6, prepared.w, prepared.h, VK_FORMAT_R16G16B16A16_SFLOAT),
       Tex(8, static_cast<int>(lanczos_lut.size()), 1, VK_FORMAT_R16_SNORM), Tex(9, 16, 16, VK_FORMAT_R16_SNORM),
       Tex(10, mip.w, mip.h, VK_FORMAT_R16_SFLOAT), Tex(11, 1, 1, VK_FORMAT_R32G32_SFLOAT),
       Tex(12, dw, dh, VK_FORMAT_R8G8B8A8_UNORM), Img(13, dw, dh, VK_FORMAT_R16G16B16A16_SFLOAT),
       Img(14, dw, dh, VK_FORMAT_R16G16_SFLOAT), Img(15, dw, dh, VK_FORMAT_R32G32B32A32_SFLOAT),
       Img(16, dw, dh, VK_FORMAT_R8_UNORM), Img(17, dw, dh, VK_FORMAT_R8G8B8A8_UNORM), Cb(18)}));
  Upload(vk, 0, {in.exposure, 0.0f});
  const auto m8 = ToUnorm8(masks);
  vk.Fill(VkKey(1, 1), m8.data(), m8.size());
  if (o.low_res_motion_vectors) {
    const auto h = ToHalves(mv);
    vk.Fill(VkKey(1, 2), h.data(), h.size() * 2);
  } else {
    Upload(vk, 2, Padded(mv, 2));
  }
  const auto hist = ToHalves(*in.history), lock = ToHalves(*in.lock_status), prep = ToHalves(prepared),
             mip16 = ToHalves(mip);
  vk.Fill(VkKey(1, 3), hist.data(), hist.size() * 2);
  vk.Fill(VkKey(1, 4), lock.data(), lock.size() * 2);
  vk.Fill(VkKey(1, 6), prep.data(), prep.size() * 2);
  vk.Fill(VkKey(1, 8), lanczos_lut.data(), lanczos_lut.size() * 2);
  vk.Fill(VkKey(1, 10), mip16.data(), mip16.size() * 2);
  Upload(vk, 11, {in.exposure, 0.0f});
  const auto luma8 = ToUnorm8(*in.luma_history), locks8 = ToUnorm8(*in.new_locks);
  vk.Fill(VkKey(1, 12), luma8.data(), luma8.size());
  vk.Fill(VkKey(1, 16), locks8.data(), locks8.size());
  vk.Fill(VkKey(1, 18), &k, sizeof(k));
  const int p = vk.AddPipeline(Module("ffx_fsr2_accumulate_pass.glsl", o), "main");
  vk.Run({{p, static_cast<uint32_t>((dw + 7) / 8), static_cast<uint32_t>((dh + 7) / 8), 1}});
  out->internal_upscaled = FromHalves(vk.Read(VkKey(1, 13)), dw, dh, 4);
  out->lock_status = FromHalves(vk.Read(VkKey(1, 14)), dw, dh, 2);
  auto unorm = [](const std::vector<uint8_t>& bytes, int w, int h, int c) {
    Fsr2Plane q(w, h, c);
    for (size_t i = 0; i < q.v.size(); ++i) q.v[i] = static_cast<float>(bytes[i]) / 255.0f;
    return q;
  };
  out->luma_history = unorm(vk.Read(VkKey(1, 17)), dw, dh, 4);
  *in.new_locks = unorm(vk.Read(VkKey(1, 16)), dw, dh, 1);
  out->output = Fsr2Plane();
  if (!o.apply_sharpening) {
    const std::vector<uint8_t> bytes = vk.Read(VkKey(1, 15));
    out->output = Fsr2Plane(dw, dh, 3);
    for (size_t i = 0; i < static_cast<size_t>(dw) * static_cast<size_t>(dh); ++i)
      std::memcpy(&out->output.v[i * 3], bytes.data() + i * 16, 12);
  }
}

std::vector<float> RunGlslExp2Log2Sin(const std::vector<float>& exp2_of, const std::vector<float>& log2_of,
                                      const std::vector<float>& sin_of) {
  const uint32_t n = static_cast<uint32_t>(exp2_of.size() + log2_of.size() + sin_of.size());
  if (n == 0) return {};
  static std::vector<uint32_t> spirv;  // compiled once per process
  if (spirv.empty()) {
    char pattern[] = "/tmp/aalab-builtin-XXXXXX";
    if (!mkdtemp(pattern)) throw std::runtime_error("RunGlslExp2Log2Sin: mkdtemp failed");
    const std::string dir = pattern, path = dir + "/builtins.comp";
    {
      std::ofstream f(path);
      f << "#version 450\nlayout(local_size_x = 64) in;\n"
           "layout(std430, set = 0, binding = 0) buffer In { uint n[2]; float x[]; };\n"
           "layout(std430, set = 0, binding = 1) buffer Out { float y[]; };\n"
           "void main() {\n  uint i = gl_GlobalInvocationID.x;\n  if (i >= uint(x.length())) return;\n"
           "  y[i] = i < n[0] ? exp2(x[i]) : i < n[1] ? log2(x[i]) : sin(x[i]);\n}\n";
    }
    try {
      spirv = PreciseSpirv(CompileGlslFile(path, {}, {}));
    } catch (...) {
      std::filesystem::remove_all(dir);
      throw;
    }
    std::filesystem::remove_all(dir);
  }
  std::vector<uint32_t> in(2 + n);
  in[0] = static_cast<uint32_t>(exp2_of.size());
  in[1] = static_cast<uint32_t>(exp2_of.size() + log2_of.size());
  size_t at = 2;
  for (const auto* v : {&exp2_of, &log2_of, &sin_of}) {
    std::memcpy(in.data() + at, v->data(), v->size() * 4);
    at += v->size();
  }
  VkBinding ib{VkBinding::kStorageBuffer, 0}, ob{VkBinding::kStorageBuffer, 1};
  ib.bytes = in.size() * 4;
  ob.bytes = static_cast<uint64_t>(n) * 4;
  VkCompute vk({ib, ob});
  vk.Fill(0, in.data(), in.size() * 4);
  const int p = vk.AddPipeline(spirv, "main");
  vk.Run({{p, (n + 63) / 64, 1, 1}});
  const std::vector<uint8_t> bytes = vk.Read(1);
  std::vector<float> y(n);
  std::memcpy(y.data(), bytes.data(), static_cast<size_t>(n) * 4);
  return y;
}

std::vector<float> ReadR16SnormTexels(const std::vector<int16_t>& codes) {
  char pattern[] = "/tmp/aalab-snorm-XXXXXX";
  if (!mkdtemp(pattern)) throw std::runtime_error("ReadR16SnormTexels: mkdtemp failed");
  const std::string dir = pattern, path = dir + "/fetch.comp";
  {
    std::ofstream f(path);
    f << "#version 450\n#extension GL_EXT_samplerless_texture_functions : require\n"
         "layout(local_size_x = 64) in;\nlayout(set = 0, binding = 0) uniform texture2D t;\n"
         "layout(std430, set = 0, binding = 1) buffer Out { float y[]; };\n"
         "void main() {\n  uint i = gl_GlobalInvocationID.x;\n"
         "  if (i < uint(y.length())) y[i] = texelFetch(t, ivec2(int(i), 0), 0).x;\n}\n";
  }
  std::vector<uint32_t> spirv;
  try {
    spirv = CompileGlslFile(path, {}, {});
  } catch (...) {
    std::filesystem::remove_all(dir);
    throw;
  }
  std::filesystem::remove_all(dir);
  const int w = static_cast<int>(codes.size());
  VkBinding tex{VkBinding::kSampledImage, 0, w, 1, VK_FORMAT_R16_SNORM}, out{VkBinding::kStorageBuffer, 1};
  out.bytes = codes.size() * 4;
  VkCompute vk({tex, out});
  vk.Fill(0, codes.data(), codes.size() * 2);
  const int p = vk.AddPipeline(spirv, "main");
  vk.Run({{p, static_cast<uint32_t>((w + 63) / 64), 1, 1}});
  const std::vector<uint8_t> bytes = vk.Read(1);
  std::vector<float> y(codes.size());
  std::memcpy(y.data(), bytes.data(), y.size() * 4);
  return y;
}

std::vector<float> RunFsr2RcasShader(const Fsr2Constants& k, const Fsr2Plane& upscaled, float exposure, uint32_t con_x,
                                     bool precise) {
  const int w = upscaled.w, h = upscaled.h;
  VkBinding rcas_cb = Cb(4);
  // FSR2_BIND_* of ffx_fsr2_rcas_pass.glsl.
  VkCompute vk(WithSamplers({Tex(0, 1, 1, VK_FORMAT_R32G32_SFLOAT), Tex(1, w, h, VK_FORMAT_R32G32B32A32_SFLOAT),
                             Img(2, w, h, VK_FORMAT_R32G32B32A32_SFLOAT), Cb(3), rcas_cb}));
  Upload(vk, 0, {exposure, 0.0f});
  Upload(vk, 1, Padded(upscaled, 4));
  vk.Fill(VkKey(1, 3), &k, sizeof(k));
  const uint32_t con[4] = {con_x, 0, 0, 0};
  vk.Fill(VkKey(1, 4), con, sizeof(con));
  const int p = vk.AddPipeline(Module("ffx_fsr2_rcas_pass.glsl", Fsr2Options{}, precise), "main");
  vk.Run({{p, static_cast<uint32_t>((w + 15) / 16), static_cast<uint32_t>((h + 15) / 16), 1}});
  const std::vector<uint8_t> bytes = vk.Read(VkKey(1, 2));
  std::vector<float> out(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
  for (size_t i = 0; i < static_cast<size_t>(w) * static_cast<size_t>(h); ++i)
    std::memcpy(&out[i * 3], bytes.data() + i * 16, 12);
  return out;
}

void RunFsr2PyramidShader(const Fsr2Constants& k, const Fsr2SpdDispatch& spd, const Fsr2Plane& color,
                          Fsr2PyramidState* state) {
  const Fsr2Plane &luma = state->luma_mip, &mip5 = state->mip5;
  VkBinding cb_spd = Cb(6);
  // FSR2_BIND_* of ffx_fsr2_compute_luminance_pyramid_pass.glsl.
  VkCompute vk(WithSamplers({Tex(0, color.w, color.h, VK_FORMAT_R32G32B32A32_SFLOAT), Img(1, 1, 1, VK_FORMAT_R32_UINT),
                             Img(2, luma.w, luma.h, VK_FORMAT_R16_SFLOAT), Img(3, mip5.w, mip5.h, VK_FORMAT_R16_SFLOAT),
                             Img(4, 1, 1, VK_FORMAT_R32G32_SFLOAT), Cb(5), cb_spd}));
  Upload(vk, 0, Padded(color, 4));
  vk.Fill(VkKey(1, 1), &state->atomic_counter, 4);
  const auto l16 = ToHalves(luma), m16 = ToHalves(mip5);
  vk.Fill(VkKey(1, 2), l16.data(), l16.size() * 2);
  vk.Fill(VkKey(1, 3), m16.data(), m16.size() * 2);
  vk.Fill(VkKey(1, 4), state->auto_exposure, 8);
  vk.Fill(VkKey(1, 5), &k, sizeof(k));
  vk.Fill(VkKey(1, 6), &spd.c, sizeof(spd.c));
  // SPD's subgroupQuadSwap* need SPIR-V 1.3 (--target-env vulkan1.1); made precise as the others.
  static const std::vector<uint32_t> module =
      PreciseSpirv(CompileGlslFileWith(ThirdPartyDir() + "/" + kDir + "/ffx_fsr2_compute_luminance_pyramid_pass.glsl",
                                       Defines(Fsr2Options{}), "--target-env vulkan1.1"));
  const int p = vk.AddPipeline(module, "main");
  vk.Run({{p, static_cast<uint32_t>(spd.groups_x), static_cast<uint32_t>(spd.groups_y), 1}});
  const std::vector<uint8_t> counter = vk.Read(VkKey(1, 1)), exposure = vk.Read(VkKey(1, 4));
  std::memcpy(&state->atomic_counter, counter.data(), 4);
  std::memcpy(state->auto_exposure, exposure.data(), 8);
  state->luma_mip = FromHalves(vk.Read(VkKey(1, 2)), luma.w, luma.h, 1);
  state->mip5 = FromHalves(vk.Read(VkKey(1, 3)), mip5.w, mip5.h, 1);
}

std::vector<float> RunLavapipeLog2Exp2(const std::vector<float>& x) {
  static const char* kText = R"(#version 450
layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) readonly buffer Args { float arg[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Results { float result[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  result[2u * i] = log2(arg[i]);
  result[2u * i + 1u] = exp2(arg[i]);
}
)";
  static const std::vector<uint32_t> module = CompileGlslText(kText, {});
  const size_t n = (x.size() + 63) / 64 * 64;
  if (n == 0) return {};
  std::vector<float> args(x);
  args.resize(n, 1.0f);
  VkBinding in{VkBinding::kStorageBuffer, 0}, out{VkBinding::kStorageBuffer, 1};
  in.bytes = n * 4;
  out.bytes = n * 8;
  VkCompute vk({in, out});
  vk.Fill(0, args.data(), n * 4);
  const int p = vk.AddPipeline(module, "main");
  vk.Run({{p, static_cast<uint32_t>(n / 64), 1, 1}});
  const std::vector<uint8_t> bytes = vk.Read(1);
  std::vector<float> r(x.size() * 2);
  std::memcpy(r.data(), bytes.data(), r.size() * 4);
  return r;
}

}  // namespace aalab::oracle
