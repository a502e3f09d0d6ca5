/// `aalab export`'s crop figure: the reference and each chosen method at the report's crop
/// windows, zoomed by pixel replication (nearest neighbour), labelled, optionally with a row
/// of absolute-error heatmaps under each crop (the HTML report's viridis map, 0 → ≥ 0.25).
/// One layout, two writers: an RGBA8 raster for PNG and an SVG whose image pixels are vector
/// squares (docs/publishing.md says why).
#pragma once
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "core/image.h"
#include "reports/export_source.h"

namespace aalab {

/// What the figure shows. Empty fields take the defaults of DefaultCropFigure.
struct CropFigureOptions {
  std::string scene;
  std::vector<std::string> methods;       ///< specs (from every report, in that order)
  std::vector<std::array<int, 4>> crops;  ///< [x, y, w, h] in output pixels
  int zoom = 0;                           ///< pixel replication factor; 0 = tiles of about 128 px
  bool heatmap = false;                   ///< add the error heatmap row under each crop
};

/// Defaults for the default suite: the scene (of `scenes`) where the chosen metric spreads
/// most over the figure's methods, methods `none`, `ssaa-4x4`, `msaa-4x`, `fxaa-high`,
/// `smaa-high`, `aaa`, `taa` as far as the report has them (else its first five), the
/// scene's first two crop windows, zoom for tiles of about 128 px. Checks given choices:
/// an unknown scene or method, a crop outside the image or one larger than 256 px, a zoom
/// outside 1..32 → UserError.
CropFigureOptions DefaultCropFigure(const std::vector<ExportSource>& sources, const ExportSelection& sel,
                                    const CropFigureOptions& asked);

/// One image tile of the figure: which pixels of which file, where.
struct FigureTile {
  int x = 0, y = 0;  ///< top-left in figure pixels
  int zoom = 1;
  std::array<int, 4> crop{};  ///< source rectangle [x, y, w, h]
  std::string path;           ///< image file (relative to the report folder of `source`)
  size_t source = 0;          ///< index into the sources
  bool heatmap = false;       ///< |this − reference| through viridis instead of the image
};

/// A text label (left-aligned at x, baseline at y), `size` px high.
struct FigureLabel {
  int x = 0, y = 0, size = 12;
  std::string text;
};

/// The figure: its size, tiles and labels, and the raster with the tiles drawn (labels are
/// drawn by the caller's text renderer; see ComposeCropFigure).
struct CropFigure {
  int width = 0, height = 0;
  std::vector<FigureTile> tiles;
  std::vector<FigureLabel> labels;
  std::string reference_path;  ///< the reference PNG of source 0, for the heatmaps
  Image8 pixels;               ///< RGBA8, white background, tiles drawn
};

/// Reads an 8-bit image (the CLI passes io's ReadImage8) by source index and path
/// relative to that source's report folder.
using ImageLoader = std::function<Image8(size_t source, const std::string& path)>;

/// Lays out and draws the figure. Heatmap tiles: per pixel mean over RGB of |method −
/// reference| of the 8-bit PNGs (values k/255) through metrics/heatmap.h's viridis with full
/// scale kErrorHeatmapMax — what the HTML report's page draws.
CropFigure ComposeCropFigure(const std::vector<ExportSource>& sources, const CropFigureOptions& options,
                             const ImageLoader& load);

/// The figure as a stand-alone SVG: labels as text, every image pixel as a square of its
/// colour (equal neighbours in a row merged into one path segment), so any viewer or
/// converter shows the exact nearest-neighbour zoom. `provenance` goes into a comment and
/// <metadata>.
std::string CropFigureToSvg(const CropFigure& fig, const std::vector<std::string>& provenance);

/// Escapes text for XML content and attributes.
std::string XmlEscape(const std::string& text);

}  // namespace aalab
