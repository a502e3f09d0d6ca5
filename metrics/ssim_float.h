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

/// Mean SSIM map of channel c over the valid region; `map_out`, when not null, receives the
/// map (nx × ny, row-major). `w`: the normalised double window of metrics/ssim.cpp.
double ChannelSsim(const ImageF& a, const ImageF& b, int c, const std::array<double, 11>& w, double* map_out);

/// The reference's half of channel c (b's window sums and tile centres).
ReferencePlanes PrepareChannel(const ImageF& b, int c, const std::array<double, 11>& w);

/// ChannelSsim(a, b, c) with b's half from PrepareChannel: the same bits.
double ChannelSsimPrepared(const ImageF& a, const ImageF& b, const ReferencePlanes& side, int c,
                           const std::array<double, 11>& w, double* map_out);

}  // namespace aalab::ssim_float
