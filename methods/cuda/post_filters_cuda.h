/// CUDA twins of the post filters (methods/fxaa1.cpp, fxaa311.cpp, rescale.cpp, smaa.cpp, taa.cpp,
/// taa_production.cpp): the same
/// per-pixel float32 arithmetic, with every fetch going through the GPU's texture units
/// (cudaTextureObject on a uchar4 cudaArray: hardware clamp-to-edge and bilinear filtering)
/// and every output written through a surface, as a render target. Built only where CMake
/// finds a CUDA compiler. Parameters come from the CPU side's registry and preset tables
/// (Fxaa1Preset, Fxaa311PresetSteps, FxaaTutorialSteps, the SMAA and TAA registry rows, the
/// SMAA area and search textures): this file holds no copies of them.
/// The kernels and their deviations from the CPU code are described at the top of each .cu
/// file beside this header (fxaa1, fxaa311, rescale, smaa, taa; gpu_frame for the frame).
#pragma once
#include <cuda_runtime_api.h>

#include <cstdint>

namespace aalab::cuda {

/// An RGBA8 frame resident on the GPU: a cudaArray (block-linear, like a render target)
/// with a surface for writes and three texture views of it. All three use clamp-to-edge
/// addressing and return k/255 floats (cudaReadModeNormalizedFloat):
///   point       point sampling, unnormalised coordinates: exact texel reads at (x+0.5, y+0.5)
///               (FxaaTexTop / FxaaTexOff / texelFetch);
///   linear_px   bilinear filtering, unnormalised coordinates (texel centre at x+0.5);
///   linear_norm bilinear filtering, normalised coordinates in [0, 1] (GL's texture()).
class GpuFrame {
 public:
  /// Allocates a width × height RGBA8 frame. Throws std::runtime_error on a CUDA error.
  GpuFrame(int width, int height);
  ~GpuFrame();
  GpuFrame(const GpuFrame&) = delete;
  GpuFrame& operator=(const GpuFrame&) = delete;
  /// Copies width·height·4 bytes (row-major RGBA8) to the GPU.
  void Upload(const uint8_t* rgba);
  /// Copies the frame back into width·height·4 bytes.
  void Download(uint8_t* rgba) const;
  int Width() const { return width_; }
  int Height() const { return height_; }
  cudaTextureObject_t Point() const { return point_; }
  cudaTextureObject_t LinearPx() const { return linear_px_; }
  cudaTextureObject_t LinearNorm() const { return linear_norm_; }
  cudaSurfaceObject_t Surface() const { return surface_; }

 private:
  int width_ = 0, height_ = 0;
  cudaArray_t array_ = nullptr;
  cudaTextureObject_t point_ = 0, linear_px_ = 0, linear_norm_ = 0;
  cudaSurfaceObject_t surface_ = 0;
};

/// FXAA 1.0 parameters as Fxaa1Params (methods/fxaa1.h), flattened for a kernel argument.
struct Fxaa1Args {
  float edge_threshold, edge_threshold_min;
  int search_steps, search_acceleration;
  float search_threshold, subpix_cap, subpix_trim;
  int subpix_faster;
};

/// Largest FXAA 3.11 step table the kernel takes (preset 39 and fxaa-high have 12).
inline constexpr int kMaxFxaaSteps = 16;

/// Where FXAA 3.11 reads luma (Fxaa311Params::Luma, same order).
enum class LumaSource : int { kRec601 = 0, kRec601Rgb = 1, kGreen = 2, kSqrtLuminance = 3 };

/// FXAA 3.11 parameters as Fxaa311Params (methods/fxaa311.h), flattened.
struct Fxaa311Args {
  float steps[kMaxFxaaSteps];
  int step_count;
  float subpix, edge_threshold, edge_threshold_min;
  LumaSource luma;
  int seed003_order;  ///< 1 = Order::kSeed003Glsl (fxaa-iter12), 0 = Order::kFxaa311
};

/// Copies `in` to `out` through the texture path (point fetch + surface write): the floor
/// every filter above is measured against (same reads and writes, no arithmetic).
void LaunchCopyTexture(const GpuFrame& in, GpuFrame& out, cudaStream_t stream);
/// Copies `bytes` bytes between linear device buffers with 16-byte loads and stores: the
/// memory-bandwidth floor without the texture path. `bytes` must be a multiple of 16.
void LaunchCopyLinear(const void* in, void* out, size_t bytes, cudaStream_t stream);

/// The luma pre-pass of Fxaa311LumaFrame: out = in with alpha = 8-bit luma, for kRec601
/// (dot(rgb, 0.299/0.587/0.114) of the encoded values) and kSqrtLuminance (sqrt of linear
/// luminance; `srgb_decode` is a device table of SrgbDecode8's 256 values), alpha stored
/// with StoreUnorm8. software_filter: texel values as the CPU reads them. Other sources
/// need no pre-pass (the caller does not launch it).
void LaunchLumaPrepass(const GpuFrame& in, GpuFrame& out, LumaSource luma, const float* srgb_decode,
                       cudaStream_t stream, bool software_filter = false);

/// FXAA 1.0 normal output (no debug views) of `in` into `out` (same size).
/// software_filter = true replaces every bilinear fetch by the CPU's float32 bilinear from
/// four point fetches (here and below): a check that the port is exact, not for timing.
void LaunchFxaa1(const GpuFrame& in, GpuFrame& out, const Fxaa1Args& args, cudaStream_t stream,
                 bool software_filter = false);

/// One FXAA 3.11 Quality pass of `in` (luma already in alpha where the source needs the
/// pre-pass) into `out` (same size).
void LaunchFxaa311(const GpuFrame& in, GpuFrame& out, const Fxaa311Args& args, cudaStream_t stream,
                   bool software_filter = false);

/// RescaleFrame (methods/rescale.h) of `in` to out's size: bicubic = false gives one
/// bilinear tap at normalised coordinates, true the B-spline from four bilinear taps.
void LaunchRescale(const GpuFrame& in, GpuFrame& out, bool bicubic, cudaStream_t stream, bool software_filter = false);

/// SMAA 1x parameters as SmaaParams (methods/smaa.h), flattened.
struct SmaaArgs {
  int color;  ///< 1 = SMAAColorEdgeDetectionPS, 0 = SMAALumaEdgeDetectionPS
  float threshold, local_contrast;
  int max_search_steps, max_search_steps_diag, corner_rounding;
  int diag, corner;
  int fixed8;  ///< 1 = SubTexel::kFixed8 (the default), 0 = kExact (software filter only: the
               ///< texture unit always filters with 8-bit fractions)
};

/// SMAA pass 1 (edge detection) of `in` into `edges` (same size): r = left edge, g = top edge
/// (0 or 255), b = a = 0; pixels the shader discards are written 0.
void LaunchSmaaEdges(const GpuFrame& in, GpuFrame& edges, const SmaaArgs& args, cudaStream_t stream,
                     bool software_filter = false);
/// SMAA pass 2 (blending weights) of `edges` into `blend`; `area` and `search` hold
/// SmaaAreaTexture() (160×560) and SmaaSearchTexture() (64×16).
void LaunchSmaaWeights(const GpuFrame& edges, const GpuFrame& area, const GpuFrame& search, GpuFrame& blend,
                       const SmaaArgs& args, cudaStream_t stream, bool software_filter = false);
/// SMAA pass 3 (neighbourhood blending) of `in` with `blend` into `out` (rgb, alpha 255).
void LaunchSmaaBlend(const GpuFrame& in, const GpuFrame& blend, GpuFrame& out, const SmaaArgs& args,
                     cudaStream_t stream, bool software_filter = false);

/// TAA's parameters as methods/taa.cpp's TaaParams (the render-side `samples` is the
/// exported frames' business).
struct TaaArgs {
  float alpha, gamma;
  int clip;  ///< 0 variance, 1 minmax, 2 none
};

/// TAA's history on the GPU: linear display RGB (`taa-prod`: and the frames accumulated in
/// alpha; `taa`: alpha unused), an RGBA32F cudaArray — or RGBA16F with `half` (`taa-prod`'s
/// precision=rgba16f: what engines store) — with a point view, a bilinear view (texel
/// coordinates, clamp-to-edge; the texture unit filters with 8-bit fixed-point weights) and a
/// surface.
class GpuHistory {
 public:
  GpuHistory(int width, int height, bool half = false);
  ~GpuHistory();
  GpuHistory(const GpuHistory&) = delete;
  GpuHistory& operator=(const GpuHistory&) = delete;
  /// Copies the history back, 4 floats per pixel, row-major (halves widened exactly).
  void Download(float* rgba) const;
  bool Half() const { return half_; }
  int Width() const { return width_; }
  int Height() const { return height_; }
  cudaTextureObject_t Point() const { return point_; }
  cudaTextureObject_t Linear() const { return linear_; }
  cudaSurfaceObject_t Surface() const { return surface_; }

 private:
  int width_ = 0, height_ = 0;
  bool half_ = false;
  cudaArray_t array_ = nullptr;
  cudaTextureObject_t point_ = 0, linear_ = 0;
  cudaSurfaceObject_t surface_ = 0;
};

/// One TAA step (TaaState::Step): `frame` (the jittered 8-bit render) with `previous`
/// (device, 2 floats per pixel: the pixel centre's position in the previous frame, NaN for
/// none) against `history` (null on the first frame: every pixel takes the current colour)
/// into `next` (the new history) and `out` (8-bit sRGB, alpha 255). `decode` is a device table
/// of SrgbDecode8's 256 values, `encode_starts` of the 255 thresholds of EncodeSrgb8 (code k
/// starts at encode_starts[k − 1]). software_filter: the history fetch in the CPU's float32
/// arithmetic from point fetches instead of the texture unit's bilinear filter.
void LaunchTaaResolve(const GpuFrame& frame, const float* previous, const GpuHistory* history, GpuHistory& next,
                      GpuFrame& out, const TaaArgs& args, const float* decode, const float* encode_starts,
                      cudaStream_t stream, bool software_filter = false);

/// The production TAA's settings (methods/taa_production.h TaaProdParams) the CUDA twin
/// supports, flattened: the box reconstruction (filter=box), no sharpening, output size = render
/// size (no TAAU). The history's precision is the GpuHistory's.
struct TaaProdArgs {
  int dilate;        ///< 1: motion of the closest depth in 3×3
  int history;       ///< 0 bilinear, 1 Catmull-Rom 4×4, 2 Catmull-Rom without corners (5 taps)
  int disocclusion;  ///< 1: drop history on a depth step (with depth) or a motion step
  float disocclusion_depth, disocclusion_px;
  int clip;  ///< 0 variance, 1 minmax, 2 none
  float gamma;
  int adaptive;  ///< 1: feedback=adaptive, 0: fixed alpha
  float alpha, alpha_min, alpha_max, motion_px;
  int luma_weight;
  float jitter_x, jitter_y;  ///< this frame's jitter (render pixels)
};

/// One frame's per-pixel inputs of the production TAA, device pointers, null where absent:
/// `previous` (2 floats a pixel, as LaunchTaaResolve; null: no history this frame), `depth`
/// (view depth, +Inf background; null: no dilation and no depth test), and the
/// previous frame's `prev_depth` and `prev_previous` (its previous positions: the motion
/// vectors the disocclusion test compares with).
struct TaaProdFrame {
  const float* previous = nullptr;
  const float* depth = nullptr;
  const float* prev_depth = nullptr;
  const float* prev_previous = nullptr;
};

/// One production TAA step (methods/taa_production.cpp TaaProdState::Step, box reconstruction,
/// no sharpening, same size): as LaunchTaaResolve, with `next` holding the new history and
/// its frame counts. `history` and `next` must have the same precision. software_filter: the
/// history fetch from point fetches in the CPU's float32 arithmetic (bit-identical to the CPU);
/// otherwise the texture unit's bilinear filter (history=bilinear: 1 fetch; Catmull-Rom: 9 or
/// 5 bilinear fetches at the combined taps, Karis 2014 / Jimenez 2016).
void LaunchTaaProdResolve(const GpuFrame& frame, const TaaProdFrame& in, const GpuHistory* history, GpuHistory& next,
                          GpuFrame& out, const TaaProdArgs& args, const float* decode, const float* encode_starts,
                          cudaStream_t stream, bool software_filter = false);

/// Throws std::runtime_error naming `what` when `err` is not cudaSuccess.
void Check(cudaError_t err, const char* what);

}  // namespace aalab::cuda
