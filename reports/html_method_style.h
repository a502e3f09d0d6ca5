/// One colour and one marker per method, the same in every chart of every aalab page (the run
/// page's quality-vs-cost charts and legends, its motion player and speed-sweep charts, the
/// history page's trends). A pure function of the spec, so two pages (or two runs) draw a
/// method alike: the colour is its family's (the spec's leading letters and digits: "fxaa311"
/// for "fxaa311-p39:subpix=0"; a fixed table for the registry's families, a hash of the name
/// for others), the marker one of six shapes picked by a hash of the whole spec (the family's
/// own name, e.g. `none`, is a circle). Two variants of one family can share a marker; their
/// labels tell them apart.
#pragma once
#include <string>

namespace aalab::html {

struct MethodStyle {
  std::string colour;  ///< "#rrggbb"
  std::string marker;  ///< "circle", "square", "diamond", "triangle", "triangle-down", "plus"
  std::string path;    ///< the marker as an SVG path of radius 1 around (0, 0)
};

/// The spec's family: its leading run of letters, then digits ("ssaa-2x2" → "ssaa"); the
/// whole spec when it does not start with a letter.
std::string MethodFamily(const std::string& spec);

/// The style of `spec` (see the file comment).
MethodStyle StyleOfMethod(const std::string& spec);

/// The marker of `spec` as an SVG element centred at (x, y) with radius r, filled and stroked
/// with its colour (`fill` overrides the fill when not empty).
std::string MarkerSvg(const std::string& spec, double x, double y, double r, const std::string& fill = "");

}  // namespace aalab::html
