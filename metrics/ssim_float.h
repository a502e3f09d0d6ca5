/// SSIM's production kernels (metrics/ssim_float.cpp): window sums in float32 over
/// tile-centred values, the map in double. Internal to metrics/ssim.cpp; the definition, the
/// precision bound and its derivation are in the block atop metrics/ssim_float.cpp.
#pragma once
#include <array>
#include <vector>

#include "core/image.h"

namespace aalab::ssim_float {

/// Output rows per tile (one parallel chunk) and output columns per tile (one strip). Every
/// tile has its own centre per image and channel; the tiling depends on the image size alone.
inline constexpr int kTileRows = 64;
inline constexpr int kTileCols = 256;

/// The reference's half of one channel: its float window sums E_w[y − c] and E_w[(y − c)²]
/// over the valid region (nx × ny, row-major) and the centre c of every tile (row-major,
/// tiles_x per row).
struct ReferencePlanes {
  std::vector<float> s1, s2;
  std::vector<float> centre;
};

/// The centre of the tile whose output block starts at (x0, y0) (sx × sy outputs): the mean
/// of the channel over a fixed subsample of the tile's input block, rounded to float (0 when
/// that mean is not finite).
float TileCentre(const ImageF& img, int c, int x0, int y0, int sx, int sy);

/// Mean SSIM map of channels 0, 1, 2 over the valid region; `map_out`, when not null,
/// receives channel `map_channel`'s map (nx × ny, row-major). `w`: the normalised double
/// window of metrics/ssim.cpp.
std::array<double, 3> Ssim(const ImageF& a, const ImageF& b, const std::array<double, 11>& w, int map_channel,
                           double* map_out);

/// The reference's half (b's window sums and tile centres), per channel.
std::array<ReferencePlanes, 3> Prepare(const ImageF& b, const std::array<double, 11>& w);

/// Ssim(a, b) with b's half from Prepare: the same bits.
std::array<double, 3> SsimPrepared(const ImageF& a, const ImageF& b, const std::array<ReferencePlanes, 3>& side,
                                   const std::array<double, 11>& w);

}  // namespace aalab::ssim_float
