/// Text on an 8-bit image through OpenImageIO's text renderer (FreeType, in the module io/oiio_loader.h loads) with the
/// DejaVu Sans font of Debian's fonts-dejavu-core: the labels of `aalab export`'s PNG figures.
#pragma once
#include <string>

#include "core/image.h"

namespace aalab {

/// Draws `text` in black, `size_px` pixels high, left-aligned at x with its baseline at y,
/// blended over `img` (RGBA8) by the glyphs' coverage. Throws UserError naming the package to
/// install when no DejaVu Sans font is found.
void DrawText(Image8& img, int x, int y, const std::string& text, int size_px);

}  // namespace aalab
