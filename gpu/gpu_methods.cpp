#include "gpu/gpu_methods.h"

#include <stdexcept>

#include "core/error.h"
#include "core/params.h"
#include "methods/fxaa1.h"
#include "methods/fxaa311.h"
#include "methods/registry.h"
#include "methods/rescale.h"
#include "methods/smaa.h"

namespace aalab {
namespace {

cuda::Fxaa1Args Fxaa1ArgsFrom(const Fxaa1Params& p) {
  cuda::Fxaa1Args a{};
  // The typed parameters methods/fxaa1.cpp's post filter runs with (MethodPlan::config).
  a.edge_threshold = p.edge_threshold;
  a.edge_threshold_min = p.edge_threshold_min;
  a.search_steps = p.search_steps;
  a.search_acceleration = p.search_acceleration;
  a.search_threshold = p.search_threshold;
  a.subpix_cap = p.subpix_cap;
  a.subpix_trim = p.subpix_trim;
  a.subpix_faster = p.subpix_faster ? 1 : 0;
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

// The typed parameters methods/smaa.cpp's post filter runs with (MethodPlan::config).
cuda::SmaaArgs SmaaArgsFrom(const SmaaParams& p) {
  cuda::SmaaArgs a{};
  a.threshold = p.threshold;
  a.max_search_steps = p.max_search_steps;
  a.max_search_steps_diag = p.max_search_steps_diag;
  a.corner_rounding = p.corner_rounding;
  a.local_contrast = p.local_contrast_factor;
  a.diag = p.diag ? 1 : 0;
  a.corner = p.corner ? 1 : 0;
  a.color = p.detection == SmaaParams::Detection::kColor ? 1 : 0;
  a.fixed8 = p.subtexel == SubTexel::kExact ? 0 : 1;
  return a;
}

std::string LumaKernelName(Fxaa311Params::Luma l) {
  return l == Fxaa311Params::Luma::kRec601 ? "luma-rec601" : "luma-sqrt-luminance";
}

// The registry rows the GPU runs through ResolveGpuMethod: a CUDA twin and no memory (TAA
// runs through --taa-frames, gpu/taa_gpu.cpp).
std::vector<const MethodEntry*> GpuRows() {
  std::vector<const MethodEntry*> rows;
  for (const auto& e : MethodRegistry()) {
    if (e.has_gpu_twin && !MakeMethod(e.name).NeedsHistory()) rows.push_back(&e);
  }
  return rows;
}

}  // namespace

GpuMethod ResolveGpuMethod(const std::string& spec) {
  GpuMethod m;
  m.plan = MakeMethod(spec);
  m.spec = m.plan.spec;
  const MethodPlan& plan = m.plan;
  if (!plan.has_gpu_twin || plan.NeedsHistory()) {
    std::vector<std::string> names;
    for (const MethodEntry* e : GpuRows()) names.push_back(e->name);
    throw UserError("method '" + spec + "' has no CUDA twin (GPU kernels exist for " + JoinNames(names) +
                    "; taa through --taa-frames)");
  }
  // A method that renders at another scale reads the scaled frame and rescales after its
  // post filter (render_scale.cpp: scale43, scale43-fxaa-high).
  m.scaled_input = plan.rescale != Rescale::kNone;
  m.rescale = plan.rescale;
  std::vector<std::string> kernels;
  if (const auto* p = plan.Config<Fxaa1Params>()) {
    m.fxaa1 = true;
    m.f1 = Fxaa1ArgsFrom(*p);
    kernels.push_back("fxaa1");
  } else if (const auto* p3 = plan.Config<Fxaa311Params>()) {
    m.fxaa311 = true;
    m.f3 = Fxaa311ArgsFrom(*p3);
    m.prepass = p3->luma == Fxaa311Params::Luma::kRec601 || p3->luma == Fxaa311Params::Luma::kSqrtLuminance;
    if (m.prepass) kernels.push_back(LumaKernelName(p3->luma));
    kernels.push_back("fxaa311");
  } else if (const auto* ps = plan.Config<SmaaParams>()) {
    m.smaa = true;
    m.sm = SmaaArgsFrom(*ps);
    kernels.insert(kernels.end(), std::begin(kSmaaPassNames), std::end(kSmaaPassNames));
  } else if (plan.post) {
    throw InternalError("method '" + plan.name +
                        "' is marked as having a CUDA twin but its post filter has no typed configuration");
  }
  if (m.scaled_input) kernels.push_back(m.rescale == Rescale::kBicubic ? "rescale-bicubic" : "rescale-bilinear");
  for (const auto& k : kernels) m.kernels += (m.kernels.empty() ? "" : " + ") + k;
  return m;
}

std::vector<std::string> DefaultGpuMethodSpecs() {
  // Every GPU row at its defaults; the rescaling rows (render scale) once more with each other
  // choice of their `rescale` parameter, after the post filters.
  std::vector<std::string> specs, scaled;
  for (const MethodEntry* e : GpuRows()) {
    const MethodPlan plan = MakeMethod(e->name);
    if (plan.rescale == Rescale::kNone) {
      specs.push_back(e->name);
      continue;
    }
    scaled.push_back(e->name);
    for (const auto& def : e->params) {
      if (def.name != "rescale") continue;
      for (const auto& choice : def.choices) {
        if (choice != def.default_choice) scaled.push_back(e->name + ":rescale=" + choice);
      }
    }
  }
  specs.insert(specs.end(), scaled.begin(), scaled.end());
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
