// SSIM and LDR-FLIP against independent implementations, on the deterministic image pairs of
// test_images.h. The expected numbers come from tests/metrics/crosscheck_reference.py (run
// with Debian's python3-skimage 0.19.3 / numpy 1.24 / scipy 1.10):
//  - SSIM: scikit-image structural_similarity(..., channel_axis=2, gaussian_weights=True,
//    sigma=1.5, use_sample_covariance=False, data_range=1) on float64 arrays;
//  - FLIP: a numpy transcription of NVIDIA's python reference (compute_ldrflip) with full
//    2-D kernels and replicated borders, in float64.
// Agreement is ~1e-15 for the double paths; the tolerances leave room for libm differences
// only. The float32 FLIP and SSIM paths are checked within float rounding (see below).
#include <gtest/gtest.h>

#include "metrics/flip.h"
#include "metrics/ssim.h"
#include "tests/metrics/ssim_bound.h"
#include "tests/metrics/test_images.h"

namespace aalab {
namespace {

struct Expected {
  int w, h;
  uint32_t seed;
  double ppd, ssim, flip_mean, flip_wmedian, flip_max, flip_at_3_4;
};

// Printed by crosscheck_reference.py.
const Expected kCases[] = {
    {48, 40, 1, 67.0, 0.8315279062465454, 0.0880244861613022, 0.11755679704693271, 0.3584472769740731,
     0.03191572155712548},
    {48, 40, 1, 20.0, 0.8315279062465454, 0.21288106510037982, 0.24111714324082248, 0.8530097670565066,
     0.1863326703392243},
    {33, 21, 2, 67.0, 0.8397625906067843, 0.052207048202305956, 0.05880138806758253, 0.13075809619604298,
     0.08220071645922042},
    {33, 21, 2, 20.0, 0.8397625906067843, 0.17446821970237272, 0.20081222020261963, 0.4959719272617525,
     0.18567325496181564},
};

// The double definition (ComputeSsimReference) to libm differences; the production path
// (float32 window sums, metrics/ssim_float.cpp) within its derived bound averaged over the
// map and channels (tests/metrics/ssim_bound.h).
TEST(CrossCheck, SsimMatchesScikitImage) {
  for (const Expected& e : kCases) {
    const auto [ref, test] = testimg::MakePair(e.w, e.h, e.seed);
    EXPECT_NEAR(*ComputeSsimReference(ref, test).ssim, e.ssim, 1e-13) << e.w << "x" << e.h;
    double bound = 0.0;
    for (int c = 0; c < 3; ++c) bound += testssim::MeasureDrift(ref, test, c).mean_bound / 3.0;
    EXPECT_NEAR(*ComputeSsim(ref, test).ssim, e.ssim, bound) << e.w << "x" << e.h << " (float path)";
  }
}

// The double-precision implementation (flip::ErrorValuesUncached) to libm differences; the
// production path (float32, flip_fast.cpp, as NVIDIA's own tools compute) within float
// rounding: ~1e-7 relative per operation, a few hundred operations a pixel, errors
// averaging out in the mean (tests/equivalence/metrics_fast_test.cpp measures the same on frames).
TEST(CrossCheck, FlipMatchesTwoDimensionalReference) {
  for (const Expected& e : kCases) {
    const auto [ref, test] = testimg::MakePair(e.w, e.h, e.seed);
    const auto v = flip::ErrorValuesUncached(ref, test, e.ppd);
    const FlipPooled p = PoolFlip(v);
    EXPECT_NEAR(p.mean, e.flip_mean, 1e-12) << e.w << "x" << e.h << " ppd " << e.ppd;
    EXPECT_NEAR(p.weighted_median, e.flip_wmedian, 1e-12);
    EXPECT_NEAR(p.max, e.flip_max, 1e-12);
    EXPECT_NEAR(v[4 * e.w + 3], e.flip_at_3_4, 1e-12);
    const auto f = flip::ErrorValues(ref, test, e.ppd);
    const FlipPooled pf = PoolFlip(f);
    EXPECT_NEAR(pf.mean, e.flip_mean, 1e-6) << e.w << "x" << e.h << " ppd " << e.ppd << " (float path)";
    EXPECT_NEAR(pf.weighted_median, e.flip_wmedian, 1e-5);
    EXPECT_NEAR(pf.max, e.flip_max, 1e-5);
    EXPECT_NEAR(f[4 * e.w + 3], e.flip_at_3_4, 1e-5);
  }
}

}  // namespace
}  // namespace aalab
