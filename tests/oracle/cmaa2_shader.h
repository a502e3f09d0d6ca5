// The original CMAA2.hlsl (read from ../shared/third_party/cmaa2 at test time, never copied
// here) compiled by glslang's HLSL front end to SPIR-V and run on lavapipe (tests/oracle/
// vk_compute.h) with the sample's pass sequence: EdgesColor2x2CS, ComputeDispatchArgsCS (2,1,1),
// ProcessCandidatesCS (indirect), ComputeDispatchArgsCS (1,2,1), DeferredColorApply2x2CS
// (indirect). Working copy: the shader's `#error` lines are dropped (glslang's preprocessor
// trips on an apostrophe in one, even when disabled); nothing else is edited.
#pragma once
#include <string>
#include <vector>

namespace aalab::oracle {

/// Runs CMAA2 on linear colour (w·h·3 floats) given to the shader as an RGBA32F texture, with
/// the colour UAV an RGBA32F image (CMAA2_UAV_STORE_TYPED 1, _TYPED_UNORM_FLOAT 0,
/// _CONVERT_TO_SRGB 0: the floats before any conversion come back). Returns w·h·4 floats:
/// the input where the shader did not write, its result where it did.
std::vector<float> RunCmaa2Shader(const std::vector<float>& rgb, int w, int h, int preset, bool extra_sharpness,
                                  bool color_edges);

/// "" when CMAA2.hlsl, glslangValidator and lavapipe are all there, else what is missing.
std::string Cmaa2ShaderAvailable();

}  // namespace aalab::oracle
