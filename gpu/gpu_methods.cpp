#include "gpu/gpu_methods.h"

#include <stdexcept>

#include "harness/core/error.h"
#include "harness/core/params.h"
#include "methods/fxaa1.h"
#include "methods/fxaa311.h"
#include "methods/registry.h"
#include "methods/rescale.h"
#include "methods/smaa.h"

namespace aalab {
namespace {

cuda::Fxaa1Args Fxaa1ArgsFrom(const ParamValues& v) {
  cuda::Fxaa1Args a{};
  // The same fields methods/fxaa1.cpp reads from the registry's values.
  a.edge_threshold = static_cast<float>(v.Number("edge_threshold"));
  a.edge_threshold_min = static_cast<float>(v.Number("edge_threshold_min"));
  a.search_steps = v.Int("search_steps");
  a.search_acceleration = v.Int("search_acceleration");
  a.search_threshold = static_cast<float>(v.Number("search_threshold"));
  a.subpix_cap = static_cast<float>(v.Number("subpix_cap"));
  a.subpix_trim = static_cast<float>(v.Number("subpix_trim"));
  a.subpix_faster = v.Int("subpix_faster");
  return a;
}

cuda::Fxaa311Args Fxaa311ArgsFrom(const Fxaa311Params& p) {
  cuda::Fxaa311Args a{};
  if (p.steps.size() < 2 || p.steps.size() > static_cast<size_t>(cuda::kMaxFxaaSteps)) {
    throw InternalError("FXAA 3.11 step table of " + std::to_string(p.steps.size()) + " entries (the kernel takes 2.." +
                        std::to_string(cuda::kMaxFxaaSteps) + ")");
  }
  for (size_t i = 0; i < p.steps.size(); ++i) a.steps[i] = p.steps[i];
  a.step_count = static_cast<int>(p.steps.size());
  a.subpix = p.subpix;
  a.edge_threshold = p.edge_threshold;
  a.edge_threshold_min = p.edge_threshold_min;
  a.luma = static_cast<cuda::LumaSource>(static_cast<int>(p.luma));
  a.seed003_order = p.order == Fxaa311Params::Order::kSeed003Glsl ? 1 : 0;
  return a;
}

// The same fields methods/smaa.cpp's registry rows read (SmaaEntry).
cuda::SmaaArgs SmaaArgsFrom(const ParamValues& v) {
  cuda::SmaaArgs a{};
  a.threshold = static_cast<float>(v.Number("threshold"));
  a.max_search_steps = v.Int("max_search_steps");
  a.max_search_steps_diag = v.Int("max_search_steps_diag");
  a.corner_rounding = v.Int("corner_rounding");
  a.local_contrast = static_cast<float>(v.Number("local_contrast"));
  a.diag = v.Choice("diag") == "on" ? 1 : 0;
  a.corner = v.Choice("corner") == "on" ? 1 : 0;
  a.color = v.Choice("detection") == "color" ? 1 : 0;
  a.fixed8 = v.Choice("subtexel") == "exact" ? 0 : 1;
  return a;
}

bool IsSmaaName(const std::string& n) { return n.rfind("smaa-", 0) == 0; }

// The step table and float order of an FXAA 3.11 registry row, from the CPU tables.
Fxaa311Params Fxaa311ParamsFor(const MethodPlan& plan) {
  Fxaa311Params p;
  const std::string& n = plan.name;
  if (n.rfind("fxaa311-p", 0) == 0) {
    p.steps = Fxaa311PresetSteps(std::stoi(n.substr(9)));
  } else if (n == "fxaa-low" || n == "fxaa-medium" || n == "fxaa-high") {
    p.steps = FxaaTutorialSteps(n.substr(5));
  } else if (n == "fxaa-iter12") {
    p.steps = Fxaa311PresetSteps(39);
    p.order = Fxaa311Params::Order::kSeed003Glsl;
  } else {
    throw InternalError("no FXAA 3.11 step table for '" + n + "'");
  }
  p.subpix = static_cast<float>(plan.params.Number("subpix"));
  p.edge_threshold = static_cast<float>(plan.params.Number("edge_threshold"));
  p.edge_threshold_min = static_cast<float>(plan.params.Number("edge_threshold_min"));
  p.luma = ParseFxaa311Luma(plan.params.Choice("luma"));
  return p;
}

bool IsFxaa311Name(const std::string& n) {
  return n.rfind("fxaa311-p", 0) == 0 || n == "fxaa-low" || n == "fxaa-medium" || n == "fxaa-high" ||
         n == "fxaa-iter12";
}

std::string LumaKernelName(Fxaa311Params::Luma l) {
  return l == Fxaa311Params::Luma::kRec601 ? "luma-rec601" : "luma-sqrt-luminance";
}

}  // namespace

GpuMethod ResolveGpuMethod(const std::string& spec) {
  GpuMethod m;
  m.plan = MakeMethod(spec);
  m.spec = m.plan.spec;
  const std::string& n = m.plan.name;
  if (n.rfind("fxaa1-p", 0) == 0) {
    m.fxaa1 = true;
    m.f1 = Fxaa1ArgsFrom(m.plan.params);
    m.kernels = "fxaa1";
    return m;
  }
  if (IsFxaa311Name(n)) {
    const Fxaa311Params p = Fxaa311ParamsFor(m.plan);
    m.fxaa311 = true;
    m.f3 = Fxaa311ArgsFrom(p);
    m.prepass = p.luma == Fxaa311Params::Luma::kRec601 || p.luma == Fxaa311Params::Luma::kSqrtLuminance;
    m.kernels = (m.prepass ? LumaKernelName(p.luma) + " + " : "") + "fxaa311";
    return m;
  }
  if (IsSmaaName(n)) {
    m.smaa = true;
    m.sm = SmaaArgsFrom(m.plan.params);
    m.kernels = std::string(kSmaaPassNames[0]) + " + " + kSmaaPassNames[1] + " + " + kSmaaPassNames[2];
    return m;
  }
  if (n == "scale43" || n == "scale43-fxaa-high") {
    m.scaled_input = true;
    m.rescale = m.plan.rescale;
    const std::string rk = m.rescale == Rescale::kBicubic ? "rescale-bicubic" : "rescale-bilinear";
    if (n == "scale43-fxaa-high") {
      const Fxaa311Params p = FxaaTutorialHighParams();  // what render_scale.cpp runs
      m.fxaa311 = true;
      m.f3 = Fxaa311ArgsFrom(p);
      m.prepass = true;
      m.kernels = LumaKernelName(p.luma) + " + fxaa311 + " + rk;
    } else {
      m.kernels = rk;
    }
    return m;
  }
  throw UserError("method '" + spec + "' has no CUDA twin (GPU kernels exist for fxaa1-p*, fxaa311-p*, fxaa-low, "
                  "fxaa-medium, fxaa-high, fxaa-iter12, smaa-low, smaa-medium, smaa-high, smaa-ultra, scale43, "
                  "scale43-fxaa-high; taa through --taa-frames)");
}

std::vector<std::string> DefaultGpuMethodSpecs() {
  std::vector<std::string> specs;
  for (const auto& e : MethodRegistry()) {
    if (e.name.rfind("fxaa1-p", 0) == 0 || IsFxaa311Name(e.name) || IsSmaaName(e.name)) specs.push_back(e.name);
  }
  for (const char* s : {"scale43", "scale43:rescale=bicubic", "scale43-fxaa-high", "scale43-fxaa-high:rescale=bicubic"}) {
    specs.push_back(s);
  }
  return specs;
}

Image8 CpuOutput(const GpuMethod& m, const Image8& frame, int out_w, int out_h, SamplerArithmetic sampler) {
  PostOptions opt;
  opt.sampler = sampler;
  Image8 out = m.plan.post ? m.plan.post(frame, opt, nullptr) : frame;
  if (m.plan.rescale != Rescale::kNone) out = RescaleFrame(out, out_w, out_h, m.plan.rescale, nullptr, sampler);
  return out;
}

GpuPipeline::GpuPipeline(int in_w, int in_h, int out_w, int out_h, const float* srgb_decode)
    : in_w_(in_w), in_h_(in_h), out_w_(out_w), out_h_(out_h), decode_(srgb_decode) {
  in_ = std::make_unique<cuda::GpuFrame>(in_w, in_h);
  luma_ = std::make_unique<cuda::GpuFrame>(in_w, in_h);
  mid_ = std::make_unique<cuda::GpuFrame>(in_w, in_h);
  out_ = std::make_unique<cuda::GpuFrame>(out_w, out_h);
  copy_src_ = std::make_unique<cuda::GpuFrame>(out_w, out_h);
  const size_t bytes = static_cast<size_t>(out_w) * out_h * 4;
  const size_t padded = (bytes + 15) / 16 * 16;
  cuda::Check(cudaMalloc(&lin_in_, padded), "cudaMalloc");
  cuda::Check(cudaMalloc(&lin_out_, padded), "cudaMalloc");
  cuda::Check(cudaMemset(lin_in_, 0x5A, padded), "cudaMemset");
}

GpuPipeline::~GpuPipeline() {
  cudaFree(lin_in_);
  cudaFree(lin_out_);
}

void GpuPipeline::Upload(const Image8& frame) {
  AALAB_CHECK(frame.Width() == in_w_ && frame.Height() == in_h_ && frame.Channels() == 4, "GpuPipeline: frame size");
  in_->Upload(frame.Data().data());
  if (in_w_ == out_w_ && in_h_ == out_h_) {
    copy_src_->Upload(frame.Data().data());
    cuda::Check(cudaMemcpy(lin_in_, frame.Data().data(), frame.Data().size(), cudaMemcpyHostToDevice), "upload");
  }
}

void GpuPipeline::Run(const GpuMethod& m, cudaStream_t stream, bool software_filter) {
  const cuda::GpuFrame* src = in_.get();
  if (m.smaa) {
    AALAB_CHECK(in_w_ == out_w_ && in_h_ == out_h_, "GpuPipeline: SMAA runs at the output size");
    if (!smaa_area_) {
      const Image8& area = SmaaAreaTexture();
      const Image8& search = SmaaSearchTexture();
      smaa_area_ = std::make_unique<cuda::GpuFrame>(area.Width(), area.Height());
      smaa_area_->Upload(area.Data().data());
      smaa_search_ = std::make_unique<cuda::GpuFrame>(search.Width(), search.Height());
      smaa_search_->Upload(search.Data().data());
    }
    // Edge target in luma_, blend target in mid_ (both the input's size; unused by SMAA otherwise).
    cuda::LaunchSmaaEdges(*in_, *luma_, m.sm, stream, software_filter);
    cuda::LaunchSmaaWeights(*luma_, *smaa_area_, *smaa_search_, *mid_, m.sm, stream, software_filter);
    cuda::LaunchSmaaBlend(*in_, *mid_, *out_, m.sm, stream, software_filter);
    return;
  }
  if (m.prepass) {
    cuda::LaunchLumaPrepass(*src, *luma_, m.f3.luma, decode_, stream, software_filter);
    src = luma_.get();
  }
  cuda::GpuFrame* fxaa_dst = m.rescale != Rescale::kNone ? mid_.get() : out_.get();
  if (m.fxaa1) {
    cuda::LaunchFxaa1(*src, *fxaa_dst, m.f1, stream, software_filter);
    src = fxaa_dst;
  }
  if (m.fxaa311) {
    cuda::LaunchFxaa311(*src, *fxaa_dst, m.f3, stream, software_filter);
    src = fxaa_dst;
  }
  if (m.rescale != Rescale::kNone) {
    cuda::LaunchRescale(*src, *out_, m.rescale == Rescale::kBicubic, stream, software_filter);
  }
}

void GpuPipeline::RunPassOnly(const GpuMethod& m, cudaStream_t stream) {
  AALAB_CHECK(m.prepass && m.rescale == Rescale::kNone, "RunPassOnly: a 1x FXAA 3.11 method with a pre-pass");
  cuda::LaunchFxaa311(*luma_, *out_, m.f3, stream);
}

void GpuPipeline::RunSmaaPass(const GpuMethod& m, int pass, cudaStream_t stream) {
  AALAB_CHECK(m.smaa && smaa_area_, "RunSmaaPass: an SMAA method after its Run");
  if (pass == 0) cuda::LaunchSmaaEdges(*in_, *luma_, m.sm, stream);
  if (pass == 1) cuda::LaunchSmaaWeights(*luma_, *smaa_area_, *smaa_search_, *mid_, m.sm, stream);
  if (pass == 2) cuda::LaunchSmaaBlend(*in_, *mid_, *out_, m.sm, stream);
}

void GpuPipeline::RunCopyTexture(cudaStream_t stream) { cuda::LaunchCopyTexture(*copy_src_, *out_, stream); }

void GpuPipeline::RunCopyLinear(cudaStream_t stream) {
  const size_t bytes = static_cast<size_t>(out_w_) * out_h_ * 4;
  cuda::LaunchCopyLinear(lin_in_, lin_out_, (bytes + 15) / 16 * 16, stream);
}

void GpuPipeline::PoisonOutput() {
  std::vector<uint8_t> poison(static_cast<size_t>(out_w_) * out_h_ * 4, 0xA5);
  out_->Upload(poison.data());
}

Image8 GpuPipeline::Output() const {
  Image8 img(out_w_, out_h_, 4);
  out_->Download(img.Data().data());
  return img;
}

}  // namespace aalab
