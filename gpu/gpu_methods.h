/// The bridge between aalab's method registry and the CUDA twins (methods/cuda/): which
/// kernels a method spec runs, with parameters taken from the registry's resolved values
/// and the CPU preset tables, and the CPU output the GPU output is checked against.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "methods/cuda/post_filters_cuda.h"
#include "methods/method.h"

namespace aalab {

/// One method as the GPU runs it.
struct GpuMethod {
  std::string spec;           ///< canonical spec, as a report row's `spec`
  std::string kernels;        ///< the kernels launched, in order ("luma-rec601 + fxaa311")
  bool scaled_input = false;  ///< reads the frame rendered at plan.render.scale (scale43*)
  bool fxaa1 = false;         ///< runs the FXAA 1.0 kernel (args f1)
  bool fxaa311 = false;       ///< runs the FXAA 3.11 kernel (args f3)
  bool prepass = false;       ///< FXAA 3.11 luma pre-pass before the FXAA kernel
  bool smaa = false;          ///< runs SMAA's three kernels (args sm)
  Rescale rescale = Rescale::kNone;
  cuda::Fxaa1Args f1{};
  cuda::Fxaa311Args f3{};
  cuda::SmaaArgs sm{};
  MethodPlan plan;  ///< the CPU method (reference output)
};

/// Resolves `spec` through the registry and maps it to kernels. Throws UserError for a
/// method without a CUDA twin (render-time methods, and post filters not ported), naming
/// the ones that have one.
GpuMethod ResolveGpuMethod(const std::string& spec);

/// Every registered post filter with a CUDA twin at its defaults (FXAA, SMAA), then scale43
/// and scale43-fxaa-high with each rescale filter.
std::vector<std::string> DefaultGpuMethodSpecs();

/// The CPU output for `frame` (the 1x frame, or the scaled frame for scaled_input methods):
/// the method's post filter, then RescaleFrame to out_w × out_h where it rescales.
Image8 CpuOutput(const GpuMethod& m, const Image8& frame, int out_w, int out_h,
                 SamplerArithmetic sampler = SamplerArithmetic::kGl);

/// The SMAA pass names, in launch order, as the JSON's `passes` and docs/gpu.md name them.
inline const char* const kSmaaPassNames[3] = {"smaa-edges", "smaa-weights", "smaa-blend"};

/// GPU buffers for one input frame and the launches of a method's kernels on them.
class GpuPipeline {
 public:
  /// Buffers for an input of in_w × in_h and an output of out_w × out_h; `srgb_decode`
  /// is a device table of SrgbDecode8's 256 values (for the sqrt-luminance pre-pass).
  GpuPipeline(int in_w, int in_h, int out_w, int out_h, const float* srgb_decode);
  ~GpuPipeline();
  GpuPipeline(const GpuPipeline&) = delete;
  GpuPipeline& operator=(const GpuPipeline&) = delete;
  /// Uploads the input frame (RGBA8, in_w × in_h).
  void Upload(const Image8& frame);
  /// Launches every kernel of `m` on `stream` (input → output). software_filter: bilinear
  /// fetches in float32 from point fetches, as the CPU (a fidelity check, not for timing).
  void Run(const GpuMethod& m, cudaStream_t stream, bool software_filter = false);
  /// Launches only the FXAA pass of a pre-pass method (the luma frame of the last Run is
  /// reused): what FXAA costs where the previous pass already wrote luma to alpha.
  void RunPassOnly(const GpuMethod& m, cudaStream_t stream);
  /// Launches SMAA pass `pass` (0 edges, 1 weights, 2 blend) alone, on the targets the last
  /// Run left: each pass's own cost inside the method.
  void RunSmaaPass(const GpuMethod& m, int pass, cudaStream_t stream);
  /// The copy floors at the output size: texture path (point fetch + surface write) and
  /// plain 16-byte global loads/stores of a linear buffer of the same byte count.
  void RunCopyTexture(cudaStream_t stream);
  void RunCopyLinear(cudaStream_t stream);
  /// Fills the output with a byte pattern (0xA5), so unwritten pixels show in checks.
  void PoisonOutput();
  /// Downloads the output frame.
  Image8 Output() const;

 private:
  int in_w_, in_h_, out_w_, out_h_;
  const float* decode_;
  std::unique_ptr<cuda::GpuFrame> in_, luma_, mid_, out_, copy_src_;
  std::unique_ptr<cuda::GpuFrame> smaa_area_, smaa_search_;  // uploaded on the first SMAA run
  void* lin_in_ = nullptr;
  void* lin_out_ = nullptr;
};

}  // namespace aalab
