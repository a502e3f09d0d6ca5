/// Automatic crop selection: where a method fails most, for zoomed side-by-side views.
#pragma once
#include <vector>

#include "core/image.h"

namespace aalab {

/// A rectangle in pixels: [x, x + w) × [y, y + h).
struct CropRect {
  int x = 0, y = 0, w = 0, h = 0;
};

/// Picks up to `count` non-overlapping size × size windows (clipped to the image) with the
/// largest summed value of `score` (1 channel), greedily from the largest. Windows whose sum
/// is 0 are not picked. Ties go to the first window in row-major order of its top-left
/// corner. Sums are double; the result does not depend on threads.
std::vector<CropRect> PickCrops(const ImageF& score, int size, int count);

/// Per-pixel score for crop picking: mean over RGB of |a − b|, times `mask` when given.
ImageF CropScore(const ImageF& a, const ImageF& b, const ImageF* mask);

}  // namespace aalab
