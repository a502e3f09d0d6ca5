/// A measurement of the texture unit's bilinear weights: how finely the hardware resolves
/// the sub-texel fraction, which is what makes GPU and CPU post-filter outputs differ.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace aalab {

/// Result of ProbeTextureFilter, errors in 8-bit code units (1/255).
struct TextureProbe {
  int samples = 0;               ///< fractions probed: f = i/4096, i = 0..4096
  double err_float = 0;          ///< max |GPU − lerp with the float32 fraction| (the CPU model)
  double err_round256 = 0;       ///< max |GPU − lerp with the fraction rounded to 1/256|
  double err_trunc256 = 0;       ///< max |GPU − lerp with the fraction truncated to 1/256|
  int distinct_values = 0;       ///< distinct filtered values seen between texels 0 and 255
  int unorm_mismatches = 0;      ///< point fetches of k = 0..255 whose float is not k / 255.0f
  int unorm_mismatches_cpu = 0;  ///< ... whose float is not the CPU's UnormToFloat(k) = k·fl(1/255)
  int half_pairs = 0;            ///< texel pairs (a, b) fetched halfway between their centres
  int half_mismatches = 0;       ///< of those, results that differ from the CPU sampler's (float32)
  double half_max_err = 0;       ///< their largest |difference| (float units, not levels)
};

/// Samples a 2×1 RGBA8 texture holding 0 and 255 (red) through a bilinear, unnormalised view
/// at u = 0.5 + i/4096 and compares with the three weight models; then point-fetches all 256
/// UNORM8 values, and fetches every pair (a, b) halfway between the two texels, against the
/// CPU sampler's float32 arithmetic. Throws on a CUDA error.
TextureProbe ProbeTextureFilter();

}  // namespace aalab

namespace aalab {

/// Raw data of the texture unit's bilinear arithmetic (aalab_gpu --probe-dump writes it as
/// little-endian files; scripts/fit_texture_rule.py fits the rule offline, CheckTextureRule
/// checks core/sampler.h's rule against it on the device):
///   pairs.bin      int32 count, the 8-bit weights k, then float32 [k][a][b]: the R channel
///                  fetched at u = 2b + 0.5 + k/256 of a 512×256 texture whose row a holds a at
///                  texel 2b and b at 2b + 1 (every pair (a, b) at each fixed weight).
///   quad8_tex.bin  a 1024×512 RGBA8 texture of hashed bytes, row-major.
///   quad8.bin      262 144 records: int16 x, y, kx, ky, then the float4 fetched at
///                  (x + 0.5 + kx/256, y + 0.5 + ky/256).
///   coord.bin      blocks of int32 size, axis (0 = u, 1 = v), normalized, count, then count
///                  float coordinates and count uint16 q (the R result is q/65535), through
///                  size×1 / 1×size textures alternating 0 and 255 (sizes 16, 97, 1080, 1920,
///                  2160, 2560, 3840, 5120).
///   quadf_tex.bin  a 256×256 RGBA32F texture of hashed floats in [0, 1).
///   quadf.bin      131 072 records of it, as quad8.bin.
struct TextureProbeData {
  struct Quad {
    int16_t x, y, kx, ky;
    float out[4];
  };
  struct Coord {
    int32_t size, axis, normalized;
    float coord, out;
  };
  std::vector<int> pair_weights;
  std::vector<float> pairs;
  std::vector<uint8_t> quad8_tex;
  std::vector<Quad> quad8;
  std::vector<Coord> coords;
  std::vector<float> quadf_tex;
  std::vector<Quad> quadf;
};

/// Runs the probe kernels on the device. Throws on a CUDA error.
TextureProbeData CollectTextureProbeData();
/// Writes the files listed above into `dir` (created). Throws on a file error.
void WriteTextureProbeData(const TextureProbeData& data, const std::string& dir);

/// Samples of each kind and how many differ from sampler.h's rule (HwFilter8 with
/// HwWeightsOf, HwFootprintAt / HwFootprintNormalized, HwFilterFloat).
struct TextureRuleCheck {
  long long pairs = 0, pair_mismatches = 0;
  long long quad8 = 0, quad8_mismatches = 0;
  long long coords = 0, coord_mismatches = 0;
  long long quadf = 0, quadf_mismatches = 0;
  long long Mismatches() const { return pair_mismatches + quad8_mismatches + coord_mismatches + quadf_mismatches; }
};
TextureRuleCheck CheckTextureRule(const TextureProbeData& data);

}  // namespace aalab
