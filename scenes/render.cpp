#include "scenes/render.h"

#include <cmath>
#include <functional>
#include <vector>

#include "harness/core/color.h"
#include "harness/core/error.h"
#include "harness/core/hash.h"
#include "harness/core/parallel.h"

namespace aalab {

namespace {

constexpr int kTile = 8;  // tiles of 8×8 pixels; the work split never depends on threads
constexpr uint64_t kStreamReference = 0x5265665374726174ULL;  // "RefStrat"
constexpr uint64_t kStreamJitter = 0x4a69747465725373ULL;     // "JitterSs"

/// Calls `resolve(x, y, samples, spp)` for every pixel after tracing its samples; sample
/// positions come from `place(x, y, s)`. Tiles run in parallel; counters merge per tile.
void RenderTiles(const Tracer& tracer, int width, int height, int spp,
                 const std::function<SamplePos(int, int, int)>& place,
                 const std::function<void(int, int, const SampleResult*, int)>& resolve,
                 TraceCounters* counters) {
  AALAB_CHECK(width > 0 && height > 0 && spp > 0, "render size and spp must be positive");
  const int tiles_x = (width + kTile - 1) / kTile;
  const int tiles_y = (height + kTile - 1) / kTile;
  const int tiles = tiles_x * tiles_y;
  std::vector<TraceCounters> per_tile(static_cast<size_t>(tiles));
  ParallelForChunks(tiles, 1, [&](int begin, int end) {
    std::vector<SamplePos> pos;
    std::vector<SampleResult> res;
    for (int t = begin; t < end; ++t) {
      const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
      const int x1 = std::min(x0 + kTile, width), y1 = std::min(y0 + kTile, height);
      pos.clear();
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          for (int s = 0; s < spp; ++s) pos.push_back(place(x, y, s));
        }
      }
      res.assign(pos.size(), SampleResult{});
      tracer.Trace(pos.data(), static_cast<int>(pos.size()), width, height, res.data(), &per_tile[t]);
      size_t k = 0;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          resolve(x, y, &res[k], spp);
          k += static_cast<size_t>(spp);
        }
      }
    }
  });
  if (counters) {
    for (const auto& c : per_tile) *counters += c;
  }
}

}  // namespace

Image8 RenderFrame(const Tracer& tracer, int width, int height, const RenderSpec& spec, uint64_t seed,
                   TraceCounters* counters) {
  const Display& display = tracer.GetScene().display;
  const int spp = spec.SamplesPerPixel();
  std::vector<std::pair<float, float>> fixed;
  if (spec.pattern != SamplePattern::kJitter && spec.pattern != SamplePattern::kStratified) {
    fixed = spec.FixedOffsets();
  }
  const int n = spec.grid;
  auto place = [&](int x, int y, int s) {
    float ox, oy;
    switch (spec.pattern) {
      case SamplePattern::kJitter:
        ox = SampleJitter(x, y, s, seed ^ kStreamJitter, 0);
        oy = SampleJitter(x, y, s, seed ^ kStreamJitter, 1);
        break;
      case SamplePattern::kStratified:
        ox = (static_cast<float>(s % n) + SampleJitter(x, y, s, seed ^ kStreamJitter, 0)) / static_cast<float>(n);
        oy = (static_cast<float>(s / n) + SampleJitter(x, y, s, seed ^ kStreamJitter, 1)) / static_cast<float>(n);
        break;
      default:
        ox = fixed[s].first;
        oy = fixed[s].second;
    }
    return SamplePos{static_cast<float>(x) + ox, static_cast<float>(y) + oy};
  };
  Image8 out(width, height, 4, 255);
  auto resolve = [&](int x, int y, const SampleResult* r, int count) {
    double sum[3] = {0, 0, 0};
    for (int s = 0; s < count; ++s) {
      const auto d = DisplayLinear(display, {r[s].rgb[0], r[s].rgb[1], r[s].rgb[2]});
      for (int c = 0; c < 3; ++c) sum[c] += d[c];
    }
    uint8_t* p = out.Pixel(x, y);
    for (int c = 0; c < 3; ++c) {
      p[c] = QuantizeUnorm8(SrgbEncode(static_cast<float>(sum[c] / count)));
    }
  };
  RenderTiles(tracer, width, height, spp, place, resolve, counters);
  return out;
}

int ReferenceGridForSpp(int spp) {
  for (int n = 2; n <= 64; n += 2) {
    if (n * n == spp) return n;
  }
  throw UserError("reference spp " + std::to_string(spp) +
                  " is not allowed: it must be n*n with n even, 2..64 (e.g. 4, 16, 64, 256, 1024, 4096)");
}

Reference RenderReference(const Tracer& tracer, int width, int height, int grid, uint64_t seed,
                          TraceCounters* counters) {
  AALAB_CHECK(grid >= 2 && grid % 2 == 0, "reference grid must be even and >= 2");
  const Display& display = tracer.GetScene().display;
  const int spp = grid * grid;
  Reference ref;
  ref.grid = grid;
  ref.image = ImageF(width, height, 3);
  ref.half_a = ImageF(width, height, 3);
  ref.half_b = ImageF(width, height, 3);
  ref.edge_mask_raw = ImageF(width, height, 1);
  auto place = [&](int x, int y, int s) {
    const int i = s % grid, j = s / grid;
    const float ox = (static_cast<float>(i) + SampleJitter(x, y, s, seed ^ kStreamReference, 0)) / static_cast<float>(grid);
    const float oy = (static_cast<float>(j) + SampleJitter(x, y, s, seed ^ kStreamReference, 1)) / static_cast<float>(grid);
    return SamplePos{static_cast<float>(x) + ox, static_cast<float>(y) + oy};
  };
  auto resolve = [&](int x, int y, const SampleResult* r, int count) {
    double all[3] = {0, 0, 0}, a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
    int na = 0, nb = 0;
    bool edge = false;
    for (int s = 0; s < count; ++s) {
      const auto d = DisplayLinear(display, {r[s].rgb[0], r[s].rgb[1], r[s].rgb[2]});
      const bool even = ((s % grid) + (s / grid)) % 2 == 0;
      for (int c = 0; c < 3; ++c) {
        all[c] += d[c];
        (even ? a : b)[c] += d[c];
      }
      (even ? na : nb)++;
      if (r[s].surface != r[0].surface || r[s].shadowed != r[0].shadowed) edge = true;
    }
    for (int c = 0; c < 3; ++c) {
      ref.image.At(x, y, c) = SrgbEncode(static_cast<float>(all[c] / count));
      ref.half_a.At(x, y, c) = SrgbEncode(static_cast<float>(a[c] / na));
      ref.half_b.At(x, y, c) = SrgbEncode(static_cast<float>(b[c] / nb));
    }
    ref.edge_mask_raw.At(x, y, 0) = edge ? 1.0f : 0.0f;
  };
  RenderTiles(tracer, width, height, spp, place, resolve, counters);

  // Dilate the mask by 1 px (3×3 neighbourhood, clamped at the border).
  ref.edge_mask = ImageF(width, height, 1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float v = 0.0f;
      for (int dy = -1; dy <= 1 && v == 0.0f; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
          if (ref.edge_mask_raw.At(xx, yy, 0) > 0.5f) {
            v = 1.0f;
            break;
          }
        }
      }
      ref.edge_mask.At(x, y, 0) = v;
    }
  }
  return ref;
}

}  // namespace aalab
