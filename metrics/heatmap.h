/// Heatmaps: a scalar error map → an 8-bit colour image through a perceptual colormap.
#pragma once
#include <array>
#include <string>

#include "core/image.h"

namespace aalab {

/// Full scale of the absolute-error heatmap of the report (sRGB-encoded units): errors ≥ 0.25
/// saturate. The report's page draws that map itself from the output and reference PNGs.
inline constexpr float kErrorHeatmapMax = 0.25f;

/// Perceptually uniform colormaps of matplotlib (van der Walt & Smith, CC0), 256 entries.
enum class Colormap { kViridis, kMagma };

/// Parses "viridis" | "magma"; throws UserError naming the allowed values.
Colormap ParseColormap(const std::string& name);
/// "viridis" or "magma".
std::string ColormapName(Colormap cmap);

/// Entry `index` (0..255) of the colormap: RGB in [0, 1] as published, i.e. display
/// (sRGB-encoded) values, written to 8 bits without any transform.
std::array<float, 3> ColormapEntry(Colormap cmap, int index);

/// Colours a 1-channel map: v is clamped to [0, vmax] (NaN → 0), mapped to the entry
/// round(255 · v / vmax) (round half up), and that entry is quantised to 8 bits by
/// round-to-nearest. Returns RGBA8 (alpha 255), the frame layout WriteImage8 expects.
/// So 0 → entry 0 and any v >= vmax → entry 255. Throws UserError when `map` does not have
/// exactly 1 channel or `vmax` is not a finite number > 0.
Image8 Heatmap(const ImageF& map, float vmax, Colormap cmap);

}  // namespace aalab
