// aalab export's crop figure (reports/export_crops.h): layout, raster and SVG.
#include "reports/export_crops.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "core/error.h"
#include "metrics/heatmap.h"
#include "reports/html_page.h"

namespace aalab {

namespace {

constexpr int kMargin = 8, kGap = 4, kHeader = 22, kFontPx = 13, kTileTarget = 128, kMaxCrop = 256;

std::string RectText(const std::array<int, 4>& c) {
  return "[" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) + ", " +
         std::to_string(c[3]) + "]";
}

/// The report's scenes' rows of `spec` must carry an output image.
std::string OutputOf(const ExportSource& src, const std::string& scene, const std::string& spec) {
  const ResultRow* row = FindRow(src.report, scene, spec);
  if (!row) throw UserError("method '" + spec + "' has no row on scene '" + scene + "' in report '" + src.dir + "'");
  const auto it = row->images.find("output");
  if (it == row->images.end() || it->second.empty()) {
    throw UserError("method '" + spec + "' has no output image on scene '" + scene + "' in report '" + src.dir + "'" +
                    (row->not_applicable.empty() ? "" : " (not applicable: " + row->not_applicable + ")"));
  }
  return it->second;
}

}  // namespace

// SVG text and attributes need the same five escapes as HTML: one implementation.
std::string XmlEscape(const std::string& text) { return HtmlEscape(text); }

CropFigureOptions DefaultCropFigure(const std::vector<ExportSource>& sources, const ExportSelection& sel,
                                    const CropFigureOptions& asked) {
  const Report& first = sources.front().report;
  CropFigureOptions o = asked;
  if (o.methods.empty()) {
    for (const char* m : {"none", "ssaa-4x4", "msaa-4x", "fxaa-high", "smaa-high", "aaa", "taa"}) {
      if (std::find(sel.methods.begin(), sel.methods.end(), m) != sel.methods.end()) o.methods.push_back(m);
    }
    if (o.methods.size() < 2) {
      o.methods.assign(sel.methods.begin(), sel.methods.begin() + std::min<size_t>(5, sel.methods.size()));
    }
  }
  for (const auto& spec : o.methods) {
    for (const auto& src : sources) {
      bool found = false;
      for (const auto& r : src.report.rows) found = found || r.spec == spec;
      if (!found) throw UserError("--figure-methods: method '" + spec + "' is not in report '" + src.dir + "'");
    }
  }
  if (o.scene.empty()) {
    // The scene where the metric spreads most over the figure's methods: where they differ.
    double best = -1;
    for (const auto& name : sel.scenes) {
      const SceneResult* s = FindScene(first, name);
      if (!s || s->crops.empty() || s->images.count("reference_png") == 0) continue;
      double lo = INFINITY, hi = -INFINITY;
      bool ok = true;
      for (const auto& spec : o.methods) {
        const ResultRow* row = FindRow(first, name, spec);
        const auto v = row ? MetricOf(*row, sel.metric) : std::nullopt;
        if (!v || !row->images.count("output")) {
          ok = false;
          break;
        }
        lo = std::min(lo, *v);
        hi = std::max(hi, *v);
      }
      if (ok && hi - lo > best) {
        best = hi - lo;
        o.scene = name;
      }
    }
    if (o.scene.empty()) {
      for (const auto& name : sel.scenes) {
        const SceneResult* s = FindScene(first, name);
        if (s && !s->crops.empty()) {
          o.scene = name;
          break;
        }
      }
    }
    if (o.scene.empty()) {
      throw UserError("no chosen scene has crop windows (and every figure method an output) in report '" +
                      sources.front().dir + "'; give --figure-scene and --crops X:Y:W:H");
    }
  }
  for (const auto& src : sources) {
    const SceneResult* s = FindScene(src.report, o.scene);
    if (!s) throw UserError("--figure-scene: scene '" + o.scene + "' is not in report '" + src.dir + "'");
  }
  if (asked.methods.empty()) {
    // Default methods without an output on this scene (not applicable on an image scene)
    // are left out rather than refused.
    std::vector<std::string> kept;
    for (const auto& spec : o.methods) {
      bool all = true;
      for (const auto& src : sources) {
        const ResultRow* row = FindRow(src.report, o.scene, spec);
        all = all && row && row->images.count("output") && !row->images.at("output").empty();
      }
      if (all) kept.push_back(spec);
    }
    o.methods = kept;
  }
  const SceneResult* scene = FindScene(first, o.scene);
  if (o.crops.empty()) {
    for (size_t i = 0; i < scene->crops.size() && i < 2; ++i) o.crops.push_back(scene->crops[i]);
    if (o.crops.empty()) {
      throw UserError("scene '" + o.scene + "' has no crop windows in report '" + sources.front().dir +
                      "' (no edge error of none there); give --crops X:Y:W:H");
    }
  }
  for (const auto& c : o.crops) {
    if (c[2] < 1 || c[3] < 1 || c[2] > kMaxCrop || c[3] > kMaxCrop || c[0] < 0 || c[1] < 0 ||
        c[0] + c[2] > scene->width || c[1] + c[3] > scene->height) {
      throw UserError("crop " + RectText(c) + " must lie inside scene '" + o.scene + "' (" +
                      std::to_string(scene->width) + "x" + std::to_string(scene->height) + ") and be 1.." +
                      std::to_string(kMaxCrop) + " px wide and high");
    }
  }
  if (o.zoom == 0) {
    int largest = 1;
    for (const auto& c : o.crops) largest = std::max({largest, c[2], c[3]});
    o.zoom = std::clamp(kTileTarget / largest, 1, 32);
  }
  if (o.zoom < 1 || o.zoom > 32) throw UserError("--zoom " + std::to_string(o.zoom) + " must be 1..32");
  return o;
}

CropFigure ComposeCropFigure(const std::vector<ExportSource>& sources, const CropFigureOptions& o,
                             const ImageLoader& load) {
  CropFigure fig;
  const SceneResult* scene = FindScene(sources.front().report, o.scene);
  AALAB_CHECK(scene && !o.crops.empty() && o.zoom >= 1, "crop figure options not resolved");
  const auto ref_it = scene->images.find("reference_png");
  if (ref_it == scene->images.end()) {
    throw UserError("scene '" + o.scene + "' has no reference_png in report '" + sources.front().dir + "'");
  }
  fig.reference_path = ref_it->second;

  // Columns: the reference, then each method in each report (method-major, so a method's
  // before and after stand side by side).
  struct Column {
    std::string label, path;
    size_t source;
  };
  std::vector<Column> cols{{"Reference", fig.reference_path, 0}};
  for (const auto& spec : o.methods) {
    for (size_t s = 0; s < sources.size(); ++s) {
      cols.push_back(
          {sources.size() > 1 ? spec + " (" + sources[s].label + ")" : spec, OutputOf(sources[s], o.scene, spec), s});
    }
  }
  int tile_w = 0;
  for (const auto& c : o.crops) tile_w = std::max(tile_w, c[2] * o.zoom);
  // A column is as wide as the widest tile or its label (about 0.6 em per character).
  std::vector<int> col_x, col_w;
  int x = kMargin;
  for (const auto& c : cols) {
    const int w = std::max(tile_w, static_cast<int>(c.label.size()) * kFontPx * 6 / 10);
    col_x.push_back(x);
    col_w.push_back(w);
    x += w + kGap;
  }
  fig.width = x - kGap + kMargin;
  int y = kMargin + kHeader;
  for (size_t i = 0; i < cols.size(); ++i) fig.labels.push_back({col_x[i], kMargin + kFontPx, kFontPx, cols[i].label});
  std::vector<std::pair<int, std::array<int, 4>>> rows;  // (y, crop) of each image row
  for (const auto& crop : o.crops) {
    const int h = crop[3] * o.zoom;
    for (size_t i = 0; i < cols.size(); ++i) {
      fig.tiles.push_back({col_x[i], y, o.zoom, crop, cols[i].path, cols[i].source, false});
    }
    y += h + kGap;
    if (o.heatmap) {
      for (size_t i = 1; i < cols.size(); ++i) {
        fig.tiles.push_back({col_x[i], y, o.zoom, crop, cols[i].path, cols[i].source, true});
      }
      // The reference column of a heatmap row holds the scale: a 256-entry viridis bar.
      const int bar_w = std::min(col_w[0], 128), bar_h = 10;
      const int by = y + std::min(h, 3 * kFontPx) - bar_h;
      fig.tiles.push_back({col_x[0], by, 1, {0, 0, bar_w, bar_h}, "", 0, true});
      fig.labels.push_back({col_x[0], by - 4, kFontPx - 2, "|error| (viridis)"});
      fig.labels.push_back({col_x[0], by + bar_h + kFontPx, kFontPx - 2, "0"});
      char full[32];
      std::snprintf(full, sizeof full, "%g+", static_cast<double>(kErrorHeatmapMax));
      const int full_w = static_cast<int>(std::string(full).size()) * (kFontPx - 2) * 65 / 100;
      fig.labels.push_back({col_x[0] + bar_w - full_w, by + bar_h + kFontPx, kFontPx - 2, full});
      y += h + kGap;
    }
  }
  fig.height = y - kGap + kMargin;
  fig.pixels = Image8(fig.width, fig.height, 4, 255);

  std::map<std::pair<size_t, std::string>, Image8> cache;
  auto image = [&](size_t source, const std::string& path) -> const Image8& {
    auto it = cache.find({source, path});
    if (it == cache.end()) {
      Image8 img = load(source, path);
      const SceneResult* s = FindScene(sources[source].report, o.scene);
      if (img.Width() != s->width || img.Height() != s->height) {
        throw UserError("image '" + path + "' of report '" + sources[source].dir + "' is " +
                        std::to_string(img.Width()) + "x" + std::to_string(img.Height()) + ", scene '" + o.scene +
                        "' is " + std::to_string(s->width) + "x" + std::to_string(s->height));
      }
      it = cache.emplace(std::make_pair(source, path), std::move(img)).first;
    }
    return it->second;
  };
  for (const auto& t : fig.tiles) {
    const auto& c = t.crop;
    Image8 tile(c[2], c[3], 4, 255);
    if (t.path.empty()) {  // the heatmap's scale bar
      ImageF ramp(c[2], c[3], 1);
      for (int j = 0; j < c[3]; ++j) {
        for (int i = 0; i < c[2]; ++i) ramp.At(i, j, 0) = kErrorHeatmapMax * i / static_cast<float>(c[2] - 1);
      }
      tile = Heatmap(ramp, kErrorHeatmapMax, Colormap::kViridis);
    } else if (t.heatmap) {
      const Image8& ref = image(0, fig.reference_path);
      const Image8& img = image(t.source, t.path);
      ImageF err(c[2], c[3], 1);
      for (int j = 0; j < c[3]; ++j) {
        for (int i = 0; i < c[2]; ++i) {
          int sum = 0;
          for (int ch = 0; ch < 3; ++ch)
            sum += std::abs(img.At(c[0] + i, c[1] + j, ch) - ref.At(c[0] + i, c[1] + j, ch));
          err.At(i, j, 0) = static_cast<float>(sum / (3.0 * 255.0));
        }
      }
      tile = Heatmap(err, kErrorHeatmapMax, Colormap::kViridis);
    } else {
      const Image8& img = image(t.source, t.path);
      for (int j = 0; j < c[3]; ++j) {
        for (int i = 0; i < c[2]; ++i) {
          for (int ch = 0; ch < 3; ++ch) tile.At(i, j, ch) = img.At(c[0] + i, c[1] + j, ch);
        }
      }
    }
    for (int j = 0; j < c[3] * t.zoom; ++j) {
      for (int i = 0; i < c[2] * t.zoom; ++i) {
        const uint8_t* p = tile.Pixel(i / t.zoom, j / t.zoom);
        uint8_t* q = fig.pixels.Pixel(t.x + i, t.y + j);
        q[0] = p[0];
        q[1] = p[1];
        q[2] = p[2];
        q[3] = 255;
      }
    }
  }
  return fig;
}

std::string CropFigureToSvg(const CropFigure& fig, const std::vector<std::string>& provenance) {
  std::string o = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!--\n";
  for (const auto& line : provenance) o += "  " + XmlEscape(line) + "\n";
  o += "-->\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(fig.width) + "\" height=\"" +
       std::to_string(fig.height) + "\" viewBox=\"0 0 " + std::to_string(fig.width) + " " + std::to_string(fig.height) +
       "\">\n<metadata>";
  for (const auto& line : provenance) o += XmlEscape(line) + "\n";
  o += "</metadata>\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  for (const auto& t : fig.tiles) {
    // One path per colour: each horizontal run of equal pixels is "Mx yhNv1h-Nz" in source
    // pixels, scaled by the zoom. crispEdges keeps the squares' edges unblended.
    o += "<g transform=\"translate(" + std::to_string(t.x) + " " + std::to_string(t.y) + ") scale(" +
         std::to_string(t.zoom) + ")\" shape-rendering=\"crispEdges\" data-crop=\"" + std::to_string(t.crop[0]) + " " +
         std::to_string(t.crop[1]) + " " + std::to_string(t.crop[2]) + " " + std::to_string(t.crop[3]) +
         "\" data-kind=\"" +
         (t.path.empty() ? "scale"
          : t.heatmap    ? "heatmap"
                         : "image") +
         "\" data-image=\"" + XmlEscape(t.path) + "\">\n";
    std::map<uint32_t, std::string> runs;
    std::vector<uint32_t> order;
    for (int j = 0; j < t.crop[3]; ++j) {
      for (int i = 0; i < t.crop[2];) {
        const uint8_t* p = fig.pixels.Pixel(t.x + i * t.zoom, t.y + j * t.zoom);
        const uint32_t rgb = (uint32_t{p[0]} << 16) | (uint32_t{p[1]} << 8) | p[2];
        int n = 1;
        while (i + n < t.crop[2]) {
          const uint8_t* q = fig.pixels.Pixel(t.x + (i + n) * t.zoom, t.y + j * t.zoom);
          if (((uint32_t{q[0]} << 16) | (uint32_t{q[1]} << 8) | q[2]) != rgb) break;
          ++n;
        }
        auto [it, fresh] = runs.try_emplace(rgb);
        if (fresh) order.push_back(rgb);
        char seg[64];
        std::snprintf(seg, sizeof seg, "M%d %dh%dv1h-%dz", i, j, n, n);
        it->second += seg;
        i += n;
      }
    }
    for (uint32_t rgb : order) {
      char fill[8];
      std::snprintf(fill, sizeof fill, "#%06x", rgb);
      o += "<path fill=\"" + std::string(fill) + "\" d=\"" + runs[rgb] + "\"/>\n";
    }
    o += "</g>\n";
  }
  for (const auto& l : fig.labels) {
    o += "<text x=\"" + std::to_string(l.x) + "\" y=\"" + std::to_string(l.y) +
         "\" font-family=\"DejaVu Sans, "
         "Helvetica, Arial, sans-serif\" font-size=\"" +
         std::to_string(l.size) + "\">" + XmlEscape(l.text) + "</text>\n";
  }
  return o + "</svg>\n";
}

}  // namespace aalab
