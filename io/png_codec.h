/// PNG through libpng directly (no OpenImageIO): the encoder writes the bytes OpenImageIO
/// 2.4's PNG writer writes for the spec io/image_io.cpp gives it, and the decoder reads what
/// its PNG reader reads (channels, names, values). Internal to io/.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/image_decoder.h"

namespace aalab::io_detail {

/// Encodes w×h pixels of nc (1..4) interleaved channels, 8-bit (`sixteen` false) or 16-bit
/// (host-endian uint16). `filter_none`: png:filter 0x08 (PNG_FILTER_NONE), else OIIO's
/// default (png_set_filter(…, 0)). `text`: tEXt chunks, renamed as OIIO renames them.
/// Returns false with `error` set on a libpng error.
bool EncodePng(int w, int h, int nc, bool sixteen, const void* data, bool filter_none,
               const std::vector<std::pair<std::string, std::string>>* text, std::string* bytes, std::string* error);

/// Opens a PNG file (`data` null) or `size` bytes in memory and reads its header; nullptr with
/// `error` set (OIIO's messages: "Not a PNG file", "PNG read error: ...") when it cannot.
std::unique_ptr<ImageDecoder> OpenPng(const std::string& path, const uint8_t* data, size_t size, std::string* error);

}  // namespace aalab::io_detail
