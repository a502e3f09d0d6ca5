// Crop selection for the report's zoomed views: the windows where the no-AA frame is
// furthest from the reference on geometric edges (summed-area table, greedy, no overlap).
#include "metrics/crops.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace aalab {

ImageF CropScore(const ImageF& a, const ImageF& b, const ImageF* mask) {
  AALAB_CHECK(a.Width() == b.Width() && a.Height() == b.Height(), "crop score of different sizes");
  ImageF s(a.Width(), a.Height(), 1);
  for (int y = 0; y < a.Height(); ++y) {
    for (int x = 0; x < a.Width(); ++x) {
      float e = 0.0f;
      for (int c = 0; c < 3; ++c) e += std::fabs(a.At(x, y, c) - b.At(x, y, c));
      e /= 3.0f;
      if (mask) e *= mask->At(x, y, 0) > 0.5f ? 1.0f : 0.0f;
      s.At(x, y, 0) = e;
    }
  }
  return s;
}

std::vector<CropRect> PickCrops(const ImageF& score, int size, int count) {
  const int W = score.Width(), H = score.Height();
  std::vector<CropRect> out;
  if (W == 0 || H == 0 || count <= 0) return out;
  const int cw = std::min(size, W), ch = std::min(size, H);
  // Summed-area table in double.
  std::vector<double> sat(static_cast<size_t>(W + 1) * (H + 1), 0.0);
  auto S = [&](int x, int y) -> double& { return sat[static_cast<size_t>(y) * (W + 1) + x]; };
  for (int y = 0; y < H; ++y) {
    double row = 0.0;
    for (int x = 0; x < W; ++x) {
      row += score.At(x, y, 0);
      S(x + 1, y + 1) = S(x + 1, y) + row;
    }
  }
  auto sum = [&](int x, int y) { return S(x + cw, y + ch) - S(x, y + ch) - S(x + cw, y) + S(x, y); };
  auto overlaps = [&](int x, int y) {
    for (const auto& r : out) {
      if (x < r.x + r.w && r.x < x + cw && y < r.y + r.h && r.y < y + ch) return true;
    }
    return false;
  };
  for (int k = 0; k < count; ++k) {
    double best = 0.0;
    int bx = -1, by = -1;
    for (int y = 0; y + ch <= H; ++y) {
      for (int x = 0; x + cw <= W; ++x) {
        const double v = sum(x, y);
        if (v > best && !overlaps(x, y)) {
          best = v;
          bx = x;
          by = y;
        }
      }
    }
    if (bx < 0) break;
    out.push_back({bx, by, cw, ch});
  }
  return out;
}

}  // namespace aalab
