/// Binary PPM (P6, maxval 255) frames: the exchange format between `aalab export-frames`
/// and the GPU tool, which must not depend on image libraries. RGB on disk, RGBA8 in memory
/// (alpha 255 on reading, dropped on writing).
#pragma once
#include <string>
#include <vector>

#include "core/image.h"

namespace aalab {

/// Reads a P6 file with maxval 255 (comments after the magic allowed) into an RGBA8 frame.
/// Throws UserError naming the path for a missing file, another format, a bad header or
/// truncated pixel data.
Image8 ReadPpm(const std::string& path);

/// Writes rgb of an RGBA8 frame as P6. Written to `path`.tmp and renamed, so a failed write
/// leaves no partial file. Throws UserError when the path is not writable.
void WritePpm(const std::string& path, const Image8& img);

/// TAA's per-pixel previous positions (TemporalInput::previous: x, y per pixel, row-major;
/// NaN for none) for the GPU tool, lossless: a text header "AALABPREV 1 W H\n", then per
/// pixel and coordinate the 32-bit pattern of the position minus that of the pixel centre
/// (x + 0.5 or y + 0.5), modulo 2^32, little-endian. Positions near their centre (small or no
/// motion) become small integers, which compress well; decoding adds the centre's pattern
/// back, so every bit (NaN payloads included) survives. Written to `path`.tmp and renamed.
void WritePreviousPositions(const std::string& path, int width, int height, const std::vector<float>& previous);

/// Reads a file WritePreviousPositions wrote; the size must be width × height. Throws
/// UserError naming the path for a missing file, a bad header, another size or truncation.
std::vector<float> ReadPreviousPositions(const std::string& path, int width, int height);

}  // namespace aalab
