/// TAA on the GPU (methods/cuda/taa.cu) over a sequence: the kernels chained on their
/// device-resident history, checked frame by frame against the CPU method (TaaState, from the
/// registry) on the same inputs, and timed per frame (docs/gpu.md).
#pragma once
#include <cuda_runtime_api.h>

#include <string>
#include <vector>

#include "gpu/measure.h"
#include "core/image.h"

namespace aalab {

/// TAA's inputs over frames 0..n-1: the jittered renders and, for t >= 1, the previous
/// positions (TemporalInput::previous; previous[0] is empty).
struct TaaInput {
  std::vector<Image8> frames;
  std::vector<std::vector<float>> previous;
};

/// A synthetic sequence for --self-test: hard-edged shapes with per-frame noise, moving by
/// (0.37, 0.13) px a frame, with a block of NaN positions (no history) and positions past
/// the left and top borders (off-screen).
TaaInput SyntheticTaaSequence(int width, int height, int frames);

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

/// The spec of every TAA method the tool runs by default ("taa").
std::vector<std::string> DefaultGpuTaaSpecs();

}  // namespace aalab
