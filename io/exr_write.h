/// OpenEXR writing through the OpenEXR library directly (no OpenImageIO): the bytes
/// OpenImageIO 2.4's EXR writer wrote for the spec io/image_io.cpp gave it. Internal to io/.
#pragma once
#include <string>

namespace aalab::io_detail {

/// Encodes w×h pixels of nc (>= 1) interleaved float channels as a scanline EXR: channels
/// named as OIIO names them by default (1: Y; else R, G, B, A, channel4, ...), 32-bit float,
/// ZIP compression (level 4), increasing-Y lines, a capDate attribute of "" (what OIIO
/// writes for DateTime ""). false with `error` set when OpenEXR throws.
bool EncodeExrFloat(int w, int h, int nc, const float* data, std::string* bytes, std::string* error);

}  // namespace aalab::io_detail
