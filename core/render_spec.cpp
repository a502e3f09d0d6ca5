#include "core/render_spec.h"

#include <string>

#include "core/error.h"

namespace aalab {

const std::vector<SampleOffset16>& StandardSamplePositions(int n) {
  // D3D11.3 functional spec §19.2.4 (pattern figures with 1/16 px coordinates) = Vulkan
  // "Standard sample locations" (there in [0,1]² from the upper-left corner: (x + 8) / 16).
  static const std::vector<SampleOffset16> k1 = {{0, 0}};
  static const std::vector<SampleOffset16> k2 = {{4, 4}, {-4, -4}};
  static const std::vector<SampleOffset16> k4 = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
  static const std::vector<SampleOffset16> k8 = {{1, -3}, {-1, 3},  {5, 1}, {-3, -5},
                                                 {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};
  static const std::vector<SampleOffset16> k16 = {{1, 1},  {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5},
                                                  {5, 3},  {3, -5},  {-2, 6}, {0, -7}, {-4, -6}, {-6, 4},
                                                  {-8, 0}, {7, -4},  {6, 7},  {-7, -8}};
  switch (n) {
    case 1: return k1;
    case 2: return k2;
    case 4: return k4;
    case 8: return k8;
    case 16: return k16;
    default: break;
  }
  throw InternalError("no standard sample positions for " + std::to_string(n) + " samples");
}

bool RenderSpec::IsPlain1x() const {
  return pattern == SamplePattern::kCenter && scale == 1.0 && !msaa.On() && !aaa.enabled && jitter.samples == 0 &&
         !specular_aa.enabled;
}

int RenderSpec::SamplesPerPixel() const {
  if (msaa.On()) return msaa.samples;
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
    case SamplePattern::kRotatedGrid: return {{0.375f, 0.125f}, {0.875f, 0.375f}, {0.125f, 0.625f}, {0.625f, 0.875f}};
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
  if (spec.sequence) return spec.sequence(frame, spec.samples);
  const int index = frame % spec.samples + 1;
  return {static_cast<float>(RadicalInverse(2, index) - 0.5), static_cast<float>(RadicalInverse(3, index) - 0.5)};
}

}  // namespace aalab
