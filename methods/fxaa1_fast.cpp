// FXAA 1.0: the production path (the filter `Fxaa1` that methods run).
//
// The same per-pixel computation as Fxaa1Reference in methods/fxaa1.cpp (Fxaa1TracePixel for
// every pixel that passes the contrast check), organised for a CPU. Its parameters, sources,
// debug views and deviations are documented at the top of methods/fxaa1.cpp.
#include <algorithm>
#include <array>
#include <memory>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "methods/fxaa1.h"
#include "methods/row_ops.h"

namespace aalab {

// The production path for the normal output. Same per-pixel computation as the reference,
// organised for a CPU: FxaaLuma of every texel once per frame into a float plane (it
// depends on the texel alone), the local contrast check over whole rows in a loop the
// compiler vectorises, then Fxaa1TracePixel only for the pixels that pass it. Early-exit
// pixels copy the input, as FxaaFilterReturn(rgbM) does, and count their 5 taps. Debug
// views go through the reference. Tests compare both paths bit for bit, taps included
// (tests/equivalence/fxaa_fast_test.cpp).

Image8 Fxaa1(const Image8& in, const Fxaa1Params& p, const std::string& debug_view, PostStats* stats) {
  // Debug views (and their name check) go through the reference, which checks p first as here;
  // so does any sampler arithmetic but the default (docs/gpu.md).
  if (!debug_view.empty() || p.sampler != SamplerArithmetic::kGl) return Fxaa1Reference(in, p, debug_view, stats);
  Fxaa1CheckParams(p);
  AALAB_CHECK(in.Channels() == 4, "fxaa1 needs an RGBA8 frame");
  Image8 out(in.Width(), in.Height(), 4, kUninitialized);  // every row written whole (CopyRowOpaque)
  if (in.Empty()) return out;
  const int height = in.Height();
  const int width = in.Width();
  // Step 1 for every texel: FxaaLuma(rgb) with rgb = UnormToFloat(k) as the sampler reads it.
  // Tables of the two terms for every 8-bit value: the same floats the sampler path computes.
  static const auto tables = [] {
    std::array<std::array<float, 256>, 2> t{};
    for (int k = 0; k < 256; ++k) {
      t[0][k] = UnormToFloat(static_cast<uint8_t>(k));                    // r
      t[1][k] = UnormToFloat(static_cast<uint8_t>(k)) * kFxaa1LumaGreen;  // g · (0.587/0.299)
    }
    return t;
  }();
  // Every value written by the parallel pass below: no serial zero-fill first.
  std::unique_ptr<float[]> luma(new float[static_cast<size_t>(width) * height]);
  ParallelForChunks(height, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const uint8_t* s = in.Row(y);
      float* l = luma.get() + static_cast<size_t>(y) * width;
      for (int x = 0; x < width; ++x) l[x] = tables[1][s[4 * x + 1]] + tables[0][s[4 * x]];
    }
  });
  constexpr int kGrain = 8;
  std::vector<uint64_t> chunk_taps(static_cast<size_t>((height + kGrain - 1) / kGrain), 0);
  ParallelForChunks(height, kGrain, [&](int y0, int y1) {
    BilinearSampler tex(in);
    thread_local std::vector<uint8_t> edge;
    if (edge.size() < static_cast<size_t>(width)) edge.resize(static_cast<size_t>(width));
    uint64_t exits = 0;
    for (int y = y0; y < y1; ++y) {
      uint8_t* orow = out.Row(y);
      CopyRowOpaque(in.Row(y), orow, width);
      const float* ln = luma.get() + static_cast<size_t>(std::max(y - 1, 0)) * width;
      const float* lm = luma.get() + static_cast<size_t>(y) * width;
      const float* ls = luma.get() + static_cast<size_t>(std::min(y + 1, height - 1)) * width;
      // Step 2, LocalContrastExit: max/min are exact, so their nesting does not matter.
      auto test = [&](float n, float w, float m, float e, float s) -> uint8_t {
        const float rmax = std::max(std::max(n, w), std::max(m, std::max(e, s)));
        const float rmin = std::min(std::min(n, w), std::min(m, std::min(e, s)));
        const float range = rmax - rmin;
        return range < std::max(p.edge_threshold_min, rmax * p.edge_threshold) ? 0 : 1;
      };
      if (width == 1) {
        edge[0] = test(ln[0], lm[0], lm[0], lm[0], ls[0]);
      } else {
        edge[0] = test(ln[0], lm[0], lm[0], lm[1], ls[0]);
        for (int x = 1; x < width - 1; ++x) edge[x] = test(ln[x], lm[x - 1], lm[x], lm[x + 1], ls[x]);
        edge[width - 1] = test(ln[width - 1], lm[width - 2], lm[width - 1], lm[width - 1], ls[width - 1]);
      }
      for (int x = 0; x < width; ++x) {
        if (!edge[x]) {
          ++exits;
          continue;
        }
        const Fxaa1Trace t = Fxaa1TracePixel(tex, x, y, p);
        AALAB_CHECK(!t.early_exit, "fxaa1 fast path: contrast test disagrees with the trace");
        uint8_t* o = orow + 4 * x;
        o[0] = QuantizeUnorm8(t.rgb_out[0]);
        o[1] = QuantizeUnorm8(t.rgb_out[1]);
        o[2] = QuantizeUnorm8(t.rgb_out[2]);
      }
    }
    chunk_taps[static_cast<size_t>(y0 / kGrain)] = tex.Taps() + 5 * exits;
  });
  if (stats != nullptr) {
    for (uint64_t taps : chunk_taps) stats->taps += taps;
  }
  return out;
}

}  // namespace aalab
