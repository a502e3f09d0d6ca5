/// TAA on the GPU (methods/cuda/taa.cu for `taa`, taa_production.cu for `taa-prod`) over a
/// sequence: the kernels chained on their device-resident history, checked frame by frame
/// against the CPU method (from the registry) on the same inputs, and timed per frame
/// (docs/gpu.md).
#pragma once
#include <cuda_runtime_api.h>

#include <string>
#include <vector>

#include "gpu/measure.h"
#include "core/image.h"
#include "core/render_spec.h"

namespace aalab {

/// TAA's inputs over frames 0..n-1: the jittered renders and, for t >= 1, the previous
/// positions (TemporalInput::previous; previous[0] is empty); `taa-prod` also reads each
/// frame's view depth (TemporalInput::depth; `depth` empty: a sequence without depth) and
/// jitter (`jitter` empty: zero).
struct TaaInput {
  std::vector<Image8> frames;
  std::vector<std::vector<float>> previous;
  std::vector<std::vector<float>> depth;
  std::vector<FrameJitter> jitter;
};

/// A synthetic sequence for --self-test: hard-edged shapes with per-frame noise, moving by
/// (0.37, 0.13) px a frame and the disc by (1.6, 0.13) (a motion step at its rim), with a
/// block of NaN positions (no history) and positions past the left and top borders
/// (off-screen). With `with_depth`: depths (disc 3, band 5, background 10 rising along x, the
/// top eighth +Inf, and a depth-only occluder at depth 1.5 that steps 3 px a frame, so that
/// the pixels it leaves are disoccluded) and Halton(2,3) jitter of 16 points.
TaaInput SyntheticTaaSequence(int width, int height, int frames, bool with_depth = false);

/// Runs the TAA spec `spec` over `seq` (width × height frames): per frame the hardware step,
/// a second hardware run (determinism), the software-filter step and the CPU step, each
/// chain on its own history, then (timing) `warmup` + `repeat` launches of the frame's
/// hardware step. Returns the sequence's row: t = the median over frames with a history of
/// each frame's median (frame_ms holds them all), fid = the worst frame of the hardware
/// path, soft = the software-filter path summed over frames. Appends failed checks (output
/// not written, runs differ, software filter not bit-identical) to `failures`.
/// `srgb_decode`: a device table of SrgbDecode8's 256 values.
Entry RunTaaSequence(const std::string& spec, const std::string& scene, const TaaInput& seq, const float* srgb_decode,
                     bool timing, int warmup, int repeat, cudaStream_t stream, std::vector<std::string>* failures);

/// Throws UserError when `spec` is not a TAA spec the tool runs (a registry row with memory
/// and a CUDA twin; for taa-prod, filter=box and sharpen=0): checked before any work.
void CheckGpuTaaSpec(const std::string& spec);

/// The spec of every TAA method the tool runs by default ("taa", "taa-prod").
std::vector<std::string> DefaultGpuTaaSpecs();

}  // namespace aalab
