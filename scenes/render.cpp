#include "scenes/render.h"

#include <cmath>
#include <algorithm>
#include <cstring>
#include <vector>

#include "core/color.h"
#include "core/edge_mask.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/parallel.h"

namespace aalab {

namespace {

constexpr int kTile = 8;  // tiles of 8×8 pixels; the work split never depends on threads

/// The renderers' split of a width × height frame into kTile × kTile tiles, row-major; the
/// last column and row of tiles are clipped to the frame.
struct TileGrid {
  int width, height, tiles_x, tiles;
  TileGrid(int w, int h)
      : width(w), height(h), tiles_x((w + kTile - 1) / kTile), tiles(tiles_x * ((h + kTile - 1) / kTile)) {}
  /// Tile t's pixels: x in [x0, x1), y in [y0, y1).
  struct Rect {
    int x0, y0, x1, y1;
  };
  Rect At(int t) const {
    const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
    return {x0, y0, std::min(x0 + kTile, width), std::min(y0 + kTile, height)};
  }
};
constexpr uint64_t kStreamReference = 0x5265665374726174ULL;  // "RefStrat"
constexpr uint64_t kStreamJitter = 0x4a69747465725373ULL;     // "JitterSs"

/// SampleJitter(x, y, s, seed, 0) and (..., 1) with the shared part of the hash computed
/// once: HashTuple(x, y, s, seed, dim) mixes x, y, s, seed in that order before dim, so the
/// pixel prefix (x, y) and the sample prefix (s, seed) are reused. Same bits as SampleJitter.
struct PixelHash {
  uint64_t h;  // HashTuple's state after mixing x and y
  PixelHash(int x, int y) {
    h = MixBits(static_cast<uint64_t>(static_cast<uint32_t>(x)) + 0x9e3779b97f4a7c15ULL);
    h = MixBits(h ^ (static_cast<uint64_t>(static_cast<uint32_t>(y)) + 0x632be59bd9b4e019ULL));
  }
  void Jitter2(int s, uint64_t seed, float* j0, float* j1) const {
    uint64_t g = MixBits(h ^ (static_cast<uint64_t>(static_cast<uint32_t>(s)) + 0x85157af5a2a6b5f1ULL));
    g = MixBits(g ^ (seed + 0xd6e8feb86659fd93ULL));
    *j0 = HashToUnitFloat(MixBits(g ^ (0ULL + 0xa0761d6478bd642fULL)));
    *j1 = HashToUnitFloat(MixBits(g ^ (1ULL + 0xa0761d6478bd642fULL)));
  }
};

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define AALAB_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define AALAB_SIMD_CLONES
#endif

/// Eight 64-bit lanes (GCC vector: one AVX-512 register, 2 AVX2 or 4 SSE2 ones in the
/// clones; the lane-wise multiply is the exact low 64 bits of the product in each).
typedef uint64_t U64x8 __attribute__((vector_size(64)));
typedef int32_t I32x8 __attribute__((vector_size(32)));
typedef float F32x8 __attribute__((vector_size(32)));

/// MixBits in every lane of v (in place: no vector passed by value across a call).
inline __attribute__((always_inline)) void MixBitsLanes(U64x8& v) {
  v ^= v >> 30;
  v *= 0xbf58476d1ce4e5b9ULL;
  v ^= v >> 27;
  v *= 0x94d049bb133111ebULL;
  v ^= v >> 31;
}

/// HashToUnitFloat(MixBits(v)) in every lane. MixBits' last step, v ^= v >> 31, leaves bits
/// 40..63 as they are (it XORs them with bits 71..94, which a 64-bit value does not have),
/// and HashToUnitFloat reads only those bits, so it is left out; the top 24 bits convert to
/// float exactly (through int32: < 2^24).
inline __attribute__((always_inline)) void UnitFloatOfMixLanes(U64x8 v, F32x8& out) {
  v ^= v >> 30;
  v *= 0xbf58476d1ce4e5b9ULL;
  v ^= v >> 27;
  v *= 0x94d049bb133111ebULL;
  const I32x8 top = __builtin_convertvector(v >> 40, I32x8);
  out = __builtin_convertvector(top, F32x8) * (1.0f / 16777216.0f);
}

/// What the reference's stratified positions share across pixels, per sample s = j·grid + i
/// (spp rounded up to a multiple of 8; the padding repeats valid strata, computed, never
/// stored): the hash input s + 0x85157af5a2a6b5f1 and the stratum's i and j as floats.
struct StrataTable {
  std::vector<U64x8> salt;
  std::vector<F32x8> fi, fj;
  explicit StrataTable(int grid) {
    const int spp = grid * grid;
    const size_t blocks = static_cast<size_t>((spp + 7) / 8);
    salt.resize(blocks);
    fi.resize(blocks);
    fj.resize(blocks);
    for (int s = 0; s < static_cast<int>(blocks) * 8; ++s) {
      const size_t b = static_cast<size_t>(s / 8);
      const int k = s % 8;
      salt[b][k] = static_cast<uint64_t>(static_cast<uint32_t>(s)) + 0x85157af5a2a6b5f1ULL;
      fi[b][k] = static_cast<float>(s % grid);
      fj[b][k] = static_cast<float>(s / grid);
    }
  }
};

/// The reference's stratified positions of one pixel, s = j·grid + i: the PixelHash::Jitter2
/// arithmetic over 8 samples at a time in vector lanes (64-bit multiplies, IEEE float adds
/// and divisions: exact operations, identical in every clone and lane), the per-sample inputs
/// from the table.
AALAB_SIMD_CLONES
void PlaceStratifiedPixel(uint64_t pixel_hash, int grid, uint64_t seed, float fx, float fy, const StrataTable& table,
                          SamplePos* out) {
  const int spp = grid * grid;
  const float g = static_cast<float>(grid);
  for (int s0 = 0; s0 < spp; s0 += 8) {
    const size_t b = static_cast<size_t>(s0 / 8);
    U64x8 h = pixel_hash ^ table.salt[b];
    MixBitsLanes(h);
    h ^= seed + 0xd6e8feb86659fd93ULL;
    MixBitsLanes(h);
    F32x8 j0, j1;
    UnitFloatOfMixLanes(h ^ (0ULL + 0xa0761d6478bd642fULL), j0);
    UnitFloatOfMixLanes(h ^ (1ULL + 0xa0761d6478bd642fULL), j1);
    const F32x8 x = fx + (table.fi[b] + j0) / g;
    const F32x8 y = fy + (table.fj[b] + j1) / g;
    const int m = std::min(8, spp - s0);
    for (int k = 0; k < m; ++k) {
      out[s0 + k].x = x[k];
      out[s0 + k].y = y[k];
    }
  }
}

/// DisplayLinearInline of every sample's rgb into d[3·k + c], for one tonemap: the
/// same operations in the same order (std::clamp written out), without the per-sample
/// switch, so that the loop has no branches and vectorises.
template <Tonemap kTone>
inline __attribute__((always_inline)) void DisplayLinearLoop(float exposure, const SampleResult* r, int n, float* d) {
  for (int k = 0; k < n; ++k) {
    for (int c = 0; c < 3; ++c) {
      float v = r[k].rgb[c];
      v = v > 0.0f ? v : 0.0f;  // negatives and NaN → 0
      v = ApplyTonemap(kTone, v * exposure);
      d[3 * k + c] = v < 0.0f ? 0.0f : (1.0f < v ? 1.0f : v);
    }
  }
}

AALAB_SIMD_CLONES
void DisplayLinearSamples(const Display& display, const SampleResult* r, int n, float* d) {
  switch (display.tonemap) {
    case Tonemap::kNone: DisplayLinearLoop<Tonemap::kNone>(display.exposure, r, n, d); break;
    case Tonemap::kReinhard: DisplayLinearLoop<Tonemap::kReinhard>(display.exposure, r, n, d); break;
    case Tonemap::kAces: DisplayLinearLoop<Tonemap::kAces>(display.exposure, r, n, d); break;
  }
}

/// Per-thread sample buffers of RenderTiles, reused from tile to tile.
struct TileScratch {
  std::vector<SamplePos> pos;
  std::vector<SampleResult> res;
  std::vector<float> display;  // 3 per sample: DisplayLinearSamples
};

/// Per-thread buffers of RenderReference's tiles, reused from tile to tile.
struct ReferenceScratch {
  std::vector<SamplePos> pos;
  std::vector<SampleResult> res;
  std::vector<float> lanes;  // one tile row: value (s·3 + c)·kTile + p (TransposeRgb)
};

/// The rgb of `row` ≤ kTile pixels of spp samples each (r[p·spp + s]) laid out pixel-parallel:
/// lanes[(s·3 + c)·kTile + p]; lanes p ≥ row repeat pixel row − 1 (summed, never read).
void TransposeRgb(const SampleResult* r, int row, int spp, float* lanes) {
  const SampleResult* px[kTile];  // lanes past the row repeat its last pixel (never read)
  for (int p = 0; p < kTile; ++p) px[p] = r + static_cast<size_t>(std::min(p, row - 1)) * spp;
  for (int s = 0; s < spp; ++s) {
    float* l = lanes + static_cast<size_t>(s) * 3 * kTile;
    for (int p = 0; p < kTile; ++p) {
      const SampleResult& q = px[p][s];
      l[p] = q.rgb[0];
      l[kTile + p] = q.rgb[1];
      l[2 * kTile + p] = q.rgb[2];
    }
  }
}

/// DisplayLinearInline's per-channel transform of n values in place, for one tonemap: the
/// same operations in the same order as DisplayLinearLoop (the value does not depend on its
/// channel), over contiguous floats so that it vectorises.
template <Tonemap kTone>
inline __attribute__((always_inline)) void DisplayLinearLanesLoop(float exposure, float* v, int n) {
  for (int k = 0; k < n; ++k) {
    float x = v[k];
    x = x > 0.0f ? x : 0.0f;  // negatives and NaN → 0
    x = ApplyTonemap(kTone, x * exposure);
    v[k] = x < 0.0f ? 0.0f : (1.0f < x ? 1.0f : x);
  }
}

AALAB_SIMD_CLONES
void DisplayLinearLanes(const Display& display, float* v, int n) {
  switch (display.tonemap) {
    case Tonemap::kNone: DisplayLinearLanesLoop<Tonemap::kNone>(display.exposure, v, n); break;
    case Tonemap::kReinhard: DisplayLinearLanesLoop<Tonemap::kReinhard>(display.exposure, v, n); break;
    case Tonemap::kAces: DisplayLinearLanesLoop<Tonemap::kAces>(display.exposure, v, n); break;
  }
}

/// The reference's three sums (all samples; strata with i + j even, half A; odd, half B),
/// sums[(kind·3 + c)·kTile + p].
enum ReferenceSum { kSumAll = 0, kSumA = 3, kSumB = 6, kSums = 9 };

/// The reference resolve's per-pixel double sums of one tile row (lanes: TransposeRgb's
/// layout, display-linear), kTile pixels side by side in the vector lanes: each pixel's sums
/// take the same additions in the same order as the per-pixel loop (samples s = j·grid + i in
/// order; (i + j) even goes to half A), so the same bits. grid is even, so in row j the
/// strata pair up (i, i + 1) with i even, and the first of a pair is in half A exactly when j
/// is even. The lanes are a GCC vector of 8 doubles: 4 SSE2 registers in the default clone,
/// 2 AVX2 or one AVX-512 register in the others (lane-wise IEEE adds, the same in each).
AALAB_SIMD_CLONES
void SumReferenceLanes(const float* lanes, int grid, double* sums) {
  static_assert(kTile == 8, "one vector of 8 lanes per tile row");
  typedef float F8 __attribute__((vector_size(32)));
  typedef double D8 __attribute__((vector_size(64)));
  for (int c = 0; c < 3; ++c) {
    D8 all = {}, a = {}, b = {};
    for (int j = 0; j < grid; ++j) {
      // Row j's pairs start in half A when j is even, in half B when it is odd.
      D8& first = j % 2 == 0 ? a : b;
      D8& second = j % 2 == 0 ? b : a;
      for (int i = 0; i < grid; i += 2) {
        const float* l0 = lanes + (static_cast<size_t>(j * grid + i) * 3 + c) * kTile;
        F8 f0, f1;
        std::memcpy(&f0, l0, sizeof f0);
        std::memcpy(&f1, l0 + 3 * kTile, sizeof f1);
        const D8 d0 = __builtin_convertvector(f0, D8), d1 = __builtin_convertvector(f1, D8);
        all += d0;
        all += d1;
        first += d0;
        second += d1;
      }
    }
    std::memcpy(sums + (kSumAll + c) * kTile, &all, sizeof all);
    std::memcpy(sums + (kSumA + c) * kTile, &a, sizeof a);
    std::memcpy(sums + (kSumB + c) * kTile, &b, sizeof b);
  }
}

/// Whether any of a pixel's samples sees another surface or another set of blocked lights
/// than its first sample (the reference's raw edge mask).
bool SamplesDiffer(const SampleResult* r, int spp) {
  const uint32_t surface = static_cast<uint32_t>(r[0].surface), shadowed = r[0].shadowed;
  uint32_t diff = 0;  // branch-free: any bit that differs in any sample
  for (int s = 0; s < spp; ++s) diff |= (static_cast<uint32_t>(r[s].surface) ^ surface) | (r[s].shadowed ^ shadowed);
  return diff != 0;
}

/// Calls `resolve(x, y, samples, display, spp)` for every pixel after tracing its samples
/// (display: the samples' DisplayLinearInline values, 3 floats each); the spp
/// sample positions of pixel (x, y) come from `place(x, y, out)`. Tiles run in parallel,
/// one Tracer::Trace call per tile (all its samples, pixel by pixel, row-major); counters
/// merge per tile in tile order.
template <typename Place, typename Resolve>
void RenderTiles(const Tracer& tracer, int width, int height, int spp, const Place& place, const Resolve& resolve,
                 TraceCounters* counters, TextureFootprint footprint) {
  const Display& display = tracer.GetScene().display;
  AALAB_CHECK(width > 0 && height > 0 && spp > 0, "render size and spp must be positive");
  const TileGrid grid_of_tiles(width, height);
  const int tiles = grid_of_tiles.tiles;
  std::vector<TraceCounters> per_tile(static_cast<size_t>(tiles));
  ParallelForChunks(tiles, 1, [&](int begin, int end) {
    thread_local TileScratch scratch;
    const size_t max_samples = static_cast<size_t>(kTile) * kTile * static_cast<size_t>(spp);
    if (scratch.pos.size() < max_samples) {
      scratch.pos.resize(max_samples);
      scratch.res.resize(max_samples);
      scratch.display.resize(3 * max_samples);
    }
    SamplePos* pos = scratch.pos.data();
    SampleResult* res = scratch.res.data();
    float* disp = scratch.display.data();
    for (int t = begin; t < end; ++t) {
      const auto [x0, y0, x1, y1] = grid_of_tiles.At(t);
      size_t n = 0;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          place(x, y, pos + n);
          n += static_cast<size_t>(spp);
        }
      }
      tracer.Trace(pos, static_cast<int>(n), width, height, res, &per_tile[t], footprint);
      DisplayLinearSamples(display, res, static_cast<int>(n), disp);
      size_t k = 0;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          resolve(x, y, res + k, disp + 3 * k, spp);
          k += static_cast<size_t>(spp);
        }
      }
    }
  });
  if (counters) {
    for (const auto& c : per_tile) *counters += c;
  }
}

/// Per-thread buffers of TraceMsaaTiles, reused from tile to tile.
struct MsaaTileScratch {
  std::vector<SamplePos> pos, centres;
  std::vector<SampleResult> res;
  std::vector<uint32_t> evals;
};

/// MSAA: tiles in parallel, one Tracer::TraceMsaa call per tile (its pixels row-major, each
/// with N samples at the standard positions), then `resolve(x, y, samples, N)` per pixel;
/// counters merged in tile order; `stats` (when not null) gets the shading evaluations.
template <typename Resolve>
void TraceMsaaTiles(const Tracer& tracer, int width, int height, const MsaaSpec& msaa, const Resolve& resolve,
                    TraceCounters* counters, FrameStats* stats, TextureFootprint footprint) {
  AALAB_CHECK(width > 0 && height > 0, "render size must be positive");
  const int spp = msaa.samples;
  std::vector<std::pair<float, float>> offsets;  // in [0, 1)² from the pixel's corner
  for (const SampleOffset16& o : StandardSamplePositions(spp)) {
    offsets.emplace_back(static_cast<float>(8 + o.x) / 16.0f, static_cast<float>(8 + o.y) / 16.0f);
  }
  if (stats) stats->shading_evals = ImageF(width, height, 1);
  const TileGrid grid_of_tiles(width, height);
  const int tiles = grid_of_tiles.tiles;
  std::vector<TraceCounters> per_tile(static_cast<size_t>(tiles));
  ParallelForChunks(tiles, 1, [&](int begin, int end) {
    thread_local MsaaTileScratch scratch;
    const size_t max_px = static_cast<size_t>(kTile) * kTile;
    if (scratch.pos.size() < max_px * static_cast<size_t>(spp)) {
      scratch.pos.resize(max_px * static_cast<size_t>(spp));
      scratch.res.resize(max_px * static_cast<size_t>(spp));
    }
    if (scratch.centres.size() < max_px) {
      scratch.centres.resize(max_px);
      scratch.evals.resize(max_px);
    }
    for (int t = begin; t < end; ++t) {
      const auto [x0, y0, x1, y1] = grid_of_tiles.At(t);
      int n = 0;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x, ++n) {
          const float fx = static_cast<float>(x), fy = static_cast<float>(y);
          scratch.centres[static_cast<size_t>(n)] = SamplePos{fx + 0.5f, fy + 0.5f};
          SamplePos* p = scratch.pos.data() + static_cast<size_t>(n) * spp;
          for (int s = 0; s < spp; ++s) p[s] = SamplePos{fx + offsets[s].first, fy + offsets[s].second};
        }
      }
      tracer.TraceMsaa(scratch.pos.data(), scratch.centres.data(), n, msaa, width, height, scratch.res.data(),
                       scratch.evals.data(), &per_tile[t], footprint);
      int k = 0;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x, ++k) {
          resolve(x, y, scratch.res.data() + static_cast<size_t>(k) * spp, spp);
          if (stats) stats->shading_evals.At(x, y, 0) = static_cast<float>(scratch.evals[static_cast<size_t>(k)]);
        }
      }
    }
  });
  if (counters) {
    for (const auto& c : per_tile) *counters += c;
  }
}

/// Traces the samples of a method frame (the render spec's pattern and jitter, or MSAA) and
/// calls `resolve(x, y, samples, spp)` for each pixel: what RenderFrame and RenderFrameLinear
/// share.
///
/// `resolve_display(x, y, samples, display, spp)` is the same resolve for samples that come
/// with their display-linear values (every render but MSAA's).
template <typename Resolve, typename ResolveDisplay>
void TraceFrameSamples(const Tracer& tracer, int width, int height, const RenderSpec& spec, uint64_t seed,
                       const Resolve& resolve, const ResolveDisplay& resolve_display, TraceCounters* counters,
                       FrameStats* stats) {
  TextureFootprint footprint;  // MSAA shades at pixel rate: a one-pixel footprint
  if (spec.specular_aa.enabled) {
    footprint.gsaa_sigma2 = static_cast<float>(spec.specular_aa.sigma2);
    footprint.gsaa_kappa = static_cast<float>(spec.specular_aa.kappa);
    footprint.gsaa = true;
    footprint.gsaa_mapped = spec.specular_aa.mapped_derivatives;
    footprint.gsaa_toksvig = static_cast<float>(spec.specular_aa.toksvig);
    footprint.gsaa_toksvig_max = static_cast<float>(spec.specular_aa.toksvig_max);
  }
  if (spec.msaa.On()) {
    TraceMsaaTiles(tracer, width, height, spec.msaa, resolve, counters, stats, footprint);
    return;
  }
  const int spp = spec.SamplesPerPixel();
  std::vector<std::pair<float, float>> fixed;
  if (spec.pattern != SamplePattern::kJitter && spec.pattern != SamplePattern::kStratified) {
    fixed = spec.FixedOffsets();
  }
  const int n = spec.grid;
  const uint64_t jseed = seed ^ kStreamJitter;
  auto place = [&](int x, int y, SamplePos* out_pos) {
    const PixelHash ph(x, y);
    const float fx = static_cast<float>(x), fy = static_cast<float>(y);
    switch (spec.pattern) {
      case SamplePattern::kJitter:
        for (int s = 0; s < spp; ++s) {
          float ox, oy;
          ph.Jitter2(s, jseed, &ox, &oy);
          out_pos[s] = SamplePos{fx + ox, fy + oy};
        }
        break;
      case SamplePattern::kStratified:
        for (int s = 0; s < spp; ++s) {  // s = j·n + i
          float j0, j1;
          ph.Jitter2(s, jseed, &j0, &j1);
          const float ox = (static_cast<float>(s % n) + j0) / static_cast<float>(n);
          const float oy = (static_cast<float>(s / n) + j1) / static_cast<float>(n);
          out_pos[s] = SamplePos{fx + ox, fy + oy};
        }
        break;
      default:
        for (int s = 0; s < spp; ++s) out_pos[s] = SamplePos{fx + fixed[s].first, fy + fixed[s].second};
    }
  };
  // Image textures take their UV derivatives over the render's own sample spacing: a
  // 1-sample render steps one pixel, an n x n supersampled one 1/n pixel (a GPU rendering at
  // n times the resolution).
  switch (spec.pattern) {
    case SamplePattern::kCenter: footprint.px = 1.0f; break;
    case SamplePattern::kRotatedGrid: footprint.px = 0.5f; break;
    case SamplePattern::kJitter: footprint.px = 1.0f / std::sqrt(static_cast<float>(spp)); break;
    default: footprint.px = 1.0f / static_cast<float>(n); break;
  }
  RenderTiles(tracer, width, height, spp, place, resolve_display, counters, footprint);
}

}  // namespace

Image8 RenderFrame(const Tracer& tracer, int width, int height, const RenderSpec& spec, uint64_t seed,
                   TraceCounters* counters, FrameStats* stats) {
  const Display& display = tracer.GetScene().display;
  Image8 out(width, height, 4, 255);
  const bool hdr_linear = spec.msaa.On() && spec.msaa.resolve == MsaaResolve::kHdrLinear;
  auto resolve = [&](int x, int y, const SampleResult* r, int count) {
    if (hdr_linear) {
      ResolveHdrLinearPixel(display, r, count, out.Pixel(x, y));
    } else {
      ResolveBoxPixel(display, r, count, out.Pixel(x, y));
    }
  };
  // The box resolve of ResolveBoxPixel from the samples' display-linear values.
  auto resolve_display = [&](int x, int y, const SampleResult*, const float* d, int count) {
    double sum[3] = {0, 0, 0};
    for (int s = 0; s < count; ++s) {
      for (int c = 0; c < 3; ++c) sum[c] += d[3 * s + c];
    }
    uint8_t* p = out.Pixel(x, y);
    for (int c = 0; c < 3; ++c) p[c] = QuantizeUnorm8(SrgbEncode(static_cast<float>(sum[c] / count)));
  };
  TraceFrameSamples(tracer, width, height, spec, seed, resolve, resolve_display, counters, stats);
  return out;
}

ImageF RenderFrameLinear(const Tracer& tracer, int width, int height, const RenderSpec& spec, uint64_t seed,
                         TraceCounters* counters) {
  const Display& display = tracer.GetScene().display;
  ImageF out(width, height, 3);
  const bool hdr_linear = spec.msaa.On() && spec.msaa.resolve == MsaaResolve::kHdrLinear;
  auto resolve = [&](int x, int y, const SampleResult* r, int count) {
    if (hdr_linear) {
      float d[3];
      HdrLinearResolve(display, r, count, d);
      for (int c = 0; c < 3; ++c) out.At(x, y, c) = d[c];
      return;
    }
    double sum[3] = {0, 0, 0};
    for (int s = 0; s < count; ++s) {
      float d[3];
      DisplayLinearInline(display, r[s].rgb, d);
      for (int c = 0; c < 3; ++c) sum[c] += d[c];
    }
    for (int c = 0; c < 3; ++c) out.At(x, y, c) = static_cast<float>(sum[c] / count);
  };
  auto resolve_display = [&](int x, int y, const SampleResult*, const float* d, int count) {
    double sum[3] = {0, 0, 0};
    for (int s = 0; s < count; ++s) {
      for (int c = 0; c < 3; ++c) sum[c] += d[3 * s + c];
    }
    for (int c = 0; c < 3; ++c) out.At(x, y, c) = static_cast<float>(sum[c] / count);
  };
  TraceFrameSamples(tracer, width, height, spec, seed, resolve, resolve_display, counters, nullptr);
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
  AALAB_CHECK(width > 0 && height > 0, "render size must be positive");
  const int spp = grid * grid;
  const Display& display = tracer.GetScene().display;
  Reference ref;
  ref.grid = grid;
  // Every pixel of the four images is written by the tile loop below: no serial zero-fill.
  ref.image = ImageF(width, height, 3, kUninitialized);
  ref.half_a = ImageF(width, height, 3, kUninitialized);
  ref.half_b = ImageF(width, height, 3, kUninitialized);
  ref.edge_mask_raw = ImageF(width, height, 1, kUninitialized);
  const uint64_t rseed = seed ^ kStreamReference;
  const TileGrid grid_of_tiles(width, height);
  const int tiles = grid_of_tiles.tiles;
  std::vector<TraceCounters> per_tile(static_cast<size_t>(tiles));
  // The truth samples image textures bilinearly on level 0 at every sub-sample (px = 0).
  const TextureFootprint footprint{0.0f, 1};
  const StrataTable strata(grid);
  ParallelForChunks(tiles, 1, [&](int begin, int end) {
    thread_local ReferenceScratch scratch;
    const size_t max_samples = static_cast<size_t>(kTile) * kTile * static_cast<size_t>(spp);
    if (scratch.pos.size() < max_samples) {
      scratch.pos.resize(max_samples);
      scratch.res.resize(max_samples);
      scratch.lanes.resize(3 * static_cast<size_t>(spp) * kTile);
    }
    SamplePos* pos = scratch.pos.data();
    SampleResult* res = scratch.res.data();
    float* lanes = scratch.lanes.data();
    for (int t = begin; t < end; ++t) {
      const auto [x0, y0, x1, y1] = grid_of_tiles.At(t);
      size_t n = 0;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          const PixelHash ph(x, y);
          PlaceStratifiedPixel(ph.h, grid, rseed, static_cast<float>(x), static_cast<float>(y), strata, pos + n);
          n += static_cast<size_t>(spp);
        }
      }
      // The resolve reads rgb, surface and shadowed only: no hit distances or points.
      tracer.Trace(pos, static_cast<int>(n), width, height, res, &per_tile[t], footprint, SampleFields::kShading);
      // One tile row at a time: its pixels' samples transposed into lanes, through the
      // display transform, summed pixel-parallel, encoded.
      const int row = x1 - x0;
      const SampleResult* r = res;
      for (int y = y0; y < y1; ++y) {
        TransposeRgb(r, row, spp, lanes);
        DisplayLinearLanes(display, lanes, 3 * spp * kTile);
        double sums[kSums * kTile];
        SumReferenceLanes(lanes, grid, sums);
        // The row's means (all, half A, half B: value (kSum… + c)·kTile + p), encoded at once.
        float enc[kSums * kTile];
        const int half = spp / 2;  // grid even: as many even strata as odd
        for (int v = 0; v < kSums * kTile; ++v) {
          enc[v] = static_cast<float>(sums[v] / (v < kSumA * kTile ? spp : half));
        }
        SrgbEncodeN(enc, enc, kSums * kTile);
        for (int p = 0; p < row; ++p) {
          const int x = x0 + p;
          for (int c = 0; c < 3; ++c) {
            ref.image.At(x, y, c) = enc[(kSumAll + c) * kTile + p];
            ref.half_a.At(x, y, c) = enc[(kSumA + c) * kTile + p];
            ref.half_b.At(x, y, c) = enc[(kSumB + c) * kTile + p];
          }
          ref.edge_mask_raw.At(x, y, 0) = SamplesDiffer(r + static_cast<size_t>(p) * spp, spp) ? 1.0f : 0.0f;
        }
        r += static_cast<size_t>(row) * spp;
      }
    }
  });
  if (counters) {
    for (const auto& c : per_tile) *counters += c;
  }

  ref.edge_mask = DilateMask(ref.edge_mask_raw);  // 1 px, 3×3 neighbourhood, clamped at the border
  return ref;
}

}  // namespace aalab
