// Test frames for the optimized-vs-reference equivalence tests: real rendered content and
// adversarial synthetic frames (noise with random alpha, 1-pixel checkers, threshold-edge
// steps, every size from 1x1 up, odd sizes).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "scenes/library.h"
#include "scenes/render.h"

namespace aalab::perf_test {

struct NamedFrame {
  std::string name;
  Image8 img;
};

inline uint64_t NextRandom(uint64_t& s) {
  s += 0x9e3779b97f4a7c15ULL;
  uint64_t z = s;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// Synthetic frames meant to hit every branch: uniform noise (alpha random too, which the
/// filters must ignore or overwrite), noise over few levels (ties), a 1-pixel checker, a
/// checker of 2x3 cells, a thin diagonal line, near-threshold steps around every 8-bit level,
/// a horizontal gradient, a flat frame and degenerate sizes.
inline std::vector<NamedFrame> SyntheticFrames() {
  std::vector<NamedFrame> out;
  auto make = [&](const std::string& name, int w, int h, auto&& pixel) {
    Image8 img(w, h, 4);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) pixel(x, y, img.Pixel(x, y));
    }
    out.push_back({name + " " + std::to_string(w) + "x" + std::to_string(h), std::move(img)});
  };
  uint64_t seed = 12345;
  for (auto [w, h] :
       std::vector<std::pair<int, int>>{{1, 1}, {1, 7}, {7, 1}, {2, 2}, {3, 3}, {5, 4}, {17, 9}, {64, 64}, {131, 77}}) {
    make("noise", w, h, [&](int, int, uint8_t* p) {
      const uint64_t r = NextRandom(seed);
      for (int c = 0; c < 4; ++c) p[c] = static_cast<uint8_t>(r >> (8 * c));
    });
  }
  make("noise-4-levels", 97, 61, [&](int, int, uint8_t* p) {
    const uint64_t r = NextRandom(seed);
    for (int c = 0; c < 3; ++c) p[c] = static_cast<uint8_t>(((r >> (8 * c)) & 3) * 85);
    p[3] = 255;
  });
  make("checker-1px", 64, 48, [&](int x, int y, uint8_t* p) {
    const uint8_t v = ((x + y) & 1) ? 255 : 0;
    p[0] = p[1] = p[2] = v;
    p[3] = 255;
  });
  make("checker-2x3", 61, 47, [&](int x, int y, uint8_t* p) {
    const bool on = ((x / 2) + (y / 3)) & 1;
    p[0] = on ? 230 : 20;
    p[1] = on ? 40 : 200;
    p[2] = on ? 90 : 10;
    p[3] = 255;
  });
  make("diagonal-line", 80, 60, [&](int x, int y, uint8_t* p) {
    const bool on = std::abs(3 * x - 4 * y) < 3;
    p[0] = p[1] = p[2] = on ? 250 : 5;
    p[3] = 255;
  });
  // Steps whose contrast sits at and around the edge thresholds, for every base level.
  make("threshold-steps", 256, 24, [&](int x, int y, uint8_t* p) {
    const int base = x;
    const int delta = (y / 4) * 3 + (x % 5);  // 0 .. 19 codes
    const int v = (y % 4) < 2 ? base : std::min(255, base + delta);
    p[0] = p[1] = p[2] = static_cast<uint8_t>(v);
    p[3] = 255;
  });
  make("gradient", 300, 20, [&](int x, int y, uint8_t* p) {
    p[0] = static_cast<uint8_t>(x * 255 / 299);
    p[1] = static_cast<uint8_t>((x * 7 + y * 13) & 255);
    p[2] = static_cast<uint8_t>(y * 12);
    p[3] = 255;
  });
  make("flat", 33, 21, [&](int, int, uint8_t* p) {
    p[0] = 100;
    p[1] = 150;
    p[2] = 200;
    p[3] = 7;
  });
  return out;
}

/// 1x frames of real library scenes (rendered once per test binary).
inline const std::vector<NamedFrame>& SceneFrames() {
  static const std::vector<NamedFrame> frames = [] {
    std::vector<NamedFrame> out;
    for (const char* name : {"wedges", "mesh", "checker-plane", "thin-wires", "detail-texture", "hard-near-horizontal",
                             "hard-subpixel", "hard-dark"}) {
      const Scene scene = LoadScene(name);
      const Tracer tracer(scene);
      out.push_back({name, RenderFrame(tracer, 203, 117, RenderSpec{}, 1, nullptr)});
    }
    return out;
  }();
  return frames;
}

}  // namespace aalab::perf_test
