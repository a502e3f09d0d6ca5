#include "harness/core/render_spec.h"

#include "harness/core/error.h"

namespace aalab {

int RenderSpec::SamplesPerPixel() const {
  switch (pattern) {
    case SamplePattern::kCenter: return 1;
    case SamplePattern::kOrderedGrid:
    case SamplePattern::kStratified: return grid * grid;
    case SamplePattern::kRotatedGrid: return 4;
    case SamplePattern::kJitter: return spp;
  }
  return 1;
}

std::vector<std::pair<float, float>> RenderSpec::FixedOffsets() const {
  switch (pattern) {
    case SamplePattern::kCenter: return {{0.5f, 0.5f}};
    case SamplePattern::kOrderedGrid: {
      std::vector<std::pair<float, float>> out;
      for (int j = 0; j < grid; ++j) {
        for (int i = 0; i < grid; ++i) {
          out.emplace_back((static_cast<float>(i) + 0.5f) / static_cast<float>(grid),
                           (static_cast<float>(j) + 0.5f) / static_cast<float>(grid));
        }
      }
      return out;
    }
    case SamplePattern::kRotatedGrid:
      return {{0.375f, 0.125f}, {0.875f, 0.375f}, {0.125f, 0.625f}, {0.625f, 0.875f}};
    case SamplePattern::kJitter:
    case SamplePattern::kStratified: break;
  }
  throw InternalError("FixedOffsets called on a jittered pattern");
}

double RadicalInverse(int base, int index) {
  AALAB_CHECK(base >= 2 && index >= 0, "radical inverse needs base >= 2 and index >= 0");
  double inv = 1.0 / base, f = inv, r = 0.0;
  for (int i = index; i > 0; i /= base) {
    r += f * (i % base);
    f *= inv;
  }
  return r;
}

FrameJitter FrameJitterAt(const JitterSpec& spec, int frame) {
  if (spec.samples <= 0) return {};
  AALAB_CHECK(frame >= 0, "frame index must be >= 0");
  const int index = frame % spec.samples + 1;
  return {static_cast<float>(RadicalInverse(2, index) - 0.5), static_cast<float>(RadicalInverse(3, index) - 0.5)};
}

}  // namespace aalab
