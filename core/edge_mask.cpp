#include "core/edge_mask.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace aalab {

namespace {

/// DilateMask's rows per parallel chunk (a 320x180 mask: 12 chunks).
constexpr int kDilateRows = 16;

/// Marks both pixels of every 4-neighbour pair (x, y)–(x+1, y) and (x, y)–(x, y+1) for which
/// `differ(a, b)` holds, where a and b point at the pixels' first channels.
template <typename Differ>
ImageF MarkPairs(const ImageF& img, Differ differ) {
  const int w = img.Width(), h = img.Height();
  ImageF mask(w, h, 1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float* p = img.Pixel(x, y);
      if (x + 1 < w && differ(p, img.Pixel(x + 1, y))) mask.At(x, y, 0) = mask.At(x + 1, y, 0) = 1.0f;
      if (y + 1 < h && differ(p, img.Pixel(x, y + 1))) mask.At(x, y, 0) = mask.At(x, y + 1, 0) = 1.0f;
    }
  }
  return mask;
}

}  // namespace

ImageF DilateMask(const ImageF& raw) {
  const int width = raw.Width(), height = raw.Height();
  ImageF mask(width, height, 1, kUninitialized);  // every pixel is written below
  // Rows in parallel chunks of kDilateRows, fixed by the height alone; a pixel reads raw only.
  ParallelForChunks(height, kDilateRows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < width; ++x) {
        float v = 0.0f;
        for (int dy = -1; dy <= 1 && v == 0.0f; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
            if (raw.At(xx, yy, 0) > 0.5f) {
              v = 1.0f;
              break;
            }
          }
        }
        mask.At(x, y, 0) = v;
      }
    }
  });
  return mask;
}

ImageF EdgesFromIds(const ImageF& ids) {
  const int nc = ids.Channels();
  return MarkPairs(ids, [nc](const float* a, const float* b) {
    for (int c = 0; c < nc; ++c) {
      if (a[c] != b[c]) return true;
    }
    return false;
  });
}

ImageF EdgesFromDepth(const ImageF& depth, float relative_jump) {
  return MarkPairs(depth, [relative_jump](const float* a, const float* b) {
    const float lo = std::min(a[0], b[0]);
    return std::fabs(a[0] - b[0]) > relative_jump * lo || (lo == 0.0f && a[0] != b[0]);
  });
}

ImageF EdgesFromGradient(const ImageF& image, float threshold) {
  const int nc = std::min(3, image.Channels());
  return MarkPairs(image, [nc, threshold](const float* a, const float* b) {
    for (int c = 0; c < nc; ++c) {
      if (std::fabs(a[c] - b[c]) > threshold) return true;
    }
    return false;
  });
}

ImageF EdgesFromIdBlocks(const ImageF& ids, int n) {
  AALAB_CHECK(n >= 2 && ids.Width() % n == 0 && ids.Height() % n == 0, "ids at n x the frame's size");
  const int W = ids.Width() / n, H = ids.Height() / n, nc = ids.Channels();
  ImageF out(W, H, 1);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const float* first = ids.Pixel(x * n, y * n);
      bool differ = false;
      for (int j = 0; j < n && !differ; ++j) {
        for (int i = 0; i < n && !differ; ++i) {
          const float* p = ids.Pixel(x * n + i, y * n + j);
          for (int c = 0; c < nc; ++c) differ = differ || p[c] != first[c];
        }
      }
      out.At(x, y, 0) = differ ? 1.0f : 0.0f;
    }
  }
  return out;
}

ImageF EdgesFromDepthBlocks(const ImageF& depth, int n, float relative_jump) {
  AALAB_CHECK(n >= 2 && depth.Width() % n == 0 && depth.Height() % n == 0, "depth at n x the frame's size");
  const int W = depth.Width() / n, H = depth.Height() / n;
  ImageF out(W, H, 1);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      float lo = depth.At(x * n, y * n, 0), hi = lo;
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const float v = depth.At(x * n + i, y * n + j, 0);
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
      }
      out.At(x, y, 0) = (hi - lo > relative_jump * lo || (lo == 0.0f && hi != 0.0f)) ? 1.0f : 0.0f;
    }
  }
  return out;
}

ImageF UnionMask(const ImageF& a, const ImageF& b) {
  AALAB_CHECK(a.Width() == b.Width() && a.Height() == b.Height() && a.Channels() == b.Channels(),
              "UnionMask needs masks of the same size");
  ImageF out = a;
  for (size_t i = 0; i < out.Data().size(); ++i) out.Data()[i] = std::max(a.Data()[i], b.Data()[i]);
  return out;
}

}  // namespace aalab
