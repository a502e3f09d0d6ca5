// Internals shared by the files of LDR-FLIP's production path (float32); not a public header:
// only metrics/flip_fast.cpp and metrics/flip_planes.cpp include it.
//   flip_fast.cpp    the CSF and feature filters streamed through row rings, the per-pixel
//                    colour transform, the reference's prepared half and the per-row error
//   flip_planes.cpp  the image to YCxCz planes (sRGB decode table, 8-bit code rows in lanes)
// Both files are compiled with the same options (metrics/CMakeLists.txt).
#pragma once
#include <vector>

#include "core/image.h"

/// The float kernels are compiled for AVX-512, AVX2 and the baseline (GCC on x86-64; a plain
/// function elsewhere). With -ffp-contract=off and no fast-math every clone gives the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_FLIP_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define AALAB_FLIP_CLONES
#endif

namespace aalab::flip::fast_detail {

/// Rows per parallel chunk (fixed: results never depend on it).
inline constexpr int kChunkRows = 48;

/// YCxCz planes of an image (float, row-major). The achromatic plane holds Ŷ = (Y + 16) / 116
/// = Y_xyz / Yn rather than Y: the CSF filter is linear with unit sum, so filtering Ŷ and
/// mapping back is the same in exact arithmetic, and float32 keeps the precision of dark
/// pixels (Y = 116·Ŷ − 16 would cancel to a few digits near black).
struct Planes {
  int w = 0, h = 0;
  /// ToPlanes writes every value: storage without a zero-fill (a serial memset of 25 MB at
  /// 1080p ahead of the parallel loop otherwise).
  std::vector<float, DefaultInitAllocator<float>> y, cx, cz;
};

/// The YCxCz planes of `img` (channels 0..2 read as sRGB-encoded R, G, B; any further channel
/// ignored; at least 3 channels, which the callers check), in parallel chunks of kChunkRows
/// rows. Same bits at any thread count and on every clone.
Planes ToPlanes(const ImageF& img);

}  // namespace aalab::flip::fast_detail
