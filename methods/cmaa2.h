/// Intel's Conservative Morphological Anti-Aliasing 2.3 (CMAA2.hlsl, GameTechDev/CMAA2), single
/// sample, as its sample runs it on an 8-bit sRGB frame: an R8G8B8A8_UNORM_SRGB view read as
/// linear colour, a typed R8G8B8A8_UNORM store with the shader's own linear-to-sRGB conversion.
/// docs/cmaa2.md; methods/cmaa2.cpp says what the port does where the shader is unspecified.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "methods/method.h"

namespace aalab {

/// The shader's compile-time options that change results.
struct Cmaa2Params {
  int preset = 2;                ///< CMAA2_STATIC_QUALITY_PRESET: 0 LOW, 1 MEDIUM, 2 HIGH (default), 3 ULTRA
  bool extra_sharpness = false;  ///< CMAA2_EXTRA_SHARPNESS
  bool color_edges = false;      ///< CMAA2_EDGE_DETECTION_LUMA_PATH 0 (colour differences) instead of 1 (luma)
  /// Sum each pixel's blend items in the reverse of the port's order (a diagnostic: how much
  /// the result depends on the order the GPU's atomics happen to give; never set by methods).
  bool reverse_sum = false;
  /// The lock-step width of the port's order (methods/cmaa2.cpp): threads of a workgroup run
  /// each statement in waves of this many lanes. 32 in aalab; the oracle sets lavapipe's.
  int lanes = 32;
};

/// What one run did (counts over the frame).
struct Cmaa2Stats {
  uint64_t candidates = 0;       ///< pixels appended to the shape-candidate list
  uint64_t blend_items = 0;      ///< colour samples stored to the deferred per-quad lists
  uint64_t z_shapes = 0;         ///< Z shapes blended
  uint64_t slm_fallbacks = 0;    ///< Z shapes that did not fit the 768-item group buffer (BlendZs path)
  uint64_t pixels_written = 0;   ///< pixels DeferredColorApply2x2CS stores
  uint64_t truncated_quads = 0;  ///< quads whose list is longer than the apply pass's 32-item walk
};

/// The linear value the sRGB view returns for code k: the IEC 61966-2-1 decode of k/255,
/// worked out in double and rounded to float once.
float Cmaa2SrgbToLinear(uint8_t k);

/// The shader's LINEAR_to_SRGB (x·12.92 below 0.0031308, else 1.055·x^(1/2.4) − 0.055), float.
float Cmaa2LinearToSrgb(float x);

/// Pack_R11G11B10_E4_FLOAT then Unpack_R11G11B10_E4_FLOAT: the colour as the deferred list
/// keeps it (clamped to [0, 2), 7-bit mantissas for r and g, 6 for b).
std::array<float, 3> Cmaa2PackUnpack(const std::array<float, 3>& rgb);

/// Runs the four passes on linear colour (w·h·3 floats, row-major): returns the colours after
/// DeferredColorApply2x2CS, linear, before the store (untouched pixels keep their input value);
/// `written` (optional) gets 1 where the apply pass stores.
std::vector<float> Cmaa2Linear(const std::vector<float>& rgb, int w, int h, const Cmaa2Params& p,
                               std::vector<uint8_t>* written = nullptr, Cmaa2Stats* stats = nullptr);

/// CMAA2 on an RGBA8 sRGB frame: untouched pixels keep their bytes; written pixels get the
/// shader's sRGB conversion and the UNORM8 store (round to nearest even); alpha is kept.
Image8 Cmaa2(const Image8& in, const Cmaa2Params& p, Cmaa2Stats* stats = nullptr);

}  // namespace aalab
