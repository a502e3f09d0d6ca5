// Frames for the FXAA oracle tests: the equivalence tests' synthetic and rendered frames
// (tests/equivalence/frames.h) plus adversarial cases for the edge search and the thresholds.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tests/equivalence/frames.h"

namespace aalab::oracle {

using perf_test::NamedFrame;

/// Hard edges of slope 1/n for n = 20 .. 1000, near-horizontal and (transposed)
/// near-vertical, dark on light and light on dark; the runs are n pixels long, so the
/// search reaches its last (guessed) step and the end of the span decides the blend.
inline std::vector<NamedFrame> SlopeFrames() {
  std::vector<NamedFrame> out;
  for (int n : {20, 37, 100, 333, 1000}) {
    const int len = std::min(n * 2 + 9, 1203);
    for (int vertical = 0; vertical < 2; ++vertical) {
      const int w = vertical ? 9 : len, h = vertical ? len : 9;
      Image8 img(w, h, 4);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const int along = vertical ? y : x, across = vertical ? x : y;
          // Edge at across = 3.3 + along / n (pixel centres compared with the edge line).
          const bool below = across + 0.5 > 3.3 + (along + 0.5) / n;
          uint8_t* p = img.Pixel(x, y);
          p[0] = below ? 220 : 30;
          p[1] = below ? 200 : 60;
          p[2] = below ? 40 : 180;
          p[3] = 255;
        }
      }
      out.push_back({"slope-1/" + std::to_string(n) + (vertical ? "-vertical" : ""), std::move(img)});
    }
  }
  return out;
}

/// Grey steps whose contrast straddles both thresholds for every base level: column
/// x = base level, rows = steps of +d codes (d = 0 .. 47), each step two rows high, so
/// range = d/255 meets max(edge_threshold_min, edge_threshold · max) exactly where it can.
inline NamedFrame ThresholdFrame() {
  Image8 img(256, 96, 4);
  for (int y = 0; y < 96; ++y) {
    for (int x = 0; x < 256; ++x) {
      const int d = y / 2;
      const int v = (y & 1) ? std::min(255, x + d) : x;
      uint8_t* p = img.Pixel(x, y);
      p[0] = p[1] = p[2] = static_cast<uint8_t>(v);
      p[3] = 255;
    }
  }
  return {"threshold-steps-0..47", std::move(img)};
}

/// Every frame the oracle tests compare on: the synthetic frames, the adversarial ones, and
/// 1x frames of eight library scenes at an odd size (101×67, small to keep llvmpipe quick).
inline std::vector<NamedFrame> OracleFrames() {
  std::vector<NamedFrame> f = perf_test::SyntheticFrames();
  for (auto& s : SlopeFrames()) f.push_back(std::move(s));
  f.push_back(ThresholdFrame());
  for (const char* name : {"wedges", "mesh", "checker-plane", "thin-wires", "detail-texture", "hard-near-horizontal",
                           "hard-subpixel", "hard-dark"}) {
    const Scene scene = LoadScene(name);
    const Tracer tracer(scene);
    f.push_back({name, RenderFrame(tracer, 101, 67, RenderSpec{}, 1, nullptr)});
  }
  return f;
}

}  // namespace aalab::oracle
