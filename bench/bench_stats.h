/// Sample statistics shared by the bench files: the median (mean of the two middle samples
/// for an even count), minimum and maximum of a set of timings.
#pragma once
#include <algorithm>
#include <vector>

namespace aalab {

struct SampleStats {
  std::vector<double> samples;
  /// Median of `samples` (non-empty).
  double Median() const {
    std::vector<double> s = samples;
    std::sort(s.begin(), s.end());
    const size_t n = s.size();
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
  }
  double Min() const { return *std::min_element(samples.begin(), samples.end()); }
  double Max() const { return *std::max_element(samples.begin(), samples.end()); }
};

}  // namespace aalab
